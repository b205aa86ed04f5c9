// SPDX-License-Identifier: Apache-2.0
// PNG charts are drawn by gnuplot (Debian gnuplot-nox, pngcairo terminal) from CSV files that the
// chart commands write first, so every chart can be redrawn or re-plotted elsewhere from its CSV.
// gnuplot is started without a shell (argument vector, script on its standard input); every path
// inside a script goes through gnuplot_quote.
#pragma once

#include <filesystem>
#include <string>

namespace railtab {

// `path` as a gnuplot single-quoted string ('' inside stands for '). A relative path starting with
// '<' or '|' (gnuplot would run it as a command) gets "./" in front. Throws railtab::Error for a
// path gnuplot cannot quote (a newline, a carriage return or a NUL character).
std::string gnuplot_quote(const std::filesystem::path& path);

// `text` escaped for the inside of a gnuplot double-quoted string (\\, \" and \n), for scene
// names and other free text in titles: a '"' in a scene name cannot end the string.
std::string gnuplot_text(const std::string& text);

// The scene as a chart title names it: "name (description)", or "name" without a description, so
// a chart says which profiles and track it shows ("default" alone does not).
std::string scene_title(const std::string& name, const std::string& description);

// Draws `png` with `script`, which starts with its `set terminal` line and has no `set output`
// (run_gnuplot adds it). The script is saved as `script_path` (to redraw the chart by hand) and
// piped to gnuplot, which writes a temporary beside `png`; the temporary replaces `png` only when
// gnuplot succeeded (table/output_file.hpp). Throws railtab::Error when gnuplot is missing or
// fails, naming the script.
void run_gnuplot(const std::filesystem::path& script_path, const std::string& script, const std::filesystem::path& png);

}  // namespace railtab
