// SPDX-License-Identifier: Apache-2.0
// Creepages of a wheel-rail contact from the wheelset's motion relative to the track (linearised
// in the yaw angle; docs/vehicle-model.md derives them). Shared by the equations of motion and by
// the wear post-processing, so both see the same creepages.
#pragma once

#include "vehicle/contact_model.hpp"

namespace railtab::vehicle {

// Motion of the wheelset in the track's design frame (Frenet frame moving along the centreline).
struct WheelsetMotion {
  double speed = 0.0;             // V, forward speed along the track [m/s]
  double lateral_velocity = 0.0;  // dy/dt relative to the design frame [m/s]
  double yaw = 0.0;               // psi, yaw relative to the design tangent, + about +z [rad]
  double yaw_rate = 0.0;          // dpsi/dt [rad/s]
  double curvature = 0.0;         // kappa of the design track, + for a curve to the left [1/m]
  double spin_speed = 0.0;        // Omega, wheel angular speed about the axle [rad/s]
};

// Lateral position of a contact from the wheelset centre (track y): sigma * (q0 + wheel_u), with
// q0 the running circle's distance from the centre (back_to_back/2 - flange_back_position).
double contact_lateral_position(int wheel, double wheel_u, double running_circle_q);

// Creepages (wheel minus rail) of one loaded contact:
//   xi  = 1 - Omega r / V - (kappa + psi_dot / V) y_c
//   eta = (y_dot / V - psi) / cos(g)
//   phi = (-Omega sin(g) + (psi_dot + V kappa) cos(g)) / V
// with g the track-frame contact angle, r the rolling radius, y_c the contact's lateral position.
SlotCreepage creepage(const WheelsetMotion& motion, int wheel, const SlotContact& contact,
                      double running_circle_q);

}  // namespace railtab::vehicle
