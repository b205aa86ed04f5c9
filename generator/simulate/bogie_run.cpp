// SPDX-License-Identifier: Apache-2.0
// One bogie run over a route with the dynamics' contact model, feeding every wear post-processor.
#include "simulate/bogie_run.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "core/check.hpp"
#include "scene/scene.hpp"
#include "simulate/direct_contact_model.hpp"
#include "simulate/lookup_contact_model.hpp"
#include "table/interrupt.hpp"
#include "table/output_file.hpp"

namespace railtab {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double slot_force_ratio(const vehicle::ContactSnapshot& snap, double mu) {
  double worst = 0.0;
  for (int w = 0; w < vehicle::kWheels; ++w) {
    for (int s = 0; s < vehicle::kContactSlots; ++s) {
      const vehicle::SlotContact& c = snap.contacts[w].slot[s];
      if (!c.loaded) continue;
      const double f = std::hypot(snap.forces[w][s].fx, snap.forces[w][s].fy);
      worst = std::max(worst, f / (mu * c.normal_force));
    }
  }
  return worst;
}

const char* kWheelsetNames[vehicle::kBogieWheelsets] = {"leading", "trailing"};

bool finite(const vehicle::WheelsetState& s) {
  return std::isfinite(s.y) && std::isfinite(s.yaw) && std::isfinite(s.lateral_velocity) && std::isfinite(s.yaw_rate);
}

// The scene's file for messages (its name when it was parsed from a string).
std::string scene_label(const SimulationScene& sim) { return sim.path.empty() ? sim.name : sim.path.string(); }

// Throws naming the scene, the step and the time when the last RK4 step left the physics: a
// state that is not finite or a wheelset off the rail head. Without this the run went on with
// nonsense (a "wear sample: speed must be > 0" error, or a worn profile from garbage states).
void check_not_blown_up(const SimulationScene& sim, const vehicle::BogieSimulation& bogie, std::uint64_t step,
                        double stable_estimate) {
  const vehicle::BogieState& x = bogie.state();
  const vehicle::BogieSnapshot& snap = bogie.snapshot();
  for (int i = 0; i < vehicle::kBogieWheelsets; ++i) {
    const double y = snap.wheelset[i].y_relative;
    if (finite(x.wheelset[i]) && finite(x.frame) && std::abs(y) <= kMaxLateralShift) continue;
    throw Error(fmt::format(
        "{}: the dynamics blew up at t = {:.4f} s (RK4 step {}, {:.2f} m along the route): {} wheelset y = {:.4g} m "
        "relative to the track, yaw = {:.4g} rad (|y| beyond {} m is off the rail head); simulation.time_step = {} s{}: "
        "lower time_step or check [vehicle]",
        scene_label(sim), bogie.time(), step + 1, bogie.distance(), kWheelsetNames[i], y, x.wheelset[i].yaw,
        kMaxLateralShift, sim.time_step,
        stable_estimate > 0.0 && std::isfinite(stable_estimate)
            ? fmt::format(" against a stable-step estimate of {:.3g} s", stable_estimate)
            : std::string()));
  }
}

std::string trajectory_header() {
  std::string h = "s_m,t_s,frame_y_m,frame_yaw_rad";
  for (const char* w : kWheelsetNames) {
    h += fmt::format(
        ",{0}_y_m,{0}_yaw_rad,{0}_y_relative_m,{0}_load_left_N,{0}_load_right_N,"
        "{0}_n_left_tread_N,{0}_n_left_flange_N,{0}_n_right_tread_N,{0}_n_right_flange_N,"
        "{0}_angle_left_tread_rad,{0}_angle_left_flange_rad,{0}_angle_right_tread_rad,{0}_angle_right_flange_rad,"
        "{0}_fy_left_tread_N,{0}_fy_left_flange_N,{0}_fy_right_tread_N,{0}_fy_right_flange_N,"
        "{0}_lateral_force_left_N,{0}_lateral_force_right_N,{0}_status",
        w);
  }
  return h + "\n";
}

std::string trajectory_part(const vehicle::WheelsetState& x, const vehicle::ContactSnapshot& snap) {
  const auto& c = snap.contacts;
  return fmt::format(
      ",{:.6e},{:.6e},{:.6e},{:.1f},{:.1f},{:.1f},{:.1f},{:.1f},{:.1f},{:.5f},{:.5f},{:.5f},{:.5f},"
      "{:.1f},{:.1f},{:.1f},{:.1f},{:.1f},{:.1f},{}",
      x.y, x.yaw, snap.y_relative, snap.load[0], snap.load[1], c[0].slot[0].normal_force, c[0].slot[1].normal_force,
      c[1].slot[0].normal_force, c[1].slot[1].normal_force, c[0].slot[0].contact_angle, c[0].slot[1].contact_angle,
      c[1].slot[0].contact_angle, c[1].slot[1].contact_angle, snap.forces[0][0].fy, snap.forces[0][1].fy,
      snap.forces[1][0].fy, snap.forces[1][1].fy, snap.lateral_force[0], snap.lateral_force[1], snap.status);
}

}  // namespace

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

