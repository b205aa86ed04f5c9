// SPDX-License-Identifier: Apache-2.0
// `railtab simulate` as a library call: the profile-evolution loop of Enblom and Berg 2008 with the contact
// tables in the time-stepping loop and the dynamics separated from the wear. Per wear step: write
// the step's contact scene (current wheel profile, the DYNAMICS' normal model, the simulation
// speed and lubrication), generate its table in parallel, run the bogie over the route with it (or
// the core directly, --direct), hand each counted wheelset's state once per wheel revolution to
// every wear post-processor (the same states for all: Enblom and Berg 2008 changed only the wear model),
// scale the wear to the step's running distance, average left/right wheels and wheelsets, and
// write the worn wheel profile that the next step runs on. Step 0 is one shared run; later steps
// run each post-processor on its own worn wheel. Outputs: docs/simulation.md.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "scene/simulation_scene.hpp"
#include "simulate/bogie_run.hpp"

namespace railtab {

// Wear at u below this lies on the flange root and flange (S1002: the flange root starts about
// 25 mm from the running circle) [m].
inline constexpr double kFlangeRootU = -0.025;

struct SimulationOptions {
  std::filesystem::path out;        // output directory; results go to OUT/<scene name>/
  int threads = 0;                  // table generation threads, 0 = all cores
  bool direct = false;              // evaluate geometry + normal + FASTSIM each call, no table
  double duration = 0.0;            // > 0: simulate at most this long per run [s] (speed checks)
  std::vector<std::string> post_processors;  // replaces the scene's wear post-processors when not empty
  // Not empty: every step's contact scene gets [grid] yaw = these nodes [rad], so the tables have a
  // yaw axis and the dynamics reads each wheelset's yaw from them (the yaw-free run's comparison).
  std::vector<double> yaw_nodes;
  std::ostream* log = nullptr;      // progress lines; nullptr = silent
  // Set = stop (Ctrl-C, SIGTERM): run_simulation throws Interrupted; every file already written is
  // whole (written through a temporary), the one in progress is not left behind.
  const std::atomic<bool>* interrupt = nullptr;
};

struct StepSummary {
  int step = 0;                            // 0-based wear step
  double running_distance = 0.0;           // distance this step stands for [m] (less than
                                           // running_distance / wear_steps when depth-limited)
  double profile_peak_depth = 0.0;         // largest depth of this step's profile update: the
                                           // mean depth smoothed as the worn profile [m]
  bool depth_limited = false;              // the step was shortened by step_depth_limit
  double worn_area = 0.0;                  // mean of left/right and positions, this step [m2]
  double cumulative_worn_area = 0.0;       // after this step [m2]
  double generate_seconds = 0.0;           // table generation wall time [s] (0 with --direct)
  std::vector<RunSummary> runs;            // the dynamics run this step's wear came from
  int wear_failures = 0;                   // wear samples that failed on a wheel [-]
  int wear_not_converged = 0;              // wheel solves of the wear flagged not_converged [-]
  std::uint32_t wear_status = 0;           // OR of the wear solves' status bits
  double wear_clipped_area = 0.0;          // wear outside the wear grid, not added [m2]
};

// One wear post-processor's results.
struct ModelSummary {
  std::string model;                       // post-processor name (wheel_wear.hpp)
  std::vector<StepSummary> steps;
  double running_distance = 0.0;           // distance covered by all steps [m]
  std::vector<double> u;                   // wear bin centres [m]
  std::vector<double> cumulative_depth;    // radial depth after the last step, mean [m]
  std::vector<std::vector<double>> step_cumulative_depth;  // after each step (steps x bins) [m]
  // Where the wear sits (flange at negative u): depth-weighted mean u and the deepest bin.
  double centroid_u = 0.0;                 // [m]
  double peak_u = 0.0;                     // [m]
  double peak_depth = 0.0;                 // [m]
  double flange_side_share = 0.0;          // share of the worn area at u < 0 [-]
  double flange_root_share = 0.0;          // share at u < kFlangeRootU [-]
};

struct SimulationSummary {
  std::string name;                        // scene name
  std::filesystem::path directory;         // OUT/<name>
  std::string dynamics_model;              // normal model of the dynamics' tables
  std::vector<ModelSummary> models;        // one per wear post-processor
  std::vector<RunSummary> runs;            // every dynamics run (step 0 once)
};

// Runs everything and writes the outputs. Throws railtab::Error (or lookup::LoadError) for bad
// scenes or I/O; numerical trouble inside a run is counted in the summary, never thrown.
SimulationSummary run_simulation(const SimulationScene& scene, const SimulationOptions& options);

// Simulated seconds per wall-clock second of the RK4 loop over all runs of a summary [-].
double simulation_speed(const SimulationSummary& summary);

}  // namespace railtab
