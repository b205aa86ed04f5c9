// SPDX-License-Identifier: Apache-2.0
// 6. Vanishing load and lift-off (FACTS 8 row 7): divisions by N, a, b must not produce NaN.
#include "stability_common.hpp"

namespace railtab::stability {
namespace {

TEST(LiftOff, ZeroTinyAndSmallLoads) {
  const ContactGeometrySolver& solver = s1002_uic60();
  for (const Variant& v : all_variants()) {
    for (Side side : {Side::left, Side::right}) {
      // y = 0 (one patch) and 4.5 mm towards the flange (two rigid points).
      for (double y : {0.0, 4.5e-3}) {
        const WheelContactGeometry g = solver.solve_wheel(side, WheelsetState{outward_sign(side) * y, 0.0});
        for (double load : {0.0, 1e-6, 1.0}) {
          const std::string where = v.label + " " + to_string(side) + " y " + std::to_string(y) +
                                    " load " + std::to_string(load);
          const WheelNormalResult r = solve_normal_for_load(g, load, Material{}, options_for(v));
          ASSERT_EQ(normal_violation(g, r), "") << where;
          EXPECT_TRUE(bitwise_equal(r, solve_normal_for_load(g, load, Material{}, options_for(v))));
          if (load == 0.0) {
            EXPECT_TRUE(r.status & status::kLiftOff) << where;
            EXPECT_TRUE(r.patches.empty()) << where;
            EXPECT_EQ(r.carried_load, 0.0) << where;
            continue;
          }
          EXPECT_TRUE(r.status & status::kConverged) << where;
          EXPECT_FALSE(r.status & status::kLiftOff) << where;
          EXPECT_NEAR(r.carried_load, load, 1e-6 * load) << where;
          // A tiny load touches the primary point only: the second contact stays unloaded.
          ASSERT_EQ(r.patches.size(), 1u) << where;
          if (g.points.size() > 1) {
            EXPECT_EQ(r.point_patch[1], -1) << where;
          }
          for (const ContactPatch& p : r.patches) {
            const CreepWear cw = creep_and_wear(g, p, Creepage{1e-3, 1e-3, 0.5});
            EXPECT_EQ(creep_violation(p, cw, 0.3), "") << where;
          }
        }
      }
    }
  }
}

TEST(LiftOff, NegativeApproachLiftsOff) {
  const ContactGeometrySolver& solver = s1002_uic60();
  for (const Variant& v : all_variants()) {
    for (double y : {0.0, 4.5e-3, 7e-3}) {
      const WheelContactGeometry g = solver.solve_wheel(Side::left, WheelsetState{y, 0.0});
      for (double dz : {-1e-3, -1e-9, 0.0}) {
        const WheelNormalResult r = solve_normal_for_approach(g, dz, Material{}, options_for(v));
        EXPECT_EQ(normal_violation(g, r), "") << v.label;
        EXPECT_TRUE(r.status & status::kLiftOff) << v.label << " dz " << dz;
        EXPECT_TRUE(r.patches.empty()) << v.label;
        EXPECT_EQ(r.carried_load, 0.0) << v.label;
        for (int k : r.point_patch) EXPECT_EQ(k, -1);
      }
      // A positive approach below the second point's separation loads only the first.
      const WheelNormalResult r = solve_normal_for_approach(g, 1e-7, Material{}, options_for(v));
      EXPECT_EQ(normal_violation(g, r), "") << v.label;
      EXPECT_FALSE(r.status & status::kLiftOff) << v.label << " y " << y;
    }
  }
}

// FASTSIM and wear on an unloaded patch: zeros and kLiftOff, never NaN - also right after a loaded
// patch was solved in the same (thread's) workspace: the wear of the unloaded patch is zero.
TEST(LiftOff, UnloadedPatchHasNoCreepOrWear) {
  const WheelContactGeometry g = s1002_uic60().solve_wheel(Side::left, WheelsetState{0.0, 0.0});
  const WheelNormalResult loaded = solve_normal_for_load(g, kLoad, Material{}, options_for(all_variants()[5]));
  ASSERT_FALSE(loaded.patches.empty());
  const CreepWear before = creep_and_wear(g, loaded.patches.front(), Creepage{0.1, 0.1, 1.0});
  ASSERT_GT(before.wear.wear_rate, 0.0);
  ContactPatch empty;
  const CreepWear cw = creep_and_wear(g, empty, Creepage{0.1, 0.1, 1.0});
  EXPECT_TRUE(cw.creep.status & status::kLiftOff);
  EXPECT_EQ(cw.creep.fx, 0.0);
  EXPECT_EQ(cw.creep.fy, 0.0);
  EXPECT_EQ(cw.creep.mz, 0.0);
  EXPECT_EQ(cw.wear.wear_rate, 0.0);
  EXPECT_EQ(cw.wear.volume_rate, 0.0);
  EXPECT_EQ(creep_violation(empty, cw, 0.3), "");
}

}  // namespace
}  // namespace railtab::stability
