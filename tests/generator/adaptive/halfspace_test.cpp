// SPDX-License-Identifier: Apache-2.0
// The exact half-space model selected as a normal model: scene keys, railtab eval and
// the table sweep (generator/kernel/halfspace_contact.hpp). Small grids only: the slow accuracy
// checks of the model itself are in tests/halfspace.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "core/check.hpp"
#include "error_message.hpp"
#include "halfspace/wheel_rail.hpp"
#include "generator/test_tables.hpp"
#include "normal/normal_model.hpp"
#include "scene/scene.hpp"
#include "kernel/contact_kernel.hpp"
#include "adaptive/contact_probe.hpp"

namespace railtab {
namespace {

TEST(HalfspaceSelectable, SceneKeysAndNames) {
  EXPECT_EQ(parse_normal_model("halfspace"), NormalModel::halfspace);
  EXPECT_STREQ(to_string(NormalModel::halfspace), "halfspace");
  const Scene scene = parse_scene(testing::kHalfspaceSmallScene, "h.toml");
  EXPECT_EQ(scene.normal.model, NormalModel::halfspace);
  EXPECT_DOUBLE_EQ(scene.halfspace.element_size, 0.3e-3);  // the default
  std::string text = testing::kHalfspaceSmallScene;
  text.replace(text.find("friction = 0.3"), 14, "element_size = 0.4e-3");
  EXPECT_DOUBLE_EQ(parse_scene(text, "h.toml").halfspace.element_size, 0.4e-3);
  text.replace(text.find("0.4e-3"), 6, "0.4");  // 0.4 m: a unit mistake, refused with the key named
  const std::string message = test::error_message([&] { parse_scene(text, "h.toml"); });
  EXPECT_NE(message.find("element_size"), std::string::npos) << message;
  // The fast normal layer refuses the model instead of silently solving something else.
  NormalOptions options;
  options.model = NormalModel::halfspace;
  EXPECT_NE(test::error_message([&] { solve_normal_for_load(WheelContactGeometry{}, 78.5e3, Material{}, options); })
                .find("halfspace"),
            std::string::npos);
}

// The table sweep with the exact model: the same bytes for one and two threads; the normal part
// carries the load; the coupled creep part balances N cos g + fy sin g against it; creep forces
// within mu N.
TEST(HalfspaceSelectable, SweepDeterministicAndBalanced) {
  const Scene scene = parse_scene(testing::kHalfspaceSmallScene, "h.toml");
  ASSERT_TRUE(scene.tangential.load_coupling);
  SweepKernel kernel = make_contact_kernel(scene);
  SweepOptions one, two;
  one.threads = 1;
  two.threads = 2;
  SweepResult a = run_sweep(scene, kernel, one);
  SweepResult b = run_sweep(scene, kernel, two);
  testing::expect_same_datasets(a.table, b.table);
  ASSERT_EQ(a.summary.failures, 0u) << a.summary.first_failure;
  for (const char* side : {"left", "right"}) {
    const TableGroup& geo = *a.table.group(std::string(side) + "/geometry");
    const TableGroup& normal = *a.table.group(std::string(side) + "/normal");
    const TableGroup& creep = *a.table.group(std::string(side) + "/creep");
    ASSERT_TRUE(creep.find("normal_force"));
    for (std::size_t iy = 0; iy < 2; ++iy) {
      // Tread contact in slot 0 at y = 0 and 3 mm (one patch).
      const std::size_t s = 0;
      const double g = geo.find("contact_angle")->values[iy * 2 + s];
      const double n0 = normal.find("normal_force")->values[iy * 2 + s];
      EXPECT_TRUE(normal.find("status")->status[iy * 2 + s] & status::kConverged) << side << " y " << iy;
      EXPECT_NEAR(n0 * std::cos(g), 78.5e3, 2e-3 * 78.5e3) << side << " y " << iy;
      for (std::size_t ix = 0; ix < 2; ++ix) {
        const std::size_t cell = (iy * 2 + ix) * 2 + s;
        const double n = creep.find("normal_force")->values[cell];
        const double fx = creep.find("fx")->values[cell], fy = creep.find("fy")->values[cell];
        EXPECT_TRUE(creep.find("status")->status[cell] & status::kConverged) << side << " y " << iy << " xi " << ix;
        EXPECT_LE(std::hypot(fx, fy), 0.3 * n * (1.0 + 1e-9));
        EXPECT_NEAR(n * std::cos(g) + fy * std::sin(g), 78.5e3, 3e-3 * 78.5e3) << side << " y " << iy;
        if (ix == 1) {
          EXPECT_LT(fx, -1e3) << "xi = 0.002: the creep force on the wheel opposes the slip";
        }
      }
    }
  }
}

}  // namespace
}  // namespace railtab

