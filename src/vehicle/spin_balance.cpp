// SPDX-License-Identifier: Apache-2.0
// Torque balance about the axle: a one-dimensional monotone root search in Omega.
#include "vehicle/spin_balance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/status.hpp"

namespace railtab::vehicle {
namespace {

constexpr int kMaxCreepCalls = 40;

// One creep evaluation at spin speed `omega`: creepages, forces and the torque they leave.
struct Trial {
  double omega = 0.0;
  double torque = 0.0;
  SlotCreepage creepage[kWheels][kContactSlots];
  SlotForces forces[kWheels][kContactSlots];
};

}  // namespace

SpinBalance solve_spin_speed(ContactModel& contact, const WheelContacts (&contacts)[kWheels],
                             double running_circle_q, double nominal_radius,
                             double torque_tolerance, SpinWarmStart* warm,
                             WheelsetMotion& motion,
                             SlotCreepage (&creepage_out)[kWheels][kContactSlots],
                             SlotForces (&forces_out)[kWheels][kContactSlots]) {
  SpinBalance result;

  // Linear estimate: fx ~ -w xi with w ~ contact area (creep stiffness G c^2 C11, c^2 = ab), and
  // xi = a - Omega r / V, so sum r w (a - Omega r / V) = 0 gives Omega directly. Exact for a
  // linear creep law with stiffness in proportion to the area.
  double sum_rwa = 0.0, sum_wr2 = 0.0;
  bool any_loaded = false;
  for (int w = 0; w < kWheels; ++w) {
    for (int k = 0; k < kContactSlots; ++k) {
      const SlotContact& c = contacts[w].slot[k];
      if (!c.loaded) continue;
      any_loaded = true;
      const double weight = c.area > 0.0 ? c.area : 1.0;
      motion.spin_speed = 0.0;
      const double a = creepage(motion, w, c, running_circle_q).xi;  // xi at Omega = 0
      sum_rwa += c.rolling_radius * weight * a;
      sum_wr2 += weight * c.rolling_radius * c.rolling_radius;
    }
  }
  if (!any_loaded) {
    motion.spin_speed = motion.speed / nominal_radius;
    for (int w = 0; w < kWheels; ++w) {
      for (int k = 0; k < kContactSlots; ++k) {
        creepage_out[w][k] = {};
        forces_out[w][k] = {};
      }
    }
    result.spin_speed = motion.spin_speed;
    result.status = status::kLiftOff;
    return result;
  }

  auto evaluate = [&](double omega, Trial& t) {
    t.omega = omega;
    motion.spin_speed = omega;
    for (int w = 0; w < kWheels; ++w) {
      for (int k = 0; k < kContactSlots; ++k) {
        const SlotContact& c = contacts[w].slot[k];
        t.creepage[w][k] = c.loaded ? creepage(motion, w, c, running_circle_q) : SlotCreepage{};
      }
    }
    contact.creep(t.creepage, t.forces);
    ++result.creep_calls;
    // Torque of the wheel's contact forces about the axle (+y), up to sign: the longitudinal
    // force at lever r, and the spin moment's component along the axle (n_y = -sin g).
    t.torque = 0.0;
    for (int w = 0; w < kWheels; ++w) {
      for (int k = 0; k < kContactSlots; ++k) {
        const SlotContact& c = contacts[w].slot[k];
        if (!c.loaded) continue;
        t.torque += c.rolling_radius * t.forces[w][k].fx +
                    t.forces[w][k].mz * std::sin(c.contact_angle);
      }
    }
  };

  // torque(Omega) increases with Omega (a faster wheel drives: xi falls, fx rises). Phase 1:
  // Newton/secant steps (a growing walk across plateaus) until the torque changes sign. Phase 2:
  // regula falsi with the Anderson-Bjoerck correction inside that bracket (superlinear, never
  // leaves it).
  const double linear_estimate = motion.speed * sum_rwa / sum_wr2;
  const bool warm_start = warm != nullptr && warm->valid;
  Trial best, previous, current;
  evaluate(linear_estimate + (warm_start ? warm->offset : 0.0), best);
  bool converged = std::abs(best.torque) <= torque_tolerance;
  double slope = warm_start ? warm->slope : 0.0;  // dT/dOmega of the last two evaluations
  // First step: Newton with the previous slope, else with each slot's secant creep stiffness
  // -fx / xi (dxi/dOmega = -r / V), else a creepage change of 1e-6 against the torque's sign.
  for (int w = 0; w < kWheels && !warm_start; ++w) {
    for (int k = 0; k < kContactSlots; ++k) {
      const SlotContact& c = contacts[w].slot[k];
      const double xi = best.creepage[w][k].xi;
      if (!c.loaded || std::abs(xi) < 1e-12) continue;
      const double stiffness = -best.forces[w][k].fx / xi;
      if (stiffness > 0.0) slope += c.rolling_radius * c.rolling_radius * stiffness / motion.speed;
    }
  }
  double next = slope > 0.0 ? best.omega - best.torque / slope
                            : best.omega * (1.0 - std::copysign(1e-6, best.torque));
  previous = best;
  auto step_to = [&](double omega) {
    evaluate(omega, current);
    if (std::abs(current.torque) < std::abs(best.torque)) best = current;
    converged = std::abs(best.torque) <= torque_tolerance;
    const double s = (current.torque - previous.torque) / (current.omega - previous.omega);
    if (s > 0.0 && std::isfinite(s)) slope = s;
  };

  bool bracketed = false;
  while (!converged && result.creep_calls < kMaxCreepCalls) {  // phase 1
    step_to(next);
    if ((current.torque < 0.0) != (previous.torque < 0.0)) {
      bracketed = true;
      break;
    }
    const double s = (current.torque - previous.torque) / (current.omega - previous.omega);
    next = current.omega - current.torque / s;
    const double walk = std::max(4.0 * std::abs(current.omega - previous.omega),
                                 1e-6 * std::abs(current.omega));
    if (!(s > 0.0) || !std::isfinite(next) || std::abs(next - current.omega) > 1e3 * walk) {
      // No usable slope (flat, saturated, noisy) or a leap: walk downhill with a growing step.
      next = current.omega - std::copysign(walk, current.torque);
    }
    previous = current;
  }
  if (bracketed) {  // phase 2: a = previous, b = current, torques of opposite sign
    double a = previous.omega, t_a = previous.torque;
    double b = current.omega, t_b = current.torque;
    while (!converged && result.creep_calls < kMaxCreepCalls) {
      if (std::abs(b - a) <= 4.0 * std::numeric_limits<double>::epsilon() * std::abs(b)) {
        converged = true;  // the root is pinned to round-off (a jump in the creep law)
        break;
      }
      double c = (a * t_b - b * t_a) / (t_b - t_a);
      if (!(c > std::min(a, b) && c < std::max(a, b))) c = 0.5 * (a + b);
      previous = current;
      step_to(c);
      if ((current.torque < 0.0) != (t_b < 0.0)) {
        a = b;
        t_a = t_b;
      } else {
        // Anderson-Bjoerck: scale the stale end's torque so it stops holding the estimate back.
        const double m = 1.0 - current.torque / t_b;
        t_a *= m > 0.0 ? m : 0.5;
      }
      b = c;
      t_b = current.torque;
    }
  }
  if (warm != nullptr) {
    warm->valid = true;
    warm->offset = best.omega - linear_estimate;
    if (slope > 0.0 && std::isfinite(slope)) warm->slope = slope;
  }
  motion.spin_speed = best.omega;
  for (int w = 0; w < kWheels; ++w) {
    for (int k = 0; k < kContactSlots; ++k) {
      creepage_out[w][k] = best.creepage[w][k];
      forces_out[w][k] = best.forces[w][k];
    }
  }
  result.spin_speed = best.omega;
  result.torque = best.torque;
  if (!converged) result.status = status::kNotConverged;
  return result;
}

}  // namespace railtab::vehicle
