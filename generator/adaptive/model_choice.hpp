// SPDX-License-Identifier: Apache-2.0
// Per-region model choice of [accuracy] scenes (docs/adaptive-grids.md, "Model choice per y"): for
// each node of the y grid, the cheapest normal model of `[accuracy] models` whose results stay within
// the accuracy targets of the reference model ([contact] normal_model) at a fixed set of probe states.
// The choice is planned, not a failure fallback: it is recorded in the table's root dataset
// `normal_model_index`, and the status bits do not change (kFallbackModel keeps meaning "the chosen
// model failed and a simpler one ran").
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/scene.hpp"
#include "adaptive/adaptive_grid.hpp"

namespace railtab {

// The states at which candidates are compared with the reference at one y node (roll as the scene).
struct ModelProbeStates {
  std::vector<double> loads;                     // both ends of the load range [N]
  std::vector<std::array<double, 3>> creepages;  // (xi [-], eta [-], phi [rad/m]): each creepage alone at
                                                 //   1/4 and all of either end of its range, and all three
                                                 //   combined at 1/4 and 1/2 (phi towards both ends)
};
ModelProbeStates model_probe_states(const Scene& scene);

// Worst error of `candidate` against `reference` over the results of one y node at the probe states,
// as a fraction of `targets` (choose_models passes the scene's targets x model_tolerance) (<= 1: within all targets), per wheel and loaded slot of the
// reference: fx and fy each against creep_force x mu x N, N against normal_force x N, the patch
// reference point's contact angle and rolling radius against contact_angle and rolling_radius.
// +infinity when the slot regimes differ (another slot occupancy or patch count, or a slot failed
// where the reference did not), or the candidate fell back to another model or did not converge.
using ProbeResults = std::vector<std::vector<std::array<ContactProbe::Wheel, 2>>>;  // [load][creepage][wheel]
double model_error(const ProbeResults& candidate, const ProbeResults& reference, const AccuracyTargets& targets,
                   double friction);

struct ModelChoice {
  std::vector<NormalModel> models;          // scene.accuracy.models: cheapest first, the reference last
  std::vector<std::size_t> by_y;            // per node of scene.grids.y: index into models
  std::vector<std::vector<double>> error;   // [y node][model]: model_error against the reference [-]
  std::size_t probes_per_node = 0;          // probe states per y node (loads x creepages) [-]
  double model_tolerance = 1.0;             // the targets were multiplied by this for the choice [-]
  double seconds = 0.0;                     // wall time [s]
  nlohmann::json to_json() const;           // models, nodes per model, probes, rule, time
};

// Choose per node of scene.grids.y (deterministic whatever `threads`). Needs scene.accuracy.models.
// error[][] is relative to the targets x model_tolerance.
ModelChoice choose_models(const Scene& scene, int threads = 0);

}  // namespace railtab
