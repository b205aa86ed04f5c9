// SPDX-License-Identifier: Apache-2.0
// Complete elliptic integrals and the Hertz ellipse shape (FACTS 1.2, 1.3).
//
// The Hertz shape depends only on the curvature ratio A_min/A_max. With g = b/a <= 1 the ratio of
// the short to the long semi-axis, the shape equation (FACTS 1.2 (*)) reads
//     A_min/A_max = (K - E) / (E/g^2 - K),   K = K(k), E = E(k), k = sqrt(1 - g^2).
// Both sides are evaluated from the arithmetic-geometric mean started at (1, g): g is the
// complementary modulus, so nothing cancels as k -> 1 (very elongated ellipses) or k -> 0 (circle).
#pragma once

namespace railtab {

struct EllipticKE {
  double K;  // complete elliptic integral of the first kind [-]
  double E;  // complete elliptic integral of the second kind [-]
};

// K and E for the modulus k (not the parameter m = k^2; std::comp_ellint_1/2 use k too, FACTS 1.2),
// 0 <= k < 1. k >= 1 or NaN throws railtab::Error.
EllipticKE complete_elliptic(double k);

// K and E from the complementary modulus kc = sqrt(1 - k^2), 0 < kc <= 1: accurate near k -> 1.
EllipticKE complete_elliptic_complementary(double kc);

// Hertz ellipse shape for a curvature ratio A_min/A_max in (0, 1] (FACTS 1.3, m along the long axis).
struct HertzShape {
  double ratio;  // A_min/A_max [-]
  double g;      // short/long semi-axis ratio b/a <= 1 [-]
  double e;      // eccentricity = modulus k = sqrt(1 - g^2) [-]
  double K;      // K(e) [-]
  double E;      // E(e) [-]
  double m;      // long semi-axis = m c [-]
  double n;      // short semi-axis = n c [-]
  double r;      // approach = r (A + B) c^2 [-]
};

// Solves the shape equation by a bracketed root find in ln g (relative tolerance 1e-13 on g).
// ratio outside (0, 1] or NaN throws railtab::Error; ratio < 1e-12 is clamped to 1e-12.
HertzShape hertz_shape(double ratio);

// The shape ratio (K - E)/(E/g^2 - K) for a given g in (0, 1] (the left side of the equation).
double hertz_curvature_ratio(double g);

// Fast g = b/a for a curvature ratio in (0, 1]: monotone cubic Hermite interpolation of ln g over
// ln ratio on a fine grid built once from hertz_shape (relative error below 1e-9, checked in
// elliptic_test); used per strip in the semi-Hertzian models, where thousands of local shapes
// per solve make the root find the bottleneck. Outside the grid it calls hertz_shape.
double hertz_axis_ratio_fast(double ratio);

}  // namespace railtab
