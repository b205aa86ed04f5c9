// SPDX-License-Identifier: Apache-2.0
// Equations of motion of the suspended wheelset and their RK4 integration
// (docs/vehicle-model.md derives every term; the names below follow it).
#include "vehicle/wheelset_model.hpp"

#include <algorithm>
#include <cmath>

#include "core/check.hpp"
#include "core/status.hpp"
#include "vehicle/wheelset_contact.hpp"

namespace railtab::vehicle {
namespace {

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

double WheelsetParameters::primary_yaw_stiffness() const {
  return 2.0 * primary_longitudinal_stiffness * axlebox_semi_spacing * axlebox_semi_spacing;
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
  RAILTAB_CHECK(is_finite(initial),
                "wheelset simulation: initial state (y {}, yaw {}, lateral_velocity {}, "
                "yaw_rate {}) is not finite",
                initial.y, initial.yaw, initial.lateral_velocity, initial.yaw_rate);
  derivative(state_, 0.0, snapshot_);
}

WheelsetState WheelsetSimulation::derivative(const WheelsetState& x, double s,
                                             ContactSnapshot& out) {
  const TrackPoint track = track_->at(s);
  evaluate_wheelset_contact(p_, *contact_, speed_, track, x, &spin_warm_start_, out);
  if (out.status & status::kInvalidInput) return {};
  const double v = speed_;
  const double a_u = unbalanced_acceleration(track, v, p_.gravity);

  // Primary suspension to the bogie frame, which follows the design centreline rigidly; the
  // wheelset sits semi_wheelbase a ahead of its centre, so the frame's point at the wheelset is
  // at y_b = -a^2 kappa / 2 with yaw psi_b = -a kappa (local curvature).
  const double a = p_.semi_wheelbase;
  const double y_bogie = -a * a * track.curvature / 2.0;
  const double yaw_bogie = -a * track.curvature;
  out.suspension_lateral_force = -p_.primary_lateral_stiffness * (x.y - y_bogie) -
                                 p_.primary_lateral_damping * x.lateral_velocity;
  out.suspension_yaw_moment = -p_.primary_yaw_stiffness() * (x.yaw - yaw_bogie);
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
  dx.yaw_rate = (out.contact_yaw_moment + out.suspension_yaw_moment) / p_.yaw_inertia -
                v * v * track.curvature_rate;
  return dx;
}

void WheelsetSimulation::step() {
  const double h = dt_;
  const double s = distance();
  ContactSnapshot stage;
  const WheelsetState k1 = derivative(state_, s, snapshot_);
  const WheelsetState k2 = derivative(add_scaled(state_, h / 2, k1), s + speed_ * h / 2, stage);
  const WheelsetState k3 = derivative(add_scaled(state_, h / 2, k2), s + speed_ * h / 2, stage);
  const WheelsetState k4 = derivative(add_scaled(state_, h, k3), s + speed_ * h, stage);
  WheelsetState dx;
  dx.y = (k1.y + 2 * k2.y + 2 * k3.y + k4.y) / 6;
  dx.yaw = (k1.yaw + 2 * k2.yaw + 2 * k3.yaw + k4.yaw) / 6;
  dx.lateral_velocity = (k1.lateral_velocity + 2 * k2.lateral_velocity +
                         2 * k3.lateral_velocity + k4.lateral_velocity) / 6;
  dx.yaw_rate = (k1.yaw_rate + 2 * k2.yaw_rate + 2 * k3.yaw_rate + k4.yaw_rate) / 6;
  state_ = add_scaled(state_, h, dx);
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
  const ContactSnapshot base = evaluate(state_, distance());
  const WheelsetRates rates = wheelset_rates(p_, *contact_, speed_, base);
  // RK4 is stable for h lambda in [-2.785, 0] on the real axis and |h omega| <= 2.83 on the
  // imaginary one; the stiffness frequencies are included as well, in case they dominate.
  const double rate = std::max(
      {(rates.lateral_damping + p_.primary_lateral_damping) / p_.mass,
       rates.yaw_damping / p_.yaw_inertia,
       std::sqrt(std::abs(p_.primary_lateral_stiffness + rates.contact_stiffness) / p_.mass),
       std::sqrt(p_.primary_yaw_stiffness() / p_.yaw_inertia)});
  return rate > 0.0 ? 2.78 / rate : INFINITY;
}

}  // namespace railtab::vehicle
