// SPDX-License-Identifier: Apache-2.0
// Adaptive grids (generator/adaptive/axis_refinement, adaptive_grid, grid_comparison): node placement
// and targets.
#include "adaptive/adaptive_grid.hpp"
#include "generator/adaptive/grid_comparison.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>

#include "core/check.hpp"
#include "error_message.hpp"
#include "generator/test_tables.hpp"
#include "kernel/contact_kernel.hpp"
#include "table/table_io.hpp"

namespace railtab {
namespace {

// A synthetic sampler: one output f(x) with an absolute tolerance, regime from r(x).
template <class F, class R>
AxisSampler synthetic(F f, R r, double tolerance, std::size_t* calls = nullptr) {
  return [=](const std::vector<double>& x) {
    if (calls) *calls += x.size();
    std::vector<AxisSample> out;
    for (double v : x) out.push_back({{f(v)}, {tolerance}, {r(v)}});
    return out;
  };
}

std::size_t nodes_in(const std::vector<double>& x, double lo, double hi) {
  return static_cast<std::size_t>(std::count_if(x.begin(), x.end(), [&](double v) { return v >= lo && v <= hi; }));
}

TEST(AdaptiveGrid, LinearFunctionKeepsTheCoarsestGrid) {
  auto s = synthetic([](double x) { return 3.0 * x + 1.0; }, [](double) { return 0u; }, 1e-6);
  AxisRefinement r = refine_axis(s, {"t", 0.0, 1.0, 0.25, 1e-3});
  EXPECT_EQ(r.nodes, (std::vector<double>{0.0, 0.25, 0.5, 0.75, 1.0}));
  EXPECT_EQ(r.jumps, 0u);
  EXPECT_LT(r.worst_error, 1e-6);
}

TEST(AdaptiveGrid, NodesGoWhereCurvatureIsHighAndTargetsAreMetAtMidpoints) {
  auto f = [](double x) { return std::exp(8.0 * x); };  // curvature 64 e^{8x}: 3000x larger at x = 1
  auto s = synthetic(f, [](double) { return 0u; }, 1e-3);
  AxisRefinement r = refine_axis(s, {"t", 0.0, 1.0, 0.25, 1e-4});
  EXPECT_GT(nodes_in(r.nodes, 0.8, 1.0), 4 * nodes_in(r.nodes, 0.0, 0.2));
  EXPECT_LE(r.worst_error, 1.0);
  EXPECT_EQ(r.unmet, 0u);
  // Independent check with a fresh sampler: every midpoint within tolerance.
  for (std::size_t i = 0; i + 1 < r.nodes.size(); ++i) {
    double a = r.nodes[i], b = r.nodes[i + 1], m = 0.5 * (a + b);
    EXPECT_LE(std::abs(f(m) - 0.5 * (f(a) + f(b))), 1e-3 * (1 + 1e-12)) << "interval " << a << " .. " << b;
    EXPECT_LE(b - a, 0.25 + 1e-12);
  }
  // Fewer nodes than the uniform grid that meets the same target (max curvature 64 e^8: h^2/8 f'' <= tol).
  double h_uniform = std::sqrt(8e-3 / (64.0 * std::exp(8.0)));
  EXPECT_LT(static_cast<double>(r.nodes.size()), 0.6 / h_uniform);
}

TEST(AdaptiveGrid, CoarseningRemovesNodesBisectionDidNotNeed) {
  // Curved only in [0, 0.1]: bisection leaves fine intervals beside it that coarsening merges.
  auto f = [](double x) { return x < 0.1 ? 100.0 * (x - 0.1) * (x - 0.1) : 0.0; };
  auto s = synthetic(f, [](double) { return 0u; }, 1e-3);
  AxisRefinement r = refine_axis(s, {"t", 0.0, 1.0, 0.5, 1e-4});
  EXPECT_LE(r.worst_error, 1.0);
  EXPECT_LE(nodes_in(r.nodes, 0.15, 1.0), 2u);  // linear part: at most the coarse nodes 0.5, 1
}

TEST(AdaptiveGrid, JumpIsRefinedToMinStepAndCounted) {
  const double jump = 0.3141;
  auto f = [=](double x) { return x < jump ? 0.0 : 1.0 + x; };
  auto regime = [=](double x) { return x < jump ? 0u : 1u; };
  const double min_step = 1.0 / 1024;
  AxisRefinement r = refine_axis(synthetic(f, regime, 1e-3), {"t", 0.0, 1.0, 0.25, min_step});
  EXPECT_EQ(r.jumps, 1u);
  auto it = std::upper_bound(r.nodes.begin(), r.nodes.end(), jump);
  ASSERT_NE(it, r.nodes.begin());
  ASSERT_NE(it, r.nodes.end());
  double width = *it - *(it - 1);
  EXPECT_GE(width, min_step * (1 - 1e-9));
  EXPECT_LT(width, 2 * min_step);
  EXPECT_LE(r.worst_error, 1e-9);  // smooth (linear) elsewhere; the jump interval is not an error
  EXPECT_LT(r.nodes.size(), 40u);  // linear neighbours coarsened again
}

// A step inside one regime (no status change) stays above target at min_step: an unmet interval,
// kept out of worst_midpoint_error. The result must then say "not met", per axis and overall,
// although the worst smooth-interval error is <= 1.
TEST(AdaptiveGrid, UnmetIntervalIsNeverReportedMet) {
  const double step = 0.3141;
  auto f = [=](double x) { return x < step ? 0.0 : 1.0 + x; };
  AxisRefinement r = refine_axis(synthetic(f, [](double) { return 0u; }, 1e-3), {"t", 0.0, 1.0, 0.25, 1.0 / 1024});
  ASSERT_GE(r.unmet, 1u);
  ASSERT_LE(r.worst_error, 1.0);  // what alone read as "met" before
  EXPECT_FALSE(r.met());
  EXPECT_FALSE(r.to_json()["met"].get<bool>());
  AdaptiveGridSummary s;
  s.axes.push_back(r);
  nlohmann::json achieved = s.achieved_json();
  EXPECT_LE(achieved["worst_midpoint_error"].get<double>(), 1.0);
  EXPECT_EQ(achieved["unmet"].get<std::size_t>(), r.unmet);
  EXPECT_FALSE(achieved["met"].get<bool>());
  // The same function without the step is met everywhere.
  AxisRefinement smooth = refine_axis(synthetic([](double x) { return 1.0 + x; }, [](double) { return 0u; }, 1e-3),
                                      {"t", 0.0, 1.0, 0.25, 1.0 / 1024});
  AdaptiveGridSummary ok;
  ok.axes.push_back(smooth);
  EXPECT_TRUE(smooth.met());
  EXPECT_TRUE(ok.achieved_json()["met"].get<bool>());
}

// ---------------------------------------------------------------------------------------------
// Scene syntax

constexpr const char* kHead = R"(
[scene]
name = "a"
[profiles]
wheel = "s1002"
rail = "uic60"
)";

std::string error_of(const std::string& text) {
  return test::error_message([&] { parse_scene(std::string(kHead) + text, "s.toml"); });
}

TEST(AdaptiveScene, ParsesTargetsAndAdaptiveAxes) {
  Scene s = parse_scene(std::string(kHead) + R"(
[accuracy]
creep_force = 0.02
contact_angle = 0.002
[grid]
y = {start = -0.01, stop = 0.01, max_step = 0.003, min_step = 1e-4}
load = 78500
xi = {start = -0.004, stop = 0.004, max_step = 0.002, min_step = 1e-5}
)",
                        "s.toml");
  EXPECT_TRUE(s.accuracy.enabled);
  EXPECT_DOUBLE_EQ(s.accuracy.creep_force, 0.02);
  EXPECT_EQ(s.accuracy.normal_force, 0.0);
  ASSERT_EQ(s.accuracy.axes.size(), 2u);
  EXPECT_EQ(s.accuracy.axes[0].axis, "y");
  EXPECT_EQ(s.accuracy.axes[1].axis, "xi");
  EXPECT_EQ(s.grids.y.size(), 8u);  // starting grid: 7 intervals of 2.86 mm <= 3 mm
  EXPECT_EQ(s.grids.y.back(), 0.01);
  EXPECT_EQ(s.grids.xi.size(), 5u);
  EXPECT_FALSE(parse_scene(std::string(kHead) + "[grid]\ny = 0\nload = 1e5\n", "s.toml").accuracy.enabled);
}

