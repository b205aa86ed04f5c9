// SPDX-License-Identifier: Apache-2.0
// The geometry chart (railtab chart-geometry): rolling radius difference and contact angles of the
// rigid wheelset against y, so the flange jump shows.
#pragma once

#include <filesystem>
#include <utility>

#include "scene/scene.hpp"

namespace railtab {

struct GeometryChartOptions {
  double y_min = -0.010;    // [m]
  double y_max = 0.010;     // [m]
  double y_step = 0.05e-3;  // [m]
};

// Writes DIR/geometry_sweep.csv and DIR/geometry.png (DIR is created); returns both paths.
std::pair<std::filesystem::path, std::filesystem::path> draw_geometry_chart(const Scene& scene,
                                                                            const std::filesystem::path& dir,
                                                                            const GeometryChartOptions& options);

}  // namespace railtab
