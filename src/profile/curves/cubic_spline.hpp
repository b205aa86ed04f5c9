// SPDX-License-Identifier: Apache-2.0
// A cubic spline f(x) through points with strictly increasing x: interpolating (not-a-knot) or
// smoothing (Reinsch). Shared by SplineProfile (z(u)) and ParametricProfile (y(s), z(s)).
#pragma once

#include <vector>

namespace railtab::detail {

struct CubicSpline {
  std::vector<double> x;    // knots, strictly increasing
  std::vector<double> f;    // values at the knots (smoothed when built by smooth())
  std::vector<double> d2f;  // second derivatives at the knots

  // Not-a-knot interpolating spline (reproduces any cubic); at least 4 points.
  static CubicSpline interpolate(std::vector<double> x, std::vector<double> f);
  // Smoothing spline minimising sum w_i (f_i - s(x_i))^2 + lambda * integral s''^2, trapezoidal
  // weights w_i (docs/profiles.md); natural ends.
  static CubicSpline smooth(std::vector<double> x, std::vector<double> f, double lambda);

  // Value, first and second derivative at x inside [x.front(), x.back()] (binary search).
  void eval(double at, double& value, double& d1, double& d2) const;
};

}  // namespace railtab::detail
