// SPDX-License-Identifier: Apache-2.0
// The normal part's linear creep coefficients (creep_coefficient_*, format 2.3) as the sweep stores
// them: equal to the slot's model computed directly at every node (FASTSIM on strip patches, the
// exact model's steady rolling), Kalker's within 2 % on Hertz patches, and one-sided values at the
// located contact jumps.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "generator/test_tables.hpp"
#include "halfspace/patch_linear_creep.hpp"
#include "kernel/contact_kernel.hpp"
#include "kernel/halfspace_contact.hpp"

namespace railtab::creep_coefficients_test {  // own namespace: unity builds compile several test files as one
namespace {

const char* const kForces[3] = {"fx", "fy", "mz"};
const char* const kCreepages[3] = {"xi", "eta", "phi"};

std::string dataset(int f, int c) { return std::string("creep_coefficient_") + kForces[f] + "_" + kCreepages[c]; }

// The stored coefficient (f, c) of a normal-part cell.
double stored(const TableGroup& normal, int f, int c, std::size_t cell) {
  const TableDataset* d = normal.find(dataset(f, c));
  EXPECT_TRUE(d) << dataset(f, c);
  return d ? d->values.at(cell) : 0.0;
}

// Strip patches (STRIPES A&B) on the tread and the flange, two loads, roll fixed at 0: every
// stored coefficient is, to the bit, the sum of FASTSIM's full-adhesion slopes over the slot's
// patches computed here from the geometry and the normal contact, and the direct terms have
// Kalker's signs.
TEST(CreepCoefficients, StoredEqualTheModelsSlopesAtEveryNode) {
  const Scene scene = parse_scene(R"(
[scene]
name = "coefficients"
[profiles]
wheel = "s1002"
rail = "uic60"
[grid]
y = [-0.004, 0.0, 0.004, 0.0085]
roll = 0.0
load = [60e3, 80e3]
xi = [-0.001, 0.0, 0.001]
)", "coefficients.toml");
  const SweepResult r = run_sweep(scene, make_contact_kernel(scene), SweepOptions{});
  ASSERT_EQ(r.summary.failures, 0u) << r.summary.first_failure;
  const ContactGeometrySolver solver = make_geometry_solver(scene);
  const CreepConditions conditions = creep_conditions(scene);
  const FastsimOptions fastsim = fastsim_options(scene);
  std::size_t loaded = 0;
  for (std::size_t wheel = 0; wheel < 2; ++wheel) {
    const Side side = wheel == 0 ? Side::left : Side::right;
    const TableGroup& normal = *r.table.group(wheel == 0 ? "left/normal" : "right/normal");
    for (std::size_t iy = 0; iy < scene.grids.y.size(); ++iy) {
      const WheelContactGeometry g = solver.solve_wheel(side, WheelsetState{scene.grids.y[iy], 0.0});
      for (std::size_t il = 0; il < scene.grids.load.size(); ++il) {
        const WheelNormalResult n = solve_normal_for_load(g, scene.grids.load[il], scene.material, scene.normal);
        const PatchSlots slots = assign_patch_slots(n, side, solver.settings().flange_angle);
        for (std::size_t s = 0; s < kSlots; ++s) {
          LinearCreep direct;
          for (int ip : slots.patch[s]) {
            if (ip < 0 || !(n.patches[static_cast<std::size_t>(ip)].normal_force > 0.0)) continue;
            const LinearCreep c = fastsim_linear_creep(g, n.patches[static_cast<std::size_t>(ip)], conditions,
                                                       scene.material, fastsim, thread_fastsim_workspace());
            for (int f = 0; f < 3; ++f)
              for (int q = 0; q < 3; ++q) direct.slope[f][q] += c.slope[f][q];
          }
          const std::size_t cell = (iy * scene.grids.load.size() + il) * kSlots + s;
          for (int f = 0; f < 3; ++f)
            for (int q = 0; q < 3; ++q)
              EXPECT_EQ(stored(normal, f, q, cell), direct.slope[f][q])
                  << dataset(f, q) << " wheel " << wheel << " y " << scene.grids.y[iy] << " load " << il << " slot " << s;
          if (!slots.occupied(s)) continue;
          ++loaded;
          EXPECT_LT(stored(normal, 0, 0, cell), 0.0);  // -G c^2 C11
          EXPECT_LT(stored(normal, 1, 1, cell), 0.0);  // -G c^2 C22
        }
      }
    }
  }
  EXPECT_GE(loaded, 16u);  // both wheels, every y and load on the tread, and flange slots at 8.5 mm
  const TableDataset* units = r.table.group("left/normal")->find("creep_coefficient_mz_phi");
  ASSERT_TRUE(units);
  EXPECT_EQ(units->units, "N m2");
}

// Hertz patches (elliptic FASTSIM): the table's own C11, C22, C23 against Kalker's on its own
// semi-axes a, b within 2 % (docs/validation/creep-coefficients.md), tread and flange.
TEST(CreepCoefficients, HertzTableIsKalkerWithinTwoPercent) {
  const Scene scene = parse_scene(R"(
[scene]
name = "hertz"
[profiles]
wheel = "s1002"
rail = "uic60"
[contact]
normal_model = "hertz"
[grid]
y = [-0.003, 0.0, 0.003, 0.0085]
roll = 0.0
load = 78.5e3
xi = 0.0
)", "hertz.toml");
  const SweepResult r = run_sweep(scene, make_contact_kernel(scene), SweepOptions{});
  ASSERT_EQ(r.summary.failures, 0u) << r.summary.first_failure;
  const TableGroup& normal = *r.table.group("left/normal");
  std::size_t checked = 0;
  for (std::size_t cell = 0; cell < normal.find("a")->values.size(); ++cell) {
    const double a = normal.find("a")->values[cell], b = normal.find("b")->values[cell];
    if (!(a > 0.0 && b > 0.0)) continue;
    if (normal.find("status")->status[cell] & status::kTwoPoint) continue;  // two patches: not one ellipse
    const LinearCreep k = kalker_linear_creep(a, b, scene.material);
    EXPECT_NEAR(stored(normal, 0, 0, cell) / k.slope[0][0], 1.0, 0.02) << "C11, cell " << cell;
    EXPECT_NEAR(stored(normal, 1, 1, cell) / k.slope[1][1], 1.0, 0.02) << "C22, cell " << cell;
    EXPECT_NEAR(stored(normal, 1, 2, cell) / k.slope[1][2], 1.0, 0.02) << "C23, cell " << cell;
    ++checked;
  }
  EXPECT_GE(checked, 4u);
}

// The exact model: the stored coefficients are its own steady rolling solution in full adhesion on
// each patch of its creepage-free normal solution (halfspace::patch_linear_creep), to the bit.
TEST(CreepCoefficients, ExactModelStoresItsOwnSteadyRollingSlopes) {
  const Scene scene = parse_scene(R"(
[scene]
name = "exact"
[profiles]
wheel = "s1002"
rail = "uic60"
[contact]
normal_model = "halfspace"
element_size = 0.5e-3
[grid]
y = [0.002]
roll = 0.0
load = 78.5e3
xi = 0.0
)", "exact.toml");
  const SweepResult r = run_sweep(scene, make_contact_kernel(scene), SweepOptions{});
  ASSERT_EQ(r.summary.failures, 0u) << r.summary.first_failure;
  const ContactGeometrySolver solver = make_geometry_solver(scene);
  const halfspace::HalfspaceOptions options = halfspace_options(scene);
  const WheelContactGeometry g = solver.solve_wheel(Side::left, WheelsetState{0.002, 0.0});
  halfspace::Workspace ws;
  const halfspace::WheelHalfspaceResult res = halfspace::solve_halfspace_for_load(g, 78.5e3, scene.material, options, ws);
  const WheelNormalResult n = to_normal_result(res, g);
  const PatchSlots slots = assign_patch_slots(n, Side::left, solver.settings().flange_angle);
  ASSERT_TRUE(slots.occupied(0));
  const TableGroup& normal = *r.table.group("left/normal");
  for (std::size_t s = 0; s < kSlots; ++s) {
    LinearCreep direct;
    for (int ip : slots.patch[s]) {
      if (ip < 0) continue;
      const halfspace::HalfspacePatch& p = res.patches[static_cast<std::size_t>(ip)];
      const LinearCreep c = halfspace::patch_linear_creep(p.grid, p.normal.pressure, scene.material, options.tangential, ws,
                                                                  p.track_sign);
      for (int f = 0; f < 3; ++f)
        for (int q = 0; q < 3; ++q) direct.slope[f][q] += c.slope[f][q];
    }
    for (int f = 0; f < 3; ++f)
      for (int q = 0; q < 3; ++q) EXPECT_EQ(stored(normal, f, q, s), direct.slope[f][q]) << dataset(f, q) << " slot " << s;
  }
  EXPECT_LT(stored(normal, 0, 0, 0), 0.0);
}

}  // namespace
}  // namespace railtab::creep_coefficients_test
