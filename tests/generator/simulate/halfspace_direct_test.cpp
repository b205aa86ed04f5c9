// SPDX-License-Identifier: Apache-2.0
// The direct contact model with the exact half-space model (normal_model = "halfspace"): at a grid
// node it returns what the table sweep stores: the normal part bit for bit (the same call,
// solve_halfspace_for_load), the coupled creep part within the coupled solve's tolerance (the
// sweep starts each creepage from its neighbour's solution, the direct model from cold; both
// stop at the same fixed point's tolerance).
#include <gtest/gtest.h>

#include "core/status.hpp"
#include "scene/scene.hpp"
#include "simulate/direct_contact_model.hpp"
#include "kernel/contact_kernel.hpp"
#include "engine/sweep.hpp"

namespace railtab {
namespace {

TEST(HalfspaceDirect, AgreesWithTheTableAtAGridNode) {
  const Scene scene = parse_scene(R"(
[scene]
name = "halfspace-direct"
[profiles]
wheel = "s1002"
rail = "uic60"
[contact]
normal_model = "halfspace"
[grid]
y = [0.0]
equilibrium_roll = true
load = [78.5e3]
xi = [0.0, 0.002]
eta = [0.0]
phi = [0.0]
)", "hd.toml");
  const SweepResult r = run_sweep(scene, make_contact_kernel(scene), SweepOptions{});
  ASSERT_EQ(r.summary.failures, 0u) << r.summary.first_failure;
  DirectContactModel direct(scene);
  const double load[vehicle::kWheels] = {78.5e3, 78.5e3};
  vehicle::WheelContacts contacts[vehicle::kWheels];
  direct.normal(0.0, 0.0, load, contacts);
  vehicle::SlotCreepage creepage[vehicle::kWheels][vehicle::kContactSlots];
  for (auto& wheel : creepage) wheel[0] = wheel[1] = {0.002, 0.0, 0.0};  // xi node 1
  vehicle::SlotForces forces[vehicle::kWheels][vehicle::kContactSlots];
  direct.creep(creepage, forces);
  EXPECT_EQ(direct.failures(), 0u);
  for (int w = 0; w < vehicle::kWheels; ++w) {
    const std::string side = w == 0 ? "left" : "right";
    const TableGroup& nor = *r.table.group(side + "/normal");
    const TableGroup& creep = *r.table.group(side + "/creep");
    const vehicle::SlotContact& c = contacts[w].slot[0];  // tread
    ASSERT_TRUE(c.loaded) << side;
    EXPECT_EQ(c.normal_force, nor.find("normal_force")->values[0]) << side;
    EXPECT_EQ(c.area, nor.find("area")->values[0]) << side;
    EXPECT_EQ(c.status, nor.find("status")->status[0]) << side;
    const std::size_t cell = 1 * kSlots + 0;  // xi index 1, slot 0
    // The warm chain's bound (HalfspaceWheelRail.WarmChainIsTheColdFixedPoint): the load split
    // within 2e-4 F_z, the creep forces within that share of mu F_z plus 1e-4 mu N.
    const double fz = load[w], mun = 0.3 * c.normal_force, creep_tol = 2e-4 * fz * 0.3 + 1e-4 * mun;
    EXPECT_NEAR(forces[w][0].fx, creep.find("fx")->values[cell], creep_tol) << side;
    EXPECT_NEAR(forces[w][0].fy, creep.find("fy")->values[cell], creep_tol) << side;
    EXPECT_NEAR(forces[w][0].mz, creep.find("mz")->values[cell], creep_tol * 0.01) << side;
    EXPECT_NEAR(forces[w][0].normal_force, creep.find("normal_force")->values[cell], 2e-4 * fz) << side;
    EXPECT_LT(forces[w][0].fx, -1e3) << side;
    EXPECT_TRUE(forces[w][0].status & status::kConverged) << side;
  }
}

}  // namespace
}  // namespace railtab
