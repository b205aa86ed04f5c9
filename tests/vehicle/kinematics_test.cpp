// SPDX-License-Identifier: Apache-2.0
// Tests of the creepages from the wheelset's motion (src/vehicle/kinematics.hpp).
#include "vehicle/kinematics.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace railtab::vehicle {
namespace {

SlotContact contact_at(double angle, double radius, double wheel_u) {
  SlotContact c;
  c.loaded = true;
  c.contact_angle = angle;
  c.rolling_radius = radius;
  c.wheel_u = wheel_u;
  return c;
}

TEST(Kinematics, ContactLateralPositionIsOutwardForBothWheels) {
  EXPECT_DOUBLE_EQ(contact_lateral_position(0, 0.01, 0.75), 0.76);
  EXPECT_DOUBLE_EQ(contact_lateral_position(1, 0.01, 0.75), -0.76);
}

TEST(Kinematics, PureRollingOnTangentTrackHasNoCreepage) {
  WheelsetMotion m;
  m.speed = 30.0;
  m.spin_speed = 30.0 / 0.46;
  const SlotCreepage c = creepage(m, 0, contact_at(0.0, 0.46, 0.0), 0.75);
  EXPECT_NEAR(c.xi, 0.0, 1e-15);
  EXPECT_EQ(c.eta, 0.0);
  EXPECT_EQ(c.phi, 0.0);
}

TEST(Kinematics, SignsFollowWheelMinusRail) {
  WheelsetMotion m;
  m.speed = 20.0;
  m.spin_speed = 0.99 * 20.0 / 0.46;  // braking: the wheel turns too slowly
  m.yaw = 2e-3;                       // nose to the left: the wheel creeps to the right
  const double g = 0.6;               // left flange
  const SlotCreepage left = creepage(m, 0, contact_at(g, 0.46, -0.03), 0.75);
  EXPECT_NEAR(left.xi, 0.01, 1e-15);
  EXPECT_NEAR(left.eta, -2e-3 / std::cos(g), 1e-15);
  EXPECT_NEAR(left.phi, -m.spin_speed * std::sin(g) / 20.0, 1e-15);
  // In a left curve the outer (right) contact must travel farther: at Omega = V / r0 it lags,
  // xi > 0 by kappa * |y_c|.
  m = WheelsetMotion{};
  m.speed = 20.0;
  m.spin_speed = 20.0 / 0.46;
  m.curvature = 1.0 / 500.0;
  const SlotCreepage right = creepage(m, 1, contact_at(-0.02, 0.46, 0.0), 0.75);
  EXPECT_NEAR(right.xi, 0.75 / 500.0, 1e-15);
  EXPECT_NEAR(right.phi, (20.0 / 0.46 * std::sin(0.02) + 20.0 / 500.0 * std::cos(0.02)) / 20.0,
              1e-15);
}

}  // namespace
}  // namespace railtab::vehicle
