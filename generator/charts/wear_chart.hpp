// SPDX-License-Identifier: Apache-2.0
// The radial wear distribution across the wheel profile (Enblom and Berg 2008, Figs. 11-13): radial wear depth
// against the wheel-profile coordinate u (+ towards the field side), several named series in one
// chart, e.g. the elliptic model (Hertz + FASTSIM) against STRIPES.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace railtab {

struct WearSeries {
  std::string name;            // key label, e.g. "hertz", "stripes-ab"
  std::vector<double> u;       // wheel-profile u of the bin centres [m]
  std::vector<double> depth;   // radial wear depth [m]
  bool bold = false;           // thick line (the series the chart is about)
};

// Writes PNG (a .png path) and, next to it, the data as NAME.csv (series, name, u_mm, depth_mm)
// and the gnuplot script NAME.gp. Depth is drawn in mm, positive up. Throws railtab::Error for an
// empty series list, mismatched or non-finite vectors, or when writing / gnuplot fails.
void draw_wear_chart(const std::vector<WearSeries>& series, const std::filesystem::path& png,
                     const std::string& title);

}  // namespace railtab
