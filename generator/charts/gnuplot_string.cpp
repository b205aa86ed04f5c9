// SPDX-License-Identifier: Apache-2.0
// gnuplot strings of octal escapes for input text, and the backquote / macro check of scripts
// (gnuplot_string.hpp).
#include "charts/gnuplot_string.hpp"

#include <fmt/format.h>

#include <cctype>

#include "core/check.hpp"

namespace railtab {

std::string gnuplot_string(std::string_view text) {
  std::string out = "\"";
  constexpr std::string_view kLiteral = " .,:;+-=/()_";  // with letters and digits: written as they are
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte == 0) {
      out += ' ';
    } else if (std::isalnum(byte) != 0 || kLiteral.find(c) != std::string_view::npos) {
      out += c;
    } else {
      out += fmt::format("\\{:03o}", byte);
    }
  }
  return out + "\"";
}

std::string gnuplot_quote(const std::filesystem::path& path) {
  std::string text = path.string();
  RAILTAB_CHECK(text.find('\0') == std::string::npos, "path \"{}\" cannot be given to gnuplot (it holds a NUL character)",
                text);
  if (path.is_relative() && !text.empty() && (text[0] == '<' || text[0] == '|')) text = "./" + text;
  return gnuplot_string(text);
}

std::string gnuplot_script_problem(std::string_view script) {
  std::size_t line = 1;
  for (const char c : script) {
    if (c == '\n') ++line;
    if (c == '`') return fmt::format("line {} holds a backquote (gnuplot would run the text as a shell command)", line);
    if (c == '@') return fmt::format("line {} holds an '@' (gnuplot would replace it by a macro)", line);
  }
  return {};
}

std::string scene_title(const std::string& name, const std::string& description) {
  return description.empty() ? name : name + " (" + description + ")";
}

}  // namespace railtab
