// SPDX-License-Identifier: Apache-2.0
// railtab generate on [accuracy] scenes (generator/generate/ over generator/adaptive/): the table
// takes the adaptive grids and records the targets; the per-y model choice is recorded and the
// bytes do not depend on threads or shards.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <fstream>

#include "adaptive/adaptive_grid.hpp"
#include "adaptive/contact_probe.hpp"
#include "generate/error_map.hpp"
#include "generate/generate.hpp"
#include "generator/test_tables.hpp"
#include "table/merge.hpp"
#include "table/table_io.hpp"

namespace railtab::adaptive_generate_test {  // own namespace: unity builds compile several test files as one
namespace {

TEST(AdaptiveContact, GenerateUsesAdaptiveGridsAndRecordsTargets) {
  testing::TempDir dir("adaptive_generate");
  std::ofstream(dir / "scene.toml") << testing::kAdaptiveTreadScene;
  GenerateOptions options;
  options.scene = dir / "scene.toml";
  options.output = dir / "t.h5";
  options.threads = 1;
  generate_table(options);
  Table t = read_table(options.output);
  Scene scene = load_scene(options.scene);
  build_adaptive_grids(scene, 1);
  EXPECT_EQ(t.axis("xi")->values, scene.grids.xi);
  EXPECT_EQ(t.axis("y")->values, scene.grids.y);
  ASSERT_NE(t.attribute("accuracy_targets"), nullptr);
  ASSERT_NE(t.attribute("accuracy_achieved"), nullptr);
  auto targets = nlohmann::json::parse(*t.attribute("accuracy_targets"));
  EXPECT_DOUBLE_EQ(targets["creep_force"].get<double>(), 0.01);
  auto achieved = nlohmann::json::parse(*t.attribute("accuracy_achieved"));
  EXPECT_LE(achieved["worst_midpoint_error"].get<double>(), 1.0);
}

TEST(ModelChoice, TableRecordsTheChoiceAndIsByteIdenticalForAnyThreadCount) {
  testing::TempDir dir("model_choice");
  std::ofstream(dir / "scene.toml") << testing::kModelChoiceScene;
  GenerateOptions options;
  options.scene = dir / "scene.toml";
  options.output = dir / "one.h5";
  options.threads = 1;
  generate_table(options);
  options.output = dir / "two.h5";
  options.threads = 2;
  generate_table(options);
  Table one = read_table(dir / "one.h5");
  Table two = read_table(dir / "two.h5");
  testing::expect_same_datasets(one, two);
  // Shards slice the choice with y; merged, they are the single run's table.
  std::vector<Table> shards;
  for (int k = 1; k <= 2; ++k) {
    options.output = dir / fmt::format("shard{}.h5", k);
    options.shard_index = k;
    options.shard_count = 2;
    generate_table(options);
    shards.push_back(read_table(options.output));
  }
  // (merged as `railtab merge` does: the error map, which needs the whole table, computed then)
  merge_table_files({(dir / "shard1.h5").string(), (dir / "shard2.h5").string()}, (dir / "merged.h5").string(),
                    error_map_merge_finish(2));
  ASSERT_TRUE(one.group(kErrorMapGroup));
  testing::expect_same_datasets(one, read_table(dir / "merged.h5"));

  Scene scene = load_scene(options.scene);
  build_adaptive_grids(scene, 1);
  const TableDataset* index = one.group("")->find("normal_model_index");
  ASSERT_NE(index, nullptr);
  EXPECT_EQ(index->axes, std::vector<std::string>{"y"});
  ASSERT_EQ(index->values.size(), scene.accuracy.model_by_y.size());
  for (std::size_t i = 0; i < index->values.size(); ++i) {
    EXPECT_EQ(index->values[i], static_cast<double>(scene.accuracy.model_by_y[i]));
  }
  auto models = nlohmann::json::parse(*one.attribute("models"));
  EXPECT_EQ(models["normal"], "stripes-ab");
  EXPECT_EQ(models["normal_models"], nlohmann::json({"hertz", "kik-piotrowski", "stripes-ab"}));

  // Each y holds the values of its chosen model (here: the left wheel's tread slot normal force).
  const TableDataset* n = one.group("left/normal")->find("normal_force");
  const std::size_t loads = scene.grids.load.size();
  for (std::size_t iy = 0; iy < scene.grids.y.size(); ++iy) {
    Scene chosen = scene;
    chosen.normal.model = scene.accuracy.models[scene.accuracy.model_by_y[iy]];
    auto r = ContactProbe(chosen).evaluate(scene.grids.y[iy], scene.grids.load, {{0.0, 0.001, 0.05}});
    for (std::size_t il = 0; il < loads; ++il) {
      EXPECT_EQ(n->values[(iy * loads + il) * kSlots], r[il][0][0].slot[0].normal_force) << "y node " << iy;
    }
  }
}

}  // namespace
}  // namespace railtab::adaptive_generate_test
