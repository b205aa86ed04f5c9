// SPDX-License-Identifier: Apache-2.0
// The measurement of docs/adaptive-grids.md: adaptive grids against uniform grids with the same
// worst midpoint error, and both against direct evaluation at random off-grid states.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "scene/scene.hpp"
#include "adaptive/adaptive_grid.hpp"

namespace railtab {

struct GridComparison {
  struct Grid {
    std::string name;                      // "adaptive" / "uniform" / "adaptive, models"
    SceneGrids grids;                      // all axes
    std::vector<NormalModel> model_by_y;   // normal model of each y node's values; empty = the scene's
    std::size_t points = 0;                // creep points (product of tabulated axes) [-]
    std::size_t bytes = 0;                 // in-memory table size (float64 + uint32 status) [B]
    std::vector<double> worst_midpoint;    // per adaptive axis: worst midpoint error / tolerance [-]
    double creep_median = 0, creep_p90 = 0, creep_max = 0;  // |dF| / (mu N) at random states [-]
    double smooth_share = 0;               // share of wheel-states whose cell has no regime change [-]
    double smooth_creep_p90 = 0, smooth_creep_max = 0;  // |dF| / (mu N) over those [-]
    double normal_median = 0, normal_p90 = 0, normal_max = 0;  // |dN| / N [-]
    double angle_median = 0, angle_max = 0;  // tread-slot contact angle error [rad]
  };
  Grid adaptive, uniform;
  std::vector<Grid> others;                // further grids measured the same way (e.g. default_stripes.toml's)
  std::size_t states = 0;                  // random states (with contact on both wheels) [-]
  std::string text() const;                // printable report
};
// `others`: further grids of the same scene (axes as in the scene's ranges) measured at the same states.
// With [accuracy] models, `others` also gets "adaptive, models": the adaptive grids with each y node's
// values from its chosen model, against the same direct evaluation with the reference model.
GridComparison compare_adaptive_with_uniform(const Scene& scene, std::size_t states, unsigned seed, int threads = 0,
                                             const std::vector<std::pair<std::string, SceneGrids>>& others = {});

}  // namespace railtab
