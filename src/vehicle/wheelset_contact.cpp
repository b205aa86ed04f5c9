// SPDX-License-Identifier: Apache-2.0
// Loads, contact and contact forces of one wheelset; docs/vehicle-model.md derives every term.
#include "vehicle/wheelset_contact.hpp"

#include <algorithm>
#include <cmath>

#include "core/status.hpp"
#include "vehicle/kinematics.hpp"

namespace railtab::vehicle {
namespace {

// The spin speed balances the creep torque to this fraction of Q0 r0.
constexpr double kRelativeTorqueTolerance = 1e-9;
// A wheel keeps at least this fraction of the static load (quasi-static transfer beyond it means
// the wheel lifts; the snapshot says kLiftOff).
constexpr double kMinimumLoadFraction = 0.01;

}  // namespace

WheelsetState add_scaled(const WheelsetState& x, double h, const WheelsetState& dx) {
  return {x.y + h * dx.y, x.yaw + h * dx.yaw, x.lateral_velocity + h * dx.lateral_velocity,
          x.yaw_rate + h * dx.yaw_rate};
}

bool is_finite(const WheelsetState& x) {
  return std::isfinite(x.y) && std::isfinite(x.yaw) && std::isfinite(x.lateral_velocity) &&
         std::isfinite(x.yaw_rate);
}

double unbalanced_acceleration(const TrackPoint& track, double speed, double gravity) {
  return speed * speed * track.curvature - gravity * std::sin(track.cant_angle);
}

void evaluate_wheelset_contact(const WheelsetParameters& p, ContactModel& contact, double speed,
                               const TrackPoint& track, const WheelsetState& x,
                               SpinWarmStart* warm, ContactSnapshot& out) {
  out = ContactSnapshot{};
  if (!is_finite(x)) {  // a diverged run: report it, never hand NaN to the contact model
    out.status = status::kInvalidInput;
    return;
  }
  const double q0 = p.running_circle_q;

  // Quasi-static load transfer of the carried mass and the wheelset under the unbalanced
  // lateral acceleration.
  const double a_u = unbalanced_acceleration(track, speed, p.gravity);
  const double q_static = p.static_wheel_load();
  const double transfer = (p.carried_mass * p.cg_height + p.mass * p.nominal_radius) * a_u /
                          (2.0 * q0);
  const double q_min = kMinimumLoadFraction * q_static;
  const double q_left = std::clamp(q_static - transfer, q_min, 2.0 * q_static - q_min);
  out.load[0] = q_left;
  out.load[1] = 2.0 * q_static - q_left;  // the total stays (m + M) g
  if (std::abs(transfer) > q_static - q_min) out.status |= status::kLiftOff;

  out.y_relative = x.y - track.lateral_irregularity;
  contact.normal(out.y_relative, x.yaw, out.load, out.contacts);

  // Creepages use the motion relative to the design frame (the irregularity enters through the
  // geometry only, to first order).
  out.motion.speed = speed;
  out.motion.lateral_velocity = x.lateral_velocity;
  out.motion.yaw = x.yaw;
  out.motion.yaw_rate = x.yaw_rate;
  out.motion.curvature = track.curvature;
  const double torque_tolerance = kRelativeTorqueTolerance * q_static * p.nominal_radius;
  const SpinBalance spin = solve_spin_speed(contact, out.contacts, q0, p.nominal_radius,
                                            torque_tolerance, warm, out.motion, out.creepage,
                                            out.forces);
  out.status |= spin.status;

  // Contact forces on the wheelset in track axes: normal force along n = (0, -sin g, cos g),
  // creep forces along x and s = (0, cos g, sin g), spin moment about n.
  for (int w = 0; w < kWheels; ++w) {
    for (int k = 0; k < kContactSlots; ++k) {
      const SlotContact& c = out.contacts[w].slot[k];
      const SlotForces& f = out.forces[w][k];
      out.status |= c.status | f.status;
      if (!c.loaded) continue;
      const double y_c = contact_lateral_position(w, c.wheel_u, q0);
      // The creepage-dependent normal force where the contact model gives one (load coupling).
      const double normal_force = f.normal_force > 0.0 ? f.normal_force : c.normal_force;
      out.lateral_force[w] +=
          -normal_force * std::sin(c.contact_angle) + f.fy * std::cos(c.contact_angle);
      out.contact_yaw_moment += -y_c * f.fx + f.mz * std::cos(c.contact_angle);
    }
  }
}

WheelsetRates wheelset_rates(const WheelsetParameters& p, ContactModel& contact, double speed,
                             const ContactSnapshot& base) {
  // Creep damping: the lateral force falls with y_dot through eta = y_dot / (V cos g), the yaw
  // moment with psi_dot through xi = ... - psi_dot y_c / V. Slopes of the creep law by central
  // differences at the current creepages (all slots at once: each slot's forces depend on its own
  // creepage only).
  WheelContacts refreshed[kWheels];
  contact.normal(base.y_relative, base.motion.yaw, base.load, refreshed);  // creep() refers to the last normal()
  constexpr double h = 1e-6;
  SlotCreepage plus[kWheels][kContactSlots], minus[kWheels][kContactSlots];
  SlotForces f_plus[kWheels][kContactSlots], f_minus[kWheels][kContactSlots];
  auto slopes = [&](bool longitudinal) {
    for (int w = 0; w < kWheels; ++w) {
      for (int k = 0; k < kContactSlots; ++k) {
        plus[w][k] = minus[w][k] = base.creepage[w][k];
        (longitudinal ? plus[w][k].xi : plus[w][k].eta) += h;
        (longitudinal ? minus[w][k].xi : minus[w][k].eta) -= h;
      }
    }
    contact.creep(plus, f_plus);
    contact.creep(minus, f_minus);
  };
  WheelsetRates rates;
  slopes(false);
  for (int w = 0; w < kWheels; ++w) {
    for (int k = 0; k < kContactSlots; ++k) {
      if (!base.contacts[w].slot[k].loaded) continue;
      rates.lateral_damping += std::abs(f_plus[w][k].fy - f_minus[w][k].fy) / (2 * h) / speed;
    }
  }
  slopes(true);
  for (int w = 0; w < kWheels; ++w) {
    for (int k = 0; k < kContactSlots; ++k) {
      const SlotContact& c = base.contacts[w].slot[k];
      if (!c.loaded) continue;
      const double y_c = contact_lateral_position(w, c.wheel_u, p.running_circle_q);
      rates.yaw_damping +=
          y_c * y_c * std::abs(f_plus[w][k].fx - f_minus[w][k].fx) / (2 * h) / speed;
    }
  }
  // Lateral stiffness of the normal forces (gravitational stiffness; large in flange contact),
  // d(sum -N sin g)/dy at the same loads. Last, so the creep() calls above saw the base normal().
  auto normal_lateral_force = [&](double y) {
    WheelContacts contacts[kWheels];
    contact.normal(y, base.motion.yaw, base.load, contacts);
    double f = 0.0;
    for (const WheelContacts& wheel : contacts) {
      for (const SlotContact& c : wheel.slot) {
        if (c.loaded) f -= c.normal_force * std::sin(c.contact_angle);
      }
    }
    return f;
  };
  constexpr double dy = 1e-6;  // [m]
  rates.contact_stiffness =
      (normal_lateral_force(base.y_relative - dy) - normal_lateral_force(base.y_relative + dy)) /
      (2 * dy);
  return rates;
}

}  // namespace railtab::vehicle
