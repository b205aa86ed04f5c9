// SPDX-License-Identifier: Apache-2.0
// The mirrored sweep (engine/mirror.hpp): on a mirror-symmetric scene railtab generate computes
// y >= 0 and the left wheel's contact jumps only, and fills the rest by the mirror that swaps the
// wheels. The table must be the full computation's to the last byte, for every dataset of both
// wheels, the jumps and their one-sided values and the error map; shards, checkpoints and
// asymmetric scenes keep their behaviour.
#include "engine/mirror.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <string>

#include "generator/synthetic_kernel.hpp"
#include "generator/test_tables.hpp"
#include "generate/error_map.hpp"
#include "generate/generate.hpp"
#include "kernel/contact_kernel.hpp"
#include "table/merge.hpp"
#include "table/table_io.hpp"

namespace railtab {
namespace {
// Own names: the folder's tests build as one unity translation unit.
namespace mirror_sweep {

// Reduced default scenes, y symmetric with flange contact and contact jumps on both sides, the
// creepage lists symmetric in eta and phi (xi need not be), normalised creep coordinates (7 eta
// nodes: normalised nodes at +-1/3, +-2/3, which must mirror to the last bit).
constexpr const char* kStripesScene = R"(
[scene]
name = "mirror_stripes"
[profiles]
wheel = "s1002"
rail = "uic60"
[contact]
normal_model = "stripes-ab"
negative_curvature = "shift"
strips = 50
[grid]
y = [-0.008, -0.0065, -0.005, 0.0, 0.005, 0.0065, 0.008]
equilibrium_roll = true
load = [60e3, 90e3]
xi = [-0.002, 0.0, 0.001, 0.002]
eta = [-0.001, -0.0005, -0.0002, 0.0, 0.0002, 0.0005, 0.001]
phi = [-0.2, 0.0, 0.2]
creep_coordinates = "normalised"
creep_knee = [1.0, 3.0, 4.0]
)";

constexpr const char* kHalfspaceScene = R"(
[scene]
name = "mirror_halfspace"
[profiles]
wheel = "s1002"
rail = "uic60"
[contact]
normal_model = "halfspace"
element_size = 0.6e-3
[grid]
y = [-0.0065, 0.0, 0.0065]
equilibrium_roll = true
load = [78.5e3]
xi = [0.0, 0.002]
eta = [-0.001, 0.001]
phi = [-0.2, 0.2]
creep_coordinates = "normalised"
creep_knee = [1.0, 3.0, 4.0]
)";

struct Generated {
  SweepSummary summary;
  Table table;
};

Generated generate(const testing::TempDir& dir, const std::string& scene, const std::string& name, bool mirror,
             int threads = 2) {
  std::ofstream(dir / "scene.toml") << scene;
  GenerateOptions o;
  o.scene = dir / "scene.toml";
  o.output = dir / name;
  o.threads = threads;
  o.mirror = mirror;
  Generated r;
  r.summary = generate_table(o);
  r.table = read_table(o.output);
  return r;
}

// Every dataset and every root attribute but the creation time, to the byte.
void expect_same_table(const Table& a, const Table& b) {
  testing::expect_same_datasets(a, b);
  ASSERT_EQ(a.attributes.size(), b.attributes.size());
  for (const auto& [name, value] : a.attributes)
    if (name != "created") {
      EXPECT_EQ(value, *b.attribute(name)) << name;
    }
}

void expect_mirror_is_full(const std::string& scene, const std::string& name, std::size_t min_jumps) {
  testing::TempDir dir{name};
  const Generated mirrored = generate(dir, scene, "mirrored.h5", true);
  const Generated full = generate(dir, scene, "full.h5", false);
  EXPECT_TRUE(mirrored.summary.mirrored) << mirrored.summary.full_sweep_reason;
  EXPECT_FALSE(full.summary.mirrored);
  // Half the columns plus the one at y = 0.
  const std::size_t ny = full.table.axis("y")->values.size();
  EXPECT_EQ(mirrored.summary.points_computed, full.summary.points_computed / ny * (ny / 2 + 1));
  const TableGroup* jumps = full.table.group(kJumpGroup);
  ASSERT_TRUE(jumps) << "the scene must have contact jumps for this test to mean anything";
  std::size_t count = 0;
  for (const char* wheel : {"left_y", "right_y"})
    for (double y : jumps->find(wheel)->values) count += !std::isnan(y);
  EXPECT_GE(count, min_jumps);
  ASSERT_TRUE(full.table.group(kErrorMapGroup)) << "no error map";
  expect_same_table(full.table, mirrored.table);
}

// The default model: the mirrored table is the full sweep's, every byte.
TEST(Mirror, StripesTableIsTheFullSweep) { expect_mirror_is_full(kStripesScene, "mirror_stripes", 8); }

// The other models that pass the mirror, on the jump scene of the other tests with spin.
TEST(Mirror, FastModelTablesAreTheFullSweep) {
  for (const char* model : {"linder", "kik-piotrowski", "stripes-a"}) {
    std::string scene = testing::kJumpScene;
    scene += "phi = [-0.2, 0.0, 0.2]\n";
    scene.replace(scene.find("hertz"), 5, model);
    SCOPED_TRACE(model);
    expect_mirror_is_full(scene, std::string("mirror_") + model, 2);
  }
}

// The exact half-space model likewise: both wheels solve one discrete problem (the patch's y
// towards the track centre on both, halfspace/wheel_rail.hpp).
TEST(Mirror, HalfspaceTableIsTheFullSweep) { expect_mirror_is_full(kHalfspaceScene, "mirror_halfspace", 2); }

// Hertz is not mirror-symmetric to the last bit: its ellipse's FASTSIM gives fx at spin +phi and
// -phi that differ in the last bits (the full sweep's odd linear creep coefficients fx_phi and
// mz_xi, rounding noise about 0, then keep their sign on both wheels). Its tables run the full
// sweep.
// The exact scene in tables/ (7 x 7 x 7 normalised creepages) is mirrored.
TEST(Mirror, DefaultSceneIsMirrored) {
  const Scene scene = load_scene(std::filesystem::path(RAILTAB_SOURCE_DIR) / "tables" / "default.toml");
  EXPECT_EQ(mirror_obstacle(scene, make_contact_kernel(scene)), "");
}

TEST(Mirror, HertzTableRunsTheFullSweep) {
  Scene scene = parse_scene(std::string(testing::kJumpScene) + "phi = [-0.2, 0.0, 0.2]\n", "mirror");
  EXPECT_EQ(mirror_obstacle(scene), "");
  EXPECT_EQ(mirror_obstacle(scene, make_contact_kernel(scene)), "the kernel's model is not mirror-symmetric");
}

// Shards of a mirrored table: a shard whose y < 0 has its +y in another shard computes that
// column aside; merged, the shards are the single run, the contact jumps (located per shard)
// and their one-sided values included.
TEST(Mirror, MergedShardsAreTheSingleRun) {
  testing::TempDir dir{"mirror_merge"};
  const Generated single = generate(dir, kStripesScene, "single.h5", true);
  for (int count : {2, 3}) {
    std::vector<std::string> shards;
    for (int i = 1; i <= count; ++i) {
      GenerateOptions o;
      o.scene = dir / "scene.toml";
      o.output = dir / fmt::format("s{}.h5", i);
      o.shard_index = i;
      o.shard_count = count;
      o.threads = 2;
      EXPECT_TRUE(generate_table(o).mirrored);
      shards.push_back(o.output.string());
    }
    merge_table_files(shards, (dir / "merged.h5").string(), error_map_merge_finish());
    testing::expect_same_datasets(single.table, read_table(dir / "merged.h5"));
  }
}

// The mirror image of a column computed by the kernel at -y is the kernel's column at y, for
// each wheel, every dataset: checked column by column so that a wrong sign names its output.
TEST(Mirror, ColumnMirrorIsTheKernelsColumn) {
  testing::TempDir dir{"mirror_columns"};
  const Generated full = generate(dir, kStripesScene, "full.h5", false);
  const Table& t = full.table;
  const std::size_t ny = t.axis("y")->values.size();
  std::size_t odd_checked = 0;
  for (const TableGroup& g : t.groups) {
    const bool left = g.path.rfind("left/", 0) == 0;
    if (!left) continue;
    const TableGroup& right = *t.group("right/" + g.path.substr(5));
    for (const TableDataset& d : g.datasets) {
      const TableDataset& r = *right.find(d.name);
      const std::size_t per_y = d.size() / ny;
      // Inner axes after y: which are reversed by the mirror.
      std::vector<std::size_t> shape(d.shape.begin() + 1, d.shape.end());
      for (std::size_t iy = 0; iy < ny; ++iy) {
        for (std::size_t c = 0; c < per_y; ++c) {
          std::size_t rest = c, image = 0, stride = 1;
          for (std::size_t a = shape.size(); a-- > 0;) {
            const std::size_t i = rest % shape[a];
            rest /= shape[a];
            const std::string& axis = d.axes[a + 1];
            image += ((axis == "eta" || axis == "phi") ? shape[a] - 1 - i : i) * stride;
            stride *= shape[a];
          }
          const std::size_t at = iy * per_y + c, mirror_at = (ny - 1 - iy) * per_y + image;
          if (d.is_status) {
            ASSERT_EQ(d.status[at], r.status[mirror_at]) << g.path << "/" << d.name << " y " << iy;
            continue;
          }
          const double a = d.values[at], b = r.values[mirror_at];
          if (a != 0.0 && a == -b) ++odd_checked;
          ASSERT_TRUE(a == b || a == -b) << g.path << "/" << d.name << " y node " << iy << " cell " << c << ": " << a
                                         << " left, " << b << " right at -y";
        }
      }
    }
  }
  EXPECT_GT(odd_checked, 500u);  // contact angles, fy, mz and the odd coefficients
}

// An asymmetric scene runs the full sweep and says why.
TEST(Mirror, AsymmetricSceneRunsTheFullSweep) {
  Scene scene = parse_scene(kStripesScene, "mirror");
  const SweepKernel kernel = testing::synthetic_kernel(scene);
  EXPECT_EQ(mirror_obstacle(scene, kernel), "the kernel's model is not mirror-symmetric");
  SweepKernel symmetric = kernel;
  symmetric.mirror_symmetric = true;
  EXPECT_EQ(mirror_obstacle(scene, symmetric), "");
  Scene moved = scene;
  moved.grids.y.back() = 0.0081;
  EXPECT_EQ(mirror_obstacle(moved, symmetric), "the y grid is not symmetric about 0");
  moved = scene;
  moved.grids.phi = {0.0, 0.2};
  EXPECT_EQ(mirror_obstacle(moved, symmetric), "the phi grid is not symmetric about 0");
  moved = scene;
  moved.equilibrium_roll = false;
  moved.grids.roll = {0.001};
  EXPECT_EQ(mirror_obstacle(moved, symmetric), "the roll grid is not symmetric about 0");
  moved = scene;
  moved.grids.yaw = {0.0, 0.01};
  moved.grids.yaw_even = true;
  EXPECT_EQ(mirror_obstacle(moved, symmetric), "the yaw axis keeps only yaw >= 0 (yaw_symmetry even)");
}

// A symmetric synthetic scene whose kernel claims the mirror: interrupted and resumed, or split
// into shards and merged, the mirrored table is the one of a single mirrored run.
constexpr const char* kSymmetricSynthetic = R"(
[scene]
name = "synthetic_mirror"
[profiles]
wheel = "s1002"
rail = "uic60"
[grid]
y = [-0.005, -0.0025, -0.001, 0.0, 0.001, 0.0025, 0.005]
roll = [-0.001, 0.001]
load = [50e3, 80e3]
xi = [-0.001, 0.0, 0.001]
eta = [-0.002, 0.0, 0.002]
phi = [-0.5, 0.5]
)";

