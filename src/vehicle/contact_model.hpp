// SPDX-License-Identifier: Apache-2.0
// What the vehicle model needs from wheel-rail contact, whoever computes it: a contact table
// through railtab::lookup (the normal case inside a time-stepping loop) or the core's models
// directly (the reference run, `railtab simulate --direct`). Frames and signs: docs/conventions.md.
#pragma once

#include <cstdint>

namespace railtab::vehicle {

inline constexpr int kWheels = 2;        // 0 = left, 1 = right (docs/conventions.md)
inline constexpr int kContactSlots = 2;  // 0 = tread, 1 = flange (docs/table-format.md)

// One contact slot of one wheel after the normal problem at the current (y, loads).
struct SlotContact {
  bool loaded = false;          // normal_force > 0
  double contact_angle = 0.0;   // track frame, + for the left wheel towards its flange [rad]
  double rolling_radius = 0.0;  // wheel radius at the contact [m]
  double wheel_u = 0.0;         // contact's u in the wheel profile frame [m]
  double normal_force = 0.0;    // along the contact normal, on the wheel [N]
  double area = 0.0;            // contact area [m2]
  std::uint32_t status = 0;     // railtab status bits (src/core/status.hpp)
};

struct WheelContacts {
  SlotContact slot[kContactSlots];
};

// Creepages in the contact frame (x, s, n) of docs/conventions.md: wheel minus rail.
struct SlotCreepage {
  double xi = 0.0;   // [-]
  double eta = 0.0;  // [-]
  double phi = 0.0;  // [rad/m]
};

// Creep forces ON THE WHEEL in the contact frame.
struct SlotForces {
  double fx = 0.0;            // along x [N]
  double fy = 0.0;            // along s [N]
  double mz = 0.0;            // about n [N m]
  double normal_force = 0.0;  // normal force at this creepage when the source couples the load
                              //   with the creep forces [N]; 0: normal()'s value holds
  std::uint32_t status = 0;   // railtab status bits (e.g. kFullSlip, kOutOfRange)
};

// A source of contact results. Not thread-safe: one instance per running simulation.
class ContactModel {
 public:
  virtual ~ContactModel() = default;

  // Geometry and normal contact of both wheels at wheelset lateral displacement `y` relative to
  // the rails [m] (track frame, + left), yaw `yaw` relative to the track [rad] (docs/conventions.md)
  // and vertical wheel loads `load` [N]. A source that does not resolve yaw (a table without a yaw
  // axis) answers at its own fixed yaw. Unloaded slots come back with loaded = false.
  virtual void normal(double y, double yaw, const double (&load)[kWheels],
                      WheelContacts (&contacts)[kWheels]) = 0;

  // Creep forces of every loaded slot of the last normal() call, each at its own creepage
  // (unloaded slots: ignored in, zeros out).
  virtual void creep(const SlotCreepage (&creepage)[kWheels][kContactSlots],
                     SlotForces (&forces)[kWheels][kContactSlots]) = 0;
};

}  // namespace railtab::vehicle
