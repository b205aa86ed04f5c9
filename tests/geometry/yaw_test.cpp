// SPDX-License-Identifier: Apache-2.0
// Contact geometry of a yawed wheelset: the closed-form flange lead and contact angle of a yawed
// cone, the lead of every point of S1002 / UIC60 against its own wheel slope, the mirror
// (y, roll, yaw) -> (-y, -roll, -yaw) between the wheels, continuity in yaw and the limit
// yaw -> 0 (the yawed path meets the yaw-free one).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/check.hpp"
#include "geometry/contact_geometry.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"
#include "synthetic_profiles.hpp"

namespace railtab::yaw_test {
namespace {

using testing::CircleRail;
using testing::ConeWheel;

constexpr double kR0 = 0.46;
constexpr double kQ0 = 0.68 + 0.07;  // back_to_back/2 - flange_back_position

ContactGeometrySolver s1002_uic60() {
  ProfilePtr w = make_s1002_profile();
  ProfilePtr r = make_uic60_profile();
  return ContactGeometrySolver(w, r, w, r, TrackGeometry{}, WheelsetGeometry{});
}

// A cone z = c u (tan(delta) = c, the wheel's own contact angle) on a circular crown, no roll.
// The contact lies where the wheel normal has no component along the track: on the circle
// through profile point u, at the angle tau from its lowest point with
//   sin(tau) = tan(delta) tan(psi_s)                       (psi_s = sigma * yaw),
// so the contact leads the wheel's axle plane by x_wheel = r sin(tau) = r tan(delta) tan(psi_s)
// (along the wheel's rolling direction: the flange lead; derivation in docs/conventions.md "Yaw")
// and lies at track x = -a sin(psi_s) + r sin(tau) cos(psi_s)
// (a = Q0 + u, the circle's distance along the axle). The normal there leans by
//   tan(g) = tan(delta) / (cos(psi_s) cos(tau)),
// so the contact on the crown (centre Qc, radius R) is at q = Qc - R sin(g), and u follows from
//   q = sigma y + a cos(psi_s) + r sin(tau) sin(psi_s).
void expect_yawed_cone(double c, Side side, double y, double yaw) {
  const double rail_r = 0.05;
  ProfilePtr wheel = std::make_shared<ConeWheel>(c);
  ProfilePtr rail = std::make_shared<CircleRail>(rail_r, 0.048);
  const ContactGeometrySolver solver(wheel, rail, wheel, rail, TrackGeometry{}, WheelsetGeometry{});
  WheelsetState state;
  state.y = y;
  state.yaw = yaw;
  const WheelContactGeometry g = solver.solve_wheel(side, state);
  ASSERT_EQ(g.points.size(), 1u);
  const ContactPoint& p = g.points[0];
  const double sigma = outward_sign(side);
  const double psi = sigma * yaw;
  const double st = c * std::tan(psi), ct = std::sqrt(1.0 - st * st);
  const double gamma = std::atan(c / (std::cos(psi) * ct));
  const double q = testing::circle_rail_centre_q(solver.track(), rail_r) - rail_r * std::sin(gamma);
  const double u = (q - sigma * y - kQ0 * std::cos(psi) - kR0 * st * std::sin(psi)) /
                   (std::cos(psi) - c * st * std::sin(psi));
  const double r = kR0 - c * u;
  const double a = kQ0 + u;
  EXPECT_NEAR(p.contact_angle_side, gamma, 1e-11) << "c " << c << " yaw " << yaw;
  EXPECT_NEAR(p.wheel_u, u, 1e-9);
  EXPECT_NEAR(p.rolling_radius, r, 1e-9);
  EXPECT_NEAR(p.y_track, sigma * q, 1e-10);
  EXPECT_NEAR(p.x_wheel, r * c * std::tan(psi), 1e-9);
  EXPECT_NEAR(p.x_track, -a * std::sin(psi) + r * st * std::cos(psi), 1e-9);
  EXPECT_EQ(g.wheel_yaw, psi);
}

TEST(YawGeometry, ClosedFormLeadOfAYawedCone) {
  for (const double yaw : {0.024, -0.024, 0.005, 0.1}) {
    for (const Side side : {Side::left, Side::right}) {
      expect_yawed_cone(0.05, side, 0.002, yaw);  // tread cone, lead 0.05 r psi
      expect_yawed_cone(2.0, side, 0.0, yaw);     // flange-steep cone (63 deg): lead 2 r psi
    }
  }
  // The magnitude engineers quote: a 63 deg flange 0.55 m in radius leads by 26 mm at 24 mrad.
  const ContactGeometrySolver steep(std::make_shared<ConeWheel>(2.0), std::make_shared<CircleRail>(0.05, 0.048),
                                    std::make_shared<ConeWheel>(2.0), std::make_shared<CircleRail>(0.05, 0.048),
                                    TrackGeometry{}, WheelsetGeometry{});
  WheelsetState s;
  s.yaw = 0.024;
  const ContactPoint p = steep.solve_wheel(Side::left, s).points[0];
  EXPECT_NEAR(p.x_wheel, 0.0264, 5e-4);
}

// For any profile and roll the lead at a point follows from the wheel's own slope there:
// x_wheel = r z'(u) tan(psi_s) (roll is about the track's x axis: it does not enter); without
// roll the track-frame normal leans by tan(g) = z' / (cos psi cos tau).
TEST(YawGeometry, LeadOfEveryPointFollowsItsWheelSlope) {
  const ContactGeometrySolver solver = s1002_uic60();
  const ProfilePtr wheel = make_s1002_profile();
  int flange = 0, points = 0;
  for (const double y : {-0.004, 0.0, 0.005, 0.0065, 0.009})
    for (const double yaw : {0.012, -0.024})
      for (const double roll : {0.0, -0.011}) {
        for (const Side side : {Side::left, Side::right}) {
          WheelsetState s;
          s.y = y;
          s.yaw = yaw;
          s.roll = roll;
          const WheelContactGeometry g = solver.solve_wheel(side, s);
          for (const ContactPoint& p : g.points) {
            const double slope = wheel->curve(p.wheel_t).dz / wheel->curve(p.wheel_t).dy;
            const double psi = outward_sign(side) * yaw;
            const double st = slope * std::tan(psi);
            EXPECT_NEAR(p.x_wheel, p.rolling_radius * st, 1e-9) << "y " << y << " yaw " << yaw;
            if (roll == 0.0) {
              EXPECT_NEAR(std::tan(p.contact_angle_side), slope / (std::cos(psi) * std::sqrt(1 - st * st)),
                          1e-6 * (1 + slope * slope));
            }
            flange += (p.status & status::kFlangeContact) != 0;
            ++points;
          }
        }
      }
  EXPECT_GE(flange, 8);  // flange points are among them
  EXPECT_GT(points, 40);
}

void expect_mirror(const WheelContactGeometry& a, const WheelContactGeometry& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  EXPECT_EQ(a.wheel_drop, b.wheel_drop);
  EXPECT_EQ(a.wheel_yaw, b.wheel_yaw);
  for (size_t k = 0; k < a.points.size(); ++k) {
    const ContactPoint &p = a.points[k], &q = b.points[k];
    EXPECT_EQ(p.y_track, -q.y_track);
    EXPECT_EQ(p.contact_angle, -q.contact_angle);
    EXPECT_EQ(p.contact_angle_side, q.contact_angle_side);
    EXPECT_EQ(p.x_track, q.x_track);  // x is not mirrored
    EXPECT_EQ(p.x_wheel, q.x_wheel);
    EXPECT_EQ(p.rolling_radius, q.rolling_radius);
    EXPECT_EQ(p.curvature_a, q.curvature_a);
    EXPECT_EQ(p.curvature_b, q.curvature_b);
  }
  ASSERT_EQ(a.band.size(), b.band.size());
  for (size_t k = 0; k < a.band.size(); ++k) {
    EXPECT_EQ(a.band[k].gap, b.band[k].gap);
    EXPECT_EQ(a.band[k].x_track, b.band[k].x_track);
  }
}

TEST(YawGeometry, MirrorSwapsTheWheels) {
  const ContactGeometrySolver solver = s1002_uic60();
  for (const double y : {-0.007, 0.0, 0.003, 0.0085})
    for (const double roll : {0.0, 0.003})
      for (const double yaw : {0.0, 0.01, -0.02}) {
        WheelsetState s{y, roll, yaw}, m{-y, -roll, -yaw};
        expect_mirror(solver.solve_wheel(Side::left, s), solver.solve_wheel(Side::right, m));
        expect_mirror(solver.solve_wheel(Side::right, s), solver.solve_wheel(Side::left, m));
      }
}

struct Primary {
  double wheel_u, rail_u, angle, radius, x_track, x_wheel, curvature_a;
};

Primary primary(const ContactGeometrySolver& solver, Side side, double y, double yaw) {
  WheelsetState s;
  s.y = y;
  s.yaw = yaw;
  const WheelContactGeometry g = solver.solve_wheel(side, s);  // kept: p refers into it
  const ContactPoint& p = g.points.front();
  return {p.wheel_u, p.rail_u, p.contact_angle, p.rolling_radius, p.x_track, p.x_wheel, p.curvature_a};
}

// Continuity: through yaw = 0 (from both sides, down to 1e-12 rad: the yawed path meets the
// yaw-free one) and in steps of 1 mrad to 30 mrad: no output jumps (a step changes an output by at
// most 3 times its median change over the sweep, plus round-off).
TEST(YawGeometry, ContinuousInYaw) {
  const ContactGeometrySolver solver = s1002_uic60();
  for (const double y : {0.0, 0.003, 0.009})
    for (const Side side : {Side::left, Side::right}) {
      const Primary p0 = primary(solver, side, y, 0.0);
      for (const double tiny : {1e-12, -1e-12, 1e-9}) {
        const Primary p = primary(solver, side, y, tiny);
        EXPECT_NEAR(p.wheel_u, p0.wheel_u, 1e-9);
        EXPECT_NEAR(p.angle, p0.angle, 1e-9);
        EXPECT_NEAR(p.radius, p0.radius, 1e-10);
        EXPECT_NEAR(p.x_track, 0.0, 1e-8);
        EXPECT_NEAR(p.curvature_a, p0.curvature_a, 1e-8);
      }
      std::vector<Primary> sweep;
      for (int k = -30; k <= 30; ++k) sweep.push_back(primary(solver, side, y, 1e-3 * k));
      auto check = [&](double Primary::*f, const char* name) {
        std::vector<double> steps;
        for (size_t k = 1; k < sweep.size(); ++k) steps.push_back(std::abs(sweep[k].*f - sweep[k - 1].*f));
        std::vector<double> sorted = steps;
        std::sort(sorted.begin(), sorted.end());
        const double median = sorted[sorted.size() / 2];
        for (size_t k = 0; k < steps.size(); ++k)
          EXPECT_LE(steps[k], 3.0 * median + 1e-12)
              << name << " jumps at yaw " << 1e-3 * (static_cast<double>(k) - 29.5) << " (y " << y << ", "
              << to_string(side) << ")";
      };
      check(&Primary::x_track, "x_track");
      check(&Primary::x_wheel, "x_wheel");
      check(&Primary::angle, "contact angle");
    }
}

TEST(YawGeometry, BadYawIsRefused) {
  const ContactGeometrySolver solver = s1002_uic60();
  WheelsetState s;
  s.yaw = std::nan("");
  EXPECT_THROW(solver.solve_wheel(Side::left, s), Error);
  s.yaw = 0.3;
  EXPECT_THROW(solver.solve_wheel(Side::left, s), Error);
}

}  // namespace
}  // namespace railtab::yaw_test
