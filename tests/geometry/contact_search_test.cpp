// SPDX-License-Identifier: Apache-2.0
// Contact search: two-point contact found and kept, separations exact, S1002 two-point range and
// the jump into flange contact.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/check.hpp"
#include "core/status.hpp"
#include "geometry/contact_geometry.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"
#include "synthetic_profiles.hpp"

namespace railtab {
namespace {

constexpr double kRailR = 0.05;
constexpr double kWave = 0.02;
constexpr double kAmplitude = 0.5e-3;
const double kTroughRadius = 1.0 / (kAmplitude * std::pow(2.0 * 3.14159265358979323846 / kWave, 2));

// Rippled wheel (troughs at u = +-L/2) on a circular crown, no inclination: centred on the
// crown the two troughs touch at once; shifted by d, the far trough lifts by about
// L d / (rho + R), rho = 1/(a k^2) the trough radius (parabolic approximation of both curves).
class RippleOnCrown : public ::testing::Test {
 protected:
  ProfilePtr wheel = std::make_shared<testing::RippleWheel>(kAmplitude, kWave);
  ProfilePtr rail = std::make_shared<testing::CircleRail>(kRailR, 0.04);
  TrackGeometry track = [] {
    TrackGeometry t;
    t.rail_inclination = 0.0;
    return t;
  }();
  ContactGeometrySolver solver{wheel, rail, wheel, rail, track, WheelsetGeometry{}};
  double y_centred = testing::circle_rail_centre_q(track, kRailR) - 0.75;

