// SPDX-License-Identifier: Apache-2.0
// The wheel spin speed that balances the creep torques about the axle (docs/vehicle-model.md,
// "Spin speed"). Internal to src/vehicle.
#pragma once

#include <cstdint>

#include "vehicle/contact_model.hpp"
#include "vehicle/kinematics.hpp"

namespace railtab::vehicle {

struct SpinBalance {
  double spin_speed = 0.0;    // Omega [rad/s]
  double torque = 0.0;        // residual creep torque about the axle at Omega [N m]
  int creep_calls = 0;        // contact.creep() evaluations spent
  std::uint32_t status = 0;   // kNotConverged when neither the torque nor the bracket met the
                              // tolerance; kLiftOff when no slot is loaded (Omega = V / r0)
};

// What the previous balance learnt, to start the next one close: consecutive evaluations (RK4
// stages, steps) differ little, so the root's offset from the linear estimate and the torque's
// slope there carry over. Costs nothing when wrong: the search is bracketed.
struct SpinWarmStart {
  bool valid = false;
  double offset = 0.0;  // Omega at the root - linear estimate [rad/s]
  double slope = 0.0;   // dT/dOmega near the root, > 0 [N m s]
};

// Finds Omega with sum over loaded slots of (r fx + mz sin g) = 0 (creep torque about the axle),
// to |torque| <= torque_tolerance or until Omega is bracketed to round-off. `motion` gives
// everything but the spin speed, which is set to the result. Fills `creepage_out` and
// `forces_out` at the returned Omega. `contacts` must be those of the contact model's last normal() call. `warm`
// (may be null) is read for the start and updated with this solution.
SpinBalance solve_spin_speed(ContactModel& contact, const WheelContacts (&contacts)[kWheels],
                             double running_circle_q, double nominal_radius,
                             double torque_tolerance, SpinWarmStart* warm,
                             WheelsetMotion& motion,
                             SlotCreepage (&creepage_out)[kWheels][kContactSlots],
                             SlotForces (&forces_out)[kWheels][kContactSlots]);

}  // namespace railtab::vehicle
