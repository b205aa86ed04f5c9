// SPDX-License-Identifier: Apache-2.0
// One state evaluated (generator/eval/, railtab eval): the exact model's load balance and friction
// bound, and inputs refused with a message naming them.
#include "eval/state_eval.hpp"
#include "eval/state_json.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/check.hpp"
#include "error_message.hpp"
#include "generator/test_tables.hpp"
#include "scene/scene.hpp"

namespace railtab::state_eval_test {  // own namespace: unity builds compile several test files as one
namespace {

// railtab eval --model halfspace at the central S1002/UIC60 state (y = 0, 78.5 kN): the vertical
// components of the normal forces carry the load; with creepage the creep forces stay within
// mu N, the load balance includes their vertical part (load coupling) and at a large creepage
// they saturate near mu N.
TEST(HalfspaceSelectable, EvalCentralStateLoadAndFrictionBound) {
  Scene scene = parse_scene(testing::kHalfspaceSmallScene, "h.toml");
  scene.normal.model = NormalModel::stripes_ab;  // --model must switch it
  StateEvalRequest request;
  request.y = 0.0;
  request.load = 78.5e3;
  request.model = "halfspace";
  const nlohmann::json normal = state_json(evaluate_state(scene, request));
  EXPECT_EQ(normal["normal_model"], "halfspace");
  for (const auto& wheel : normal["wheels"]) {
    ASSERT_GE(wheel["contacts"].size(), 1u);
    double vertical = 0.0;
    for (const auto& c : wheel["contacts"]) {
      EXPECT_EQ(c["model"], "halfspace");
      EXPECT_GT(c["area"].get<double>(), 50e-6);  // about 1.5 cm2 on the tread
      EXPECT_GT(c["max_pressure"].get<double>(), 500e6);
      EXPECT_NE(c["status"].get<std::string>().find("converged"), std::string::npos) << c["status"];
      vertical += c["normal_force"].get<double>() * std::cos(c["contact_angle"].get<double>());
    }
    EXPECT_NEAR(vertical, 78.5e3, 1e-3 * 78.5e3);
    EXPECT_NEAR(wheel["vertical_load"].get<double>(), 78.5e3, 1e-3 * 78.5e3);
  }
  const double mu = 0.3;
  for (const double xi : {0.001, 0.02}) {
    request.creepage = {xi, 0.001, 0.1};
    const nlohmann::json creep = state_json(evaluate_state(scene, request));
    EXPECT_EQ(creep["spin"], "exact");
    for (const auto& wheel : creep["wheels"]) {
      const double load_normal = wheel["vertical_load_normal"].get<double>();
      const double load_tangential = wheel["vertical_load_tangential"].get<double>();
      EXPECT_NEAR(load_normal + load_tangential, 78.5e3, 2e-4 * 78.5e3);
      EXPECT_NE(wheel["load_coupling"]["status"].get<std::string>().find("converged"), std::string::npos);
      for (const auto& c : wheel["contacts"]) {
        const double n = c["normal_force"].get<double>();
        const double f = std::hypot(c["fx"].get<double>(), c["fy"].get<double>());
        EXPECT_LE(f, mu * n * (1.0 + 1e-9)) << "xi = " << xi;
        EXPECT_LT(c["fx"].get<double>(), 0.0) << "braking force on the wheel for xi > 0";
        EXPECT_GT(c["wear_rate"].get<double>(), 0.0);
        if (xi > 0.01) {
          EXPECT_GT(f, 0.95 * mu * n) << "xi = " << xi;
        } else {
          EXPECT_LT(f, 0.8 * mu * n) << "xi = " << xi;
        }
      }
    }
  }
}

TEST(NonFinite, CreepagesBeyondPhysicalAreRefused) {
  const std::string scene = std::string(testing::kTreadPointScene);
  const std::string huge = scene.substr(0, scene.find("xi =")) + "xi = [0.0, 1e300]\n";
  EXPECT_NE(test::error_message([&] { parse_scene(huge, "huge.toml"); }).find("far beyond physical"), std::string::npos);
  StateEvalRequest request;
  request.y = 0.001;
  request.creepage = {1e300, 0.0, 0.0};
  EXPECT_NE(test::error_message([&] { evaluate_state(parse_scene(testing::kTreadPointScene, "t.toml"), request); }).find("far beyond"),
            std::string::npos);
}

// eval --load 78.5 (kN typed for N) is refused with the SI spelling; 0 (unloaded) and real loads pass.
TEST(NonFinite, EvalLoadInKiloNewtonsIsRefused) {
  const Scene scene = parse_scene(testing::kTreadPointScene, "t.toml");
  StateEvalRequest request;
  request.y = 0.001;
  request.load = 78.5;
  EXPECT_NE(test::error_message([&] { evaluate_state(scene, request); }).find("78.5e3"), std::string::npos);
  request.load = 78.5e3;
  EXPECT_EQ(test::error_message([&] { evaluate_state(scene, request); }), "");
}

}  // namespace
}  // namespace railtab::state_eval_test
