// SPDX-License-Identifier: Apache-2.0
// Equilibrium (kinematic) roll: both wheels touch at once, odd in y, Manchester magnitudes.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/contact_geometry.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"
#include "synthetic_profiles.hpp"

namespace railtab {
namespace {

TEST(EquilibriumRoll, BothWheelsTouchAndOddInY) {
  const ContactGeometrySolver s(make_s1002_profile(), make_uic60_profile(), make_s1002_profile(),
                                make_uic60_profile(), TrackGeometry{}, WheelsetGeometry{});
  EXPECT_EQ(s.equilibrium_roll(0.0), 0.0);
  for (double y : {-8e-3, -6.5e-3, -3e-3, 1e-3, 5e-3}) {
    const double roll = s.equilibrium_roll(y);
    const WheelsetContactGeometry g = s.solve({y, roll});
    EXPECT_NEAR(g.wheels[0].wheel_drop, g.wheels[1].wheel_drop, 1e-12) << y;
    EXPECT_NEAR(s.equilibrium_roll(-y), -roll, 1e-12) << y;
    // The wheel on the larger radius lifts its side: roll has the sign of y.
    EXPECT_GT(roll * y, 0.0) << y;
  }
}

// The rigid kinematic roll is close to CONTACT's loaded Manchester roll (FACTS 6, with yaw and
// elastic approach, so only a loose check): 6.0 mm -> 6.27e-4, 6.5 mm -> 4.376e-3, 7 -> 6.393e-3.
TEST(EquilibriumRoll, ManchesterMagnitudes) {
  const ContactGeometrySolver s(make_s1002_profile(), make_uic60_profile(), make_s1002_profile(),
                                make_uic60_profile(), TrackGeometry{}, WheelsetGeometry{});
  EXPECT_NEAR(-s.equilibrium_roll(-6.0e-3), 6.27e-4, 0.1 * 6.27e-4);
  EXPECT_NEAR(-s.equilibrium_roll(-6.5e-3), 4.376e-3, 0.1 * 4.376e-3);
  EXPECT_NEAR(-s.equilibrium_roll(-7.0e-3), 6.393e-3, 0.1 * 6.393e-3);
}

// Cones of conicity c on circular crowns: with the roll found, the drops agree; roll is small
// and of the sign of y.
TEST(EquilibriumRoll, ConeWheelset) {
  ProfilePtr w = std::make_shared<testing::ConeWheel>(0.05);
  ProfilePtr r = std::make_shared<testing::CircleRail>(0.05, 0.04);
  const ContactGeometrySolver s(w, r, w, r, TrackGeometry{}, WheelsetGeometry{});
  const double roll = s.equilibrium_roll(0.004);
  EXPECT_GT(roll, 0.0);
  const WheelsetContactGeometry g = s.solve({0.004, roll});
  EXPECT_NEAR(g.wheels[0].wheel_drop, g.wheels[1].wheel_drop, 1e-12);
}

}  // namespace
}  // namespace railtab
