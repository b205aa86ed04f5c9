// SPDX-License-Identifier: Apache-2.0
// Creepages of a patch from the rigid motion of a (yawed, rolled) wheelset on tangent track:
// the wheel material's velocity at the patch's reference point relative to the rail, in the
// contact frame (docs/conventions.md "Creepages" and "Yaw").
#pragma once

#include "geometry/contact_geometry.hpp"
#include "halfspace/wheel_rail.hpp"
#include "tangential/fastsim.hpp"

namespace railtab::halfspace {

// Motion of the wheelset relative to the track (steady: no yaw rate).
struct WheelsetMotion {
  double speed = 0.0;             // V, forward speed of the wheelset centre along track x [m/s]
  double spin = 0.0;              // Omega, angular speed about the axle, + rolling forward
                                  // (CONTACT's -VPITCH) [rad/s]
  double lateral_velocity = 0.0;  // dy/dt of the wheelset centre, track frame [m/s]
};

// Creepages (wheel minus rail, per distance travelled V t) at the reference of `patch`, a patch
// of `geometry` (the wheel's roll and yaw, the reference's radius, lead and contact angle):
//   v = V x + dy/dt y + Omega e_axle x r rho,  rho the radial direction to the point on the
//   wheel circle (angle tau from its lowest point, r sin(tau) = x_wheel);
//   xi = v.x / V,  eta = v.s / V,  phi = Omega e_axle.n / V.
// Without yaw: xi = 1 - Omega r / V, eta = (dy/dt) cos(g) / V, phi = -Omega sin(g) / V. With yaw
// the wheel's velocity at the contact has no normal component (the contact lies on the
// silhouette), and eta = -sin(yaw) (cos(tau) cos(g) + ...) ~ -yaw / cos(g): the yaw angle adds a
// lateral creepage opposite to it on both wheels, 2.5 times larger on a 66 deg flange.
Creepage rigid_creepage(const WheelContactGeometry& geometry, const HalfspacePatch& patch,
                        const WheelsetMotion& motion);

}  // namespace railtab::halfspace
