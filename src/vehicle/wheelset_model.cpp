// Equations of motion of the suspended wheelset and their RK4 integration
// (docs/vehicle-model.md derives every term; the names below follow it).
#include "vehicle/wheelset_model.hpp"

#include <algorithm>
#include <cmath>

#include "core/check.hpp"
#include "core/status.hpp"
#include "vehicle/spin_balance.hpp"

namespace railtab::vehicle {
namespace {

// The spin speed balances the creep torque to this fraction of Q0 r0.
constexpr double kRelativeTorqueTolerance = 1e-9;
// A wheel keeps at least this fraction of the static load (quasi-static transfer beyond it means
// the wheel lifts; the snapshot says kLiftOff).
constexpr double kMinimumLoadFraction = 0.01;

bool finite(const WheelsetState& x) {
  return std::isfinite(x.y) && std::isfinite(x.yaw) && std::isfinite(x.lateral_velocity) &&
         std::isfinite(x.yaw_rate);
}

WheelsetState add(const WheelsetState& x, double h, const WheelsetState& dx) {
  return {x.y + h * dx.y, x.yaw + h * dx.yaw, x.lateral_velocity + h * dx.lateral_velocity,
          x.yaw_rate + h * dx.yaw_rate};
}

void check_positive(double value, const char* name) {
  RAILTAB_CHECK(std::isfinite(value) && value > 0.0, "wheelset simulation: {} = {}, must be > 0",
                name, value);
}

void check_non_negative(double value, const char* name) {
  RAILTAB_CHECK(std::isfinite(value) && value >= 0.0,
                "wheelset simulation: {} = {}, must be >= 0", name, value);
}

}  // namespace

double WheelsetParameters::static_wheel_load() const {
  return (mass + carried_mass) * gravity / 2.0;
}

WheelsetSimulation::WheelsetSimulation(const WheelsetParameters& parameters,
                                       const TrackLayout& track, ContactModel& contact,
                                       double speed, double time_step,
                                       const WheelsetState& initial)
    : p_(parameters), track_(&track), contact_(&contact), speed_(speed), dt_(time_step),
      state_(initial) {
  check_positive(speed, "speed");
  check_positive(time_step, "time_step");
  check_positive(p_.mass, "mass");
  check_positive(p_.yaw_inertia, "yaw_inertia");
  check_non_negative(p_.carried_mass, "carried_mass");
  check_positive(p_.nominal_radius, "nominal_radius");
  check_positive(p_.running_circle_q, "running_circle_q");
  check_positive(p_.gravity, "gravity");
  check_non_negative(p_.primary_lateral_stiffness, "primary_lateral_stiffness");
  check_non_negative(p_.primary_longitudinal_stiffness, "primary_longitudinal_stiffness");
  check_non_negative(p_.primary_lateral_damping, "primary_lateral_damping");
  check_non_negative(p_.axlebox_semi_spacing, "axlebox_semi_spacing");
  RAILTAB_CHECK(std::isfinite(p_.cg_height), "wheelset simulation: cg_height = {} is not finite",
                p_.cg_height);
  RAILTAB_CHECK(std::isfinite(p_.semi_wheelbase),
                "wheelset simulation: semi_wheelbase = {} is not finite", p_.semi_wheelbase);
  RAILTAB_CHECK(finite(initial),
                "wheelset simulation: initial state (y {}, yaw {}, lateral_velocity {}, "
                "yaw_rate {}) is not finite",
                initial.y, initial.yaw, initial.lateral_velocity, initial.yaw_rate);
  derivative(state_, 0.0, snapshot_);
}

WheelsetState WheelsetSimulation::derivative(const WheelsetState& x, double s,
                                             ContactSnapshot& out) {
  out = ContactSnapshot{};
  if (!finite(x)) {  // a diverged run: report it, never hand NaN to the contact model
    out.status = status::kInvalidInput;
    return {};
  }
  const double v = speed_;
  const double g = p_.gravity;
  const double q0 = p_.running_circle_q;
  const TrackPoint track = track_->at(s);

  // Unbalanced lateral acceleration and the quasi-static load transfer it causes.
  const double a_u = v * v * track.curvature - g * std::sin(track.cant_angle);
  const double q_static = p_.static_wheel_load();
  const double transfer = (p_.carried_mass * p_.cg_height + p_.mass * p_.nominal_radius) * a_u /
                          (2.0 * q0);
  const double q_min = kMinimumLoadFraction * q_static;
  const double q_left = std::clamp(q_static - transfer, q_min, 2.0 * q_static - q_min);
  out.load[0] = q_left;
  out.load[1] = 2.0 * q_static - q_left;  // the total stays (m + M) g
  if (std::abs(transfer) > q_static - q_min) out.status |= status::kLiftOff;

  out.y_relative = x.y - track.lateral_irregularity;
  contact_->normal(out.y_relative, out.load, out.contacts);

  // Creepages use the motion relative to the design frame (the irregularity enters through the
  // geometry only, to first order).
  out.motion.speed = v;
  out.motion.lateral_velocity = x.lateral_velocity;
  out.motion.yaw = x.yaw;
  out.motion.yaw_rate = x.yaw_rate;
  out.motion.curvature = track.curvature;
  const double torque_tolerance = kRelativeTorqueTolerance * q_static * p_.nominal_radius;
  const SpinBalance spin =
      solve_spin_speed(*contact_, out.contacts, q0, p_.nominal_radius, torque_tolerance,
                       &spin_warm_start_, out.motion, out.creepage, out.forces);
  out.status |= spin.status;

  // Contact forces on the wheelset in track axes: normal force along n = (0, -sin g, cos g),
  // creep forces along x and s = (0, cos g, sin g), spin moment about n.
  double yaw_moment = 0.0;
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
      yaw_moment += -y_c * f.fx + f.mz * std::cos(c.contact_angle);
    }
  }

  // Primary suspension to the bogie frame, which follows the design centreline rigidly; the
  // wheelset sits semi_wheelbase a ahead of its centre, so the frame's point at the wheelset is
  // at y_b = -a^2 kappa / 2 with yaw psi_b = -a kappa (local curvature).
  const double a = p_.semi_wheelbase;
  const double y_bogie = -a * a * track.curvature / 2.0;
  const double yaw_bogie = -a * track.curvature;
  const double yaw_stiffness = 2.0 * p_.primary_longitudinal_stiffness *
                               p_.axlebox_semi_spacing * p_.axlebox_semi_spacing;
  out.suspension_lateral_force = -p_.primary_lateral_stiffness * (x.y - y_bogie) -
                                 p_.primary_lateral_damping * x.lateral_velocity;
  out.suspension_yaw_moment = -yaw_stiffness * (x.yaw - yaw_bogie);
  // The carried mass's uncompensated centrifugal force reaches the wheelset through the primary
  // suspension (quasi-static: the bogie frame is a kinematic guide, not a force sink).
  out.unbalanced_lateral_force = -p_.carried_mass * a_u;

  WheelsetState dx;
  dx.y = x.lateral_velocity;
  dx.yaw = x.yaw_rate;
  dx.lateral_velocity = (out.lateral_force[0] + out.lateral_force[1] +
                         out.suspension_lateral_force + out.unbalanced_lateral_force) /
                            p_.mass -
                        a_u;
  // psi is measured from the design tangent, which turns at V kappa: its angular acceleration
  // V^2 dkappa/ds (transitions) is taken off the absolute yaw acceleration.
  dx.yaw_rate = (yaw_moment + out.suspension_yaw_moment) / p_.yaw_inertia -
                v * v * track.curvature_rate;
  return dx;
}

