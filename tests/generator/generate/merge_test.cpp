// SPDX-License-Identifier: Apache-2.0
// Shards of one sweep merged (generator/table/merge.hpp) equal a single run; foreign shards
// rejected.
#include "table/merge.hpp"

#include <gtest/gtest.h>

#include <railtab/lookup.hpp>

#include <cstring>
#include <fstream>

#include "core/check.hpp"
#include "generator/synthetic_kernel.hpp"
#include "generator/test_tables.hpp"
#include "generate/error_map.hpp"
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

// Positions of the jumps of one wheel ("left"/"right") at load node `l` (the list before its NaN
// padding).
std::vector<double> jump_positions(const Table& t, const std::string& wheel, std::size_t l) {
  std::vector<double> out;
  const TableDataset* y = t.group(kJumpGroup)->find(wheel + "_y");
  const std::size_t width = y->shape.back();
  for (std::size_t j = 0; j < width && !std::isnan(y->values[l * width + j]); ++j) out.push_back(y->values[l * width + j]);
  return out;
}

TEST(Merge, MergedTableCarriesTheJumpsAndAnswersOfASingleRun) {
  testing::TempDir dir{"merge_jumps"};
  std::ofstream(dir / "scene.toml") << testing::kJumpScene;
  auto generate = [&](const std::string& output, int index, int count) {
    GenerateOptions o;
    o.scene = dir / "scene.toml";
    o.output = dir / output;
    o.shard_index = index;
    o.shard_count = count;
    o.threads = 2;
    generate_table(o);
    return o.output.string();
  };
  const std::string single_path = generate("single.h5", 1, 1);
  // Three shards: the two shard boundaries cut the y grid, so jumps in the cells between shards count.
  std::vector<std::string> shards;
  for (int i = 1; i <= 3; ++i) shards.push_back(generate(fmt::format("s{}.h5", i), i, 3));
  const std::string merged_path = (dir / "merged.h5").string();
  merge_table_files({shards[2], shards[0], shards[1]}, merged_path, error_map_merge_finish());

  const Table single = read_table(single_path), merged = read_table(merged_path);
  ASSERT_TRUE(single.group(kJumpGroup)) << "the scene must have contact jumps for this test to mean anything";
  ASSERT_TRUE(merged.group(kJumpGroup)) << "the merged table lost the jumps";
  ASSERT_TRUE(single.group(kErrorMapGroup) && merged.group(kErrorMapGroup)) << "no error map";
  EXPECT_EQ(*single.attribute("error_map_sampling"), *merged.attribute("error_map_sampling"));
  testing::expect_same_datasets(single, merged);  // the jump lists and one-sided values included

  // The lookup's answers near every located jump (both sides, within the bisection tolerance and
  // a little beyond) and at every y node, linear and cubic, bit for bit.
  const TableAxis& loads = *single.axis("load");
  std::size_t jumps = 0;
  for (lookup::Method method : {lookup::Method::kLinear, lookup::Method::kCubic}) {
    const lookup::Table a = lookup::Table::load(single_path, {method});
    const lookup::Table b = lookup::Table::load(merged_path, {method});
    for (int w = 0; w < 2; ++w) {
      for (std::size_t l = 0; l < loads.values.size(); ++l) {
        std::vector<double> ys = jump_positions(single, w == 0 ? "left" : "right", l);
        jumps += ys.size();
        std::vector<double> probes = single.axis("y")->values;
        for (double y : ys)
          for (double dy : {-1e-5, -1e-6, -4e-7, 0.0, 4e-7, 1e-6, 1e-5}) probes.push_back(y + dy);
        for (double y : probes) {
          lookup::State s = a.default_state();
          s.y = y;
          s.load = loads.values[l] + (l == 0 ? 1e3 : -1e3);  // inside the load cell, not on a node
          s.xi = 0.001;
          const lookup::Wheel wheel = w == 0 ? lookup::Wheel::kLeft : lookup::Wheel::kRight;
          lookup::Result ra{}, rb{};
          a.query(wheel, s, ra);
          b.query(wheel, s, rb);
          EXPECT_EQ(std::memcmp(&ra, &rb, sizeof ra), 0)
              << "wheel " << w << " load " << s.load << " y " << y << ": contact angle "
              << ra.contact[0].value[static_cast<int>(lookup::Output::kContactAngle)] << " (single) vs "
              << rb.contact[0].value[static_cast<int>(lookup::Output::kContactAngle)] << " (merged)";
        }
      }
    }
  }
  EXPECT_GT(jumps, 0u);
}

TEST(Merge, RefusesShardsWithoutTheirJumps) {
  Shards two(2);
  std::vector<Table> old = two.tables;
  old[0].remove_attribute("shard_jumps");
  try {
    merge_shards(old, two.names);
    ADD_FAILURE() << "a shard without its jumps was merged";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(two.names[0]), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("contact jumps"), std::string::npos) << e.what();
  }
}

// y values of one shard's axis (the shards are edited in memory, as a tampered file reads).
std::vector<double>& y_values(Table& t) {
  for (TableAxis& a : t.axes)
    if (a.name == "y") return a.values;
  throw Error("no y axis");
}

std::string merge_message(const std::vector<Table>& t, const std::vector<std::string>& n) {
  try {
    merge_shards(t, n);
  } catch (const Error& e) {
    return e.what();
  }
  return "(merged)";
}

// A shard whose y values do not continue the previous shards, or are not increasing, is named
// with the y values at fault, before anything is joined (the merged table's own check would blame
// the output).
TEST(Merge, ShardWhoseYDoesNotContinueIsNamedWithItsValues) {
  Shards two(2);
  const double last_of_first = y_values(two.tables[0]).back();
  std::vector<Table> shifted = two.tables;
  for (double& y : y_values(shifted[1])) y -= 0.004;  // its first y now below the first shard's last
  const double first_of_second = y_values(shifted[1]).front();
  ASSERT_LE(first_of_second, last_of_first);
  const std::string m = merge_message(shifted, two.names);
  EXPECT_NE(m.find("merge: " + two.names[1] + ": its y values do not continue the previous shards"),
            std::string::npos) << m;
  EXPECT_NE(m.find(fmt::format("first y = {} m is not above y = {} m, the last of {}", first_of_second,
                               last_of_first, two.names[0])),
            std::string::npos) << m;

  std::vector<Table> swapped = two.tables;
  std::vector<double>& y = y_values(swapped[0]);
  ASSERT_GE(y.size(), 2u);
  std::swap(y[0], y[1]);
  const std::string n = merge_message(swapped, two.names);
  EXPECT_NE(n.find(fmt::format("merge: {}: its y values are not increasing: y = {} m after {} m", two.names[0], y[1],
                               y[0])),
            std::string::npos) << n;
  EXPECT_EQ(merge_message(two.tables, two.names), "(merged)");
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
