// SPDX-License-Identifier: Apache-2.0
// One wheelset state of a scene through the whole chain (geometry -> normal -> FASTSIM -> wear), as
// `railtab eval` and `railtab.evaluate` report it: a typed result in SI units (its JSON form, the
// keys of `railtab eval --json`, is eval/state_json.hpp).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "geometry/contact_geometry.hpp"
#include "normal/normal_model.hpp"
#include "scene/scene.hpp"
#include "tangential/fastsim_contact.hpp"
#include "wear/archard.hpp"

namespace railtab {

struct StateEvalRequest {
  double y = 0.0;                 // wheelset lateral displacement [m]
  std::optional<double> roll;     // roll [rad]; default: the scene's choice
  bool equilibrium_roll = false;  // use the kinematic equilibrium roll
  std::optional<double> yaw;      // yaw [rad]; default: the scene's first yaw, 0 without one
  std::optional<double> load;     // vertical wheel load [N]; default: the scene's first load
  std::string model;              // normal model name overriding the scene's; empty: the scene's
  std::vector<double> creepage;   // xi, eta [-], phi [rad/m]; empty: no creep forces and wear
  std::optional<double> mu;       // friction overriding the scene's [-]
};

// One loaded contact patch: its normal contact and, with a creepage, its creep forces and wear.
struct EvaluatedContact {
  ContactPatch patch;      // normal contact at the patch's reference point
  FastsimResult force;     // creep forces on the wheel (with a creepage only)
  WearResult wear;         // Archard wear of the same solve (with a creepage only)
  StatusBits status = 0;   // the patch's, the load control's verdict and the creep solve's bits;
                           //   failed (never converged) when any of its numbers is not finite
};

// One rigid contact point of the geometry.
struct EvaluatedPoint {
  ContactPoint point;
  int patch = -1;          // the loaded patch it belongs to, -1 for none
  StatusBits status = 0;   // the point's bits, failed when any of its numbers is not finite
};

struct EvaluatedWheel {
  Side side = Side::left;
  double vertical_approach = 0.0;  // [m]
  double carried_load = 0.0;       // carried load [N]; with load coupling the sum of the next two
  bool coupled = false;            // with a creepage: the coupled load control ran
  double vertical_load_normal = 0.0;      // sum N cos g [N] (coupled only)
  double vertical_load_tangential = 0.0;  // sum fy sin g [N] (coupled only)
  StatusBits coupling_status = 0;  // the coupled control's verdict (kConverged / kNotConverged)
  int coupling_iterations = -1;    // its normal solves beyond the uncoupled one; -1: not reported
                                   //   (the half-space model's coupled solve does not count them)
  std::vector<EvaluatedContact> contacts;  // loaded patches
  std::vector<EvaluatedPoint> rigid_points;
  StatusBits status = 0;  // geometry, normal and coupling bits; failed when a contact failed
};

struct StateEvaluation {
  std::string scene;               // the scene's name
  double y = 0.0, roll = 0.0;      // the state [m], [rad]
  double yaw = 0.0;                // [rad]
  double load = 0.0;               // vertical wheel load [N]
  NormalModel normal_model = NormalModel::hertz;
  bool with_creep = false;         // a creepage was given
  std::array<double, 3> creepage{};  // xi, eta [-], phi [rad/m] (with_creep)
  double friction = 0.0;           // [-] (with_creep)
  std::string spin;                // FASTSIM's spin treatment, "exact" for the half-space model (with_creep)
  std::optional<double> element_size;  // the half-space model's element size [m]
  bool load_coupling = false;      // the scene's load coupling switch
  double rolling_radius_difference = 0.0;  // r_left - r_right [m]
  std::array<EvaluatedWheel, 2> wheels;    // left, right
};

// Evaluates the request on the scene. Throws railtab::Error naming the option for a bad request.
StateEvaluation evaluate_state(const Scene& scene, const StateEvalRequest& request);

}  // namespace railtab
