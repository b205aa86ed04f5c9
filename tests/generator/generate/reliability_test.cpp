// SPDX-License-Identifier: Apache-2.0
// Reliability of railtab generate, merge and eval (docs/reliability.md): the output is never an
// input or a non-regular file, table sizes are checked (overflow, --max-points, --max-bytes) before
// any allocation, and non-finite results are failed, never converged.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/check.hpp"
#include "error_message.hpp"
#include "generator/synthetic_kernel.hpp"
#include "generator/test_tables.hpp"
#include "kernel/contact_kernel.hpp"
#include "generate/generate.hpp"
#include "engine/table_size.hpp"
#include "table/merge.hpp"
#include "table/table_io.hpp"

namespace railtab::reliability_test {  // own namespace: unity builds compile several test files as one
namespace {

namespace fs = std::filesystem;

std::string read_all(const fs::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

GenerateOptions synthetic_options(const testing::TempDir& dir, const std::string& scene_text = testing::kSyntheticScene) {
  std::ofstream(dir / "scene.toml") << scene_text;
  GenerateOptions o;
  o.scene = dir / "scene.toml";
  o.output = dir / "t.h5";
  o.threads = 1;
  o.make_kernel = [](const Scene& s) { return testing::synthetic_kernel(s); };
  return o;
}

TEST(GenerateOutput, RefusesTheSceneItselfAndNonRegularTargets) {
  testing::TempDir dir("rel_scene_out");
  GenerateOptions o = synthetic_options(dir);
  const std::string scene_before = read_all(o.scene);
  fs::create_symlink("scene.toml", dir / "link.h5");
  for (const fs::path& target : {o.scene, dir / "link.h5", dir.path() / "." / "scene.toml"}) {
    o.output = target;
    EXPECT_NE(test::error_message([&] { generate_table(o); }).find("is the input"), std::string::npos) << target;
  }
  EXPECT_EQ(read_all(o.scene), scene_before);  // the scene is untouched
  o.output = "/dev/null";
  EXPECT_NE(test::error_message([&] { generate_table(o); }).find("character device"), std::string::npos);
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"link.h5", "scene.toml"}));
}

TEST(MergeOutput, RefusesAnInputShardAsOutput) {
  testing::TempDir dir("rel_merge_out");
  GenerateOptions o = synthetic_options(dir);
  std::vector<std::string> shards;
  for (int i = 1; i <= 2; ++i) {
    o.output = dir / fmt::format("s{}.h5", i);
    o.shard_index = i;
    o.shard_count = 2;
    generate_table(o);
    shards.push_back(o.output.string());
  }
  const std::string before = read_all(shards[0]);
  EXPECT_NE(test::error_message([&] { merge_table_files(shards, shards[0]); }).find("is the input"), std::string::npos);
  EXPECT_EQ(read_all(shards[0]), before);
  EXPECT_NO_THROW(merge_table_files(shards, (dir / "all.h5").string()));
}

// --resume continues OUTPUT.partial only when it is the run's own regular file: a symbolic link,
// a second name of another file or a FIFO planted there is refused and the file it leads to is
// untouched (it used to be overwritten with the checkpoint, exit 0).
TEST(ResumeCheckpoint, RefusesALinkOrFifoPlantedAsThePartialFile) {
  testing::TempDir dir("rel_partial");
  GenerateOptions o = synthetic_options(dir);
  o.resume = true;
  std::ofstream(dir / "victim.txt") << "precious data";
  fs::create_symlink("victim.txt", dir / "t.h5.partial");
  EXPECT_NE(test::error_message([&] { generate_table(o); }).find("symbolic link"), std::string::npos);
  fs::remove(dir / "t.h5.partial");
  fs::create_hard_link(dir / "victim.txt", dir / "t.h5.partial");
  EXPECT_NE(test::error_message([&] { generate_table(o); }).find("hard links"), std::string::npos);
  fs::remove(dir / "t.h5.partial");
  ASSERT_EQ(::mkfifo((dir / "t.h5.partial").c_str(), 0600), 0);
  EXPECT_NE(test::error_message([&] { generate_table(o); }).find("FIFO"), std::string::npos);
  EXPECT_EQ(read_all(dir / "victim.txt"), "precious data");
  EXPECT_FALSE(fs::exists(dir / "t.h5"));
}

// The profile files a scene names are inputs: -o naming one is refused, whatever the spelling.
TEST(GenerateOutput, RefusesAProfileOfTheScene) {
  testing::TempDir dir("rel_profile_out");
  const fs::path profiles = fs::path(RAILTAB_SOURCE_DIR) / "tests" / "data" / "profiles";
  fs::copy_file(profiles / "Car7216_0001r.whl", dir / "Car7216_0001r.whl");
  fs::copy_file(profiles / "avg_HR.BAN", dir / "avg_HR.BAN");
  GenerateOptions o = synthetic_options(dir, R"([scene]
name = "worn"
[profiles]
wheel = "Car7216_0001r.whl"
rail = "avg_HR.BAN"
[grid]
y = { start = -0.004, stop = 0.004, count = 3 }
load = 80e3
)");
  const std::string rail_before = read_all(dir / "avg_HR.BAN");
  for (const fs::path& target : {dir / "avg_HR.BAN", dir.path() / "." / "Car7216_0001r.whl"}) {
    o.output = target;
    EXPECT_NE(test::error_message([&] { generate_table(o); }).find("is the input"), std::string::npos) << target;
  }
  EXPECT_EQ(read_all(dir / "avg_HR.BAN"), rail_before);
}

