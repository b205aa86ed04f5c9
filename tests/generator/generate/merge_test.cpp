// SPDX-License-Identifier: Apache-2.0
// Shards of one sweep merged (generator/table/merge.hpp) equal a single run; foreign shards
// rejected.
#include "table/merge.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "core/check.hpp"
#include "generator/synthetic_kernel.hpp"
#include "generator/test_tables.hpp"
#include "generate/generate.hpp"
#include "table/table_io.hpp"

namespace railtab {
namespace {

struct Shards {
  testing::TempDir dir{"merge"};
  std::vector<Table> tables;
  std::vector<std::string> names;

  Shards(int count, const std::string& scene_text = testing::kSyntheticScene) {
    std::ofstream(dir / "scene.toml") << scene_text;
    for (int i = 1; i <= count; ++i) {
      GenerateOptions o;
      o.scene = dir / "scene.toml";
      o.output = dir / fmt::format("s{}.h5", i);
      o.shard_index = i;
      o.shard_count = count;
      o.threads = 2;
      o.make_kernel = [](const Scene& s) { return testing::synthetic_kernel(s); };
      generate_table(o);
      tables.push_back(read_table(o.output));
      names.push_back(o.output.string());
    }
  }
};

TEST(Merge, ShardsEqualASingleRun) {
  Shards single(1);
  Shards three(3);
  // Given in any order.
  std::swap(three.tables[0], three.tables[2]);
  std::swap(three.names[0], three.names[2]);
  Table merged = merge_shards(three.tables, three.names);
  write_table(merged, three.dir / "merged.h5");
  Table back = read_table(three.dir / "merged.h5");
  testing::expect_same_datasets(single.tables[0], back);
  EXPECT_FALSE(back.attribute("shard"));
  for (const char* attr : {"format_version", "scene", "scene_name", "models", "fixed_axes"}) {
    EXPECT_EQ(*back.attribute(attr), *single.tables[0].attribute(attr)) << attr;
  }
}

TEST(Merge, RejectsIncompleteOrForeignShards) {
  Shards three(3);
  auto message = [](const std::vector<Table>& t, const std::vector<std::string>& n) -> std::string {
    try {
      merge_shards(t, n);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message({three.tables[0], three.tables[1]}, {three.names[0], three.names[1]}).find("3 but 2"),
            std::string::npos);
  EXPECT_NE(message({three.tables[0], three.tables[1], three.tables[1]}, three.names).find("missing or given twice"),
            std::string::npos);
  std::vector<Table> other = three.tables;
  other[1].set_attribute("scene", "something else");
  EXPECT_NE(message(other, three.names).find("'scene'"), std::string::npos);
  Shards single(1);
  EXPECT_NE(message(single.tables, single.names).find("not a shard"), std::string::npos);
}

}  // namespace
}  // namespace railtab
