// SPDX-License-Identifier: Apache-2.0
// The sweep engine (generator/engine/) on a synthetic kernel: table layout, failures as status,
// thread-count determinism, shards, interruption.
#include "engine/sweep.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/check.hpp"
#include "generator/synthetic_kernel.hpp"
#include "generator/test_tables.hpp"

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
  EXPECT_EQ(*t.attribute("format_version"), "2.3");
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

}  // namespace
}  // namespace railtab
