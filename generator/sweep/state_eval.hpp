// SPDX-License-Identifier: Apache-2.0
// One wheelset state of a scene through the whole chain (geometry -> normal -> FASTSIM -> wear), as
// `railtab eval` prints it: a JSON document with stable keys in SI units.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/scene.hpp"

namespace railtab {

struct StateEvalRequest {
  double y = 0.0;                 // wheelset lateral displacement [m]
  std::optional<double> roll;     // roll [rad]; default: the scene's choice
  bool equilibrium_roll = false;  // use the kinematic equilibrium roll
  std::optional<double> load;     // vertical wheel load [N]; default: the scene's first load
  std::string model;              // normal model name overriding the scene's; empty: the scene's
  std::vector<double> creepage;   // xi, eta [-], phi [rad/m]; empty: no creep forces and wear
  std::optional<double> mu;       // friction overriding the scene's [-]
};

// Per wheel: "contacts" (loaded patches: normal contact and, with creepage, creep forces and wear)
// and "rigid_points" (the geometry's contact points); keys as in docs (railtab eval --json).
// Throws railtab::Error naming the option for a bad request.
nlohmann::json evaluate_state(const Scene& scene, const StateEvalRequest& request);

}  // namespace railtab
