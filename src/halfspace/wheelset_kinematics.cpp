// SPDX-License-Identifier: Apache-2.0
// Rigid-body creepages of a yawed wheelset at a patch's reference point.
#include "halfspace/wheelset_kinematics.hpp"

#include <algorithm>
#include <cmath>

#include "core/check.hpp"

namespace railtab::halfspace {

Creepage rigid_creepage(const WheelContactGeometry& g, const HalfspacePatch& patch,
                        const WheelsetMotion& m) {
  RAILTAB_CHECK(std::isfinite(m.speed) && m.speed > 0.0,
                "wheelset kinematics: speed = {} m/s must be finite and > 0", m.speed);
  RAILTAB_CHECK(std::isfinite(m.spin) && std::isfinite(m.lateral_velocity),
                "wheelset kinematics: spin = {} rad/s and lateral velocity = {} m/s must be finite",
                m.spin, m.lateral_velocity);
  const double sigma = outward_sign(g.side);
  // Side-frame angles (the wheel's own), then the radial direction rho to the contact point on
  // its circle: rho = -cos(tau) e_v + sin(tau) e_f with e_f = (cp, sp ct, sp st), e_v = (0, -st, ct)
  // for R_x(roll) R_z(yaw) (geometry/placement.cpp); a side-frame position maps to the track by
  // q = sigma y.
  const double th = g.wheel_roll, ps = g.wheel_yaw;
  const double ct = std::cos(th), st = std::sin(th), cp = std::cos(ps), sp = std::sin(ps);
  const double r = patch.rolling_radius;
  const double s_tau = std::clamp(patch.x_wheel / r, -1.0, 1.0);
  const double c_tau = std::sqrt(1.0 - s_tau * s_tau);
  const double rho_x = s_tau * cp;
  const double rho_y = sigma * (c_tau * st + s_tau * sp * ct);
  const double rho_z = -c_tau * ct + s_tau * sp * st;
  // Axle direction (towards the left wheel) in the track frame for R_x(roll) R_z(yaw).
  const double yaw = sigma * ps, roll = sigma * th;
  const double ax = -std::sin(yaw), ay = std::cos(yaw) * std::cos(roll), az = std::cos(yaw) * std::sin(roll);
  // v = V x + y_dot y + Omega a x (r rho)
  const double w = m.spin * r;
  const double vx = m.speed + w * (ay * rho_z - az * rho_y);
  const double vy = m.lateral_velocity + w * (az * rho_x - ax * rho_z);
  const double vz = w * (ax * rho_y - ay * rho_x);
  const double gt = patch.contact_angle;  // track frame: s = (0, cos g, sin g), n = (0, -sin g, cos g)
  Creepage c;
  c.xi = vx / m.speed;
  c.eta = (vy * std::cos(gt) + vz * std::sin(gt)) / m.speed;
  c.phi = m.spin * (-ay * std::sin(gt) + az * std::cos(gt)) / m.speed;
  return c;
}

}  // namespace railtab::halfspace
