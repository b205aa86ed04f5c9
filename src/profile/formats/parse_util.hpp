// SPDX-License-Identifier: Apache-2.0
// Internal to the profile readers: the small text-parsing helpers they share.
#pragma once

#include <charconv>
#include <cmath>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/check.hpp"
#include "profile/formats/profile_limits.hpp"

namespace railtab::detail {

namespace fs = std::filesystem;

// One profile point as it goes through the file's processing options.
struct FilePoint {
  double y;  // lateral, towards the field side once oriented [file length unit, then m]
  double z;  // vertical, positive downwards [file length unit, then m]
  int line;  // 1-based line of the file it came from
};

[[noreturn]] inline void fail(const fs::path& file, int line, const std::string& message) {
  if (line > 0) throw Error(fmt::format("{}:{}: {}", file.string(), line, message));
  throw Error(fmt::format("{}: {}", file.string(), message));
}

inline std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return s.substr(first, last - first + 1);
}

// Cuts the line at the first comment character outside single or double quotes.
inline std::string_view strip_comment(std::string_view s, std::string_view comment_chars) {
  char quote = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (quote != 0) {
      if (c == quote) quote = 0;
    } else if (c == '\'' || c == '"') {
      quote = c;
    } else if (comment_chars.find(c) != std::string_view::npos) {
      return s.substr(0, i);
    }
  }
  return s;
}

// Fields separated by white space and/or commas.
inline std::vector<std::string_view> split_fields(std::string_view s) {
  std::vector<std::string_view> fields;
  std::size_t i = 0;
  auto is_sep = [](char c) { return c == ' ' || c == '\t' || c == ',' || c == ';' || c == '\r'; };
  while (i < s.size()) {
    while (i < s.size() && is_sep(s[i])) ++i;
    const std::size_t start = i;
    while (i < s.size() && !is_sep(s[i])) ++i;
    if (i > start) fields.push_back(s.substr(start, i - start));
  }
  return fields;
}

inline double parse_number(std::string_view token, const fs::path& file, int line, std::string_view what) {
  std::string_view digits = token;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);  // from_chars rejects '+'
  double value = 0.0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (ec != std::errc() || end != digits.data() + digits.size() || digits.empty()) {
    fail(file, line, fmt::format("malformed number '{}' for {}", token, what));
  }
  if (!std::isfinite(value)) fail(file, line, fmt::format("{} is not finite ('{}')", what, token));
  return value;
}

// Stops a reader before a hostile file makes it allocate without bound.
inline void check_point_count(std::size_t count, const fs::path& file, int line) {
  if (count > limits::kMaxProfilePoints) {
    fail(file, line, fmt::format("more than {} profile points: refused", limits::kMaxProfilePoints));
  }
}

}  // namespace railtab::detail
