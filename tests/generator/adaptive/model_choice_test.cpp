// SPDX-License-Identifier: Apache-2.0
// Per-region model choice of [accuracy] scenes (generator/adaptive/model_choice.*, docs/adaptive-grids.md).
#include "adaptive/model_choice.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "core/check.hpp"
#include "error_message.hpp"
#include "generator/test_tables.hpp"
#include "kernel/contact_kernel.hpp"
#include "generator/adaptive/grid_comparison.hpp"
#include "table/merge.hpp"
#include "table/table_io.hpp"

namespace railtab::model_choice_test {  // own namespace: unity builds compile several test files as one
namespace {

constexpr const char* kHead = R"([scene]
name = "a"
[profiles]
wheel = "s1002"
rail = "uic60"
[contact]
normal_model = "stripes-ab"
)";
constexpr const char* kGrid = R"(
[grid]
y = {start = -0.01, stop = 0.01, max_step = 0.002, min_step = 1e-4}
load = 1e5
)";

std::string error_of(const std::string& accuracy) {
  return test::error_message([&] { parse_scene(std::string(kHead) + accuracy + kGrid, "s.toml"); });
}

TEST(ModelChoiceScene, ModelsEndWithTheReference) {
  Scene s = parse_scene(std::string(kHead) + "[accuracy]\ncreep_force = 0.02\nmodels = [\"hertz\", \"kik-piotrowski\"]\n" + kGrid,
                        "s.toml");
  EXPECT_EQ(s.accuracy.models,
            (std::vector<NormalModel>{NormalModel::hertz, NormalModel::kik_piotrowski, NormalModel::stripes_ab}));
  Scene listed = parse_scene(std::string(kHead) + "[accuracy]\ncreep_force = 0.02\nmodels = [\"hertz\", \"stripes-ab\"]\n" + kGrid,
                             "s.toml");
  EXPECT_EQ(listed.accuracy.models, (std::vector<NormalModel>{NormalModel::hertz, NormalModel::stripes_ab}));
  Scene none = parse_scene(std::string(kHead) + "[accuracy]\ncreep_force = 0.02\n" + kGrid, "s.toml");
  EXPECT_TRUE(none.accuracy.models.empty());
}

TEST(ModelChoiceScene, BadEntryGivesALocatedError) {
  // kHead has 7 lines; [accuracy] is line 8, creep_force 9, models 10.
  const std::string acc = "[accuracy]\ncreep_force = 0.02\n";
  EXPECT_NE(error_of(acc + "models = [\"hertz\", \"hertzz\"]\n").find("s.toml:10: accuracy.models[1]: unknown normal model 'hertzz'"),
            std::string::npos)
      << error_of(acc + "models = [\"hertz\", \"hertzz\"]\n");
  EXPECT_NE(error_of(acc + "models = [\"hertz\", \"hertz\"]\n").find("s.toml:10: accuracy.models[1]: 'hertz' is listed twice"),
            std::string::npos);
  EXPECT_NE(error_of(acc + "models = [\"stripes-ab\", \"hertz\"]\n")
                .find("accuracy.models[0]: 'stripes-ab' is the reference ([contact] normal_model): it may only be the last"),
            std::string::npos);
  EXPECT_NE(error_of(acc + "models = [\"hertz\", 3]\n").find("s.toml:10: accuracy.models[1]: expected a string, got integer"),
            std::string::npos);
  EXPECT_NE(error_of(acc + "models = \"hertz\"\n").find("s.toml:10: accuracy.models: expected a non-empty list"),
            std::string::npos);
  EXPECT_NE(error_of(acc + "models = []\n").find("accuracy.models: expected a non-empty list of normal model names"),
            std::string::npos);
  EXPECT_NE(error_of(acc + "model = [\"hertz\"]\n").find("s.toml:10: accuracy.model: unknown key"), std::string::npos);
  EXPECT_NE(error_of(acc + "model_tolerance = 2\n").find("s.toml:10: accuracy.model_tolerance: needs accuracy.models"),
            std::string::npos);
  EXPECT_NE(error_of(acc + "models = [\"hertz\"]\nmodel_tolerance = 0\n").find("s.toml:11: accuracy.model_tolerance: must be > 0"),
            std::string::npos);
}

// ---------------------------------------------------------------------------------------------