  // Vertical gap of the placed wheel (no roll) at wheel u, from the closed forms.
  double gap_at(const WheelContactGeometry& g, double y, double u) const {
    const double q = y + 0.75 + u;
    const double dq = q - testing::circle_rail_centre_q(track, kRailR);
    const double z_rail = std::sqrt(kRailR * kRailR - dq * dq) - kRailR;
    return g.wheel_drop + wheel->eval(u).z - z_rail;
  }
};

TEST_F(RippleOnCrown, SymmetricTwoPointContact) {
  const WheelContactGeometry g = solver.solve_wheel(Side::left, {y_centred, 0.0});
  ASSERT_EQ(g.points.size(), 2u);
  EXPECT_NE(g.status & status::kTwoPoint, 0u);
  EXPECT_NEAR(g.points[0].separation, 0.0, 1e-12);
  EXPECT_NEAR(g.points[1].separation, 0.0, 1e-12);
  EXPECT_NEAR(g.points[0].wheel_u + g.points[1].wheel_u, 0.0, 1e-9);
  EXPECT_NEAR(g.points[0].contact_angle_side, -g.points[1].contact_angle_side, 1e-9);
}

TEST_F(RippleOnCrown, ShiftedSecondPointKeepsItsSeparation) {
  const double d = 0.1e-3;
  const double y = y_centred + d;
  const WheelContactGeometry g = solver.solve_wheel(Side::left, {y, 0.0});
  ASSERT_EQ(g.points.size(), 2u);
  EXPECT_EQ(g.points[0].separation, 0.0);
  EXPECT_GT(g.points[1].separation, 0.0);
  const double approx = kWave * d / (kTroughRadius + kRailR);
  EXPECT_NEAR(g.points[1].separation, approx, 0.1 * approx);
  for (const ContactPoint& p : g.points) {
    EXPECT_NEAR(gap_at(g, y, p.wheel_u), p.separation, 1e-12);
    // Stationary gap: the wheel slope equals the rail slope (same tangent angle).
    EXPECT_NEAR(std::atan(wheel->eval(p.wheel_u).dz), p.contact_angle_side, 1e-9);
    // and it is a minimum: the gap grows on both sides.
    EXPECT_GT(gap_at(g, y, p.wheel_u + 1e-5), p.separation);
    EXPECT_GT(gap_at(g, y, p.wheel_u - 1e-5), p.separation);
  }
  // Beyond max_separation the second point is dropped.
  const WheelContactGeometry far = solver.solve_wheel(Side::left, {y_centred + 1.3 * 0.5e-3 * (kTroughRadius + kRailR) / kWave, 0.0});
  EXPECT_EQ(far.points.size(), 1u);
  EXPECT_EQ(far.status & status::kTwoPoint, 0u);
}

class S1002Search : public ::testing::Test {
 protected:
  ContactGeometrySolver solver{make_s1002_profile(), make_uic60_profile(), make_s1002_profile(),
                               make_uic60_profile(), TrackGeometry{}, WheelsetGeometry{}};
};

// Right wheel at y = -5 mm: tread plus flange root, both reported; the left wheel mirrors it.
TEST_F(S1002Search, TwoPointNearFlangeRoot) {
  const WheelContactGeometry g = solver.solve_wheel(Side::right, {-5e-3, 0.0});
  ASSERT_EQ(g.points.size(), 2u);
  EXPECT_NE(g.status & status::kTwoPoint, 0u);
  EXPECT_EQ(g.points[0].separation, 0.0);
  EXPECT_GT(g.points[1].separation, 1e-7);
  EXPECT_LT(g.points[1].separation, 0.5e-3);
  EXPECT_LT(g.points[0].contact_angle_side, 0.2);  // tread
  EXPECT_GT(g.points[1].contact_angle_side, 0.25);  // flange root
  EXPECT_LT(g.points[1].wheel_u, g.points[0].wheel_u);
  const WheelContactGeometry left = solver.solve_wheel(Side::left, {5e-3, 0.0});
  ASSERT_EQ(left.points.size(), 2u);
  EXPECT_EQ(left.points[1].separation, g.points[1].separation);
  EXPECT_EQ(left.points[1].contact_angle, -g.points[1].contact_angle);
}

// The primary contact moves from tread to flange root with the shift: at some offset the two
// minima swap; step through y in 0.05 mm and check the swap and the later jump to the flank.
TEST_F(S1002Search, JumpIntoFlangeContact) {
  double prev = solver.solve_wheel(Side::right, {-6.0e-3, 0.0}).points[0].contact_angle_side;
  EXPECT_LT(prev, 0.45);
  int jumps = 0;
  double jump_at = 0.0;
  for (int k = 1; k <= 20; ++k) {
    const double dy = 6.0e-3 + 0.05e-3 * k;
    const ContactPoint p = solver.solve_wheel(Side::right, {-dy, 0.0}).points[0];
    if (p.contact_angle_side - prev > 0.4) {
      ++jumps;
      jump_at = dy;
      EXPECT_GT(p.contact_angle_side, 1.1);
      EXPECT_LT(p.contact_angle_side, 1.25);
      EXPECT_NE(p.status & status::kFlangeContact, 0u);
    }
    prev = p.contact_angle_side;
  }
  EXPECT_EQ(jumps, 1);
  EXPECT_NEAR(jump_at, 6.65e-3, 1e-9);  // measured: between 6.60 and 6.65 mm
}

// Far outside the operating range the solver either returns finite results or throws
// railtab::Error; it never crashes or returns NaN.
TEST_F(S1002Search, WideSweepFiniteOrError) {
  int errors = 0;
  for (int i = 0; i <= 60; ++i) {
    for (int j = 0; j <= 8; ++j) {
      const WheelsetState st{-30e-3 + 1e-3 * i, -0.04 + 0.01 * j};
      for (Side side : {Side::left, Side::right}) {
        try {
          const WheelContactGeometry g = solver.solve_wheel(side, st);
          ASSERT_FALSE(g.points.empty());
          EXPECT_TRUE(std::isfinite(g.wheel_drop));
          for (const ContactPoint& p : g.points) {
            EXPECT_TRUE(std::isfinite(p.contact_angle) && std::isfinite(p.rolling_radius) &&
                        std::isfinite(p.curvature_a) && std::isfinite(p.curvature_b))
                << st.y << " " << st.roll;
          }
          for (const BandSample& b : g.band) EXPECT_TRUE(std::isfinite(b.gap));
        } catch (const Error&) {
          ++errors;
        }
      }
    }
  }
  std::printf("wide sweep: %d of %d states rejected with railtab::Error\n", errors, 61 * 9 * 2);
}

}  // namespace
}  // namespace railtab
