// SPDX-License-Identifier: Apache-2.0
// Numeric command-line options through the one number reader (number_options.hpp).
#include "cli/number_options.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "core/check.hpp"

namespace railtab {
namespace {

// Runs a parse; its railtab::Error becomes CLI11's usage error (exit 2) with the same message.
template <class Parse>
auto as_usage_error(Parse parse) {
  try {
    return parse();
  } catch (const Error& e) {
    throw CLI::ValidationError(e.what());
  }
}

std::string with_range(const std::string& help, const NumberRule& rule) {
  return fmt::format("{} ({})", help, describe(rule));
}

std::string joined(const std::vector<std::string>& parts) {
  std::string text;
  for (std::size_t k = 0; k < parts.size(); ++k) text += (k ? "," : "") + parts[k];
  return text;
}

template <class Int>
CLI::Option* add_count(CLI::App* cmd, const std::string& name, Int& value, const NumberRule& rule,
                       const std::string& help) {
  RAILTAB_CHECK(rule.whole, "{}: a count option needs a whole-number rule", name);
  return cmd
      ->add_option_function<std::string>(
          name,
          [&value, name, rule](const std::string& text) {
            value = static_cast<Int>(as_usage_error([&] { return parse_number_input(text, name, rule); }));
          },
          with_range(help, rule))
      ->default_str(std::to_string(value));
}

}  // namespace

CLI::Option* add_number_option(CLI::App* cmd, const std::string& name, double& value, const NumberRule& rule,
                               const std::string& help) {
  return cmd
      ->add_option_function<std::string>(
          name,
          [&value, name, rule](const std::string& text) {
            value = as_usage_error([&] { return parse_number_input(text, name, rule); });
          },
          with_range(help, rule))
      ->default_str(fmt::format("{:g}", value));
}

CLI::Option* add_number_option(CLI::App* cmd, const std::string& name, std::optional<double>& value,
                               const NumberRule& rule, const std::string& help) {
  return cmd->add_option_function<std::string>(
      name,
      [&value, name, rule](const std::string& text) {
        value = as_usage_error([&] { return parse_number_input(text, name, rule); });
      },
      with_range(help, rule));
}

CLI::Option* add_count_option(CLI::App* cmd, const std::string& name, int& value, const NumberRule& rule,
                              const std::string& help) {
  return add_count(cmd, name, value, rule, help);
}

CLI::Option* add_count_option(CLI::App* cmd, const std::string& name, std::uint64_t& value, const NumberRule& rule,
                              const std::string& help) {
  return add_count(cmd, name, value, rule, help);
}

CLI::Option* add_number_list_option(CLI::App* cmd, const std::string& name, std::vector<double>& values,
                                    const NumberRule& rule, const std::string& help) {
  return cmd->add_option_function<std::vector<std::string>>(
      name,
      [&values, name, rule](const std::vector<std::string>& parts) {
        values = as_usage_error([&] { return parse_number_list(joined(parts), name, rule); });
      },
      with_range(help, rule));
}

CLI::Option* add_number_fields_option(CLI::App* cmd, const std::string& name, std::vector<double>& values,
                                      std::span<const NumberField> fields, const std::string& help) {
  std::string ranges;
  for (const NumberField& f : fields) ranges += fmt::format("{}{}: {}", ranges.empty() ? "" : "; ", f.name, describe(f.rule));
  const std::vector<NumberField> kept(fields.begin(), fields.end());
  return cmd
      ->add_option_function<std::vector<std::string>>(
          name,
          [&values, name, kept](const std::vector<std::string>& parts) {
            values = as_usage_error([&] { return parse_number_fields(joined(parts), name, kept); });
          },
          fmt::format("{} ({})", help, ranges))
      ->expected(1, static_cast<int>(fields.size()));
}

}  // namespace railtab
