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

#include "charts/gnuplot_string.hpp"

namespace railtab {

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