ProbeResults one_slot(double fx, double fy, double n, std::uint32_t status, std::uint32_t patch_status) {
  ContactProbe::Wheel w{};
  w.slot[0].loaded = true;
  w.slot[0].fx = fx;
  w.slot[0].fy = fy;
  w.slot[0].normal_force = n;
  w.slot[0].status = status;
  w.slot[0].patch_status = patch_status;
  return {{{w, w}}};
}

TEST(ModelChoiceError, FractionOfTheTargetsAndRejection) {
  AccuracyTargets t;
  t.creep_force = 0.02;
  t.normal_force = 0.01;
  const ProbeResults ref = one_slot(1000.0, -500.0, 1e5, 5u, status::kConverged);
  EXPECT_EQ(model_error(ref, ref, t, 0.3), 0.0);
  // fy off by 1.5 x (0.02 x 0.3 x 1e5 = 600 N); N off by 0.5 x (1000 N).
  EXPECT_DOUBLE_EQ(model_error(one_slot(1000.0, 400.0, 1e5 + 500.0, 5u, status::kConverged), ref, t, 0.3), 1.5);
  // Another slot regime, a fallback or a non-converged candidate: never chosen.
  EXPECT_TRUE(std::isinf(model_error(one_slot(1000.0, -500.0, 1e5, 7u, status::kConverged), ref, t, 0.3)));
  EXPECT_TRUE(std::isinf(
      model_error(one_slot(1000.0, -500.0, 1e5, 5u, status::kConverged | status::kFallbackModel), ref, t, 0.3)));
  EXPECT_TRUE(std::isinf(model_error(one_slot(1000.0, -500.0, 1e5, 5u, status::kNotConverged), ref, t, 0.3)));
}

// ---------------------------------------------------------------------------------------------
// The contact chain (testing::kModelChoiceScene): tread (|y| <= 3 mm) and flange contact of the
// left wheel (y = 9 mm).

// The error of a model at one y as a fraction of the targets x model_tolerance, computed here from the
// probe outputs directly (not model_error).
double direct_error(const Scene& scene, NormalModel model, double y) {
  Scene a = scene, b = scene;
  a.normal.model = model;
  const ModelProbeStates states = model_probe_states(scene);
  auto c = ContactProbe(a).evaluate(y, states.loads, states.creepages);
  auto r = ContactProbe(b).evaluate(y, states.loads, states.creepages);
  double worst = 0.0;
  for (std::size_t il = 0; il < r.size(); ++il)
    for (std::size_t ic = 0; ic < r[il].size(); ++ic)
      for (std::size_t w = 0; w < 2; ++w)
        for (std::size_t s = 0; s < kSlots; ++s) {
          const auto& cs = c[il][ic][w].slot[s];
          const auto& rs = r[il][ic][w].slot[s];
          if (cs.loaded != rs.loaded) return INFINITY;
          if (!rs.loaded) continue;
          const double k = scene.accuracy.model_tolerance;
          const double f = k * scene.accuracy.creep_force * scene.tangential.friction * rs.normal_force;
          worst = std::max({worst, std::abs(cs.fx - rs.fx) / f, std::abs(cs.fy - rs.fy) / f,
                            std::abs(cs.normal_force - rs.normal_force) / (k * scene.accuracy.normal_force * rs.normal_force)});
        }
  return worst;
}

TEST(ModelChoice, DeterministicAndNeverAModelThatMissesTheTargets) {
  Scene scene = parse_scene(testing::kModelChoiceScene, "choice.toml");
  ASSERT_EQ(scene.accuracy.models.size(), 3u);
  const ModelChoice one = choose_models(scene, 1);
  const ModelChoice two = choose_models(scene, 2);
  EXPECT_EQ(one.by_y, two.by_y);
  EXPECT_EQ(one.error, two.error);
  ASSERT_EQ(one.by_y.size(), scene.grids.y.size());
  for (std::size_t iy = 0; iy < scene.grids.y.size(); ++iy) {
    const std::size_t m = one.by_y[iy];
    const double y = scene.grids.y[iy];
    // The chosen model meets the targets at the probes; every cheaper one does not.
    EXPECT_LE(one.error[iy][m], 1.0) << "y = " << y;
    EXPECT_LE(direct_error(scene, scene.accuracy.models[m], y), 1.0) << "y = " << y;
    for (std::size_t k = 0; k < m; ++k) EXPECT_GT(one.error[iy][k], 1.0) << "y = " << y << " model " << k;
  }
  // At 3 x the targets some y node must take a cheaper model, or this test checks nothing.
  EXPECT_TRUE(std::any_of(one.by_y.begin(), one.by_y.end(), [](std::size_t m) { return m < 2; }));
}

