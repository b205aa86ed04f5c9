// SPDX-License-Identifier: Apache-2.0
// Text in gnuplot scripts: text from outside the code (paths, scene and simulation names,
// descriptions) as gnuplot strings that gnuplot takes word for word, and the check run_gnuplot
// (charts/gnuplot.hpp) makes on every script before gnuplot sees it. Pure text handling, so the
// fuzz target fuzz/fuzz_chart_title.cpp compiles it alone.
#pragma once

#include <filesystem>
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

}  // namespace railtab
