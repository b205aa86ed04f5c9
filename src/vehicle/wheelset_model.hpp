// SPDX-License-Identifier: Apache-2.0
// A single wheelset running at constant speed on a TrackLayout, held by a primary suspension
// (lateral and longitudinal springs, lateral dampers) to a bogie frame that follows the track's
// design centreline rigidly. Degrees of freedom: lateral displacement y and yaw psi (relative to
// the design frame). The wheel spin speed is not a degree of freedom: it follows from the torque
// balance of the longitudinal creep forces about the axle (its time constant, ~1 ms, is far below
// the lateral dynamics). Equations: docs/vehicle-model.md.
#pragma once

#include <cstdint>

#include "vehicle/contact_model.hpp"
#include "vehicle/kinematics.hpp"
#include "vehicle/spin_balance.hpp"
#include "vehicle/track_layout.hpp"

namespace railtab::vehicle {

struct WheelsetParameters {
  double mass = 1500.0;                 // wheelset mass [kg]
  double yaw_inertia = 700.0;           // about z [kg m2]
  double carried_mass = 6500.0;         // sprung mass (bogie + car body share) per wheelset [kg]
  double cg_height = 1.5;               // height of the carried mass above the rails [m]
  double primary_lateral_stiffness = 5.0e6;       // total of both axleboxes [N/m]
  double primary_longitudinal_stiffness = 5.0e6;  // per axlebox [N/m]
  double primary_lateral_damping = 0.0;           // total [N s/m]
  double axlebox_semi_spacing = 1.0;    // lateral half-distance of the axlebox springs [m]
  double semi_wheelbase = 1.25;         // distance of the wheelset ahead of the bogie centre,
                                        // + leading, - trailing [m]
  double nominal_radius = 0.46;         // r0 [m]
  double running_circle_q = 0.75;       // running circle's lateral distance from the centre [m]
  double gravity = 9.81;                // [m/s2]

  double static_wheel_load() const;     // (mass + carried_mass) g / 2 [N]
  double primary_yaw_stiffness() const; // 2 k_x b_x^2 [N m/rad]
};

struct WheelsetState {
  double y = 0.0;                 // lateral displacement from the design centreline, + left [m]
  double yaw = 0.0;               // psi [rad]
  double lateral_velocity = 0.0;  // [m/s]
  double yaw_rate = 0.0;          // [rad/s]
};

// Everything about the contact at one evaluation of the equations of motion.
struct ContactSnapshot {
  double y_relative = 0.0;        // y - lateral irregularity: the lookup's y [m]
  double load[kWheels] = {};      // vertical wheel loads [N]
  WheelContacts contacts[kWheels];
  SlotCreepage creepage[kWheels][kContactSlots];
  SlotForces forces[kWheels][kContactSlots];
  WheelsetMotion motion;          // incl. the spin speed from the torque balance
  double lateral_force[kWheels] = {};  // track-y force of each wheel's contacts on the wheelset [N]
  double contact_yaw_moment = 0.0;        // sum of the contacts' moments about z [N m]
  double suspension_lateral_force = 0.0;  // [N]
  double suspension_yaw_moment = 0.0;     // [N m]
  double unbalanced_lateral_force = 0.0;  // carried mass's uncompensated centrifugal force [N]
  std::uint32_t status = 0;       // OR of every slot's normal and creep status
};

class WheelsetSimulation {
 public:
  // `track` and `contact` must outlive the simulation. Throws railtab::Error for non-positive or
  // non-finite speed, time step, masses or inertias (carried_mass may be 0), radius or
  // running_circle_q, for negative stiffness or damping, and for a non-finite initial state.
  // Evaluates the contact at the initial state, so snapshot() is valid before the first step.
  WheelsetSimulation(const WheelsetParameters& parameters, const TrackLayout& track,
                     ContactModel& contact, double speed, double time_step,
                     const WheelsetState& initial = {});

  // One classical Runge-Kutta (RK4) step of time_step; the contact model is called at each of the
  // four stages. Afterwards snapshot() holds the contact at the start of the step.
  void step();

  double time() const;          // [s]
  double distance() const;      // s along the centreline = V t [m]
  const WheelsetState& state() const;
  const ContactSnapshot& snapshot() const;  // contact at the start of the last step
  const WheelsetParameters& parameters() const;
  double speed() const;
  double time_step() const;

  // Largest stable RK4 step estimated from the linear creep damping of the current contact
  // (2.78 / lambda_max, lambda = creep damping / inertia of the lateral and yaw motion), or from
  // the lateral (suspension + normal-force) and yaw stiffness frequencies when those are higher
  // (docs/vehicle-model.md) [s]. Calls normal() and creep() a few times; the next step() starts
  // with a fresh normal().
  double stable_time_step_estimate();

  // The contact at an arbitrary state and distance, without stepping (for output and the wear
  // post-processing).
  ContactSnapshot evaluate(const WheelsetState& state, double distance);

 private:
  // d(state)/dt at (state, s); fills `snapshot`.
  WheelsetState derivative(const WheelsetState& state, double s, ContactSnapshot& snapshot);

  WheelsetParameters p_;
  const TrackLayout* track_;
  ContactModel* contact_;
  double speed_;
  double dt_;
  double time_ = 0.0;
  long long steps_ = 0;  // time = steps * time_step (no accumulated round-off)
  WheelsetState state_;
  ContactSnapshot snapshot_;
  SpinWarmStart spin_warm_start_;  // the last spin balance, to start the next one close
};

}  // namespace railtab::vehicle