void WheelsetSimulation::step() {
  const double h = dt_;
  const double s = distance();
  ContactSnapshot stage;
  const WheelsetState k1 = derivative(state_, s, snapshot_);
  const WheelsetState k2 = derivative(add(state_, h / 2, k1), s + speed_ * h / 2, stage);
  const WheelsetState k3 = derivative(add(state_, h / 2, k2), s + speed_ * h / 2, stage);
  const WheelsetState k4 = derivative(add(state_, h, k3), s + speed_ * h, stage);
  WheelsetState dx;
  dx.y = (k1.y + 2 * k2.y + 2 * k3.y + k4.y) / 6;
  dx.yaw = (k1.yaw + 2 * k2.yaw + 2 * k3.yaw + k4.yaw) / 6;
  dx.lateral_velocity = (k1.lateral_velocity + 2 * k2.lateral_velocity +
                         2 * k3.lateral_velocity + k4.lateral_velocity) / 6;
  dx.yaw_rate = (k1.yaw_rate + 2 * k2.yaw_rate + 2 * k3.yaw_rate + k4.yaw_rate) / 6;
  state_ = add(state_, h, dx);
  ++steps_;
  time_ = double(steps_) * dt_;
}

double WheelsetSimulation::time() const { return time_; }
double WheelsetSimulation::distance() const { return speed_ * time_; }
const WheelsetState& WheelsetSimulation::state() const { return state_; }
const ContactSnapshot& WheelsetSimulation::snapshot() const { return snapshot_; }
const WheelsetParameters& WheelsetSimulation::parameters() const { return p_; }
double WheelsetSimulation::speed() const { return speed_; }
double WheelsetSimulation::time_step() const { return dt_; }