struct SyntheticRun {
  testing::TempDir dir;
  testing::SyntheticControl control;
  std::atomic<bool> stop{false};
  GenerateOptions options;
  explicit SyntheticRun(const std::string& name) : dir(name) {
    std::ofstream(dir / "scene.toml") << kSymmetricSynthetic;
    options.scene = dir / "scene.toml";
    options.output = dir / "t.h5";
    options.threads = 2;
    options.interrupt = &stop;
    control.flag = &stop;
    options.make_kernel = [this](const Scene& s) {
      SweepKernel k = testing::synthetic_kernel(s, &control);
      k.mirror_symmetric = true;
      return k;
    };
  }
};

TEST(Mirror, ResumedAndShardedRunsEqualASingleRun) {
  SyntheticRun fresh("mirror_fresh");
  const SweepSummary s = generate_table(fresh.options);
  EXPECT_TRUE(s.mirrored);
  EXPECT_EQ(fresh.control.columns.load(), 8);  // y >= 0: 4 blocks x 2 rolls
  const Table single = read_table(fresh.options.output);
  for (int threads : {1, 2}) {
    for (int after : {1, 3, 6}) {
      SyntheticRun run("mirror_resume");
      run.options.resume = true;
      run.options.threads = threads;
      run.control.interrupt_after = after;
      EXPECT_THROW(generate_table(run.options), Interrupted);
      run.stop = false;
      run.control.interrupt_after = -1;
      run.control.columns = 0;
      const SweepSummary r = generate_table(run.options);
      EXPECT_TRUE(r.mirrored);
      if (after == 6) {
        EXPECT_LT(run.control.columns.load(), 8) << threads << " threads: finished blocks were not recomputed";
      }
      testing::expect_same_datasets(single, read_table(run.options.output));
    }
  }
  for (int count : {2, 3, 4}) {
    SyntheticRun run("mirror_shards");
    std::vector<Table> shards;
    std::vector<std::string> names;
    for (int i = 1; i <= count; ++i) {
      run.options.shard_index = i;
      run.options.shard_count = count;
      run.options.output = run.dir / fmt::format("s{}.h5", i);
      generate_table(run.options);
      shards.push_back(read_table(run.options.output));
      names.push_back(run.options.output.string());
    }
    testing::expect_same_datasets(single, merge_shards(shards, names));
  }
}

}  // namespace mirror_sweep
}  // namespace
}  // namespace railtab