TEST(AdaptiveScene, InvalidInputNamesTheKey) {
  const std::string grid = "[grid]\ny = {start = -0.01, stop = 0.01, max_step = 0.002, min_step = 1e-4}\nload = 1e5\n";
  EXPECT_NE(error_of("[accuracy]\ncreep_forces = 0.02\n" + grid).find("s.toml:8: accuracy.creep_forces: unknown key"),
            std::string::npos);
  EXPECT_NE(error_of("[accuracy]\ncreep_force = -0.02\n" + grid).find("accuracy.creep_force: must be > 0"),
            std::string::npos);
  EXPECT_NE(error_of("[accuracy]\ncreep_force = \"x\"\n" + grid).find("accuracy.creep_force: expected a number"),
            std::string::npos);
  EXPECT_NE(error_of("[accuracy]\n" + grid).find("accuracy: needs at least one target"), std::string::npos);
  EXPECT_NE(error_of(grid).find("grid.y: an adaptive range {start, stop, max_step, min_step} needs an [accuracy]"),
            std::string::npos);
  EXPECT_NE(error_of("[accuracy]\ncreep_force = 0.02\n[grid]\ny = 0\nload = 1e5\n").find("accuracy: no grid axis is adaptive"),
            std::string::npos);
  const std::string acc = "[accuracy]\ncreep_force = 0.02\n[grid]\nload = 1e5\n";
  EXPECT_NE(error_of(acc + "y = {start = -0.01, stop = 0.01, max_step = 1e-4, min_step = 1e-3}\n")
                .find("grid.y.max_step: must be >= min_step"),
            std::string::npos);
  EXPECT_NE(error_of(acc + "y = {start = -0.01, stop = 0.01, max_step = 1e-3}\n").find("grid.y.min_step: missing"),
            std::string::npos);
  EXPECT_NE(error_of(acc + "y = {start = -0.01, stop = 0.01, max_step = 1e-3, min_step = 0}\n")
                .find("grid.y.min_step: must be > 0"),
            std::string::npos);
  EXPECT_NE(error_of(acc + "y = {start = 0.01, stop = -0.01, max_step = 1e-3, min_step = 1e-4}\n")
                .find("grid.y: an adaptive range needs stop > start"),
            std::string::npos);
  EXPECT_NE(error_of(acc + "y = {start = -0.01, stop = 0.01, max_step = 1e-3, min_step = 1e-4, step = 1}\n")
                .find("grid.y.step: unknown key in an adaptive range"),
            std::string::npos);
  EXPECT_NE(error_of(acc + "y = [0, {start = 0.001, stop = 0.01, max_step = 1e-3, min_step = 1e-4}]\n")
                .find("grid.y.max_step: an adaptive range {start, stop, max_step, min_step} must be the whole axis"),
            std::string::npos);
  EXPECT_NE(error_of(acc + "y = 0\nroll = {start = -0.01, stop = 0.01, max_step = 1e-3, min_step = 1e-4}\n")
                .find("grid.roll: roll cannot be adaptive"),
            std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// The contact chain (testing::kAdaptiveTreadScene)

TEST(AdaptiveContact, ProbeMatchesTheSweepKernel) {
  Scene scene = parse_scene(testing::kAdaptiveTreadScene, "tread.toml");
  scene.grids.y = {0.0013};
  scene.grids.xi = {0.0021};
  SweepKernel kernel = make_contact_kernel(scene);
  SweepOptions options;
  options.threads = 1;
  Table t = run_sweep(scene, kernel, options).table;
  ContactProbe probe(scene);
  auto r = probe.evaluate(0.0013, {78500.0}, {{0.0021, 0.0, 0.0}})[0][0];
  const TableDataset* fx = t.group("left/creep")->find("fx");
  const TableDataset* n = t.group("right/normal")->find("normal_force");
  const TableDataset* angle = t.group("left/geometry")->find("contact_angle");
  EXPECT_EQ(fx->values[0], r[0].slot[0].fx);
  EXPECT_EQ(n->values[0], r[1].slot[0].normal_force);
  EXPECT_EQ(angle->values[0], r[0].slot[0].contact_angle);
  EXPECT_GT(std::abs(r[0].slot[0].fx), 1e3);
}

TEST(AdaptiveContact, CreepageAxisRefinedWhereTheCreepCurveBends) {
  Scene scene = parse_scene(testing::kAdaptiveTreadScene, "tread.toml");
  AdaptiveGridSummary s = build_adaptive_grids(scene, 1);
  ASSERT_EQ(s.axes.size(), 2u);
  for (const AxisRefinement& r : s.axes) {
    EXPECT_LE(r.worst_error, 1.0) << r.axis;
    EXPECT_LE(r.unmet, 4u) << r.axis;
  }
  const std::vector<double>& xi = scene.grids.xi;
  EXPECT_EQ(xi, s.axes[1].nodes);
  EXPECT_GT(xi.size(), 3u);
  // The bend (creep curve towards saturation) sits at small creepage: more nodes below 0.004 than above.
  EXPECT_GT(nodes_in(xi, 0.0, 0.004), nodes_in(xi, 0.004, 0.008));
  nlohmann::json achieved = s.achieved_json();
  EXPECT_LE(achieved["worst_midpoint_error"].get<double>(), 1.0);
}

TEST(AdaptiveContact, LoadAxisRefinedWhereCreepForceBendsWithLoad) {
  // At fixed creepage, fx / (mu N) falls with the load (the patch grows like N^(1/3)), so fx is not
  // linear in the load: a tight target needs nodes between the three of the starting grid.
  Scene scene = parse_scene(R"(
[scene]
name = "load"
[profiles]
wheel = "s1002"
rail = "uic60"
[accuracy]
creep_force = 0.002
normal_force = 0.001
[grid]
y = 0.002
load = {start = 20e3, stop = 160e3, max_step = 70e3, min_step = 2.5e3}
xi = 0.002
)",
                            "load.toml");
  AdaptiveGridSummary s = build_adaptive_grids(scene, 1);
  ASSERT_EQ(s.axes.size(), 1u);
  const std::vector<double>& load = scene.grids.load;
  EXPECT_GT(load.size(), 3u);
  EXPECT_LE(s.axes[0].worst_error, 1.0);
  // Independent midpoint check of the left wheel's tread fx with the probe.
  ContactProbe probe(scene);
  for (std::size_t i = 0; i + 1 < load.size(); ++i) {
    const double mid = 0.5 * (load[i] + load[i + 1]);
    auto r = probe.evaluate(0.002, {load[i], mid, load[i + 1]}, {{0.002, 0.0, 0.0}});
    const ContactProbe::Slot& a = r[0][0][0].slot[0];
    const ContactProbe::Slot& m = r[1][0][0].slot[0];
    const ContactProbe::Slot& b = r[2][0][0].slot[0];
    ASSERT_TRUE(a.loaded && m.loaded && b.loaded);
    const double tolerance = 0.002 * 0.3 * std::max({a.normal_force, m.normal_force, b.normal_force});
    EXPECT_LE(std::abs(m.fx - 0.5 * (a.fx + b.fx)), tolerance * (1 + 1e-9)) << load[i] << " .. " << load[i + 1];
  }
}

TEST(AdaptiveContact, GridsDoNotDependOnThreads) {
  Scene one = parse_scene(testing::kAdaptiveTreadScene, "tread.toml");
  Scene two = one;
  build_adaptive_grids(one, 1);
  build_adaptive_grids(two, 2);
  EXPECT_EQ(one.grids.y, two.grids.y);
  EXPECT_EQ(one.grids.xi, two.grids.xi);
}

// The measurement of docs/adaptive-grids.md (minutes; run by hand):
//   build/release/tests/test_generator_adaptive --gtest_also_run_disabled_tests --gtest_filter='*AdaptiveReport*'
TEST(AdaptiveReport, DISABLED_DefaultAdaptiveAgainstUniform) {
  Scene scene = load_scene(std::filesystem::path(RAILTAB_SOURCE_DIR) / "tables/default_adaptive.toml");
  Scene adaptive = scene;
  AdaptiveGridSummary s = build_adaptive_grids(adaptive, 0);
  std::cout << s.achieved_json().dump(1) << "\n";
  // The shipped STRIPES table's fixed grids (same ranges) at the same states, for context.
  Scene fixed = load_scene(std::filesystem::path(RAILTAB_SOURCE_DIR) / "tables/default_stripes.toml");
  GridComparison c = compare_adaptive_with_uniform(scene, 400, 20261122u, 0, {{"default_stripes.toml", fixed.grids}});
  std::cout << c.text();
}

}  // namespace
}  // namespace railtab