TEST(ModelChoice, ReferenceWhereNoCheaperModelMeetsTheTargets) {
  // At the plain targets (2 % of mu N, 1 % of N) neither Hertz nor Kik-Piotrowski is close enough
  // to STRIPES A&B, in the flange contact of the left wheel (y = 9 mm) or on the tread.
  Scene scene = parse_scene(testing::kModelChoiceScene, "choice.toml");
  scene.accuracy.model_tolerance = 1.0;
  const ModelChoice c = choose_models(scene, 1);
  for (std::size_t iy = 0; iy < scene.grids.y.size(); ++iy) {
    EXPECT_EQ(c.by_y[iy], 2u) << "y = " << scene.grids.y[iy];
    EXPECT_GT(direct_error(scene, NormalModel::hertz, scene.grids.y[iy]), 1.0) << "y = " << scene.grids.y[iy];
    EXPECT_GT(direct_error(scene, NormalModel::kik_piotrowski, scene.grids.y[iy]), 1.0) << "y = " << scene.grids.y[iy];
  }
}

TEST(ModelChoice, ModelToleranceScalesTheTargets) {
  Scene scene = parse_scene(testing::kModelChoiceScene, "choice.toml");
  scene.accuracy.model_tolerance = 1.0;
  const ModelChoice strict = choose_models(scene, 1);
  scene.accuracy.model_tolerance = 100.0;
  const ModelChoice loose = choose_models(scene, 1);
  for (std::size_t iy = 0; iy < scene.grids.y.size(); ++iy) {
    for (std::size_t m = 0; m < strict.models.size(); ++m) {
      if (std::isfinite(strict.error[iy][m])) {
        EXPECT_NEAR(loose.error[iy][m] * 100.0, strict.error[iy][m], 1e-9 * strict.error[iy][m]);
      }
    }
    EXPECT_LE(loose.by_y[iy], strict.by_y[iy]);  // a looser tolerance never picks a dearer model
  }
  // At 100 x (2 % of mu N) every y of this scene has a cheaper model than STRIPES A&B.
  EXPECT_TRUE(std::all_of(loose.by_y.begin(), loose.by_y.end(), [](std::size_t m) { return m < 2; }));
}

// The measurement of docs/adaptive-grids.md, "Model choice per y" (minutes; run by hand):
//   build/release/tests/test_generator_adaptive --gtest_also_run_disabled_tests --gtest_filter='*ModelChoiceReport*'
// Prints the choice of tables/default_mixed.toml, the shares per model at other model tolerances on the
// same grids, and the table error at random off-grid states (GridComparison, row "adaptive, models";
// row "adaptive" is the same grids with the reference model everywhere) at model_tolerance 5 and 10.
TEST(ModelChoiceReport, DISABLED_DefaultMixed) {
  const Scene scene = load_scene(std::filesystem::path(RAILTAB_SOURCE_DIR) / "tables/default_mixed.toml");
  Scene placed = scene;
  AdaptiveGridSummary s = build_adaptive_grids(placed, 0);
  std::cout << "default_mixed.toml: " << s.model_choice.dump() << "\n";
  // Other model tolerances, same grids: which share of the y nodes each model gets.
  for (double tolerance : {1.0, 2.0, 5.0, 10.0}) {
    Scene variant = placed;
    variant.accuracy.model_tolerance = tolerance;
    ModelChoice c = choose_models(variant, 0);
    std::cout << fmt::format("model_tolerance {:4.1f}: y nodes per model {}\n", tolerance,
                             c.to_json()["y_nodes_per_model"].dump());
  }
  if (std::getenv("RAILTAB_CHOICE_ONLY")) return;
  for (double tolerance : {5.0, 10.0}) {
    Scene variant = scene;
    variant.accuracy.model_tolerance = tolerance;
    GridComparison c = compare_adaptive_with_uniform(variant, 400, 20261122u, 0);
    std::cout << fmt::format("model_tolerance {}:\n", tolerance) << c.text();
  }
}

}  // namespace
}  // namespace railtab::model_choice_test
