// SPDX-License-Identifier: Apache-2.0
// A profile through measured points (u, z): a C2 cubic spline, interpolating or smoothing.
#pragma once

#include <string>
#include <vector>

#include "profile/curves/cubic_spline.hpp"
#include "profile/curves/profile.hpp"

namespace railtab {

// Cubic spline z(u) through points with strictly increasing u.
// - smoothing_length == 0: interpolating spline with not-a-knot ends (reproduces any cubic
//   exactly); needs at least 4 points.
// - smoothing_length = L_filt > 0 [m]: smoothing spline (Reinsch), the minimiser of
//     sum_i w_i (z_i - f(u_i))^2 + lambda * integral f''(u)^2 du,  lambda = (L_filt / 2 pi)^4,
//   with trapezoidal weights w_i = (u_{i+1} - u_{i-1}) / 2. The data term then approximates an
//   integral, so the spline acts as a low-pass filter (transfer 1 / (1 + lambda k^4)) with a
//   half-amplitude wavelength L_filt whatever the point spacing, as CONTACT's profile smoothing.
//   The minimiser is a natural spline: zero second derivative at the two end points.
// Evaluation is allocation-free (binary search of the knot interval).
class SplineProfile final : public Profile {
 public:
  SplineProfile(std::string name, ProfileKind kind, std::vector<double> u, std::vector<double> z,
                double smoothing_length = 0.0);

  const std::vector<double>& knots() const { return spline_.x; }        // knot positions u_i [m]
  const std::vector<double>& knot_values() const { return spline_.f; }  // spline values at the knots [m]
  double smoothing_length() const { return smoothing_length_; }    // L_filt, 0 = interpolating [m]

 protected:
  ProfileSample eval_unchecked(double u) const override;

 private:
  detail::CubicSpline spline_;  // z(u): knots, values (smoothed if L_filt > 0), second derivatives
  double smoothing_length_;   // L_filt [m]
};

}  // namespace railtab
