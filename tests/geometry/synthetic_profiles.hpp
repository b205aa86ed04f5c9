// SPDX-License-Identifier: Apache-2.0
// Analytic profiles with hand-computable contact geometry, for the geometry tests.
#pragma once

#include <cmath>
#include <memory>
#include <numbers>

#include "geometry/contact_geometry.hpp"
#include "profile/curves/profile.hpp"

namespace railtab::testing {

// Rail crown: circle of radius R through (0, 0), z = sqrt(R^2 - u^2) - R, |u| <= half_width.
class CircleRail : public Profile {
 public:
  CircleRail(double radius, double half_width)
      : Profile("circle rail", ProfileKind::rail, -half_width, half_width), r_(radius) {}
  double radius() const { return r_; }

 protected:
  ProfileSample eval_unchecked(double u) const override {
    const double w = std::sqrt(r_ * r_ - u * u);
    return {w - r_, -u / w, -r_ * r_ / (w * w * w)};
  }

 private:
  double r_;
};

// Cone wheel: radius r0 - c*u, i.e. z = c*u (flangeless).
class ConeWheel : public Profile {
 public:
  explicit ConeWheel(double conicity)
      : Profile("cone wheel", ProfileKind::wheel, -0.07, 0.06), c_(conicity) {}

 protected:
  ProfileSample eval_unchecked(double u) const override { return {c_ * u, c_, 0.0}; }

 private:
  double c_;
};

// Concave circular tread: z = sqrt(R^2 - u^2) - R (hollow towards the rail, k_w = -1/R).
class HollowWheel : public Profile {
 public:
  explicit HollowWheel(double radius)
      : Profile("hollow wheel", ProfileKind::wheel, -0.07, 0.06), r_(radius) {}

 protected:
  ProfileSample eval_unchecked(double u) const override {
    const double w = std::sqrt(r_ * r_ - u * u);
    return {w - r_, -u / w, -r_ * r_ / (w * w * w)};
  }

 private:
  double r_;
};

// Rippled tread: z = a*cos(2 pi u / L); troughs (lowest wheel points) at u = +-L/2, +-3L/2...
class RippleWheel : public Profile {
 public:
  RippleWheel(double amplitude, double wavelength)
      : Profile("ripple wheel", ProfileKind::wheel, -0.07, 0.06), a_(amplitude), l_(wavelength) {}

 protected:
  ProfileSample eval_unchecked(double u) const override {
    const double k = 2.0 * std::numbers::pi / l_;
    return {a_ * std::cos(k * u), -a_ * k * std::sin(k * u), -a_ * k * k * std::cos(k * u)};
  }

 private:
  double a_, l_;
};

// Lateral position of the centre of a CircleRail crown placed in the side frame: the gauge point
// lies on the circle at depth d below its top, whatever the inclination.
inline double circle_rail_centre_q(const TrackGeometry& t, double radius) {
  const double d = t.gauge_measuring_depth;
  return 0.5 * t.gauge + std::sqrt(2.0 * radius * d - d * d);
}

}  // namespace railtab::testing
