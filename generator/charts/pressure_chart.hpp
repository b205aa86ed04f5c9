// SPDX-License-Identifier: Apache-2.0
// The pressure comparison of Sichani et al. 2014: peak pressure along the strip centre lines of one wheel's
// patch, every normal model and negative-curvature treatment side by side.
#pragma once

#include <filesystem>

#include "scene/scene.hpp"

namespace railtab {

struct PressureChartOptions {
  double y = 0.0;          // wheelset lateral displacement [m]
  double load = 78.5e3;    // vertical wheel load [N]
  Side side = Side::right; // the seed's case is the right wheel
  double reference_max_pressure = 0.0;  // half-space p_max to draw, 0 = none [Pa]
};

// Writes DIR/pressure.csv (variant, s_mm, rail_y_mm, pressure_MPa per strip) and DIR/pressure.png;
// returns the peak pressure of each variant in the CSV order. Throws railtab::Error on failure.
void draw_pressure_chart(const Scene& scene, const std::filesystem::path& out_dir,
                         const PressureChartOptions& options);

}  // namespace railtab
