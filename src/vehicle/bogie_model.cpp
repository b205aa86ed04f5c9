// SPDX-License-Identifier: Apache-2.0
// Equations of motion of the bogie and their RK4 integration (docs/vehicle-model.md, "The bogie";
// the names below follow it).
#include "vehicle/bogie_model.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/check.hpp"
#include "core/status.hpp"
#include "vehicle/wheelset_contact.hpp"

namespace railtab::vehicle {
namespace {

void check_positive(double value, const std::string& name) {
  RAILTAB_CHECK(std::isfinite(value) && value > 0.0, "bogie simulation: {} = {}, must be > 0",
                name, value);
}

void check_non_negative(double value, const std::string& name) {
  RAILTAB_CHECK(std::isfinite(value) && value >= 0.0, "bogie simulation: {} = {}, must be >= 0",
                name, value);
}

void check_finite(double value, const std::string& name) {
  RAILTAB_CHECK(std::isfinite(value), "bogie simulation: {} = {} is not finite", name, value);
}

BogieState add_scaled(const BogieState& x, double h, const BogieState& dx) {
  BogieState out;
  for (int i = 0; i < kBogieWheelsets; ++i) {
    out.wheelset[i] = vehicle::add_scaled(x.wheelset[i], h, dx.wheelset[i]);
  }
  out.frame = vehicle::add_scaled(x.frame, h, dx.frame);
  return out;
}

}  // namespace

WheelsetParameters BogieParameters::default_wheelset() {
  WheelsetParameters w;
  w.mass = 1500.0;
  w.yaw_inertia = 700.0;
  w.primary_lateral_stiffness = 5.0e6;
  w.primary_longitudinal_stiffness = 1.2e6;
  w.primary_lateral_damping = 0.0;
  w.axlebox_semi_spacing = 1.0;
  w.semi_wheelbase = 1.35;
  w.nominal_radius = 0.46;
  w.running_circle_q = 0.75;
  return w;
}

double BogieParameters::carried_mass() const { return body_mass / 4.0 + frame_mass / 2.0; }

double BogieParameters::carried_cg_height() const {
  const double m = carried_mass();
  return m > 0.0 ? (body_mass / 4.0 * body_cg_height + frame_mass / 2.0 * frame_cg_height) / m
                 : 0.0;
}

double BogieParameters::static_wheel_load() const {
  return (wheelset.mass + carried_mass()) * wheelset.gravity / 2.0;
}

BogieSimulation::BogieSimulation(const BogieParameters& parameters, const TrackLayout& track,
                                 ContactModel& contact, double speed, double time_step,
                                 const BogieState& initial, double start_distance)
    : p_(parameters), track_(&track), contact_(&contact), speed_(speed), dt_(time_step),
      start_(start_distance), state_(initial) {
  const WheelsetParameters& w = p_.wheelset;
  check_positive(speed, "speed");
  check_positive(time_step, "time_step");
  check_positive(w.mass, "wheelset.mass");
  check_positive(w.yaw_inertia, "wheelset.yaw_inertia");
  check_positive(w.nominal_radius, "wheelset.nominal_radius");
  check_positive(w.running_circle_q, "wheelset.running_circle_q");
  check_positive(w.gravity, "wheelset.gravity");
  check_positive(w.semi_wheelbase, "wheelset.semi_wheelbase");
  check_non_negative(w.primary_lateral_stiffness, "wheelset.primary_lateral_stiffness");
  check_non_negative(w.primary_longitudinal_stiffness, "wheelset.primary_longitudinal_stiffness");
  check_non_negative(w.primary_lateral_damping, "wheelset.primary_lateral_damping");
  check_non_negative(w.axlebox_semi_spacing, "wheelset.axlebox_semi_spacing");
  check_positive(p_.frame_mass, "frame_mass");
  check_positive(p_.frame_yaw_inertia, "frame_yaw_inertia");
  check_non_negative(p_.body_mass, "body_mass");
  check_finite(p_.frame_cg_height, "frame_cg_height");
  check_finite(p_.body_cg_height, "body_cg_height");
  check_finite(p_.bogie_semi_spacing, "bogie_semi_spacing");
  check_non_negative(p_.secondary_lateral_stiffness, "secondary_lateral_stiffness");
  check_non_negative(p_.secondary_lateral_damping, "secondary_lateral_damping");
  check_non_negative(p_.secondary_yaw_stiffness, "secondary_yaw_stiffness");
  check_non_negative(p_.secondary_yaw_damping, "secondary_yaw_damping");
  check_non_negative(start_distance, "start_distance");
  const char* names[] = {"leading wheelset", "trailing wheelset", "frame"};
  for (int i = 0; i <= kBogieWheelsets; ++i) {
    const WheelsetState& x = i < kBogieWheelsets ? initial.wheelset[i] : initial.frame;
    RAILTAB_CHECK(is_finite(x),
                  "bogie simulation: initial state of the {} (y {}, yaw {}, lateral_velocity {}, "
                  "yaw_rate {}) is not finite",
                  names[i], x.y, x.yaw, x.lateral_velocity, x.yaw_rate);
  }
  wheelset_ = w;
  wheelset_.carried_mass = p_.carried_mass();
  wheelset_.cg_height = p_.carried_cg_height();
  derivative(state_, start_, snapshot_);
}

double BogieSimulation::wheelset_offset(int i) const {
  return i == 0 ? p_.wheelset.semi_wheelbase : -p_.wheelset.semi_wheelbase;
}

BogieState BogieSimulation::derivative(const BogieState& x, double s, BogieSnapshot& out) {
  out = BogieSnapshot{};
  const double v = speed_;
  const double g = p_.wheelset.gravity;
  const TrackPoint centre = track_->at(s);
  const WheelsetState& f = x.frame;
  const double k_y = wheelset_.primary_lateral_stiffness;
  const double c_y = wheelset_.primary_lateral_damping;
  const double k_psi = wheelset_.primary_yaw_stiffness();

  BogieState dx;
  double frame_force = 0.0, frame_moment = 0.0;
  for (int i = 0; i < kBogieWheelsets; ++i) {
    const double a = wheelset_offset(i);
    const TrackPoint track = track_->at(s + a);
    ContactSnapshot& c = out.wheelset[i];
    evaluate_wheelset_contact(wheelset_, *contact_, v, track, x.wheelset[i],
                              &spin_warm_start_[i], c);
    out.status |= c.status;
    if (c.status & status::kInvalidInput) return {};
    // The frame's point above the wheelset in the design frame at the wheelset: the centreline
    // between the two points is a clothoid piece (curvature linear in s), so it turns by
    // a (kappa_0 + kappa_a) / 2 and lies a^2 (2 kappa_0 + kappa_a) / 6 to the side.
    const double y_frame = f.y + a * f.yaw - a * a * (2 * centre.curvature + track.curvature) / 6;
    const double yaw_frame = f.yaw - a * (centre.curvature + track.curvature) / 2;
    const WheelsetState& w = x.wheelset[i];
    c.suspension_lateral_force = -k_y * (w.y - y_frame) -
                                 c_y * (w.lateral_velocity - f.lateral_velocity - a * f.yaw_rate);
    c.suspension_yaw_moment = -k_psi * (w.yaw - yaw_frame);
    const double a_u = unbalanced_acceleration(track, v, g);
    dx.wheelset[i].y = w.lateral_velocity;
    dx.wheelset[i].yaw = w.yaw_rate;
    dx.wheelset[i].lateral_velocity =
        (c.lateral_force[0] + c.lateral_force[1] + c.suspension_lateral_force) /
            wheelset_.mass -
        a_u;
    dx.wheelset[i].yaw_rate =
        (c.contact_yaw_moment + c.suspension_yaw_moment) / wheelset_.yaw_inertia -
        v * v * track.curvature_rate;
    // Reactions on the frame (the small angle between the two design frames is neglected).
    frame_force -= c.suspension_lateral_force;
    frame_moment -= a * c.suspension_lateral_force + c.suspension_yaw_moment;
  }

  // Secondary suspension: the body pivot stays on the centreline and carries the body's share of
  // the unbalanced centrifugal force; the body's yaw at this bogie is that of the chord between
  // the pivots, -L kappa relative to the local tangent (L = bogie_semi_spacing, signed).
  const double a_u = unbalanced_acceleration(centre, v, g);
  const double L = p_.bogie_semi_spacing;
  const double body_yaw = -L * centre.curvature;
  const double body_yaw_rate = -L * centre.curvature_rate * v;
  out.secondary_lateral_force = -p_.secondary_lateral_stiffness * f.y -
                                p_.secondary_lateral_damping * f.lateral_velocity -
                                p_.body_mass / 2.0 * a_u;
  out.secondary_yaw_moment = -p_.secondary_yaw_stiffness * (f.yaw - body_yaw) -
                             p_.secondary_yaw_damping * (f.yaw_rate - body_yaw_rate);
  dx.frame.y = f.lateral_velocity;
  dx.frame.yaw = f.yaw_rate;
  dx.frame.lateral_velocity = (frame_force + out.secondary_lateral_force) / p_.frame_mass - a_u;
  dx.frame.yaw_rate = (frame_moment + out.secondary_yaw_moment) / p_.frame_yaw_inertia -
                      v * v * centre.curvature_rate;
  return dx;
}

void BogieSimulation::step() {
  const double h = dt_;
  const double s = distance();
  BogieSnapshot stage;
  const BogieState k1 = derivative(state_, s, snapshot_);
  const BogieState k2 = derivative(add_scaled(state_, h / 2, k1), s + speed_ * h / 2, stage);
  const BogieState k3 = derivative(add_scaled(state_, h / 2, k2), s + speed_ * h / 2, stage);
  const BogieState k4 = derivative(add_scaled(state_, h, k3), s + speed_ * h, stage);
  // x + h (k1 + 2 k2 + 2 k3 + k4) / 6, summed in the same order as the wheelset model.
  BogieState sum = add_scaled(add_scaled(add_scaled(k1, 2.0, k2), 2.0, k3), 1.0, k4);
  state_ = add_scaled(state_, h / 6, sum);
  ++steps_;
  time_ = double(steps_) * dt_;
}

double BogieSimulation::time() const { return time_; }
double BogieSimulation::distance() const { return start_ + speed_ * time_; }
double BogieSimulation::wheelset_distance(int i) const { return distance() + wheelset_offset(i); }
const BogieState& BogieSimulation::state() const { return state_; }
const BogieSnapshot& BogieSimulation::snapshot() const { return snapshot_; }
const BogieParameters& BogieSimulation::parameters() const { return p_; }
double BogieSimulation::speed() const { return speed_; }
double BogieSimulation::time_step() const { return dt_; }

BogieSnapshot BogieSimulation::evaluate(const BogieState& x, double s) {
  BogieSnapshot out;
  derivative(x, s, out);
  return out;
}

double BogieSimulation::stable_time_step_estimate() {
  const BogieSnapshot base = evaluate(state_, distance());
  const double k_y = wheelset_.primary_lateral_stiffness;
  const double k_psi = wheelset_.primary_yaw_stiffness();
  const double a = wheelset_.semi_wheelbase;
  double rate = 0.0;
  for (const ContactSnapshot& c : base.wheelset) {
    const WheelsetRates r = wheelset_rates(wheelset_, *contact_, speed_, c);
    rate = std::max({rate, (r.lateral_damping + wheelset_.primary_lateral_damping) / wheelset_.mass,
                     r.yaw_damping / wheelset_.yaw_inertia,
                     std::sqrt(std::abs(k_y + r.contact_stiffness) / wheelset_.mass),
                     std::sqrt(k_psi / wheelset_.yaw_inertia)});
  }
  // The frame on both wheelsets' primary springs and the secondary suspension.
  const double mf = p_.frame_mass, jf = p_.frame_yaw_inertia;
  rate = std::max({rate,
                   (2 * wheelset_.primary_lateral_damping + p_.secondary_lateral_damping) / mf,
                   (2 * a * a * wheelset_.primary_lateral_damping + p_.secondary_yaw_damping) / jf,
                   std::sqrt((2 * k_y + p_.secondary_lateral_stiffness) / mf),
                   std::sqrt((2 * (k_y * a * a + k_psi) + p_.secondary_yaw_stiffness) / jf)});
  return rate > 0.0 ? 2.78 / rate : INFINITY;
}

}  // namespace railtab::vehicle