WheelsetSample wheelset_sample(int wheelset, const vehicle::ContactSnapshot& snapshot, double distance) {
  WheelsetSample s;
  s.wheelset = wheelset;
  s.y_relative = snapshot.y_relative;
  for (int w = 0; w < vehicle::kWheels; ++w) {
    for (int k = 0; k < vehicle::kContactSlots; ++k) {
      const vehicle::SlotContact& c = snapshot.contacts[w].slot[k];
      if (!c.loaded) continue;
      // The dynamics' normal force at its creepage where the contact model couples the load
      // (load coupling), so the post-processor's patches carry the same N as the dynamics' ones.
      const double f_n = snapshot.forces[w][k].normal_force;
      s.load[w] += (f_n > 0.0 ? f_n : c.normal_force) * std::cos(c.contact_angle);
    }
  }
  s.motion = snapshot.motion;
  s.distance = distance;
  return s;
}

WearPostProcessing::WearPostProcessing(const Scene& scene, const std::vector<std::string>& post_processors,
                                       const std::vector<std::string>& positions, const WearGrid& grid,
                                       int halfspace_every)
    : post_processors_(post_processors), positions_(positions) {
  RAILTAB_CHECK(halfspace_every >= 1, "half-space sample stride must be >= 1, got {}", halfspace_every);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const std::string& p = positions[i];
    RAILTAB_CHECK(p == "leading" || p == "trailing", "wear position '{}': expected \"leading\" or \"trailing\"", p);
    position_of_wheelset_[p == "leading" ? 0 : 1] = static_cast<int>(i);
  }
  for (const std::string& name : post_processors) {
    every_.push_back(name == "halfspace" ? halfspace_every : 1);
    for (std::size_t i = 0; i < positions.size(); ++i) {
      accumulators_.push_back(std::make_unique<WearAccumulator>(scene, name, grid));
    }
  }
}

bool WearPostProcessing::counts(int wheelset) const {
  return wheelset >= 0 && wheelset < 2 && position_of_wheelset_[static_cast<std::size_t>(wheelset)] >= 0;
}

void WearPostProcessing::sample(const WheelsetSample& sample) {
  if (!counts(sample.wheelset)) return;
  const auto t0 = Clock::now();
  if (record_) record_->push_back(sample);
  const auto position = static_cast<std::size_t>(position_of_wheelset_[static_cast<std::size_t>(sample.wheelset)]);
  const long n = seen_[static_cast<std::size_t>(sample.wheelset)]++;
  for (std::size_t p = 0; p < post_processors_.size(); ++p) {
    if (n % every_[p] != 0) continue;  // a sampled post-processor: this sample stands for `every` of them
    accumulator(p, position).sample(sample.y_relative, sample.load, sample.motion,
                                    sample.distance * every_[p]);
  }
  wall_seconds_ += seconds_since(t0);
}

WearAccumulator& WearPostProcessing::accumulator(std::size_t post_processor, std::size_t position) {
  RAILTAB_CHECK(post_processor < post_processors_.size() && position < positions_.size(),
                "wear accumulator ({}, {}) out of range", post_processor, position);
  return *accumulators_[post_processor * positions_.size() + position];
}

