// SPDX-License-Identifier: Apache-2.0
// Hertz contact of two identical elastic bodies with relative curvatures A (rolling direction x)
// and B (lateral direction) (FACTS 1.1, 1.3; CONTACT's hzcalc3d gives the same numbers, 1.4).
#pragma once

#include "core/material.hpp"
#include "normal/elliptic.hpp"

namespace railtab {

struct HertzContact {
  double a = 0.0;             // semi-axis along the rolling direction x [m]
  double b = 0.0;             // semi-axis along the lateral direction [m]
  double approach = 0.0;      // normal approach delta [m]
  double normal_force = 0.0;  // [N]
  double p0 = 0.0;            // peak pressure 3N/(2 pi a b) [Pa]
  double area = 0.0;          // pi a b [m2]
  double coef_a = 1.0;        // a = coef_a c (Sichani et al.'s (2014) m0: m or n of FACTS 1.3 by direction) [-]
  double coef_b = 1.0;        // b = coef_b c (Sichani et al.'s (2014) n0) [-]
  HertzShape shape{};         // shape for A_min/A_max (m, n along long/short axis) [-]

  // Semi-elliptic pressure at (x, y) relative to the centre [Pa]; zero outside the ellipse.
  double pressure(double x, double y) const;
};

// A > 0, B > 0 [1/m], normal_force >= 0 [N]; otherwise throws railtab::Error naming the values.
// A zero force gives zero axes, approach and pressure.
HertzContact hertz_for_force(double A, double B, double normal_force, const Material& material);
// approach >= 0 [m].
HertzContact hertz_for_approach(double A, double B, double approach, const Material& material);

// Shape part only (no load): coefficients by direction for curvatures A, B > 0.
struct HertzCoefficients {
  double coef_a;  // Sichani et al. 2014 m0 (x direction) [-]
  double coef_b;  // Sichani et al. 2014 n0 (lateral) [-]
  double r;       // approach coefficient r0 [-]
  double K;       // K(e) [-]
  double E;       // E(e) [-]
};
HertzCoefficients hertz_coefficients(double A, double B);

}  // namespace railtab
