// PNG charts are drawn by gnuplot (Debian gnuplot-nox, pngcairo terminal) from CSV files that the
// chart commands write first, so every chart can be redrawn or re-plotted elsewhere from its CSV.
#pragma once

#include <filesystem>
#include <string>

namespace railtab {

// Writes `script` next to the chart as NAME.gp and runs gnuplot on it. Throws railtab::Error when
// gnuplot is missing or fails, naming the script.
void run_gnuplot(const std::filesystem::path& script_path, const std::string& script);

}  // namespace railtab
