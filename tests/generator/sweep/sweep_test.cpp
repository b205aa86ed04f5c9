// SPDX-License-Identifier: Apache-2.0
// The sweep engine and contact kernel (generator/sweep/): table layout, failures as status,
// thread-count determinism.
#include "sweep/sweep.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/check.hpp"
#include "generator/synthetic_kernel.hpp"
#include "generator/test_tables.hpp"
#include "sweep/contact_kernel.hpp"

namespace railtab {
namespace {

SweepResult run(const Scene& scene, int threads, int shard_index = 1, int shard_count = 1) {
  SweepOptions o;
  o.threads = threads;
  o.shard_index = shard_index;
  o.shard_count = shard_count;
  return run_sweep(scene, testing::synthetic_kernel(scene), o);
}

TEST(Sweep, LayoutFollowsTheFormat) {
  Scene scene = parse_scene(testing::kSyntheticScene, "s.toml");
  SweepResult r = run(scene, 1);
  const Table& t = r.table;
  EXPECT_EQ(*t.attribute("format_version"), "2.2");
  EXPECT_EQ(*t.attribute("scene"), scene.text);
  EXPECT_EQ(*t.attribute("scene_name"), "synthetic");
  EXPECT_EQ(*t.attribute("fixed_axes"), R"({"eta":0.0})");
  EXPECT_FALSE(t.attribute("created")->empty());
  EXPECT_FALSE(t.attribute("shard"));
  std::vector<std::string> axes;
  for (const TableAxis& a : t.axes) axes.push_back(a.name);
  EXPECT_EQ(axes, (std::vector<std::string>{"y", "roll", "load", "xi", "phi", "slot"}));  // eta fixed
  const TableDataset* fx = t.group("right/creep")->find("fx");
  ASSERT_TRUE(fx);
  EXPECT_EQ(fx->axes, (std::vector<std::string>{"y", "roll", "load", "xi", "phi", "slot"}));
  EXPECT_EQ(fx->shape, (std::vector<std::size_t>{7, 2, 2, 3, 2, 2}));
  EXPECT_EQ(t.group("left/geometry")->find("status")->shape, (std::vector<std::size_t>{7, 2, 2}));
  EXPECT_EQ(r.summary.points_total, 7u * 2 * 2 * 3 * 2);
  EXPECT_EQ(r.summary.points_computed, r.summary.points_total);
  EXPECT_FALSE(r.summary.interrupted);
  // Value at a known flat index: y index 3, roll 1, load 1, xi 2, phi 1, slot 1 of the right wheel.
  // Column cell (((load * nxi + xi) * neta + eta) * nphi + phi) * nslot + slot:
  std::size_t cell = (((1 * 3 + 2) * 1 + 0) * 2 + 1) * 2 + 1;
  std::size_t flat = (3 * 2 + 1) * (2 * 3 * 1 * 2 * 2) + cell;
  double expected = std::sin(1e3 * scene.grids.y[3] + 7e2 * 0.001 + 0.1 * static_cast<double>(cell) + 2 + 0.0 + 0.5);
  EXPECT_EQ(fx->values[flat], expected);
}

TEST(Sweep, FailuresBecomeStatusFlagsNotAborts) {
  Scene scene = parse_scene(testing::kSyntheticScene, "s.toml");
  SweepResult r = run(scene, 2);
  EXPECT_EQ(r.summary.failures, 1u);
  EXPECT_EQ(r.summary.first_failure, "synthetic failure");
  const TableDataset* st = r.table.group("right/normal")->find("status");
  EXPECT_EQ(st->status[(1 * 2 + 0) * 4], status::kNotConverged);
}

TEST(Sweep, BitIdenticalForAnyThreadCount) {
  Scene scene = parse_scene(testing::kSyntheticScene, "s.toml");
  SweepResult one = run(scene, 1);
  SweepResult two = run(scene, 2);
  SweepResult four = run(scene, 4);
  testing::expect_same_datasets(one.table, two.table);
  testing::expect_same_datasets(one.table, four.table);
  EXPECT_EQ(two.summary.threads, 2);
}

TEST(Sweep, EquilibriumRollIsARootDataset) {
  Scene scene = parse_scene(std::string(testing::kSyntheticScene).replace(
                                std::string(testing::kSyntheticScene).find("roll = [-0.001, 0.001]"), 22,
                                "equilibrium_roll = true"),
                            "s.toml");
  SweepResult r = run(scene, 2);
  EXPECT_FALSE(r.table.axis("roll"));
  EXPECT_EQ(*r.table.attribute("fixed_axes"), R"({"eta":0.0,"roll":"equilibrium"})");
  const TableDataset* roll = r.table.group("")->find("equilibrium_roll");
  ASSERT_TRUE(roll);
  EXPECT_EQ(roll->axes, std::vector<std::string>{"y"});
  for (std::size_t i = 0; i < scene.grids.y.size(); ++i) EXPECT_EQ(roll->values[i], -0.05 * scene.grids.y[i]);
  EXPECT_EQ(r.table.group("left/normal")->find("area")->shape, (std::vector<std::size_t>{7, 2, 2}));
}

TEST(Sweep, ShardsSplitYIntoContiguousParts) {
  EXPECT_EQ(shard_range(7, 1, 3), (std::pair<std::size_t, std::size_t>{0, 2}));
  EXPECT_EQ(shard_range(7, 2, 3), (std::pair<std::size_t, std::size_t>{2, 4}));
  EXPECT_EQ(shard_range(7, 3, 3), (std::pair<std::size_t, std::size_t>{4, 7}));
  EXPECT_THROW(shard_range(7, 0, 3), Error);
  EXPECT_THROW(shard_range(2, 1, 3), Error);
  Scene scene = parse_scene(testing::kSyntheticScene, "s.toml");
  SweepResult r = run(scene, 1, 2, 3);
  EXPECT_EQ(*r.table.attribute("shard"), "2/3");
  EXPECT_EQ(r.table.axis("y")->values, (std::vector<double>{scene.grids.y[2], scene.grids.y[3]}));
  EXPECT_EQ(r.summary.points_total, 2u * 2 * 2 * 3 * 2);
}

TEST(Sweep, PreSetInterruptComputesNothing) {
  Scene scene = parse_scene(testing::kSyntheticScene, "s.toml");
  std::atomic<bool> stop{true};
  SweepOptions o;
  o.interrupt = &stop;
  SweepResult r = run_sweep(scene, testing::synthetic_kernel(scene), o);
  EXPECT_TRUE(r.summary.interrupted);
  EXPECT_EQ(r.summary.points_computed, 0u);
}

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
  // points share a slot (kTwoPoint) the slot's force is the sum of its patches but the geometry part
  // holds one point's angle, so there only an upper bound is checked (tests/generator/simulate/
  // slot_sum_test.cpp checks the balance within the spread of the patch angles).
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

// Load coupling (issue 14): the creep part holds the normal contact per creepage. Left wheel in
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

}  // namespace
}  // namespace railtab
