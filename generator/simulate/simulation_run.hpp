// `railtab simulate` as a library call: the profile-evolution loop of seed 001 with the contact
// tables in the time-stepping loop. Per normal model and wear step: write the step's contact scene
// (current wheel profile, the model, the simulation speed and lubrication), generate its table in
// parallel, run one wheelset over the route for every position (leading, trailing) with the table
// (or the core directly, --direct), sample the wear once per wheel revolution, scale it to the
// step's running distance, average left/right wheels and positions, and write the worn wheel
// profile that the next step runs on. Outputs: docs/simulation.md.
#pragma once

#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "scene/simulation_scene.hpp"

namespace railtab {

struct SimulationOptions {
  std::filesystem::path out;        // output directory; results go to OUT/<scene name>/
  int threads = 0;                  // table generation threads, 0 = all cores
  bool direct = false;              // evaluate geometry + normal + FASTSIM each call, no table
  double duration = 0.0;            // > 0: simulate at most this long per run [s] (speed checks)
  std::vector<std::string> models;  // replaces the scene's models when not empty
  std::ostream* log = nullptr;      // progress lines; nullptr = silent
};

// One run of one wheelset position over the route.
struct RunSummary {
  std::string position;                    // "leading" or "trailing"
  double simulated_seconds = 0.0;          // [s]
  double distance = 0.0;                   // [m]
  double dynamics_wall_seconds = 0.0;      // wall time of the RK4 steps only [s]
  double wear_wall_seconds = 0.0;          // wall time of the wear samples [s]
  double stable_time_step_estimate = 0.0;  // smallest estimate seen along the route [s]
  double max_creep_force_ratio = 0.0;      // max over steps and slots of |(fx, fy)| / (mu N) [-]
  double max_abs_y = 0.0;                  // largest |y - irregularity| [m]
  std::uint64_t steps = 0;                 // RK4 steps [-]
  std::uint64_t queries = 0;               // table queries (lookup only) [-]
  std::uint64_t out_of_range = 0;          // of them flagged kOutOfRange [-]
  std::uint64_t invalid_input = 0;         // of them flagged kInvalidInput [-]
  std::uint64_t outside_axis[5] = {};      // per variable y, load, xi, eta, phi [-]
  std::uint64_t contact_failures = 0;      // direct model: evaluations where the core threw [-]
  int wear_samples = 0;                    // [-]
  int wear_failures = 0;                   // wear samples that failed on a wheel [-]
  double wear_clipped_area = 0.0;          // wear outside the wear grid, not added [m2]
  std::uint32_t status = 0;                // OR of the snapshot status over the run
};

struct StepSummary {
  int step = 0;                            // 0-based wear step
  double running_distance = 0.0;           // distance this step stands for [m]
  double worn_area = 0.0;                  // mean of left/right and positions, this step [m2]
  double cumulative_worn_area = 0.0;       // after this step [m2]
  double generate_seconds = 0.0;           // table generation wall time [s] (0 with --direct)
  std::vector<RunSummary> runs;            // one per position
};

struct ModelSummary {
  std::string model;                       // normal model name
  std::vector<StepSummary> steps;
  std::vector<double> u;                   // wear bin centres [m]
  std::vector<double> cumulative_depth;    // radial depth after the last step, mean [m]
  std::vector<std::vector<double>> step_cumulative_depth;  // after each step (steps x bins) [m]
  // Where the wear sits (flange at negative u): depth-weighted mean u and the deepest bin.
  double centroid_u = 0.0;                 // [m]
  double peak_u = 0.0;                     // [m]
  double peak_depth = 0.0;                 // [m]
};

struct SimulationSummary {
  std::string name;                        // scene name
  std::filesystem::path directory;         // OUT/<name>
  std::vector<ModelSummary> models;
};

// Runs everything and writes the outputs. Throws railtab::Error (or lookup::LoadError) for bad
// scenes or I/O; numerical trouble inside a run is counted in the summary, never thrown.
SimulationSummary run_simulation(const SimulationScene& scene, const SimulationOptions& options);

// Simulated seconds per wall-clock second of the RK4 loop over all runs of a summary [-].
double simulation_speed(const SimulationSummary& summary);

}  // namespace railtab