// A shard that is not a regular file (a FIFO without a writer) is refused at once, not waited on.
TEST(MergeInput, RefusesAFifoShardWithoutBlocking) {
  testing::TempDir dir("rel_merge_fifo");
  GenerateOptions o = synthetic_options(dir);
  o.output = dir / "s1.h5";
  o.shard_index = 1;
  o.shard_count = 2;
  generate_table(o);
  ASSERT_EQ(::mkfifo((dir / "s2.h5").c_str(), 0600), 0);
  const std::string error =
      test::error_message([&] { merge_table_files({(dir / "s1.h5").string(), (dir / "s2.h5").string()}, (dir / "m.h5").string()); });
  EXPECT_NE(error.find("s2.h5"), std::string::npos) << error;
  EXPECT_NE(error.find("FIFO"), std::string::npos) << error;
  EXPECT_FALSE(fs::exists(dir / "m.h5"));
}

// A shard holding a NaN (written past the lookup's check, as a tampered file would be) is refused
// by merge before anything is joined, naming the shard; no output is written.
TEST(MergeInput, ShardTheLookupRefusesIsNamed) {
  testing::TempDir dir("rel_merge_nan");
  GenerateOptions o = synthetic_options(dir);
  std::vector<std::string> shards;
  for (int i = 1; i <= 2; ++i) {
    o.output = dir / fmt::format("s{}.h5", i);
    o.shard_index = i;
    o.shard_count = 2;
    generate_table(o);
    shards.push_back(o.output.string());
  }
  Table bad = read_table(shards[1]);
  TableDataset* d = nullptr;
  for (TableGroup& g : bad.groups)
    for (TableDataset& x : g.datasets)
      if (!d && !x.is_status && !g.path.empty()) d = &x;
  ASSERT_TRUE(d);
  d->values[0] = std::nan("");
  write_table(bad, shards[1] + ".nan", nullptr, {}, WrittenCheck::none);
  fs::rename(shards[1] + ".nan", shards[1]);
  const std::string m = test::error_message([&] { merge_table_files(shards, (dir / "all.h5").string()); });
  EXPECT_NE(m.find("merge: " + shards[1] + ": "), std::string::npos) << m;
  EXPECT_NE(m.find("non-finite"), std::string::npos) << m;
  EXPECT_FALSE(fs::exists(dir / "all.h5"));
}

// hostile/grid_product_overflow.toml: every axis under the per-axis limit, the product wraps 2^64.
constexpr const char* kOverflowScene = R"(
[scene]
name = "ovf"
[profiles]
wheel = "s1002"
rail = "uic60"
[grid]
y = [0.0, 0.001]
roll = [0.0, 0.0001]
load = {start = 60000, stop = 100000, count = 524288}
xi = {start = -0.01, stop = 0.01, count = 524288}
eta = {start = -0.01, stop = 0.01, count = 524288}
phi = {start = -1, stop = 1, count = 32}
)";

TEST(TableSize, ProductOverflowIsAnErrorNotACrash) {
  testing::TempDir dir("rel_overflow");
  GenerateOptions o = synthetic_options(dir, kOverflowScene);
  EXPECT_NE(test::error_message([&] { generate_table(o); }).find("overflows 64 bits"), std::string::npos);
  Scene scene = parse_scene(kOverflowScene, "ovf.toml");
  EXPECT_THROW(table_points(scene, scene.grids.y.size()), Error);
  // run_sweep checks the same before allocating, whoever calls it.
  EXPECT_THROW(run_sweep(scene, testing::synthetic_kernel(scene), SweepOptions{}), Error);
  EXPECT_EQ(dir.files(), std::vector<std::string>{"scene.toml"});
}

