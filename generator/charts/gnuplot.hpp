// SPDX-License-Identifier: Apache-2.0
// PNG charts are drawn by gnuplot (Debian gnuplot-nox, pngcairo terminal) from CSV files that the
// chart commands write first, so every chart can be redrawn or re-plotted elsewhere from its CSV.
// gnuplot is started without a shell (argument vector, script on its standard input); every text
// from outside the code (paths, scene and simulation names, descriptions) reaches a script only as
// a gnuplot_string, and run_gnuplot refuses a script holding a backquote or an '@' (gnuplot's
// command and macro substitution), wherever it came from.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <string_view>

namespace railtab {

// `text` as a gnuplot double-quoted string literal that gnuplot takes word for word. gnuplot
// replaces `...` by the output of a shell command and @name by a variable's text on every script
// line before it reads strings, even inside double quotes; so every byte but letters, digits,
// space and . , : ; + - = / ( ) _ is written as an octal escape (\ooo): the script line then holds
// no backquote, '@', '$', quote, backslash or newline, and gnuplot's string reader turns the
// escapes back into the original bytes (UTF-8 included). A NUL byte (which would end gnuplot's
// string) becomes a space. Titles made of it are drawn `noenhanced` (no ^ _ { } markup).
std::string gnuplot_string(std::string_view text);

// `path` as a gnuplot string (gnuplot_string). A relative path starting with '<' or '|' (gnuplot
// would run it as a command) gets "./" in front. Throws railtab::Error for a path with a NUL.
std::string gnuplot_quote(const std::filesystem::path& path);

// Empty when `script` may be given to gnuplot; otherwise what is wrong, naming the line: a
// backquote or an '@' anywhere (only input text could have put one there, since gnuplot_string
// never writes either).
std::string gnuplot_script_problem(std::string_view script);

// The scene as a chart title names it: "name (description)", or "name" without a description, so
// a chart says which profiles and track it shows ("default" alone does not).
std::string scene_title(const std::string& name, const std::string& description);

// Draws `png` with `script`, which starts with its `set terminal` line and has no `set output`
// (run_gnuplot adds it). The script is saved as `script_path` (to redraw the chart by hand) and
// piped to gnuplot, which writes a temporary beside `png`; the temporary replaces `png` only when
// gnuplot succeeded (table/output_file.hpp). gnuplot's messages are captured: a failure throws
// railtab::Error naming the script with gnuplot's last message; the warnings of a chart that was
// drawn go to the stream set_gnuplot_messages chose. Throws also for a script with a
// gnuplot_script_problem (before gnuplot starts) and when gnuplot is missing.
void run_gnuplot(const std::filesystem::path& script_path, const std::string& script, const std::filesystem::path& png);

// Where gnuplot's warnings go (std::cerr unless set): a command passes its diagnostics stream,
// the null stream with -q/--quiet.
void set_gnuplot_messages(std::ostream& out);

}  // namespace railtab
