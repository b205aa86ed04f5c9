// SPDX-License-Identifier: Apache-2.0
// Profiles that are not a function z(u): a parametric curve through measured points (parametric_profile.hpp).
#include "profile/curves/parametric_profile.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "core/check.hpp"

namespace railtab {
namespace {

// Chord-length knots of the points; checks them before the base class sees their range.
std::vector<double> chord_knots(const std::string& name, const std::vector<double>& y,
                                const std::vector<double>& z, double smoothing_length) {
  RAILTAB_CHECK(y.size() == z.size(), "profile '{}': {} y values but {} z values", name, y.size(),
                z.size());
  RAILTAB_CHECK(y.size() >= 4, "profile '{}': a spline needs at least 4 points, got {}", name, y.size());
  RAILTAB_CHECK(std::isfinite(smoothing_length) && smoothing_length >= 0.0,
                "profile '{}': smoothing length {} m must be finite and >= 0", name, smoothing_length);
  std::vector<double> s(y.size(), 0.0);
  for (std::size_t i = 0; i < y.size(); ++i) {
    RAILTAB_CHECK(std::isfinite(y[i]) && std::isfinite(z[i]),
                  "profile '{}': point {} ({}, {}) is not finite", name, i, y[i], z[i]);
    if (i == 0) continue;
    const double ds = std::hypot(y[i] - y[i - 1], z[i] - z[i - 1]);
    RAILTAB_CHECK(ds > 0.0, "profile '{}': point {} repeats point {}", name, i, i - 1);
    s[i] = s[i - 1] + ds;
  }
  return s;
}

std::pair<double, double> knot_range(const std::vector<double>& y) {
  const auto [lo, hi] = std::minmax_element(y.begin(), y.end());
  return {*lo, *hi};
}

}  // namespace

ParametricProfile::ParametricProfile(std::string name, ProfileKind kind, std::vector<double> y,
                                     std::vector<double> z, double smoothing_length)
    : Profile(name, kind, knot_range(y).first, y.size() >= 2 ? knot_range(y).second : 1.0),
      smoothing_length_(smoothing_length) {
  std::vector<double> s = chord_knots(name, y, z, smoothing_length);
  if (smoothing_length > 0.0) {
    const double lambda = std::pow(smoothing_length / (2.0 * std::numbers::pi), 4);
    y_ = detail::CubicSpline::smooth(s, std::move(y), lambda);
    z_ = detail::CubicSpline::smooth(std::move(s), std::move(z), lambda);
  } else {
    y_ = detail::CubicSpline::interpolate(s, std::move(y));
    z_ = detail::CubicSpline::interpolate(std::move(s), std::move(z));
  }
}

CurveSample ParametricProfile::curve_unchecked(double t) const {
  CurveSample c;
  y_.eval(t, c.y, c.dy, c.d2y);
  z_.eval(t, c.z, c.dz, c.d2z);
  return c;
}

ProfileSample ParametricProfile::eval_unchecked(double u) const {
  const bool highest = kind() == ProfileKind::rail;
  bool found = false;
  CurveSample best{};
  const std::vector<double>& s = y_.x;
  const std::vector<double>& yk = y_.f;
  for (std::size_t i = 0; i + 1 < s.size(); ++i) {
    if ((yk[i] - u) * (yk[i + 1] - u) > 0.0) continue;
    // Bisection on y(t) = u inside the interval (y is monotone there for any sane point spacing).
    double a = s[i], b = s[i + 1];
    const bool rising = yk[i + 1] >= yk[i];
    for (int it = 0; it < 60; ++it) {
      const double m = 0.5 * (a + b);
      double ym, d1, d2;
      y_.eval(m, ym, d1, d2);
      ((ym < u) == rising ? a : b) = m;
    }
    const CurveSample c = curve_unchecked(0.5 * (a + b));
    if (!found || (highest ? c.z > best.z : c.z < best.z)) best = c;
    found = true;
  }
  if (!found) best = curve_unchecked(std::abs(yk.front() - u) < std::abs(yk.back() - u) ? s.front() : s.back());
  const double slope = best.dz / best.dy;
  return {best.z, slope, (best.dy * best.d2z - best.dz * best.d2y) / (best.dy * best.dy * best.dy)};
}

}  // namespace railtab
