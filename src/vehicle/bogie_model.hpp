// SPDX-License-Identifier: Apache-2.0
// A bogie running at constant speed on a TrackLayout: two wheelsets (lateral and yaw each) held by
// a primary suspension to a bogie frame (lateral and yaw), the frame held by a secondary
// suspension (lateral and yaw springs and dampers) to a car body that follows the track
// quasi-statically: its pivot above the bogie centre stays on the design centreline, its yaw is
// the chord between the car's two bogie pivots, its unbalanced centrifugal force reaches the frame
// through the secondary suspension, and its weight is transferred between the wheels by the cant
// deficiency. 12 states. The wheel spin speeds follow from the torque balance (as in the
// single-wheelset model, whose contact evaluation this reuses). Equations: docs/vehicle-model.md.
#pragma once

#include <cstdint>

#include "vehicle/contact_model.hpp"
#include "vehicle/spin_balance.hpp"
#include "vehicle/track_layout.hpp"
#include "vehicle/wheelset_model.hpp"

namespace railtab::vehicle {

inline constexpr int kBogieWheelsets = 2;  // 0 = leading (ahead of the frame centre), 1 = trailing

// Defaults: a commuter-class electric multiple unit car, ASSUMED (Enblom and Berg 2008 names its vehicle
// only as "commuter car ... reasonably soft wheelset guidance"): docs/vehicle-model.md lists
// each value and why.
struct BogieParameters {
  // Each wheelset: mass, yaw inertia, primary suspension per wheelset, semi_wheelbase (> 0: the
  // wheelsets sit at +a and -a from the frame centre), r0, q0, gravity. Its carried_mass and
  // cg_height are NOT read: each wheelset carries half the frame and a quarter of the body
  // (carried_mass(), carried_cg_height()).
  WheelsetParameters wheelset = default_wheelset();
  double frame_mass = 3000.0;                 // bogie frame incl. what moves with it [kg]
  double frame_yaw_inertia = 2000.0;          // about z [kg m2]
  double frame_cg_height = 0.6;               // above the rails [m]
  double body_mass = 51600.0;                 // car body incl. payload, on two bogies [kg]
  double body_cg_height = 1.6;                // above the rails [m]
  double bogie_semi_spacing = 9.5;            // bogie centre from the car centre, + leading
                                              // bogie of the car, - trailing [m]
  double secondary_lateral_stiffness = 0.3e6; // per bogie [N/m]
  double secondary_lateral_damping = 3.0e4;   // per bogie [N s/m]
  double secondary_yaw_stiffness = 0.3e6;     // frame against body [N m/rad]
  double secondary_yaw_damping = 0.0;         // yaw dampers [N m s/rad]

  double carried_mass() const;       // per wheelset: body / 4 + frame / 2 [kg]
  double carried_cg_height() const;  // height of that carried mass [m]
  double static_wheel_load() const;  // (wheelset + carried) g / 2 [N]
  static WheelsetParameters default_wheelset();
};

// The frame uses the same four coordinates as a wheelset (y, yaw and rates relative to the
// design frame at the bogie centre); each wheelset's are relative to the design frame at its own
// position along the track.
struct BogieState {
  WheelsetState wheelset[kBogieWheelsets];
  WheelsetState frame;
};

struct BogieSnapshot {
  ContactSnapshot wheelset[kBogieWheelsets];  // suspension_* are the primary forces on it
  double secondary_lateral_force = 0.0;       // on the frame, incl. the body's unbalanced force [N]
  double secondary_yaw_moment = 0.0;          // on the frame [N m]
  std::uint32_t status = 0;                   // OR of both wheelsets' status
};

class BogieSimulation {
 public:
  // `track` and `contact` must outlive the simulation; the one contact model serves both
  // wheelsets in turn. distance() is the frame centre's position along the track, starting at
  // start_distance; the leading wheelset runs a ahead of it, so start_distance >= a keeps the
  // trailing one on the route. Throws railtab::Error naming the parameter for a non-positive or
  // non-finite speed, time step, mass, inertia, radius, q0 or semi_wheelbase, negative stiffness
  // or damping, a non-finite height or bogie_semi_spacing, start_distance < 0, or a non-finite
  // initial state. Evaluates the contact at the initial state.
  BogieSimulation(const BogieParameters& parameters, const TrackLayout& track,
                  ContactModel& contact, double speed, double time_step,
                  const BogieState& initial = {}, double start_distance = 0.0);

  void step();  // one RK4 step; snapshot() then holds the contact at its start

  double time() const;      // [s]
  double distance() const;  // frame centre along the track [m]
  double wheelset_distance(int wheelset) const;  // that wheelset along the track [m]
  const BogieState& state() const;
  const BogieSnapshot& snapshot() const;
  const BogieParameters& parameters() const;
  double speed() const;
  double time_step() const;

  // The contact at an arbitrary state and frame position, without stepping.
  BogieSnapshot evaluate(const BogieState& state, double distance);

  // Largest stable RK4 step estimate: each wheelset's creep damping and contact stiffness as in
  // WheelsetSimulation, and the frame's suspension frequencies and damping [s].
  double stable_time_step_estimate();

 private:
  BogieState derivative(const BogieState& state, double s, BogieSnapshot& snapshot);
  double wheelset_offset(int wheelset) const;  // +a, -a [m]

  BogieParameters p_;
  WheelsetParameters wheelset_;  // p_.wheelset with the carried mass and its height filled in
  const TrackLayout* track_;
  ContactModel* contact_;
  double speed_;
  double dt_;
  double start_;
  double time_ = 0.0;
  long long steps_ = 0;
  BogieState state_;
  BogieSnapshot snapshot_;
  SpinWarmStart spin_warm_start_[kBogieWheelsets];
};

}  // namespace railtab::vehicle
