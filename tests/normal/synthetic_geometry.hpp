// SPDX-License-Identifier: Apache-2.0
// Synthetic WheelContactGeometry for the normal-contact tests: a gap band with a prescribed gap
// function (quadratic B s^2 for Hertzian cases), constant A via the rolling radius, and contact
// points placed by hand. Independent of the geometry solver.
#pragma once

#include <cmath>
#include <functional>

#include "geometry/contact_geometry.hpp"

namespace railtab::test {

struct BandSpec {
  double A = 1.0 / (2.0 * 0.46);  // rolling-direction curvature at the points [1/m]
  double step = 0.02e-3;          // band step [m]
  double half_width = 20e-3;      // band from -half_width to +half_width [m]
  double angle = 0.0;             // contact angle, side frame [rad] (constant unless angle_fn)
  std::function<double(double)> gap;       // gap(s) [m]
  std::function<double(double)> B_local;   // lateral relative curvature B(s) [1/m]
  std::function<double(double)> angle_fn;  // optional contact angle(s) [rad]
};

inline ContactPoint make_point(double s, double separation, double A, double B, double angle) {
  ContactPoint p{};
  p.wheel_u = s;
  p.rail_u = s;
  p.y_track = -0.75 - s;
  p.contact_angle = -angle;  // right wheel (side frame angle mirrored to track frame)
  p.contact_angle_side = angle;
  p.rolling_radius = std::cos(angle) / (2.0 * A);
  p.separation = separation;
  p.curvature_a = A;
  p.curvature_b = B;
  p.band_s = s;
  p.status = 0;
  return p;
}

inline WheelContactGeometry make_band(const BandSpec& spec) {
  WheelContactGeometry g;
  g.side = Side::right;
  g.band_step = spec.step;
  const int n = static_cast<int>(std::lround(2.0 * spec.half_width / spec.step));
  g.band.reserve(n + 1);
  for (int i = 0; i <= n; ++i) {
    const double s = -spec.half_width + i * spec.step;
    BandSample b{};
    b.s = s;
    b.rail_u = s;
    b.wheel_u = s;
    b.q = 0.75 + s;
    b.contact_angle_side = spec.angle_fn ? spec.angle_fn(s) : spec.angle;
    b.gap = spec.gap(s);
    b.rolling_radius = std::cos(b.contact_angle_side) / (2.0 * spec.A);
    const double B = spec.B_local(s);
    b.curvature_wheel = B;  // B = (k_w + k_r)/2
    b.curvature_rail = B;
    g.band.push_back(b);
  }
  return g;
}

// One Hertzian point at s = 0: gap B s^2.
inline WheelContactGeometry hertz_band(double A, double B, double step = 0.02e-3,
                                       double half_width = 20e-3) {
  BandSpec spec;
  spec.A = A;
  spec.step = step;
  spec.half_width = half_width;
  spec.gap = [B](double s) { return B * s * s; };
  spec.B_local = [B](double) { return B; };
  WheelContactGeometry g = make_band(spec);
  g.points.push_back(make_point(0.0, 0.0, A, B, 0.0));
  return g;
}

}  // namespace railtab::test
