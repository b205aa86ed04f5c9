// Adaptive grids: the nodes of each adaptive axis of an [accuracy] scene, placed before the sweep
// so that linear interpolation between neighbouring nodes meets the scene's error targets at the
// midpoints (docs/adaptive-grids.md). Refinement is separable (one axis at a time, the others at a
// few representative states), so the table stays a tensor grid.
//
// Two layers: refine_axis() is a generic 1-D refiner over any batch sampler (tests drive it with
// synthetic functions); build_adaptive_grids() samples the contact chain of the scene (geometry ->
// normal -> FASTSIM, the same core calls and slot rules as the sweep kernel) and fills scene.grids.
#pragma once

#include <array>
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
  nlohmann::json to_json() const;   // nodes count, steps, errors, counts
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

// The direct contact chain of a scene at single states (geometry -> normal -> FASTSIM), as the
// sweep kernel computes it (same core calls, same slot assignment). Thread-safe.
class ContactProbe {
 public:
  explicit ContactProbe(const Scene& scene);
  ~ContactProbe();
  ContactProbe(const ContactProbe&) = delete;
  ContactProbe& operator=(const ContactProbe&) = delete;

  struct Slot {
    bool geometry = false;        // a geometric contact point is in this slot
    double contact_angle = 0.0;   // [rad]
    double rolling_radius = 0.0;  // [m]
    bool loaded = false;          // a loaded patch is in this slot
    double normal_force = 0.0;    // [N]
    double patch_angle = 0.0;     // contact angle of the loaded patch's reference point [rad]
    double patch_radius = 0.0;    // rolling radius of the loaded patch's reference point [m]
    std::uint32_t patch_status = 0;  // status bits of the loaded patch (src/core/status.hpp)
    double fx = 0.0, fy = 0.0;    // creep forces on the wheel [N]
    std::uint32_t status = 0;     // geometry and patch slot bits (kTwoPoint, occupancy)
  };
  struct Wheel {
    Slot slot[2];                 // 0 tread, 1 flange
  };
  // Both wheels at (y, roll of the scene at y, load, creepage). loads/creepages: several at once on
  // one geometry; result [load][creepage][wheel].
  std::vector<std::vector<std::array<Wheel, 2>>> evaluate(double y, const std::vector<double>& loads,
                                                           const std::vector<std::array<double, 3>>& creepages) const;
  double roll_at(double y) const;   // equilibrium roll or the roll grid's first value [rad]
  double friction() const;          // mu [-]

 private:
  struct Data;
  Data* data_;
};

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

// The measurement of docs/adaptive-grids.md: adaptive grids against uniform grids with the same
// worst midpoint error, and both against direct evaluation at random off-grid states.
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
  std::vector<Grid> others;                // further grids measured the same way (e.g. default.toml's)
  std::size_t states = 0;                  // random states (with contact on both wheels) [-]
  std::string text() const;                // printable report
};
// `others`: further grids of the same scene (axes as in the scene's ranges) measured at the same states.
// With [accuracy] models, `others` also gets "adaptive, models": the adaptive grids with each y node's
// values from its chosen model, against the same direct evaluation with the reference model.
GridComparison compare_adaptive_with_uniform(const Scene& scene, std::size_t states, unsigned seed, int threads = 0,
                                             const std::vector<std::pair<std::string, SceneGrids>>& others = {});

}  // namespace railtab
