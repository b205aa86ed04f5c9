// SPDX-License-Identifier: Apache-2.0
// A simulation scene for `railtab simulate`: which contact scene, the contact model of the
// dynamics and the wear post-processors (Enblom and Berg 2008: one dynamics, several wear models), the
// vehicle (a bogie of vehicle::BogieParameters), the route (tangent, transition and circular
// sections, lateral irregularity) and the wear loop (steps, running distance, lubrication,
// smoothing). TOML, checked key by key like the contact scenes; docs/simulation.md.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "vehicle/track_layout.hpp"
#include "vehicle/bogie_model.hpp"

namespace railtab {

// Limits of a simulation scene (docs/simulation.md): a run must end and its wear stay physical.
inline constexpr double kMinTimeStep = 1e-6;            // [s]: 1000x below the RK4 steps that run
inline constexpr double kMaxDynamicsSteps = 1e8;        // RK4 steps of one run over the route [-]
inline constexpr double kMaxRunningDistance = 1e9;      // [m]: 1e6 km, beyond any wheel's life
inline constexpr double kMaxProfileUpdateDepth = 0.01;  // [m]: one wear step's deepest profile update

struct SimulationScene {
  std::string name;                        // [simulation] name (default: the file's stem)
  std::string description;                 // [simulation] description
  std::filesystem::path path;              // where it was read from (empty when parsed from a string)
  std::filesystem::path contact_scene;     // contact scene (docs/scenes.md), resolved against the file
  std::string dynamics_model = "hertz";    // normal model of the dynamics' table (as Gensys: Hertz)
  std::vector<std::string> wear_post_processors;  // wear contact models (wheel_wear.hpp names)
  std::vector<std::string> positions;      // wheelsets of the bogie whose wear counts: "leading"
                                           // and/or "trailing"
  double speed = 0.0;                      // forward speed [m/s]
  double time_step = 0.5e-3;               // fixed RK4 step [s]
  double initial_y = 0.0;                  // wheelset lateral displacement at the start [m]
  int wear_steps = 1;                      // profile updates over the running distance [-]
  double running_distance = 0.0;           // total distance the wear stands for [m]
  double lubrication_factor = 5.5;         // k_dry divisor: 5.5 natural, 11 lubricated [-]
  double profile_smoothing = 0.0;          // moving-average length of the wear depth [m]
  double step_depth_limit = 0.0;           // > 0: a wear step ends where the smoothed mean
                                           // depth of its profile update reaches this, at most
                                           // running_distance / wear_steps; 0 = fixed steps [m]
  int halfspace_sample_every = 1;          // the "halfspace" post-processor sees every k-th wear
                                           // sample, standing for k revolutions (its solves are
                                           // ~1000x slower than the others'); 1 = all [-]
  double trajectory_interval = 0.5;        // distance between trajectory CSV rows [m]
  vehicle::BogieParameters vehicle;        // [vehicle]
  std::vector<vehicle::TrackSection> route;  // [[route.section]], transitions resolved
  vehicle::Irregularity irregularity;      // [route.irregularity]; amplitude 0 = none
  double rail_centre_distance = 1.5;       // [route] rail_centre_distance, for the cant angle [m]

  double route_length() const;             // sum of section lengths [m]
};

// Throws railtab::Error naming the known wear post-processors (simulate/wheel_wear.hpp) for an
// unknown name.
void check_wear_post_processor(const std::string& name);

// Read a simulation scene. Unknown keys, missing required keys, wrong types, non-finite or
// out-of-range values throw railtab::Error naming the file, the dotted key and (where known) the
// line. The contact scene is only located here (it must exist), not parsed.
SimulationScene load_simulation_scene(const std::filesystem::path& path);
SimulationScene parse_simulation_scene(std::string_view toml_text, const std::string& source_name,
                                       const std::filesystem::path& base_dir = {});

}  // namespace railtab
