// SPDX-License-Identifier: Apache-2.0
// Generic 1-D grid refinement: refine_axis() places the nodes of one axis so that linear
// interpolation between neighbours meets a tolerance at the midpoints, over any batch sampler
// (tests drive it with synthetic functions; adaptive_grid.hpp gives it the contact chain).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/scene.hpp"

namespace railtab {

// What a sampler returns for one axis position.
struct AxisSample {
  std::vector<double> values;       // outputs at this position [output units]
  std::vector<double> tolerance;    // allowed interpolation error per output at this position, same
                                    //   units; <= 0: output not checked here
  std::vector<std::uint32_t> regime;  // contact regime (slot occupancy, status bits); a change
                                      //   between neighbours is a jump, not smoothed
};

// Evaluates a batch of positions (may run them in parallel; must be deterministic).
using AxisSampler = std::function<std::vector<AxisSample>(const std::vector<double>& x)>;

struct AxisRefinement {
  std::string axis;                 // axis name
  std::vector<double> nodes;        // final grid, strictly increasing [axis units]
  double worst_error = 0.0;         // largest midpoint error / tolerance over smooth intervals,
                                    //   jumps and unmet intervals excluded [-]
  double worst_error_at = 0.0;      // midpoint where it occurs [axis units]
  std::size_t jumps = 0;            // intervals with a regime change (refined to min_step) [-]
  std::size_t unmet = 0;            // intervals without regime change still above tolerance at
                                    //   min_step: discontinuities the status does not show [-]
  double unresolved_error = 0.0;    // largest midpoint error / tolerance of those [-]
  std::vector<double> discontinuities;  // midpoints of the jump and unmet intervals [axis units]
  std::size_t evaluations = 0;      // sampler positions evaluated [-]
  int passes = 0;                   // refinement + coarsening passes [-]
  // The target is met: every smooth interval within it (worst_error <= 1) and no unmet interval.
  bool met() const { return worst_error <= 1.0 && unmet == 0; }
  nlohmann::json to_json() const;   // nodes count, steps, errors, counts, met
};

// Refine [spec.start, spec.stop]: start uniform at <= max_step; insert the midpoint of every interval
// whose midpoint error exceeds its tolerance or whose ends/midpoint differ in regime, while the halves
// stay >= min_step; then remove nodes whose removal keeps every sampled point of the merged interval
// (and its new midpoint) within tolerance, the regime unchanged and the step <= max_step.
AxisRefinement refine_axis(const AxisSampler& sampler, const AdaptiveAxisSpec& spec, int max_passes = 60);

// The midpoint errors of a given grid (no refinement): worst smooth-interval error and jump count.
// Intervals that contain a position of `exclude` (e.g. another grid's discontinuities) count as unmet,
// not in worst_error.
AxisRefinement check_axis(const AxisSampler& sampler, const std::string& axis, const std::vector<double>& nodes,
                          const std::vector<double>& exclude = {});

// n + 1 equally spaced nodes from start to stop (n >= 1).
std::vector<double> uniform_nodes(double start, double stop, std::size_t intervals);

}  // namespace railtab
