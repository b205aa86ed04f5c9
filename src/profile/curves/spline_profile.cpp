// SPDX-License-Identifier: Apache-2.0
// A profile through measured points as a C2 cubic spline (spline_profile.hpp).
#include "profile/curves/spline_profile.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "core/check.hpp"
#include "profile/curves/cubic_spline.hpp"

namespace railtab {
namespace {

// Validates the points before the base class sees their range; returns the name.
std::string checked_name(std::string name, const std::vector<double>& u, const std::vector<double>& z,
                         double smoothing_length) {
  RAILTAB_CHECK(u.size() == z.size(), "profile '{}': {} u values but {} z values", name, u.size(),
                z.size());
  RAILTAB_CHECK(u.size() >= 4, "profile '{}': a spline needs at least 4 points, got {}", name,
                u.size());
  RAILTAB_CHECK(std::isfinite(smoothing_length) && smoothing_length >= 0.0,
                "profile '{}': smoothing length {} m must be finite and >= 0", name,
                smoothing_length);
  for (std::size_t i = 0; i < u.size(); ++i) {
    RAILTAB_CHECK(std::isfinite(u[i]) && std::isfinite(z[i]),
                  "profile '{}': point {} ({}, {}) is not finite", name, i, u[i], z[i]);
    RAILTAB_CHECK(i == 0 || u[i] > u[i - 1],
                  "profile '{}': u must increase strictly, point {} has u = {} m after {} m", name,
                  i, u[i], u[i - 1]);
  }
  return name;
}

}  // namespace

SplineProfile::SplineProfile(std::string name, ProfileKind kind, std::vector<double> u,
                             std::vector<double> z, double smoothing_length)
    : Profile(checked_name(std::move(name), u, z, smoothing_length), kind,
              u.size() >= 4 ? u.front() : 0.0, u.size() >= 4 ? u.back() : 1.0),
      spline_(smoothing_length > 0.0
                  ? detail::CubicSpline::smooth(std::move(u), std::move(z),
                                                std::pow(smoothing_length / (2.0 * std::numbers::pi), 4))
                  : detail::CubicSpline::interpolate(std::move(u), std::move(z))),
      smoothing_length_(smoothing_length) {}

ProfileSample SplineProfile::eval_unchecked(double u) const {
  ProfileSample p;
  spline_.eval(u, p.z, p.dz, p.d2z);
  return p;
}

}  // namespace railtab
