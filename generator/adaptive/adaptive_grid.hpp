// SPDX-License-Identifier: Apache-2.0
// Adaptive grids: the nodes of each adaptive axis of an [accuracy] scene, placed before the sweep
// so that linear interpolation between neighbouring nodes meets the scene's error targets at the
// midpoints (docs/adaptive-grids.md). Refinement is separable (one axis at a time, the others at a
// few representative states), so the table stays a tensor grid.
//
// Layers: refine_axis() (axis_refinement.hpp) is a generic 1-D refiner over any batch sampler;
// build_adaptive_grids() samples the contact chain of the scene through a ContactProbe
// (contact_probe.hpp: the same core calls and slot rules as the sweep kernel) and fills
// scene.grids. The measurement against uniform grids is in grid_comparison.hpp.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/scene.hpp"
#include "adaptive/axis_refinement.hpp"
#include "adaptive/contact_probe.hpp"

namespace railtab {

// The adaptive-grid summary of a scene: per adaptive axis, its refinement.
struct AdaptiveGridSummary {
  std::vector<AxisRefinement> axes;   // in the order of scene.accuracy.axes
  nlohmann::json model_choice;        // ModelChoice::to_json() with [accuracy] models; null without
  double seconds = 0.0;               // wall time, grids and model choice [s]
  nlohmann::json targets_json(const Scene& scene) const;   // `accuracy_targets` attribute
  nlohmann::json achieved_json() const;                    // `accuracy_achieved` attribute
};

// The sampler of one adaptive axis of the scene (outputs, tolerances and regimes at the
// representative states of docs/adaptive-grids.md). `grids` gives the other axes' ranges.
AxisSampler contact_axis_sampler(const Scene& scene, const ContactProbe& probe, const std::string& axis, int threads);

// Refine every adaptive axis of scene.accuracy and write the grids into scene.grids; with
// [accuracy] models, then choose the model per y node into scene.accuracy.model_by_y (model_choice.hpp).
AdaptiveGridSummary build_adaptive_grids(Scene& scene, int threads = 0);

// The range of an axis: its adaptive spec's [start, stop], else its grid's ends.
struct AxisRange {
  double lo = 0.0, hi = 0.0;
};
AxisRange axis_range_of(const Scene& scene, const std::string& axis);

// The grid of an axis by name ("y", "load", "xi", "eta", "phi").
std::vector<double>& axis_grid_of(SceneGrids& grids, const std::string& axis);

}  // namespace railtab
