// SPDX-License-Identifier: Apache-2.0
// Where a profile's lateral curvature steps inside a cell of the contact band (a radius
// transition: UIC60's R300/R80 and R80/R13, S1002's section joins), located from the band's own
// samples. Shared by STRIPES (cell-averaged curvature) and the geometry's curvature_step flag.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/contact_geometry.hpp"

namespace railtab::detail {

// A curvature difference over a cell counts as a step when it exceeds 1 1/m and 10 % of the
// larger of the two values.
inline bool curvature_differs(double k0, double k1) {
  const double dk = k1 - k0;
  return std::abs(dk) > 1.0 && std::abs(dk) > 0.1 * std::max(std::abs(k0), std::abs(k1));
}

// Fraction t in [0, 1] of the cell [j, j + 1] that carries the rail curvature of sample j, or NaN
// when the rail's curvature does not step there. Located from the change of the contact angle,
// -d angle/ds = k_rail (s the rail arc length); 0.5 where the angles do not locate it.
inline double rail_step_fraction(const WheelContactGeometry& g, int j) {
  const int nb = static_cast<int>(g.band.size());
  if (j < 0 || j + 1 >= nb) return std::numeric_limits<double>::quiet_NaN();
  const double k0 = g.band[j].curvature_rail, k1 = g.band[j + 1].curvature_rail;
  if (!curvature_differs(k0, k1)) return std::numeric_limits<double>::quiet_NaN();
  const double kbar = -(g.band[j + 1].contact_angle_side - g.band[j].contact_angle_side) / g.band_step;
  const double f = (kbar - k1) / (k0 - k1);
  return std::isfinite(f) ? std::clamp(f, 0.0, 1.0) : 0.5;
}

// The same for the wheel's curvature, located from the gap, whose second derivative is k_w + k_r
// (plus a smooth remainder from the finite gap and the inclination): the second difference D_j
// at sample j is the hat-weighted mean of it, so with the step at fraction t of the cell
// (k_w = a before, b after), D_j + D_j+1 - (a + k_r,j) - (b + k_r,j+1) = 2 r + (b - a)(1 - 2t)/2;
// the remainder r is taken from the neighbouring samples, whose hats do not reach the step.
inline double wheel_step_fraction(const WheelContactGeometry& g, int j) {
  const int nb = static_cast<int>(g.band.size());
  if (j < 2 || j + 3 >= nb) return std::numeric_limits<double>::quiet_NaN();
  const double a = g.band[j].curvature_wheel, b = g.band[j + 1].curvature_wheel;
  if (!curvature_differs(a, b)) return std::numeric_limits<double>::quiet_NaN();
  const double h2 = g.band_step * g.band_step;
  auto gap_excess = [&](int i) {  // D_i - (k_w + k_r) at sample i
    const double D = (g.band[i + 1].gap - 2.0 * g.band[i].gap + g.band[i - 1].gap) / h2;
    return D - (g.band[i].curvature_wheel + g.band[i].curvature_rail);
  };
  const double r = 0.5 * (gap_excess(j - 1) + gap_excess(j + 2));
  const double f = 0.5 - (gap_excess(j) + gap_excess(j + 1) - 2.0 * r) / (b - a);
  return std::isfinite(f) ? std::clamp(f, 0.0, 1.0) : 0.5;
}

}  // namespace railtab::detail