namespace railtab {
namespace {

// The contact-jump locator's configuration probe (ContactProbe::configuration: one wheel, no creep,
// the exact normal problem only with two or more candidate patches) gives the signature the full
// contact chain (ContactProbe::evaluate, which solves the exact normal and tangential problems at
// every state) gives: the jumps it locates are those of the exact model, found cheaper (the loaded
// patch's reference near the exact one, which is placed again at the exact approach,
// wheel_rail.hpp). States
// across the default exact scene's y range, tread and flange, where one and two patches occur.
TEST(HalfspaceSelectable, JumpConfigurationIsTheContactChains) {
  namespace pb = probe_slot_bits;
  constexpr std::uint32_t kConfig = pb::kGeometry | pb::kGeometryTwo | pb::kGeometryFirst | pb::kLoaded;
  int two_patch = 0, loaded = 0;
  std::size_t compared = 0;
  double max_angle = 0.0, max_radius = 0.0;  // candidate against exact reference
  // The default exact scene every 0.7 mm at the nominal load (one candidate patch throughout: its
  // S1002/UIC60 contacts lie within the 8 mm that merge into one patch), and the worn pairs' scenes
  // with the exact model at the first states with two candidate patches (0.05 mm scan, no exact
  // solve).
  for (const char* file : {"default.toml", "worn_rail.toml", "worn_miniprof.toml"}) {
    Scene scene = load_scene(std::filesystem::path(RAILTAB_SOURCE_DIR) / "tables" / file);
    scene.normal.model = NormalModel::halfspace;
    const ContactProbe probe(scene);
    const ContactGeometrySolver solver = make_geometry_solver(scene);
    auto candidates = [&](double y, std::size_t w, double load) {
      const WheelContactGeometry g =
          solver.solve_wheel(w == 0 ? Side::left : Side::right, WheelsetState{y, probe.roll_at(y)});
      return halfspace::candidate_patches(g, load, scene.material).patches.size();
    };
    struct State {
      double y, load;
    };
    std::vector<State> states;
    if (std::string(file) == "default.toml")
      for (double y = -0.0101; y <= 0.0101; y += 0.0007) states.push_back({y, 78.5e3});
    const std::vector<double>& y_grid = scene.grids.y;
    int scanned = 0;
    for (double y = y_grid.front(); y <= y_grid.back() && scanned < 3; y += 0.00005)
      if (candidates(y, 0, scene.grids.load.front()) > 1 || candidates(y, 1, scene.grids.load.front()) > 1)
        states.push_back({y, scene.grids.load.front()}), ++scanned;
    for (const State& st : states) {
      const auto chain = probe.evaluate(st.y, {st.load}, {{0.0, 0.0, 0.0}})[0][0];
      for (std::size_t w = 0; w < 2; ++w) {
        const ContactProbe::Wheel c = probe.configuration(st.y, w, st.load);
        for (std::size_t s = 0; s < kSlots; ++s) {
          const ContactProbe::Slot &a = chain[w].slot[s], &b = c.slot[s];
          const std::string where = fmt::format("{} y {} load {} wheel {} slot {}", file, st.y, st.load, w, s);
          EXPECT_EQ(a.status & kConfig, b.status & kConfig) << where;
          EXPECT_EQ(a.contact_angle, b.contact_angle) << where;
          EXPECT_EQ(a.rolling_radius, b.rolling_radius) << where;
          // The exact result's reference lies at the exact approach, the candidate's at STRIPES's
          // (wheel_rail.hpp, "Reference points"): measured at most 3.1e-3 rad and 29 um apart at
          // these creepage-free states (tread at 4.6 mm), below a jump's radius step
          // (JumpLocatorOptions::radius_step, 50 um).
          EXPECT_NEAR(a.patch_angle, b.patch_angle, 5e-3) << where;
          EXPECT_NEAR(a.patch_radius, b.patch_radius, 4.5e-5) << where;
          max_angle = std::max(max_angle, std::abs(a.patch_angle - b.patch_angle));
          max_radius = std::max(max_radius, std::abs(a.patch_radius - b.patch_radius));
          EXPECT_EQ(b.fx, 0.0);
          if (a.loaded) ++loaded;
        }
        if (candidates(st.y, w, st.load) > 1) ++two_patch;
        ++compared;
      }
    }
  }
  std::printf("%zu wheel states compared, %d with two candidate patches (the exact normal path); candidate "
              "against exact reference: angle %.2e rad, rolling radius %.2e m at most\n", compared, two_patch,
              max_angle, max_radius);
  EXPECT_GT(loaded, 40);    // both wheels loaded nearly everywhere
  EXPECT_GT(two_patch, 0);  // the exact path was compared too
}

}  // namespace
}  // namespace railtab