RunSummary run_bogie(const SimulationScene& sim, vehicle::ContactModel& contact, const LookupContactModel* lookup,
                     const DirectContactModel* direct, double friction, double max_duration,
                     const fs::path& trajectory_csv, WearPostProcessing& wear,
                     const std::atomic<bool>* interrupt) {
  const vehicle::TrackLayout track(sim.route, sim.irregularity, sim.rail_centre_distance);
  vehicle::BogieParameters parameters = sim.vehicle;
  const double a = parameters.wheelset.semi_wheelbase;
  RAILTAB_CHECK(track.length() > 2.0 * a, "route of {} m is shorter than the bogie's wheelbase {} m", track.length(),
                2.0 * a);
  vehicle::BogieState initial;
  initial.wheelset[0].y = initial.wheelset[1].y = initial.frame.y = sim.initial_y;
  vehicle::BogieSimulation bogie(parameters, track, contact, sim.speed, sim.time_step, initial, a);
  const LookupCounts counts_before = lookup ? lookup->counts() : LookupCounts{};
  const std::uint64_t failures_before = direct ? direct->failures() : 0;
  const double wear_before = wear.wall_seconds();

  RunSummary r;
  double duration = (track.length() - 2.0 * a) / sim.speed;
  if (max_duration > 0.0) duration = std::min(duration, max_duration);
  const double step_count = std::round(duration / sim.time_step);
  RAILTAB_CHECK(step_count <= kMaxDynamicsSteps, "{}: simulation.time_step: {} s over {} s is {:.3g} RK4 steps, above "
                "the limit of {:.0e}", scene_label(sim), sim.time_step, duration, step_count, kMaxDynamicsSteps);
  const auto steps = static_cast<std::uint64_t>(step_count);
  const double revolution = 2.0 * std::numbers::pi * parameters.wheelset.nominal_radius;
  double next_row = 0.0, next_estimate = 0.0;
  double next_wear[vehicle::kBogieWheelsets] = {0.0, 0.0};
  r.stable_time_step_estimate = std::numeric_limits<double>::infinity();

  std::ostringstream csv;
  csv << trajectory_header();
  for (std::uint64_t k = 0; k < steps; ++k) {
    if (interrupt && interrupt->load(std::memory_order_relaxed)) {
      throw Interrupted(fmt::format("interrupted at t = {:.3f} s of {:.3f} s: {} not written", bogie.time(), duration,
                                    trajectory_csv.string()));
    }
    const vehicle::BogieState before = bogie.state();
    const auto t0 = Clock::now();
    bogie.step();
    r.dynamics_wall_seconds += seconds_since(t0);
    ++r.steps;
    check_not_blown_up(sim, bogie, k, r.stable_time_step_estimate);
    const vehicle::BogieSnapshot& snap = bogie.snapshot();
    const double travelled = bogie.distance() - a - sim.speed * sim.time_step;  // the snapshot's, from the start
    r.status |= snap.status;
    for (int i = 0; i < vehicle::kBogieWheelsets; ++i) {
      const vehicle::ContactSnapshot& w = snap.wheelset[i];
      r.max_creep_force_ratio = std::max(r.max_creep_force_ratio, slot_force_ratio(w, friction));
      r.max_abs_y[i] = std::max(r.max_abs_y[i], std::abs(w.y_relative));
      r.max_abs_yaw[i] = std::max(r.max_abs_yaw[i], std::abs(before.wheelset[i].yaw));
      for (int side = 0; side < vehicle::kWheels; ++side) {
        if (w.load[side] > 0.0) r.max_y_over_q[i] = std::max(r.max_y_over_q[i], std::abs(w.lateral_force[side]) / w.load[side]);
      }
      if (wear.counts(i) && travelled >= next_wear[i]) {
        try {
          wear.sample(wheelset_sample(i, w, revolution));
        } catch (const Error& e) {
          throw Error(fmt::format("{}: t = {:.4f} s (RK4 step {}), {} wheelset: {}", scene_label(sim), bogie.time(),
                                  k + 1, kWheelsetNames[i], e.what()));
        }
        next_wear[i] += revolution;
      }
    }
    if (travelled >= next_estimate) {  // every 50 m: the contact stiffens in the curve
      r.stable_time_step_estimate = std::min(r.stable_time_step_estimate, bogie.stable_time_step_estimate());
      next_estimate += 50.0;
    }
    if (travelled >= next_row) {
      csv << fmt::format("{:.3f},{:.5f},{:.6e},{:.6e}", bogie.distance() - sim.speed * sim.time_step,
                         bogie.time() - sim.time_step, before.frame.y, before.frame.yaw);
      for (int i = 0; i < vehicle::kBogieWheelsets; ++i) csv << trajectory_part(before.wheelset[i], snap.wheelset[i]);
      csv << "\n";
      next_row += sim.trajectory_interval;
    }
  }
  write_text_file(trajectory_csv, csv.str());  // through a locked, synced temporary (table/output_file.hpp)

  r.simulated_seconds = bogie.time();
  r.distance = bogie.distance() - a;
  r.wear_wall_seconds = wear.wall_seconds() - wear_before;
  if (!wear.post_processors().empty() && !wear.positions().empty()) r.wear_samples = wear.accumulator(0, 0).samples();
  if (!std::isfinite(r.stable_time_step_estimate)) r.stable_time_step_estimate = 0.0;
  if (lookup) {
    const LookupCounts& now = lookup->counts();
    r.queries = now.queries - counts_before.queries;
    r.out_of_range = now.out_of_range - counts_before.out_of_range;
    r.invalid_input = now.invalid_input - counts_before.invalid_input;
    for (std::size_t v = 0; v < kLookupVariables; ++v) r.outside_axis[v] = now.outside_axis[v] - counts_before.outside_axis[v];
  }
  if (direct) r.contact_failures = direct->failures() - failures_before;
  r.yaw_axis = (lookup && lookup->has_yaw_axis()) || (direct && direct->has_yaw_axis());
  return r;
}

}  // namespace railtab
