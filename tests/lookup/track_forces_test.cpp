// SPDX-License-Identifier: Apache-2.0
// track_forces: the rotation of a slot's contact-frame forces into track axes at a known contact
// angle (by hand), the left/right signs of Y, the sum over slots, a loaded slot without its rigid
// point, and the zeros of an empty or invalid result.
#include <gtest/gtest.h>

#include <cmath>

#include "railtab/lookup.hpp"

namespace railtab::lookup {
namespace {

// A result with one loaded slot: contact angle g [rad], normal force [N], fy [N], rolling radius [m].
void set_slot(Result& r, int slot, double g, double normal, double fy, double radius = 0.46) {
  r.contact[slot].value[kContactAngle] = g;
  r.contact[slot].value[kNormalForce] = normal;
  r.contact[slot].value[kFy] = fy;
  r.contact[slot].value[kFx] = 1234.0;  // longitudinal: along track x already, enters neither sum
  r.contact[slot].value[kRollingRadius] = radius;
}

TEST(TrackForces, RotationAtThirtyDegreesByHand) {
  // Left wheel, g = 30 deg (sin 1/2, cos sqrt(3)/2), N = 1000 N, fy = 200 N:
  //   lateral  = -1000/2 + 200 sqrt(3)/2 = -(500 - 100 sqrt 3) = -326.79491924311 N
  //   vertical = 1000 sqrt(3)/2 + 200/2  = 500 sqrt 3 + 100    =  966.02540378444 N
  // Y = -lateral (left wheel, outward = +y) = 326.79491924311 N, Q = 966.02540378444 N,
  // Y/Q = 0.33828812157825.
  Result r;
  r.n_slots = 2;
  set_slot(r, 0, std::acos(-1.0) / 6.0, 1000.0, 200.0);
  const TrackForces f = track_forces(Wheel::kLeft, r);
  EXPECT_NEAR(f.lateral[0], -326.79491924311, 1e-9);
  EXPECT_NEAR(f.vertical[0], 966.02540378444, 1e-9);
  EXPECT_EQ(f.lateral[1], 0.0);  // empty slot
  EXPECT_EQ(f.vertical[1], 0.0);
  EXPECT_NEAR(f.wheel_lateral, -326.79491924311, 1e-9);
  EXPECT_NEAR(f.y_force, 326.79491924311, 1e-9);
  EXPECT_NEAR(f.q_force, 966.02540378444, 1e-9);
  EXPECT_NEAR(f.y_over_q, 0.33828812157825, 1e-13);
  EXPECT_DOUBLE_EQ(f.contact_angle[0], std::acos(-1.0) / 6.0);
}

TEST(TrackForces, RightWheelIsTheMirrorImage) {
  // The mirror (y -> -y) of the state above: the right wheel's angle is -30 deg and its fy (along
  // s, close to +y on both wheels) changes sign. The force on the wheel mirrors (lateral changes
  // sign, vertical stays), so Y, + outward on each rail, is the same: flange-side contact pushes
  // either rail outward.
  Result left, right;
  left.n_slots = right.n_slots = 2;
  set_slot(left, 1, 1.1, 90e3, -5e3);
  set_slot(right, 1, -1.1, 90e3, 5e3);
  const TrackForces l = track_forces(Wheel::kLeft, left), r = track_forces(Wheel::kRight, right);
  EXPECT_NEAR(r.wheel_lateral, -l.wheel_lateral, 1e-9);
  EXPECT_NEAR(r.wheel_vertical, l.wheel_vertical, 1e-9);
  EXPECT_NEAR(r.y_force, l.y_force, 1e-9);
  EXPECT_GT(l.y_force, 0.0);
  EXPECT_NEAR(r.y_over_q, l.y_over_q, 1e-15);
  // The right wheel's own numbers: lateral = -90e3 sin(-1.1) + 5e3 cos(-1.1), Y = +lateral.
  EXPECT_NEAR(r.wheel_lateral, 90e3 * std::sin(1.1) + 5e3 * std::cos(1.1), 1e-9);
  EXPECT_NEAR(r.y_force, r.wheel_lateral, 1e-9);
}

TEST(TrackForces, NadalAtZeroCreepIsTheTangentOfTheAngle) {
  // Without creep force Y/Q of a single contact is tan(g) of its side-frame angle, either wheel.
  for (double g : {0.025, 0.4, 1.2}) {
    Result l, r;
    l.n_slots = r.n_slots = 2;
    set_slot(l, 1, g, 50e3, 0.0);
    set_slot(r, 1, -g, 50e3, 0.0);
    EXPECT_NEAR(track_forces(Wheel::kLeft, l).y_over_q, std::tan(g), 1e-14) << g;
    EXPECT_NEAR(track_forces(Wheel::kRight, r).y_over_q, std::tan(g), 1e-14) << g;
  }
}

TEST(TrackForces, SumsTheSlotsAndRotatesAnUnpairedSlotWithTheOtherSlotsAngle) {
  Result r;
  r.n_slots = 2;
  set_slot(r, 0, 0.03, 40e3, 1e3);
  set_slot(r, 1, 1.15, 30e3, -2e3);
  TrackForces f = track_forces(Wheel::kLeft, r);
  EXPECT_NEAR(f.wheel_lateral, (-40e3 * std::sin(0.03) + 1e3 * std::cos(0.03)) +
                                   (-30e3 * std::sin(1.15) - 2e3 * std::cos(1.15)), 1e-9);
  EXPECT_NEAR(f.wheel_vertical, (40e3 * std::cos(0.03) + 1e3 * std::sin(0.03)) +
                                    (30e3 * std::cos(1.15) - 2e3 * std::sin(1.15)), 1e-9);
  EXPECT_DOUBLE_EQ(f.wheel_lateral, f.lateral[0] + f.lateral[1]);
  // Hand-over: slot 0 carries the patch but holds no rigid point (radius 0, angle 0); the point,
  // with its angle 0.74 rad, is in slot 1, which carries no force.
  Result h;
  h.n_slots = 2;
  set_slot(h, 0, 0.0, 80e3, 0.0, 0.0);
  set_slot(h, 1, 0.74, 0.0, 0.0);
  f = track_forces(Wheel::kLeft, h);
  EXPECT_DOUBLE_EQ(f.contact_angle[0], 0.74);
  EXPECT_NEAR(f.lateral[0], -80e3 * std::sin(0.74), 1e-9);
  EXPECT_NEAR(f.y_over_q, std::tan(0.74), 1e-14);
  EXPECT_EQ(f.lateral[1], 0.0);
}

TEST(TrackForces, EmptyAndInvalidGiveZeros) {
  Result r;
  r.n_slots = 2;
  TrackForces f = track_forces(Wheel::kLeft, r);  // no loaded slot
  EXPECT_EQ(f.q_force, 0.0);
  EXPECT_EQ(f.y_over_q, 0.0);
  set_slot(r, 0, 0.3, 1e3, 0.0);
  f = track_forces(static_cast<Wheel>(7), r);
  EXPECT_EQ(f.wheel_vertical, 0.0);
  EXPECT_EQ(f.y_over_q, 0.0);
  r.contact[0].value[kNormalForce] = std::nan("");  // a NaN force is not a contact
  EXPECT_EQ(track_forces(Wheel::kLeft, r).wheel_vertical, 0.0);
}

}  // namespace
}  // namespace railtab::lookup
