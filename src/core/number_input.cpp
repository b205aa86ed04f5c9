// SPDX-License-Identifier: Apache-2.0
// Numbers typed by a user, checked against their rule (number_input.hpp).
#include "core/number_input.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <system_error>

#include "core/check.hpp"

namespace railtab {
namespace {

// At most this much of a refused text is quoted back (a pasted file must not flood the terminal).
constexpr std::size_t kQuoteChars = 40;

std::string quoted(std::string_view text) {
  std::string out;
  for (const char c : text.substr(0, kQuoteChars)) {
    const auto u = static_cast<unsigned char>(c);
    out += (u < 0x20 || u == 0x7f) ? fmt::format("\\x{:02x}", u) : std::string(1, c);
  }
  if (text.size() > kQuoteChars) out += "...";
  return "'" + out + "'";
}

std::string with_unit(double v, const NumberRule& rule) {
  return *rule.unit ? fmt::format("{:g} {}", v, rule.unit) : fmt::format("{:g}", v);
}

}  // namespace

std::string describe(const NumberRule& rule) {
  const std::string range = *rule.unit ? fmt::format("[{:g}, {:g}] {}", rule.min, rule.max, rule.unit)
                                       : fmt::format("[{:g}, {:g}]", rule.min, rule.max);
  return (rule.whole ? "a whole number in " : "a number in ") + range;
}

std::string number_problem(double value, const NumberRule& rule) {
  if (std::isnan(value)) return fmt::format("must be {}, got NaN", describe(rule));
  if (std::isinf(value)) return fmt::format("must be {}, got {}infinity", describe(rule), value < 0 ? "-" : "");
  if (rule.whole && value != std::floor(value)) {
    return fmt::format("must be {}, got {} (not a whole number)", describe(rule), value);
  }
  if (value < rule.min || value > rule.max) {
    return fmt::format("must be {}, got {}", describe(rule), with_unit(value, rule));
  }
  return {};
}

std::string number_problem(std::string_view text, const NumberRule& rule, double& value) {
  if (text.empty()) return fmt::format("must be {}, got an empty value", describe(rule));
  std::string_view digits = text;
  if (digits.front() == '+') digits.remove_prefix(1);  // from_chars refuses '+'; "+-1" stays refused
  const char* end = digits.data() + digits.size();
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(digits.data(), end, v);
  if (digits.empty() || (digits.front() == '-' && text.front() == '+') || ptr != end) {
    return fmt::format("must be {}, got {} (not a number)", describe(rule), quoted(text));
  }
  if (ec == std::errc::result_out_of_range) {  // beyond +-1.8e308, or nonzero and below 2.2e-308 in magnitude
    return fmt::format("must be {}, got {} (not representable as a double)", describe(rule), quoted(text));
  }
  if (ec != std::errc()) return fmt::format("must be {}, got {} (not a number)", describe(rule), quoted(text));
  std::string problem = number_problem(v, rule);
  if (problem.empty()) value = v;
  return problem;
}

double parse_number_input(std::string_view text, std::string_view name, const NumberRule& rule) {
  double value = 0.0;
  const std::string problem = number_problem(text, rule, value);
  RAILTAB_CHECK(problem.empty(), "{}: {}", name, problem);
  return value;
}

std::vector<double> parse_number_list(std::string_view text, std::string_view name, const NumberRule& rule,
                                      std::size_t count) {
  std::vector<double> values;
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = text.find(',', begin);
    const std::string_view field = text.substr(begin, comma == std::string_view::npos ? text.npos : comma - begin);
    double value = 0.0;
    const std::string problem = number_problem(field, rule, value);
    RAILTAB_CHECK(problem.empty(), "{}: value {} of {}: {}", name, values.size() + 1, quoted(text), problem);
    values.push_back(value);
    if (comma == std::string_view::npos) break;
    begin = comma + 1;
  }
  RAILTAB_CHECK(count == 0 || values.size() == count, "{}: takes {} comma-separated numbers, got {} in {}", name,
                count, values.size(), quoted(text));
  return values;
}

std::vector<double> parse_number_fields(std::string_view text, std::string_view name,
                                        std::span<const NumberField> fields) {
  std::vector<std::string_view> parts;
  for (std::size_t begin = 0;;) {
    const std::size_t comma = text.find(',', begin);
    parts.push_back(text.substr(begin, comma == std::string_view::npos ? text.npos : comma - begin));
    if (comma == std::string_view::npos) break;
    begin = comma + 1;
  }
  RAILTAB_CHECK(parts.size() == fields.size(), "{}: takes {} comma-separated numbers, got {} in {}", name,
                fields.size(), parts.size(), quoted(text));
  std::vector<double> values(fields.size());
  for (std::size_t k = 0; k < fields.size(); ++k) {
    const std::string problem = number_problem(parts[k], fields[k].rule, values[k]);
    RAILTAB_CHECK(problem.empty(), "{}: {} (value {} of {}): {}", name, fields[k].name, k + 1, quoted(text), problem);
  }
  return values;
}

double check_number_input(double value, std::string_view name, const NumberRule& rule) {
  const std::string problem = number_problem(value, rule);
  RAILTAB_CHECK(problem.empty(), "{}: {}", name, problem);
  return value;
}

}  // namespace railtab
