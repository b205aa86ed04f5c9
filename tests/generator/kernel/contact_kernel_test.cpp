// SPDX-License-Identifier: Apache-2.0
// The contact kernel (generator/kernel/) run by the sweep engine: thread-count determinism,
// physically sane parts, slot assignment, and non-finite results stored as failed, never converged.
#include "kernel/contact_kernel.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/check.hpp"
#include "generator/test_tables.hpp"
#include "kernel/creep_map.hpp"
#include "kernel/finite_status.hpp"
#include "kernel/halfspace_contact.hpp"
#include "halfspace/patch_linear_creep.hpp"

namespace railtab::contact_kernel_test {  // own namespace: unity builds compile several test files as one
namespace {

// The real contact kernel on a tiny grid: deterministic across thread counts, and physically sane.
TEST(ContactSweep, DefaultProfilesSmallGrid) {
  Scene scene = parse_scene(R"(
[scene]
name = "small"
[profiles]
wheel = "s1002"
rail = "uic60"
[grid]
y = [-0.004, 0.0, 0.004, 0.009]
equilibrium_roll = true
load = [60e3, 80e3]
)", "small.toml");
  SweepKernel kernel = make_contact_kernel(scene);
  SweepOptions one, two;
  one.threads = 1;
  two.threads = 2;
  SweepResult a = run_sweep(scene, kernel, one);
  SweepResult b = run_sweep(scene, kernel, two);
  testing::expect_same_datasets(a.table, b.table);
  EXPECT_EQ(a.summary.failures, 0u) << a.summary.first_failure;
  // At y = 0 the left wheel runs on its tread: slot 0 holds a converged contact, radius ~ 0.46 m.
  const TableGroup& geo = *a.table.group("left/geometry");
  EXPECT_TRUE(geo.find("status")->status[1 * 2 + 0] & status::kConverged);
  EXPECT_NEAR(geo.find("rolling_radius")->values[1 * 2 + 0], 0.46, 0.005);
  // The vertical components of the normal forces of one wheel carry its load. Where two rigid
  // points share a slot (kTwoPoint) the slot's force is the sum of its patches but the geometry
  // part holds one point's angle, so there only an upper bound is checked
  // (tests/generator/simulate/ slot_sum_test.cpp checks the balance within the spread of the patch
  // angles).
  const TableGroup& nor = *a.table.group("left/normal");
  for (std::size_t iy = 0; iy < 4; ++iy) {
    bool dropped = false;
    for (std::size_t s = 0; s < 2; ++s) dropped |= (geo.find("status")->status[iy * 2 + s] & status::kTwoPoint) != 0;
    for (std::size_t il = 0; il < 2; ++il) {
      double vertical = 0.0;
      for (std::size_t s = 0; s < 2; ++s) {
        vertical += nor.find("normal_force")->values[(iy * 2 + il) * 2 + s] *
                    std::cos(geo.find("contact_angle")->values[iy * 2 + s]);
      }
      if (dropped) {
        EXPECT_LT(vertical, 1.01 * scene.grids.load[il]) << "y index " << iy;
      } else {
        EXPECT_NEAR(vertical, scene.grids.load[il], 1e-2 * scene.grids.load[il]) << "y index " << iy;
      }
    }
  }
  // At y = +9 mm the left wheel is in flange contact (slot 1).
  EXPECT_TRUE(geo.find("status")->status[3 * 2 + 1] & status::kFlangeContact);
}

// Load coupling: the creep part holds the normal contact per creepage. Left wheel in
// flange contact (y = +8 mm, Hertz, one patch): N cos g + fy sin g equals the load within the
// coupling tolerance at every creepage (g of the rigid point = the Hertz patch's angle), N moves
// by tens of per cent between eta = -0.001 and +0.001, and the normal part keeps the
// creepage-free N. Without the coupling the creep part has no normal outputs.
TEST(ContactSweep, CreepPartHoldsTheCoupledNormalForce) {
  const char* text = R"(
[scene]
name = "coupled"
[profiles]
wheel = "s1002"
rail = "uic60"
[contact]
normal_model = "hertz"
load_coupling = LOAD_COUPLING
[grid]
y = [0.0, 0.008]
roll = 0.0
load = 78.5e3
xi = 0.0
eta = [-0.001, 0.0, 0.001]
phi = 0.0
)";
  auto scene_with = [&](const char* coupling) {
    std::string t = text;
    t.replace(t.find("LOAD_COUPLING"), 13, coupling);
    return parse_scene(t, "coupled.toml");
  };
  const Scene scene = scene_with("true");
  SweepResult r = run_sweep(scene, make_contact_kernel(scene), SweepOptions{});
  ASSERT_EQ(r.summary.failures, 0u) << r.summary.first_failure;
  const TableGroup& creep = *r.table.group("left/creep");
  const TableGroup& normal = *r.table.group("left/normal");
  const TableGroup& geo = *r.table.group("left/geometry");
  ASSERT_TRUE(creep.find("normal_force"));
  ASSERT_TRUE(creep.find("area") && creep.find("max_pressure") && creep.find("approach"));
  // Cells: y index iy, eta index ie, slot s: (iy * 3 + ie) * 2 + s. Flange slot at y = 8 mm.
  const std::size_t iy = 1, s = 1;
  ASSERT_TRUE(geo.find("status")->status[iy * 2 + s] & status::kFlangeContact);
  const double g = geo.find("contact_angle")->values[iy * 2 + s];
  const double n0 = normal.find("normal_force")->values[iy * 2 + s];
  double n[3];
  for (std::size_t ie = 0; ie < 3; ++ie) {
    const std::size_t cell = (iy * 3 + ie) * 2 + s;
    n[ie] = creep.find("normal_force")->values[cell];
    const double fy = creep.find("fy")->values[cell];
    EXPECT_NEAR(n[ie] * std::cos(g) + fy * std::sin(g), 78.5e3, 2 * coupled_load_options(scene).tolerance * 78.5e3)
        << "eta index " << ie;
    EXPECT_FALSE(creep.find("status")->status[cell] & status::kNotConverged);
  }
  EXPECT_NEAR(n[1], n0, 1e-3 * n0);  // no lateral creepage: (almost) the creepage-free N
  EXPECT_GT(std::abs(n[2] - n[0]), 0.3 * n0);
  // Without the coupling the creep part has no normal outputs (format 1.0 layout).
  const Scene off = scene_with("false");
  SweepResult u = run_sweep(off, make_contact_kernel(off), SweepOptions{});
  EXPECT_FALSE(u.table.group("left/creep")->find("normal_force"));
}

TEST(ContactKernel, SlotsByFlangeFlagLowerSeparationWins) {
  WheelContactGeometry g;
  ContactPoint tread{};
  tread.status = 0;
  tread.separation = 0.0;
  ContactPoint flange_far{};
  flange_far.status = status::kFlangeContact;
  flange_far.separation = 3e-4;
  ContactPoint flange_near = flange_far;
  flange_near.separation = 1e-4;
  g.points = {tread, flange_far, flange_near};
  SlotAssignment a = assign_slots(g);
  EXPECT_EQ(a.point[0], 0);
  EXPECT_EQ(a.point[1], 2);
  EXPECT_EQ(a.extra[0], 0u);
  EXPECT_EQ(a.extra[1], status::kTwoPoint);
  g.points = {flange_near};
  a = assign_slots(g);
  EXPECT_EQ(a.point[0], -1);
  EXPECT_EQ(a.point[1], 0);
}

// A creepage past the scene check (a caller building the grid itself) overflows FASTSIM to NaN:
// the table stores zeros with `failed`, never NaN with `converged`.
TEST(NonFinite, NaNInTheKernelIsFailedNotConverged) {
  Scene scene = parse_scene(testing::kTreadPointScene, "t.toml");
  scene.grids.xi = {1e300};
  const SweepResult r = run_sweep(scene, make_contact_kernel(scene), SweepOptions{});
  EXPECT_GT(r.summary.failures, 0u);
  EXPECT_NE(r.summary.first_failure.find("not finite"), std::string::npos) << r.summary.first_failure;
  std::size_t failed = 0;
  for (const TableGroup& g : r.table.groups) {
    for (const TableDataset& d : g.datasets) {
      for (double v : d.values) EXPECT_TRUE(std::isfinite(v)) << g.path << "/" << d.name;
      if (!d.is_status || g.path.find("creep") == std::string::npos) continue;
      for (StatusBits s : d.status) {
        if (s == 0) continue;  // empty slot
        EXPECT_FALSE(s & status::kConverged) << g.path << ": " << status::describe(s);
        EXPECT_TRUE(s & status::kFailed) << g.path << ": " << status::describe(s);
        ++failed;
      }
    }
  }
  EXPECT_GT(failed, 0u);
}

// A column that fails (here a wheel off its rail at y = 0.1 m) keeps positive creep scales in a
// normalised table: with zeros the lookup refused the whole table ("holds a scale that is not
// finite and > 0"), so one failed point made every other unusable.
TEST(NonFinite, FailedColumnKeepsPositiveCreepScales) {
  std::string text = testing::kTreadPointScene;
  text.replace(text.find("y = [0.001]"), 11, "y = [0.001, 0.1]");
  text += "eta = [0.0]\nphi = [0.0]\ncreep_coordinates = \"normalised\"\n";
  const Scene scene = parse_scene(text, "t.toml");
  ASSERT_TRUE(scene.creep_normalised);
  const SweepResult r = run_sweep(scene, make_contact_kernel(scene), SweepOptions{});
  ASSERT_GT(r.summary.failures, 0u);
  std::size_t scales = 0;
  for (const TableGroup& g : r.table.groups) {
    for (const char* name : {"creep_scale_xi", "creep_scale_eta", "creep_scale_phi"}) {
      const TableDataset* d = g.find(name);
      if (!d) continue;
      for (double v : d->values) EXPECT_TRUE(std::isfinite(v) && v > 0.0) << g.path << "/" << name << " " << v;
      scales += d->values.size();
    }
  }
  EXPECT_GT(scales, 0u);
}

// The exact model in normalised creep coordinates: each slot's scales are those of the exact
// model's own linear creep coefficients (patch_linear_creep on the creepage-free exact solution:
// s_xi = 3 mu N / k_xx, s_eta = 3 mu N / k_yy, s_phi = mu N / k_y,phi), each node's stored
// normalised forces are the cold exact solve at that node's physical creepage (to the coupled
// solve's tolerance: the sweep's solves are warm-started along the creepage chain), the creep
// part's normal_force is the vertical share, and 1 and 2 threads give the same bytes. Tread
// (y = 0) and flange contact (y = 7 mm, left wheel), element size 0.6 mm to keep it quick.
TEST(ContactSweep, ExactNormalisedNodesAreTheExactModel) {
  const Scene scene = parse_scene(R"(
[scene]
name = "exact_normalised"
[profiles]
wheel = "s1002"
rail = "uic60"
[contact]
normal_model = "halfspace"
element_size = 0.6e-3
[grid]
y = [0.0, 0.007]
load = [78.5e3]
xi = [-0.004, 0.0, 0.004]
eta = [-0.004, 0.004]
phi = [-0.5, 0.5]
creep_coordinates = "normalised"
)", "exact_normalised.toml");
  const SweepKernel kernel = make_contact_kernel(scene);
  SweepOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const SweepResult a = run_sweep(scene, kernel, one);
  const SweepResult b = run_sweep(scene, kernel, two);
  testing::expect_same_datasets(a.table, b.table);
  ASSERT_EQ(a.summary.failures, 0u) << a.summary.first_failure;
  const double mu = scene.tangential.friction, fz = 78.5e3;
  const Material material = scene.material;
  const halfspace::HalfspaceOptions options = halfspace_options(scene);
  halfspace::Workspace ws;
  const ContactGeometrySolver solver = make_geometry_solver(scene);
  const std::size_t ncreep = 3 * 2 * 2;
  int checked = 0, flange = 0;
  for (std::size_t iy = 0; iy < 2; ++iy) {
    const double y = scene.grids.y[iy];
    const WheelContactGeometry g = solver.solve_wheel(Side::left, {y, 0.0});
    const halfspace::WheelHalfspaceResult free = halfspace::solve_halfspace_for_load(g, fz, material, options, ws);
    const WheelNormalResult normal = to_normal_result(free, g);
    const PatchSlots slots = assign_patch_slots(normal, Side::left, solver.settings().flange_angle);
    const TableGroup& nor = *a.table.group("left/normal");
    const TableGroup& creep = *a.table.group("left/creep");
    for (std::size_t s = 0; s < kSlots; ++s) {
      if (!slots.occupied(s)) continue;
      flange += s == 1;
      // The scales from the exact model's own slopes.
      double kxx = 0.0, kyy = 0.0, kyp = 0.0;
      for (const int ip : slots.patch[s]) {
        if (ip < 0) continue;
        const halfspace::HalfspacePatch& hp = free.patches[static_cast<std::size_t>(ip)];
        const LinearCreep c = halfspace::patch_linear_creep(hp.grid, hp.normal.pressure, material, options.tangential, ws,
                                                                  hp.track_sign);
        kxx -= c.slope[0][0];
        kyy -= c.slope[1][1];
        kyp -= c.slope[1][2];
      }
      const double mun = mu * slot_normal(normal, slots, s).normal_force;
      const creep_map::Scales sc{3.0 * mun / kxx, 3.0 * mun / kyy, mun / kyp};
      EXPECT_NEAR(nor.find("creep_scale_xi")->values[iy * 2 + s], sc.xi, 1e-9 * sc.xi) << y << " slot " << s;
      EXPECT_NEAR(nor.find("creep_scale_eta")->values[iy * 2 + s], sc.eta, 1e-9 * sc.eta) << y << " slot " << s;
      EXPECT_NEAR(nor.find("creep_scale_phi")->values[iy * 2 + s], sc.phi, 1e-9 * sc.phi) << y << " slot " << s;
      // Every node against a cold solve at its physical creepage (all patches of the wheel at the
      // slot's creepage, as the sweep).
      const std::vector<double> vx = creep_map::nodes(3), ve = creep_map::nodes(2), vp = creep_map::nodes(2);
      for (std::size_t node = 0; node < ncreep; ++node) {
        const Creepage c{creep_map::physical(vx[node / 4], -0.004, 0.004, sc.xi),
                         creep_map::physical(ve[node / 2 % 2], -0.004, 0.004, sc.eta),
                         creep_map::physical(vp[node % 2], -0.5, 0.5, sc.phi)};
        const halfspace::WheelHalfspaceResult r = halfspace::solve_halfspace_rolling(g, fz, c, mu, material, options, ws);
        const WheelNormalResult rn = to_normal_result(r, g);
        const PatchSlots rs = assign_patch_slots(rn, Side::left, solver.settings().flange_angle);
        ASSERT_TRUE(rs.occupied(s));
        double fx = 0.0, fy = 0.0;
        for (const int ip : rs.patch[s])
          if (ip >= 0) fx += r.patches[static_cast<std::size_t>(ip)].tangential.fx, fy += r.patches[static_cast<std::size_t>(ip)].tangential.fy;
        const double n = slot_normal(rn, rs, s).normal_force;
        const std::array<double, 2> law = creep_map::law(c.xi / sc.xi, c.eta / sc.eta, c.phi / sc.phi, 0.0);
        const std::size_t cell = (iy * ncreep + node) * kSlots + s;
        const std::string where = "y " + std::to_string(y) + " slot " + std::to_string(s) + " node " + std::to_string(node);
        EXPECT_TRUE(creep.find("status")->status[cell] & status::kConverged) << where;
        // 2e-4 F_z on the load balance moves N, hence F / (mu N), by about 2e-4 F_z / N.
        const double tol = 2e-4 * fz / n + 1e-4;
        EXPECT_NEAR(creep.find("fx_normalised")->values[cell] + law[0], fx / (mu * n), tol) << where;
        EXPECT_NEAR(creep.find("fy_normalised")->values[cell] + law[1], fy / (mu * n), tol) << where;
        const double angle = g.points[static_cast<std::size_t>(assign_slots(g).point[s])].contact_angle;
        EXPECT_NEAR(creep.find("normal_force")->values[cell], creep_map::vertical_share(n, fy, angle), 2e-4 * fz)
            << where;
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 2 * static_cast<int>(ncreep));  // the tread column and the flange column (one slot each)
  EXPECT_EQ(flange, 1);
}

TEST(NonFinite, StatusHelperDropsConverged) {
  const StatusBits s = non_finite_status(status::kConverged | status::kTwoPoint);
  EXPECT_EQ(s, status::kFailed | status::kTwoPoint);
}

}  // namespace
}  // namespace railtab::contact_kernel_test
