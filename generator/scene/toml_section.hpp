// SPDX-License-Identifier: Apache-2.0
// Checked reading of TOML scene files (contact scenes and simulation scenes): every table knows
// its allowed keys, so a typo is an error and never a silently ignored setting, and every error
// names the file, the line and the dotted key ("bad.toml:12: grid.load: must be > 0, got -1").
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "core/check.hpp"

namespace railtab::scene_toml {

// The file being read, for messages.
struct Context {
  std::string file;  // file name as given to the parser
};

[[noreturn]] void fail(const Context& ctx, const toml::source_region& where, const std::string& key,
                       const std::string& message);
const char* type_name(const toml::node& node);
std::string join(const std::vector<std::string>& words);  // "a, b, c"

bool positive(double v);
bool non_negative(double v);

// One TOML table with a fixed list of allowed keys; a key outside the list is an error at
// construction. A null table (section absent) reads every key as absent.
class Section {
 public:
  Section(const Context& ctx, std::string name, const toml::table* table,
          std::vector<std::string> allowed);

  bool present() const { return table_ != nullptr; }
  bool has(const std::string& key) const { return table_ && table_->get(key) != nullptr; }
  const toml::node* node(const std::string& key) const { return table_ ? table_->get(key) : nullptr; }
  std::string dotted(const std::string& key) const { return name_ + "." + key; }
  const Context& context() const { return ctx_; }
  toml::source_region source() const { return table_ ? table_->source() : toml::source_region{}; }

  const toml::node& required(const std::string& key) const;
  double number(const toml::node& n, const std::string& key) const;  // integer or float, finite
  // A number checked by `check` (with its description for the message); absent: `fallback`, or
  // an error when `is_required`.
  double number(const std::string& key, double fallback, bool (*check)(double) = nullptr,
                const char* requirement = "", bool is_required = false) const;
  int integer(const std::string& key, int fallback, int min_value, int max_value = 1'000'000) const;
  bool boolean(const std::string& key, bool fallback) const;
  std::string string(const toml::node& n, const std::string& key) const;
  std::optional<std::string> string(const std::string& key) const;
  // A non-empty list of distinct strings, each passed to `check` (which throws railtab::Error).
  template <class Check>
  std::vector<std::string> strings(const std::string& key, std::vector<std::string> fallback,
                                   Check check) const;

  // Runs a parser of a string value (e.g. parse_normal_model), turning its Error into one that
  // names the file, line and key.
  template <class Parse>
  auto parse_string(const std::string& key, Parse parse) const
      -> std::optional<decltype(parse(""))>;

 private:
  const Context& ctx_;
  std::string name_;
  const toml::table* table_;
  std::vector<std::string> allowed_;
};

// The table `key` of `parent` (nullptr when absent; an error naming `dotted_name` when not a table).
const toml::table* table_at(const Context& ctx, const toml::table& parent, const std::string& key,
                            const std::string& dotted_name);
// The whole text of a scene file; `what` names the kind of file in the error ("scene file").
// Only a regular file of at most 4 MiB: a device or FIFO is refused at once (no read, no block).
std::string read_text(const std::filesystem::path& path, const char* what);
// Parses TOML text; a syntax error names the file, line and column.
toml::table parse(std::string_view text, const std::string& source_name);

// Section `name` of the file's root table.
Section section(const Context& ctx, const toml::table& root, const std::string& name,
                std::vector<std::string> allowed);

template <class Check>
std::vector<std::string> Section::strings(const std::string& key, std::vector<std::string> fallback,
                                          Check check) const {
  const toml::node* n = node(key);
  if (!n) return fallback;
  const toml::array* a = n->as_array();
  if (!a || a->empty()) fail(ctx_, n->source(), dotted(key), "expected a non-empty list of strings");
  std::vector<std::string> out;
  for (const toml::node& e : *a) {
    std::string text = string(e, key);
    try {
      check(text);
    } catch (const Error& err) {
      fail(ctx_, e.source(), dotted(key), err.what());
    }
    for (const std::string& seen : out) {
      if (seen == text) fail(ctx_, e.source(), dotted(key), "'" + text + "' is listed twice");
    }
    out.push_back(std::move(text));
  }
  return out;
}

template <class Parse>
auto Section::parse_string(const std::string& key, Parse parse) const
    -> std::optional<decltype(parse(""))> {
  const toml::node* n = node(key);
  if (!n) return std::nullopt;
  std::string text = string(*n, key);
  try {
    return parse(text);
  } catch (const Error& e) {
    fail(ctx_, n->source(), dotted(key), e.what());
  }
}

}  // namespace railtab::scene_toml
