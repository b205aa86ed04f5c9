// SPDX-License-Identifier: Apache-2.0
// ContactGeometrySolver on analytic profiles: closed-form contact position, angle, rolling radius,
// A and B; mirror symmetry of the wheelset; input errors.
#include "geometry/contact_geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/check.hpp"
#include "core/status.hpp"
#include "synthetic_profiles.hpp"

namespace railtab::contact_geometry_test {  // own namespace: unity builds compile several test files as one
namespace {

using testing::CircleRail;
using testing::ConeWheel;
using testing::HollowWheel;

constexpr double kRailR = 0.05;
constexpr double kR0 = 0.46;

ContactGeometrySolver make_solver(ProfilePtr wheel, double inclination = 1.0 / 40.0) {
  ProfilePtr rail = std::make_shared<CircleRail>(kRailR, 0.04);
  TrackGeometry track;
  track.rail_inclination = inclination;
  return ContactGeometrySolver(wheel, rail, wheel, rail, track, WheelsetGeometry{});
}

// Cone (conicity c) rolled by theta on a circular crown: the contact normal is the cone's normal,
// gamma = theta + atan(c), at q = Qc - R sin(gamma) on the crown.
void expect_cone_closed_form(Side side, double y, double roll, double inclination) {
  const double c = 0.05;
  const ContactGeometrySolver solver = make_solver(std::make_shared<ConeWheel>(c), inclination);
  const WheelContactGeometry g = solver.solve_wheel(side, {y, roll});
  ASSERT_EQ(g.points.size(), 1u);
  const ContactPoint& p = g.points[0];
  const double sigma = outward_sign(side);
  const double theta = sigma * roll;
  const double gamma = theta + std::atan(c);
  const double qc = testing::circle_rail_centre_q(solver.track(), kRailR);
  const double q = qc - kRailR * std::sin(gamma);
  const double z = -kRailR + kRailR * std::cos(gamma);
  const double q0 = 0.68 + 0.07;
  // Wheel point: Q(u) = sigma*y + cos(theta)(Q0 + u) - sin(theta)(c u - r0).
  const double u_w = (q - sigma * y - std::cos(theta) * q0 - std::sin(theta) * kR0) /
                     (std::cos(theta) - c * std::sin(theta));
  const double r = kR0 - c * u_w;
  EXPECT_NEAR(p.contact_angle_side, gamma, 1e-12);
  EXPECT_NEAR(p.contact_angle, sigma * gamma, 1e-12);
  EXPECT_NEAR(p.rail_u, -kRailR * std::sin(gamma - std::atan(inclination)), 1e-10);
  EXPECT_NEAR(p.y_track, sigma * q, 1e-10);
  EXPECT_NEAR(p.z_track, z, 1e-10);
  EXPECT_NEAR(p.wheel_u, u_w, 1e-9);
  EXPECT_NEAR(p.rolling_radius, r, 1e-10);
  EXPECT_NEAR(p.curvature_a, 0.5 * std::cos(std::atan(c)) / r, 1e-12);
  EXPECT_NEAR(p.curvature_b, 0.5 / kRailR, 1e-9);
  EXPECT_EQ(p.separation, 0.0);
  EXPECT_EQ(p.status, 0u);
  EXPECT_EQ(g.status, 0u);
  // The axle centre sits at r0 + drop; the cone's contact point is below it by the geometry.
  const double axle_z = std::sin(theta) * (q0 + u_w) + std::cos(theta) * (c * u_w - kR0);
  EXPECT_NEAR(kR0 + g.wheel_drop + axle_z, z, 1e-10);
}

TEST(ContactGeometry, ConeOnCircularCrownNoRoll) {
  expect_cone_closed_form(Side::left, 0.0, 0.0, 0.0);
  expect_cone_closed_form(Side::left, 0.004, 0.0, 1.0 / 40.0);
  expect_cone_closed_form(Side::right, -0.003, 0.0, 1.0 / 40.0);
}

TEST(ContactGeometry, ConeOnCircularCrownWithRoll) {
  expect_cone_closed_form(Side::left, 0.002, 0.01, 1.0 / 40.0);
  expect_cone_closed_form(Side::right, 0.002, 0.01, 1.0 / 40.0);
  expect_cone_closed_form(Side::right, -0.005, -0.02, 1.0 / 20.0);
}

// Hollow (concave) tread of radius Rw on a crown of radius R < Rw: internal tangency on the line
// of the centres, sin(gamma) = offset / (Rw - R), B = (1/R - 1/Rw)/2.
TEST(ContactGeometry, HollowTreadOnCircularCrown) {
  const double rw = 0.08;
  const ContactGeometrySolver solver = make_solver(std::make_shared<HollowWheel>(rw));
  for (double y : {-0.006, 0.0, 0.005}) {
    const WheelContactGeometry g = solver.solve_wheel(Side::left, {y, 0.0});
    ASSERT_EQ(g.points.size(), 1u) << y;
    const ContactPoint& p = g.points[0];
    const double offset = y + 0.75 - testing::circle_rail_centre_q(solver.track(), kRailR);
    const double gamma = std::asin(offset / (rw - kRailR));
    const double u_w = -rw * std::sin(gamma);
    const double r = kR0 - (std::sqrt(rw * rw - u_w * u_w) - rw);
    EXPECT_NEAR(p.contact_angle_side, gamma, 1e-9) << y;
    EXPECT_NEAR(p.wheel_u, u_w, 1e-9) << y;
    EXPECT_NEAR(p.rolling_radius, r, 1e-10) << y;
    EXPECT_NEAR(p.curvature_a, 0.5 * std::cos(gamma) / r, 1e-12) << y;
    EXPECT_NEAR(p.curvature_b, 0.5 * (1.0 / kRailR - 1.0 / rw), 1e-8) << y;
    EXPECT_EQ(p.status & status::kNonHertzian, 0u);
  }
}

TEST(ContactGeometry, MirrorSymmetrySwapsWheels) {
  const ContactGeometrySolver solver = make_solver(std::make_shared<HollowWheel>(0.08));
  for (const WheelsetState s : {WheelsetState{0.003, 0.002}, WheelsetState{-0.0045, 0.0},
                                WheelsetState{0.001, -0.004}}) {
    const WheelsetContactGeometry a = solver.solve(s);
    const WheelsetContactGeometry b = solver.solve({-s.y, -s.roll});
    for (int w = 0; w < 2; ++w) {
      const ContactPoint& pa = a.wheels[w].points.at(0);
      const ContactPoint& pb = b.wheels[1 - w].points.at(0);
      EXPECT_EQ(pa.contact_angle_side, pb.contact_angle_side);
      EXPECT_EQ(pa.contact_angle, -pb.contact_angle);
      EXPECT_EQ(pa.y_track, -pb.y_track);
      EXPECT_EQ(pa.rolling_radius, pb.rolling_radius);
      EXPECT_EQ(pa.curvature_a, pb.curvature_a);
      EXPECT_EQ(pa.curvature_b, pb.curvature_b);
      EXPECT_EQ(a.wheels[w].wheel_drop, b.wheels[1 - w].wheel_drop);
      EXPECT_EQ(a.wheels[w].band.size(), b.wheels[1 - w].band.size());
    }
    EXPECT_EQ(a.rolling_radius_difference, -b.rolling_radius_difference);
    if (s.y != 0.0) {
      EXPECT_NE(a.rolling_radius_difference, 0.0);
    }
  }
}

TEST(ContactGeometry, RollingRadiusDifferenceSign) {
  const ContactGeometrySolver solver = make_solver(std::make_shared<ConeWheel>(0.05));
  // Shift left: the left wheel runs on a larger radius of the cone.
  EXPECT_GT(solver.solve({0.003, 0.0}).rolling_radius_difference, 0.0);
  EXPECT_LT(solver.solve({-0.003, 0.0}).rolling_radius_difference, 0.0);
  // A cone of conicity c gives r_L - r_R = 2 c y exactly with no roll.
  EXPECT_NEAR(solver.solve({0.003, 0.0}).rolling_radius_difference, 2 * 0.05 * 0.003, 1e-12);
}

TEST(ContactGeometry, NonFiniteInputThrowsNamingIt) {
  const ContactGeometrySolver solver = make_solver(std::make_shared<ConeWheel>(0.05));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  try {
    solver.solve({nan, 0.0});
    FAIL() << "no throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(" y "), std::string::npos) << e.what();
  }
  try {
    solver.solve_wheel(Side::right, {0.0, inf});
    FAIL() << "no throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("roll"), std::string::npos) << e.what();
  }
  EXPECT_THROW(solver.equilibrium_roll(nan), Error);
  TrackGeometry bad;
  bad.gauge = nan;
  ProfilePtr w = std::make_shared<ConeWheel>(0.05);
  ProfilePtr r = std::make_shared<CircleRail>(kRailR, 0.04);
  EXPECT_THROW(ContactGeometrySolver(w, r, w, r, bad, WheelsetGeometry{}), Error);
  EXPECT_THROW(ContactGeometrySolver(r, w, w, r, TrackGeometry{}, WheelsetGeometry{}), Error);
}

TEST(ContactGeometry, WheelOffTheRailIsAnErrorNotACrash) {
  const ContactGeometrySolver solver = make_solver(std::make_shared<ConeWheel>(0.05));
  EXPECT_THROW(solver.solve_wheel(Side::left, {0.5, 0.0}), Error);
  // Partly overlapping: the lowest wheel point sits at the end of the search range.
  const WheelContactGeometry g = solver.solve_wheel(Side::left, {-0.09, 0.0});
  EXPECT_NE(g.status & status::kProfileEdge, 0u);
}

TEST(ContactGeometry, SideNames) {
  EXPECT_STREQ(to_string(Side::left), "left");
  EXPECT_STREQ(to_string(Side::right), "right");
}

}  // namespace
}  // namespace railtab::contact_geometry_test