TEST(TableSize, LimitsRefuseAndAFlagRaisesThem) {
  testing::TempDir dir("rel_limits");
  GenerateOptions o = synthetic_options(dir);
  const Scene scene = parse_scene(testing::kSyntheticScene, "s.toml");
  const std::uint64_t points = table_points(scene, scene.grids.y.size());
  EXPECT_EQ(points, 7u * 2 * 2 * 3 * 1 * 2);
  o.max_points = points - 1;
  EXPECT_NE(test::error_message([&] { generate_table(o); }).find("--max-points"), std::string::npos);
  o.max_points = points;
  o.max_bytes = 1000;
  EXPECT_NE(test::error_message([&] { generate_table(o); }).find("--max-bytes"), std::string::npos);
  o.max_bytes = kDefaultMaxBytes;
  std::ostringstream log;
  o.log = &log;
  EXPECT_NO_THROW(generate_table(o));
  EXPECT_NE(log.str().find("table: 168 grid points"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("estimated time"), std::string::npos);
}

// The refusal states the run time at the scene's model's cost per point: microseconds for a fast
// model, tens of milliseconds for the exact one.
TEST(TableSize, RefusalUsesTheModelsCostPerPoint) {
  Scene scene = parse_scene(testing::kSyntheticScene, "s.toml");
  const std::string fast = test::error_message([&] { check_table_size(scene, 3, 0, 2, kDefaultMaxBytes, contact_point_cost(scene)); });
  EXPECT_NE(fast.find("100-600 us per point"), std::string::npos) << fast;
  scene.normal.model = NormalModel::halfspace;
  const std::string exact = test::error_message([&] { check_table_size(scene, 3, 0, 2, kDefaultMaxBytes, contact_point_cost(scene)); });
  EXPECT_NE(exact.find("15-45 ms per point"), std::string::npos) << exact;
}

// The estimate counts the points the sweep solves: a mirrored sweep the columns y >= 0 (and a
// shard's columns y < 0 whose image is in another shard), at the exact model's cost scaled to
// the element size. Its range holds the measured whole runs of tables/default.toml
// (docs/validation/exact-tables.md, "Generation cost"): 0.3 mm elements, 31,899 computed points,
// 6 min 05 s wall on a quiet 2-core machine (counting every point at the earlier cost printed 21
// to 63 min); 0.4 mm elements, 22,638 computed points, 247 s CPU (loaded machine).
TEST(TableSize, EstimateCountsTheComputedPoints) {
  const Scene scene = load_scene(fs::path(RAILTAB_SOURCE_DIR) / "tables" / "default.toml");
  const std::size_t ny = scene.grids.y.size();
  std::size_t non_negative = 0;
  for (double y : scene.grids.y) non_negative += y >= 0.0 ? 1 : 0;
  ASSERT_LT(non_negative, ny);
  const std::uint64_t points = table_points(scene, ny);
  EXPECT_EQ(computed_points(scene, 0, ny, false), points);
  const std::uint64_t computed = computed_points(scene, 0, ny, true);
  EXPECT_EQ(computed, table_points(scene, non_negative));
  // A shard of the columns y < 0 only: their images lie in the other shard, so all are computed.
  const std::size_t negative = ny - non_negative;
  EXPECT_EQ(computed_points(scene, 0, negative, true), table_points(scene, negative));
  // A shard holding y = 0 and its neighbours on both sides computes 0 and the positive side only.
  EXPECT_EQ(computed_points(scene, negative - 2, negative + 3, true), table_points(scene, 3));

  Scene fine = scene;
  fine.halfspace.element_size = 0.3e-3;
  const PointCost cost = contact_point_cost(fine);
  const double wall_03 = 365.0, points_03 = 31899.0;  // [s], [-] 0.3 mm, 2 threads (see above)
  EXPECT_LE(points_03 / 2.0 * cost.low, wall_03);
  EXPECT_GE(points_03 / 2.0 * cost.high, wall_03);
  Scene coarse = scene;
  coarse.halfspace.element_size = 0.4e-3;
  const PointCost cost_04 = contact_point_cost(coarse);
  const double cpu_04 = 247.0, points_04 = 22638.0;  // [s], [-] 0.4 mm, CPU of both threads
  EXPECT_LE(points_04 * cost_04.low, cpu_04);
  EXPECT_GE(points_04 * cost_04.high, cpu_04);
  EXPECT_NEAR(cost_04.low / cost.low, 0.5625, 1e-12);  // (0.3 / 0.4)^2
  const std::string line = describe_table_size(points, computed, 1000, 2, cost);
  EXPECT_NE(line.find(fmt::format("table: {} grid points ({} computed, the others their mirror images)", points,
                                  computed)),
            std::string::npos)
      << line;
  EXPECT_EQ(describe_table_size(points, points, 1000, 2, cost).find("computed"), std::string::npos);
}

// A y grid reaching off the rail with the equilibrium roll fails in the jump locator: the message
// names the scene file and the stage (it was the bare "wheel 'S1002' does not overlap its rail").
TEST(NonFinite, JumpLocatorFailureNamesSceneAndStage) {
  testing::TempDir dir("jump_locator_failure");
  std::string text = testing::kTreadPointScene;
  text.replace(text.find("y = [0.001]"), 11, "y = {start = -0.08, stop = 0.08, step = 0.01}");
  text += "equilibrium_roll = true\n";
  std::ofstream(dir / "off.toml") << text;
  GenerateOptions o;
  o.scene = dir / "off.toml";
  o.output = dir / "off.h5";
  o.threads = 1;
  const std::string message = test::error_message([&] { generate_table(o); });
  EXPECT_NE(message.find("off.toml: locating the contact jumps along y"), std::string::npos) << message;
  EXPECT_NE(message.find("does not overlap its rail"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(dir / "off.h5"));
}

}  // namespace
}  // namespace railtab::reliability_test
