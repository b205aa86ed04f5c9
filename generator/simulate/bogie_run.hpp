// SPDX-License-Identifier: Apache-2.0
// One run of the bogie over a simulation scene's route with the dynamics' contact model (a table
// or the core directly), and the wear post-processing it feeds: once per wheel revolution each
// counted wheelset's state goes, as ONE WheelsetSample, to every wear post-processor (Enblom and Berg 2008:
// one dynamics, the wear models differ only in the contact model). docs/simulation.md.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "scene/simulation_scene.hpp"
#include "simulate/lookup_contact_model.hpp"  // kLookupVariables
#include "simulate/wear_accumulator.hpp"
#include "vehicle/bogie_model.hpp"

namespace railtab {

class DirectContactModel;

// The state a wear post-processor works from: the dynamics' wheelset at one wheel revolution.
struct WheelsetSample {
  int wheelset = 0;                          // 0 leading, 1 trailing wheelset of the bogie
  double y_relative = 0.0;                   // lateral displacement relative to the rails [m]
  // Wheel load the dynamics' contacts carry [N]: sum of N cos(g) (N at the creepage with the load
  // coupling).
  double load[vehicle::kWheels] = {};
                                             // over the wheel's slots [N]
  vehicle::WheelsetMotion motion;            // incl. the balanced spin speed
  double distance = 0.0;                     // rolled distance the sample stands for [m]
};

// The sample of wheelset `wheelset` at `snapshot`.
WheelsetSample wheelset_sample(int wheelset, const vehicle::ContactSnapshot& snapshot, double distance);

// One accumulator per (post-processor, counted wheelset), all fed from the same samples.
class WearPostProcessing {
 public:
  // `scene`: the contact scene of the wheel profile the dynamics runs on. `positions`: the
  // wheelsets whose wear is kept ("leading", "trailing"). `halfspace_every`: the "halfspace"
  // post-processor gets only every k-th sample of each wheelset (the 1st, k+1-th, ...), with k
  // times its distance (SimulationScene::halfspace_sample_every). Throws railtab::Error for an
  // unknown post-processor or position.
  WearPostProcessing(const Scene& scene, const std::vector<std::string>& post_processors,
                     const std::vector<std::string>& positions, const WearGrid& grid = {},
                     int halfspace_every = 1);

  bool counts(int wheelset) const;            // is this wheelset's wear kept?
  void sample(const WheelsetSample& sample);  // to every post-processor's accumulator
  // Every sample handed on, in order (for checks; off unless asked).
  void record_samples(std::vector<WheelsetSample>* record) { record_ = record; }

  const std::vector<std::string>& post_processors() const { return post_processors_; }
  const std::vector<std::string>& positions() const { return positions_; }
  // accumulator(p, i): post-processor p, i-th entry of positions().
  WearAccumulator& accumulator(std::size_t post_processor, std::size_t position);
  double wall_seconds() const { return wall_seconds_; }

 private:
  std::vector<std::string> post_processors_;
  std::vector<std::string> positions_;
  std::array<int, 2> position_of_wheelset_{-1, -1};  // index into positions_, -1 = not kept
  std::vector<std::unique_ptr<WearAccumulator>> accumulators_;  // post_processor-major
  std::vector<int> every_;                    // per post-processor: sample stride [-]
  std::array<long, 2> seen_{0, 0};            // samples handed on per wheelset
  std::vector<WheelsetSample>* record_ = nullptr;
  double wall_seconds_ = 0.0;
};

// One bogie run over the route (the dynamics of one wear step).
struct RunSummary {
  std::string label;                       // "shared" (step 0, every post-processor) or the post-processor
  double simulated_seconds = 0.0;          // [s]
  double distance = 0.0;                   // frame centre's distance run [m]
  double dynamics_wall_seconds = 0.0;      // wall time of the RK4 steps only [s]
  double wear_wall_seconds = 0.0;          // wall time of the wear samples [s]
  double stable_time_step_estimate = 0.0;  // smallest estimate seen along the route [s]
  double max_creep_force_ratio = 0.0;      // max over steps, wheelsets and slots of |(fx, fy)| / (mu N) [-]
  double max_abs_y[vehicle::kBogieWheelsets] = {};  // largest |y - irregularity| per wheelset [m]
  double max_abs_yaw[vehicle::kBogieWheelsets] = {};  // largest |psi| per wheelset [rad]
  // Largest |Y| / Q per wheelset over its two wheels: Y the contact's lateral force on the wheel
  // (track axes), Q the wheel's vertical load [-].
  double max_y_over_q[vehicle::kBogieWheelsets] = {};
  bool yaw_axis = false;                   // the contact model follows the wheelsets' yaw (its table
                                           //   or, --direct, its scene has a yaw axis)
  std::uint64_t steps = 0;                 // RK4 steps [-]
  std::uint64_t queries = 0;               // table queries (lookup only) [-]
  std::uint64_t out_of_range = 0;          // of them flagged kOutOfRange [-]
  std::uint64_t invalid_input = 0;         // of them flagged kInvalidInput [-]
  std::uint64_t outside_axis[kLookupVariables] = {};  // per variable y, load, xi, eta, phi, yaw [-]
  std::uint64_t contact_failures = 0;      // direct model: evaluations where the core threw [-]
  int wear_samples = 0;                    // samples per counted wheelset [-]
  std::uint32_t status = 0;                // OR of the snapshot status over the run
};

// Runs the bogie of `sim` from rest on the design line (initial_y on every body) with its
// centre starting a semi-wheelbase into the route until the trailing wheelset reaches the end
// (or `max_duration` > 0 s), RK4 at sim.time_step. Samples every counted wheelset once per wheel
// revolution into `wear`; writes the trajectory (every sim.trajectory_interval) to
// `trajectory_csv`. `lookup` / `direct` (either may be null) are `contact` seen as what it is,
// for the counters. `interrupt` (may be null) is polled every RK4 step: set, the run throws
// Interrupted before writing the trajectory (a direct run takes hours; Ctrl-C must not wait).
// Wall seconds since `start` (the runs' timings in their summaries).
double seconds_since(std::chrono::steady_clock::time_point start);

RunSummary run_bogie(const SimulationScene& sim, vehicle::ContactModel& contact, const LookupContactModel* lookup,
                     const DirectContactModel* direct, double friction, double max_duration,
                     const std::filesystem::path& trajectory_csv, WearPostProcessing& wear,
                     const std::atomic<bool>* interrupt = nullptr);

}  // namespace railtab
