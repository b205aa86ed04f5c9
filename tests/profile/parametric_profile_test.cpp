// SPDX-License-Identifier: Apache-2.0
// ParametricProfile: a curve through points in their order, parametrised by chord length, that
// may overhang. Checked on a circle (which turns back on itself laterally) and on the
// single-valued view eval(u) that wheel and rail callers get.
#include "profile/curves/parametric_profile.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "error_message.hpp"

namespace railtab {
namespace {

// 225 degrees of a circle of radius 10 mm centred at (0, -10 mm): from below on the left
// (an overhang: y first decreases) over the top to the right side.
ParametricProfile circle_profile(ProfileKind kind, int n = 121) {
  std::vector<double> y, z;
  for (int i = 0; i < n; ++i) {
    const double a = -0.75 * std::numbers::pi + 1.25 * std::numbers::pi * i / (n - 1);  // from -135 deg
    y.push_back(0.010 * std::sin(a));
    z.push_back(-0.010 + 0.010 * std::cos(a));
  }
  return ParametricProfile("circle", kind, y, z);
}

TEST(ParametricProfile, CircleWithOverhangPositionsTangentsCurvature) {
  const ParametricProfile p = circle_profile(ProfileKind::rail);
  EXPECT_TRUE(p.parametric());
  EXPECT_NEAR(p.u_min(), -0.010, 1e-6);  // the leftmost point lies inside the curve, not at an end
  for (int k = 1; k < 20; ++k) {
    const double t = p.t_min() + (p.t_max() - p.t_min()) * k / 20.0;
    const CurveSample c = p.curve(t);
    EXPECT_NEAR(std::hypot(c.y, c.z + 0.010), 0.010, 2e-9) << "t = " << t;    // on the circle
    EXPECT_NEAR(std::hypot(c.dy, c.dz), 1.0, 2e-4) << "t = " << t;            // chord ~ arc length
    EXPECT_NEAR(c.y * c.dy + (c.z + 0.010) * c.dz, 0.0, 2e-6) << "t = " << t;  // tangent _|_ radius
    const double k_signed = (c.dy * c.d2z - c.dz * c.d2y) / std::pow(c.dy * c.dy + c.dz * c.dz, 1.5);
    EXPECT_NEAR(k_signed, -100.0, 0.5) << "t = " << t;  // clockwise: curvature -1/R
  }
}

TEST(ParametricProfile, SingleValuedViewFacesTheOtherBody) {
  // At u = -8 mm the circle is crossed twice (z = -4 mm and z = -16 mm): a rail sees the upper
  // point, a wheel (same points) the lower one.
  const double u = -0.008;
  const double upper = -0.010 + std::sqrt(0.010 * 0.010 - u * u);
  const double lower = -0.010 - std::sqrt(0.010 * 0.010 - u * u);
  EXPECT_NEAR(circle_profile(ProfileKind::rail).eval(u).z, upper, 1e-8);
  EXPECT_NEAR(circle_profile(ProfileKind::wheel).eval(u).z, lower, 1e-8);
  EXPECT_NEAR(circle_profile(ProfileKind::rail).eval(u).dz, -u / (upper + 0.010), 1e-4);
}

TEST(ParametricProfile, RejectsRepeatedAndNonFinitePoints) {
  const std::vector<double> y = {0.0, 0.001, 0.001, 0.002, 0.003};
  const std::vector<double> z = {0.0, 0.0, 0.0, 0.001, 0.0};
  EXPECT_NE(test::error_message([&] { ParametricProfile("p", ProfileKind::rail, y, z); }).find("repeats point 1"),
            std::string::npos);
  std::vector<double> bad = {0.0, 0.001, NAN, 0.002, 0.003};
  EXPECT_NE(test::error_message([&] { ParametricProfile("p", ProfileKind::rail, bad, z); }).find("not finite"),
            std::string::npos);
}

}  // namespace
}  // namespace railtab
