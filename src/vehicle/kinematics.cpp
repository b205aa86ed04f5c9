// SPDX-License-Identifier: Apache-2.0
// Creepages of one contact from the wheelset motion; derivation in docs/vehicle-model.md.
#include "vehicle/kinematics.hpp"

#include <cmath>

namespace railtab::vehicle {

double contact_lateral_position(int wheel, double wheel_u, double running_circle_q) {
  // u grows towards the field side of each wheel, which is +y for the left and -y for the right.
  const double sigma = wheel == 0 ? 1.0 : -1.0;
  return sigma * (running_circle_q + wheel_u);
}

SlotCreepage creepage(const WheelsetMotion& motion, int wheel, const SlotContact& contact,
                      double running_circle_q) {
  const double v = motion.speed;
  const double g = contact.contact_angle;
  const double y_c = contact_lateral_position(wheel, contact.wheel_u, running_circle_q);
  // Yaw of the frame (V kappa) and of the wheelset in it (psi_dot) move the contact at y_c
  // backwards; the rail under it is fixed to the ground.
  const double yaw_velocity = motion.yaw_rate + v * motion.curvature;  // absolute [rad/s]
  SlotCreepage c;
  c.xi = 1.0 - motion.spin_speed * contact.rolling_radius / v - yaw_velocity * y_c / v;
  c.eta = (motion.lateral_velocity / v - motion.yaw) / std::cos(g);
  c.phi = (-motion.spin_speed * std::sin(g) + yaw_velocity * std::cos(g)) / v;
  return c;
}

}  // namespace railtab::vehicle
