// SPDX-License-Identifier: Apache-2.0
// track_forces: a query result's contact-frame forces rotated into track axes, summed per wheel,
// and the wheel's Y/Q (docs/conventions.md, "Track-frame forces and Y/Q").
#include <cmath>

#include "railtab/lookup.hpp"

namespace railtab::lookup {

TrackForces track_forces(Wheel wheel, const Result& result) noexcept {
  TrackForces out;
  if (wheel != Wheel::kLeft && wheel != Wheel::kRight) return out;
  const int n = result.n_slots < 0 ? 0 : (result.n_slots > kMaxSlots ? kMaxSlots : result.n_slots);
  for (int slot = 0; slot < n; ++slot) {
    const Contact& c = result.contact[slot];
    const double normal = c.value[kNormalForce];
    if (!(normal > 0.0)) continue;  // no contact in this slot (or a non-finite value)
    double angle = c.value[kContactAngle];
    // A patch whose rigid point is in another slot: that point's angle is the patch's.
    if (!(c.value[kRollingRadius] > 0.0)) {
      for (int other = 0; other < n; ++other) {
        if (other != slot && result.contact[other].value[kRollingRadius] > 0.0) {
          angle = result.contact[other].value[kContactAngle];
          break;
        }
      }
    }
    const double fy = c.value[kFy];
    const double s = std::sin(angle), co = std::cos(angle);
    out.contact_angle[slot] = angle;
    out.lateral[slot] = -normal * s + fy * co;
    out.vertical[slot] = normal * co + fy * s;
    out.wheel_lateral += out.lateral[slot];
    out.wheel_vertical += out.vertical[slot];
  }
  const double sigma = wheel == Wheel::kLeft ? 1.0 : -1.0;
  out.y_force = -sigma * out.wheel_lateral;
  out.q_force = out.wheel_vertical;
  out.y_over_q = out.q_force > 0.0 ? out.y_force / out.q_force : 0.0;
  return out;
}

}  // namespace railtab::lookup
