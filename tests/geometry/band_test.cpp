// SPDX-License-Identifier: Apache-2.0
// Gap band: non-negative at rigid contact, zero at the contacts, quadratic with curvature 2B.
#include <gtest/gtest.h>

#include <cmath>

#include "core/status.hpp"
#include "geometry/contact_geometry.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"
#include "synthetic_profiles.hpp"

namespace railtab {
namespace {

// Cone on a circular crown: the rail normal through the crown centre meets the cone's straight
// generator (tangent to the crown) at R/cos(phi), so gap(s) = R (1/cos(s/R) - 1) exactly.
TEST(Band, ConeOnCircleClosedForm) {
  const double radius = 0.05;
  ProfilePtr wheel = std::make_shared<testing::ConeWheel>(0.05);
  ProfilePtr rail = std::make_shared<testing::CircleRail>(radius, 0.04);
  const ContactGeometrySolver solver(wheel, rail, wheel, rail, TrackGeometry{}, WheelsetGeometry{});
  const WheelContactGeometry g = solver.solve_wheel(Side::right, {0.002, 0.003});
  ASSERT_EQ(g.points.size(), 1u);
  ASSERT_GT(g.band.size(), 100u);
  EXPECT_DOUBLE_EQ(g.band_step, solver.settings().band_step);
  bool has_zero = false;
  for (std::size_t i = 0; i < g.band.size(); ++i) {
    const BandSample& b = g.band[i];
    if (i > 0) {
      EXPECT_NEAR(b.s - g.band[i - 1].s, g.band_step, 1e-12);
    }
    EXPECT_NEAR(b.gap, radius * (1.0 / std::cos(b.s / radius) - 1.0), 1e-10) << b.s;
    EXPECT_NEAR(b.curvature_rail, 1.0 / radius, 1e-9);
    EXPECT_NEAR(b.curvature_wheel, 0.0, 1e-12);
    if (b.s == 0.0) {
      has_zero = true;
      EXPECT_NEAR(b.gap, 0.0, 1e-12);
      EXPECT_NEAR(b.rail_u, g.points[0].rail_u, 1e-9);
      EXPECT_NEAR(b.wheel_u, g.points[0].wheel_u, 1e-9);
      EXPECT_NEAR(b.contact_angle_side, g.points[0].contact_angle_side, 1e-9);
      EXPECT_NEAR(b.rolling_radius, g.points[0].rolling_radius, 1e-9);
    }
    // Contact angle of the crown normal: the primary's angle minus s/R (s grows outward).
    EXPECT_NEAR(b.contact_angle_side, g.points[0].contact_angle_side - b.s / radius, 1e-9);
  }
  EXPECT_TRUE(has_zero);
  // The band stops where the gap passes band_max_gap (before the half width).
  EXPECT_LE(g.band.back().gap, solver.settings().band_max_gap);
  EXPECT_LE(g.band.back().s, solver.settings().band_half_width + 1e-12);
}

class S1002Band : public ::testing::Test {
 protected:
  ContactGeometrySolver solver{make_s1002_profile(), make_uic60_profile(), make_s1002_profile(),
                               make_uic60_profile(), TrackGeometry{}, WheelsetGeometry{}};
};

TEST_F(S1002Band, NonNegativeZeroAtContactsQuadraticNearPrimary) {
  for (double y : {0.003, 0.0, -0.002, -0.005, -0.0055, -0.008}) {
    for (double roll : {0.0, -0.002}) {
      const WheelContactGeometry g = solver.solve_wheel(Side::right, {y, roll});
      ASSERT_FALSE(g.band.empty());
      const double h = g.band_step;
      long zero = -1;
      for (std::size_t i = 0; i < g.band.size(); ++i) {
        EXPECT_GE(g.band[i].gap, -1e-11) << y << " s " << g.band[i].s;
        if (g.band[i].s == 0.0) zero = long(i);
      }
      ASSERT_GE(zero, 1) << y;
      ASSERT_LT(zero + 1, long(g.band.size())) << y;
      EXPECT_NEAR(g.band[zero].gap, 0.0, 1e-12) << y;
      // Symmetric second difference at s = +-h: 2B to the order of the variation of B.
      const double second = (g.band[zero + 1].gap + g.band[zero - 1].gap - 2 * g.band[zero].gap) / (h * h);
      const double b = g.points[0].curvature_b;
      EXPECT_NEAR(second, 2 * b, 0.02 * 2 * b + 1e-3) << y;
      // Secondary contacts: the band passes them at a normal gap of about separation*cos(angle).
      for (std::size_t k = 1; k < g.points.size(); ++k) {
        const ContactPoint& p = g.points[k];
        const long j = zero + std::lround(p.band_s / h);
        ASSERT_GE(j, 0);
        ASSERT_LT(j, long(g.band.size()));
        EXPECT_NEAR(g.band[j].gap, p.separation * std::cos(p.contact_angle_side), 2e-6) << y;
      }
    }
  }
}

}  // namespace
}  // namespace railtab