ContactSnapshot WheelsetSimulation::evaluate(const WheelsetState& x, double s) {
  ContactSnapshot out;
  derivative(x, s, out);
  return out;
}

double WheelsetSimulation::stable_time_step_estimate() {
  // Creep damping: the lateral force falls with y_dot through eta = y_dot / (V cos g), the yaw
  // moment with psi_dot through xi = ... - psi_dot y_c / V. Slopes of the creep law by central
  // differences at the current creepages (all slots at once: each slot's forces depend on its own
  // creepage only).
  const ContactSnapshot base = evaluate(state_, distance());
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
    contact_->creep(plus, f_plus);
    contact_->creep(minus, f_minus);
  };
  const double v = speed_;
  double lateral_damping = p_.primary_lateral_damping;  // dFy/d(y_dot) [N s/m]
  slopes(false);
  for (int w = 0; w < kWheels; ++w) {
    for (int k = 0; k < kContactSlots; ++k) {
      if (!base.contacts[w].slot[k].loaded) continue;
      lateral_damping += std::abs(f_plus[w][k].fy - f_minus[w][k].fy) / (2 * h) / v;
    }
  }
  double yaw_damping = 0.0;  // dM/d(psi_dot) [N m s]
  slopes(true);
  for (int w = 0; w < kWheels; ++w) {
    for (int k = 0; k < kContactSlots; ++k) {
      const SlotContact& c = base.contacts[w].slot[k];
      if (!c.loaded) continue;
      const double y_c = contact_lateral_position(w, c.wheel_u, p_.running_circle_q);
      yaw_damping += y_c * y_c * std::abs(f_plus[w][k].fx - f_minus[w][k].fx) / (2 * h) / v;
    }
  }
  // Lateral stiffness of the normal forces (gravitational stiffness; large in flange contact),
  // d(sum -N sin g)/dy at the same loads. Last, so the creep() calls above saw the base normal().
  auto normal_lateral_force = [&](double y) {
    WheelContacts contacts[kWheels];
    contact_->normal(y, base.load, contacts);
    double f = 0.0;
    for (const WheelContacts& wheel : contacts) {
      for (const SlotContact& c : wheel.slot) {
        if (c.loaded) f -= c.normal_force * std::sin(c.contact_angle);
      }
    }
    return f;
  };
  constexpr double dy = 1e-6;  // [m]
  const double contact_stiffness =
      (normal_lateral_force(base.y_relative - dy) - normal_lateral_force(base.y_relative + dy)) /
      (2 * dy);
  const double yaw_stiffness = 2.0 * p_.primary_longitudinal_stiffness *
                               p_.axlebox_semi_spacing * p_.axlebox_semi_spacing;
  // RK4 is stable for h lambda in [-2.785, 0] on the real axis and |h omega| <= 2.83 on the
  // imaginary one; the stiffness frequencies are included as well, in case they dominate.
  const double rate = std::max(
      {lateral_damping / p_.mass, yaw_damping / p_.yaw_inertia,
       std::sqrt(std::abs(p_.primary_lateral_stiffness + contact_stiffness) / p_.mass),
       std::sqrt(yaw_stiffness / p_.yaw_inertia)});
  return rate > 0.0 ? 2.78 / rate : INFINITY;
}

}  // namespace railtab::vehicle
