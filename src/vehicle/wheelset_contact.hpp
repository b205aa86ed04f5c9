// SPDX-License-Identifier: Apache-2.0
// The contact side of one wheelset's equations of motion, shared by the single-wheelset model
// (wheelset_model.hpp) and the bogie (bogie_model.hpp): quasi-static wheel loads, the contact
// model's normal problem, the spin balance, and the contact forces and yaw moment in track axes.
// Also the linear rates that bound a stable RK4 step. Equations: docs/vehicle-model.md.
#pragma once

#include "vehicle/contact_model.hpp"
#include "vehicle/spin_balance.hpp"
#include "vehicle/track_layout.hpp"
#include "vehicle/wheelset_model.hpp"

namespace railtab::vehicle {

// x + h dx, component by component (RK4 stages), and whether every component is finite.
WheelsetState add_scaled(const WheelsetState& x, double h, const WheelsetState& dx);
bool is_finite(const WheelsetState& x);

// Unbalanced lateral acceleration at a track point: V^2 kappa - g sin(phi_c) [m/s2].
double unbalanced_acceleration(const TrackPoint& track, double speed, double gravity);

// Fills `out` (cleared first) for the wheelset at state `x` on `track`: the loads (static plus the
// quasi-static transfer of the carried mass at cg_height and of the wheelset at r0), y relative to
// the rails, the contacts, creepages and forces at the balanced spin speed, each wheel's lateral
// contact force and the contacts' yaw moment. Leaves the suspension terms at zero. A non-finite
// state gives kInvalidInput and no contact call.
void evaluate_wheelset_contact(const WheelsetParameters& p, ContactModel& contact, double speed,
                               const TrackPoint& track, const WheelsetState& x,
                               SpinWarmStart* warm, ContactSnapshot& out);

// Linearised rates of one wheelset at the contact of `base` (a snapshot from
// evaluate_wheelset_contact): creep damping of the lateral and yaw motion and the normal forces'
// lateral stiffness. Calls contact.normal() at base first, so it can follow any other call.
struct WheelsetRates {
  double lateral_damping = 0.0;   // -d(sum F_y)/d(y_dot) of the creep forces [N s/m]
  double yaw_damping = 0.0;       // -d(sum M_z)/d(psi_dot) [N m s]
  double contact_stiffness = 0.0; // -d(sum -N sin g)/dy at the same loads [N/m]
};
WheelsetRates wheelset_rates(const WheelsetParameters& p, ContactModel& contact, double speed,
                             const ContactSnapshot& base);

}  // namespace railtab::vehicle
