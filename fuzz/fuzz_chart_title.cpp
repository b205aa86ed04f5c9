// SPDX-License-Identifier: Apache-2.0
// Fuzz target: scene names and descriptions through the chart title path. The input is a scene
// name and description (split at the first NUL byte). They go (1) as raw bytes and (2) through
// the scene reader (a scene file holding them as TOML strings) into scene_title and gnuplot_string
// (charts/gnuplot_string.hpp), as every chart and the wear charts do. Checked for every input:
// the gnuplot string holds only letters, digits, " .,:;+-=/()_" and \ooo escapes between its
// quotes, so gnuplot can neither substitute a command (backquote) or a macro ('@') nor leave the
// string; a script line made of it passes gnuplot_script_problem; gnuplot's escape reading gives
// back the title exactly (a NUL read as a space). A violation aborts (a libFuzzer finding).

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>

#include "charts/gnuplot_string.hpp"
#include "core/check.hpp"
#include "scene/scene.hpp"

namespace {

[[noreturn]] void finding(const char* what, const std::string& text) {
  std::fprintf(stderr, "fuzz_chart_title: %s: %s\n", what, text.c_str());
  std::abort();
}

bool literal(unsigned char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
         std::string_view(" .,:;+-=/()_").find(static_cast<char>(c)) != std::string_view::npos;
}

// Reads `quoted` the way gnuplot reads a double-quoted string of this form, checking the form.
std::string read_back(const std::string& quoted) {
  if (quoted.size() < 2 || quoted.front() != '"' || quoted.back() != '"') finding("not a quoted string", quoted);
  std::string text;
  for (std::size_t i = 1; i + 1 < quoted.size(); ++i) {
    const auto c = static_cast<unsigned char>(quoted[i]);
    if (c != '\\') {
      if (!literal(c)) finding("character gnuplot could act on", quoted);
      text += static_cast<char>(c);
      continue;
    }
    if (i + 4 >= quoted.size()) finding("cut escape", quoted);
    int value = 0;
    for (std::size_t k = 1; k <= 3; ++k) {
      const char d = quoted[i + k];
      if (d < '0' || d > '7') finding("escape that is not octal", quoted);
      value = value * 8 + (d - '0');
    }
    if (value == 0 || value > 255) finding("escape out of range", quoted);
    text += static_cast<char>(value);
    i += 3;
  }
  return text;
}

void check_title(const std::string& name, const std::string& description) {
  const std::string title = railtab::scene_title(name, description);
  const std::string quoted = railtab::gnuplot_string(title);
  std::string expected = title;
  for (char& c : expected) {
    if (c == '\0') c = ' ';
  }
  if (read_back(quoted) != expected) finding("title not read back exactly", quoted);
  const std::string problem = railtab::gnuplot_script_problem("set title " + quoted + " noenhanced\n");
  if (!problem.empty()) finding(problem.c_str(), quoted);
}

// `text` as a TOML basic string (every byte below 0x20, '"' and '\' escaped).
std::string toml_string(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f || c == '"' || c == '\\') {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\u%04x", byte);
      out += escape;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t split = input.find('\0');
  const std::string name(input.substr(0, split));
  const std::string description(split == std::string_view::npos ? std::string_view() : input.substr(split + 1));
  check_title(name, description);
  // The same text as a scene file gives it: what a chart command draws.
  const std::string scene_text = "[scene]\nname = " + toml_string(name) + "\ndescription = " + toml_string(description) +
                                 "\n[profiles]\nwheel = \"s1002\"\nrail = \"uic60\"\n[contact]\nnormal_model = "
                                 "\"hertz\"\n[grid]\ny = [-0.002, 0.0, 0.002]\nload = [60e3, 90e3]\n";
  try {
    const railtab::Scene scene = railtab::parse_scene(scene_text, "fuzz.toml", std::filesystem::path("."));
    check_title(scene.name, scene.description);
  } catch (const railtab::Error&) {
    // A name the scene reader refuses (invalid UTF-8, too long) never reaches a chart.
  }
  return 0;
}
