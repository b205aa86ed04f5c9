// SPDX-License-Identifier: Apache-2.0
// The torque balance about the axle on creep laws where the first estimate is not the answer.
#include "vehicle/spin_balance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "core/status.hpp"

namespace railtab::vehicle {
namespace {

// Tread contacts on both wheels, creep law given per wheel as fx(xi).
class LawContact : public ContactModel {
 public:
  std::function<double(int wheel, double xi)> law;
  int calls = 0;
  void normal(double, double, const double (&)[kWheels], WheelContacts (&)[kWheels]) override {}
  void creep(const SlotCreepage (&creepage)[kWheels][kContactSlots],
             SlotForces (&forces)[kWheels][kContactSlots]) override {
    ++calls;
    for (int w = 0; w < kWheels; ++w) {
      forces[w][0] = SlotForces{};
      forces[w][0].fx = law(w, creepage[w][0].xi);
      forces[w][1] = SlotForces{};
    }
  }
};

struct Case {
  WheelContacts contacts[kWheels];
  WheelsetMotion motion;
  SlotCreepage creepage[kWheels][kContactSlots];
  SlotForces forces[kWheels][kContactSlots];
  // Curvature and yaw rate set the creepages: |xi| ~ (kappa + psi_dot / V) q0.
  explicit Case(double curvature = 1.0 / 1000.0, double yaw_rate = 0.0) {
    for (int w = 0; w < kWheels; ++w) {
      SlotContact& c = contacts[w].slot[0];
      c.loaded = true;
      c.rolling_radius = w == 0 ? 0.4612 : 0.4590;  // wheelset off centre
      c.area = w == 0 ? 1.2e-4 : 1.6e-4;
    }
    motion.speed = 30.0;
    motion.curvature = curvature;
    motion.yaw_rate = yaw_rate;
  }
  double torque() const {
    return contacts[0].slot[0].rolling_radius * forces[0][0].fx +
           contacts[1].slot[0].rolling_radius * forces[1][0].fx;
  }
};

constexpr double kTolerance = 1e-9 * 40000.0 * 0.46;

// Saturating laws with different stiffness and an offset (as spin creepage gives in tables).
double saturating_law(int w, double xi) {
  const double limit = 12000.0, stiffness = w == 0 ? 9e6 : 14e6;
  return -limit * std::tanh(stiffness * xi / limit) + (w == 0 ? 150.0 : -40.0);
}

TEST(SpinBalance, NonlinearUnequalLawsBalanceToTolerance) {
  LawContact contact;
  contact.law = saturating_law;
  Case c;  // |xi| ~ 7.5e-4: partly saturated
  SpinWarmStart warm;
  const SpinBalance r = solve_spin_speed(contact, c.contacts, 0.75, 0.46, kTolerance, &warm,
                                         c.motion, c.creepage, c.forces);
  EXPECT_EQ(r.status, 0u);
  EXPECT_LE(std::abs(c.torque()), kTolerance);
  EXPECT_EQ(c.motion.spin_speed, r.spin_speed);
  EXPECT_LE(r.creep_calls, 6);
  // The same case again starts from the learnt offset: one call.
  Case again;
  const SpinBalance r2 = solve_spin_speed(contact, again.contacts, 0.75, 0.46, kTolerance, &warm,
                                          again.motion, again.creepage, again.forces);
  EXPECT_EQ(r2.creep_calls, 1);
  EXPECT_LE(std::abs(again.torque()), kTolerance);
}

TEST(SpinBalance, DeepSaturationOfBothWheelsStillConverges) {
  // |xi| ~ 5e-3 on both wheels, far into the tanh: the torque is nearly flat at the root and
  // steep beside it, the hard case for a bracketed secant.
  LawContact contact;
  contact.law = saturating_law;
  Case c(1.0 / 400.0, 0.01);
  const SpinBalance r = solve_spin_speed(contact, c.contacts, 0.75, 0.46, kTolerance, nullptr,
                                         c.motion, c.creepage, c.forces);
  std::printf("  spin balance, both wheels deep in saturation: %d creep() calls\n", r.creep_calls);
  EXPECT_EQ(r.status, 0u);
  EXPECT_LE(std::abs(c.torque()), kTolerance);
}

TEST(SpinBalance, CoulombPlateauIsCrossedAndTheRootPinned) {
  LawContact contact;
  // Both wheels saturate at a tiny creepage: the torque is flat almost everywhere, with a steep
  // step where the wheels change sides.
  contact.law = [](int w, double xi) {
    const double limit = w == 0 ? 9000.0 : 15000.0;
    return -limit * std::clamp(xi / 1e-7, -1.0, 1.0);
  };
  Case c;
  const SpinBalance r = solve_spin_speed(contact, c.contacts, 0.75, 0.46, kTolerance, nullptr,
                                         c.motion, c.creepage, c.forces);
  EXPECT_EQ(r.status & status::kNotConverged, 0u) << r.creep_calls << " calls";
  // The lighter wheel's limit cannot balance the heavier one's unless one of them is in its
  // linear zone: the root has |xi| <= 1e-7 on at least one wheel.
  EXPECT_LE(std::min(std::abs(c.creepage[0][0].xi), std::abs(c.creepage[1][0].xi)), 1e-7);
  EXPECT_LE(std::abs(c.torque()), kTolerance);
}

TEST(SpinBalance, NoLoadedSlotGivesNominalSpinAndLiftOff) {
  LawContact contact;
  contact.law = [](int, double) { return 0.0; };
  Case c;
  c.contacts[0].slot[0].loaded = false;
  c.contacts[1].slot[0].loaded = false;
  const SpinBalance r = solve_spin_speed(contact, c.contacts, 0.75, 0.46, kTolerance, nullptr,
                                         c.motion, c.creepage, c.forces);
  EXPECT_EQ(r.status, status::kLiftOff);
  EXPECT_DOUBLE_EQ(r.spin_speed, 30.0 / 0.46);
  EXPECT_EQ(contact.calls, 0);
}

}  // namespace
}  // namespace railtab::vehicle
