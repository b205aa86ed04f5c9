// SPDX-License-Identifier: Apache-2.0
// The speed-against-accuracy charts of `railtab chart` (docs/speed-vs-accuracy.md): the measurement
// of speed_accuracy.hpp, its CSVs and two PNG charts.
#pragma once

#include <filesystem>

#include "speed_accuracy/speed_accuracy.hpp"

namespace railtab {

struct SpeedAccuracyChartFiles {
  std::filesystem::path csv, png;                // speed_accuracy.csv / .png
  std::filesystem::path memory_csv, memory_png;  // table_memory.csv / .png
};

// Measures (options.work_dir is set to DIR/tables, removed afterwards unless keep_tables), writes
// the CSVs (speed_accuracy*.csv, table_memory.csv) and draws the charts into DIR; `files` gets the
// main paths. Returns the measurement for printing.
SpeedAccuracyResult draw_speed_accuracy_charts(const Scene& scene, const std::filesystem::path& dir,
                                               SpeedAccuracyOptions options, SpeedAccuracyChartFiles& files);

}  // namespace railtab
