// SPDX-License-Identifier: Apache-2.0
// --shard's split (generator/engine/shard_split.hpp): cost-balanced contiguous ranges and the Slurm job-array form.
#include "engine/shard_split.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>

#include "core/check.hpp"

namespace railtab {
namespace {

// The shards of `costs` tile [0, ny) without gaps, each non-empty.
std::vector<std::pair<std::size_t, std::size_t>> all_shards(const std::vector<double>& costs, int count) {
  std::vector<std::pair<std::size_t, std::size_t>> shards;
  for (int i = 1; i <= count; ++i) shards.push_back(weighted_shard_range(costs, i, count));
  return shards;
}

TEST(ShardSplit, EqualCostsSplitIntoEqualCounts) {
  const auto shards = all_shards(std::vector<double>(12, 1.0), 4);
  for (std::size_t i = 0; i < shards.size(); ++i) {
    EXPECT_EQ(shards[i].first, 3 * i);
    EXPECT_EQ(shards[i].second, 3 * i + 3);
  }
}

TEST(ShardSplit, ExpensiveColumnsGetNarrowerShards) {
  // Ten tread columns (cost 2) then ten flange columns (cost 3): the cost is split, not the count.
  std::vector<double> costs(20, 2.0);
  std::fill(costs.begin() + 10, costs.end(), 3.0);
  const auto shards = all_shards(costs, 2);
  // Half the cost (25 of 50) lies between columns 11 (23) and 12 (26): the nearer edge, 12.
  EXPECT_EQ(shards[0], (std::pair<std::size_t, std::size_t>{0, 12}));
  EXPECT_EQ(shards[1], (std::pair<std::size_t, std::size_t>{12, 20}));
}

TEST(ShardSplit, EveryShardGetsAColumnEvenWhenOneColumnDominates) {
  std::vector<double> costs{1, 1, 1000, 1, 1};
  const auto shards = all_shards(costs, 5);
  std::size_t next = 0;
  for (const auto& [begin, end] : shards) {
    EXPECT_EQ(begin, next);
    EXPECT_GT(end, begin);
    next = end;
  }
  EXPECT_EQ(next, costs.size());
}

TEST(ShardSplit, BadShardsAreNamed) {
  EXPECT_THROW(weighted_shard_range({1, 1}, 3, 3), Error);
  EXPECT_THROW(weighted_shard_range({1, 1}, 0, 2), Error);
}

struct SlurmEnv {
  SlurmEnv(const char* id, const char* count, const char* min) {
    setenv("SLURM_ARRAY_TASK_ID", id, 1);
    setenv("SLURM_ARRAY_TASK_COUNT", count, 1);
    if (min) setenv("SLURM_ARRAY_TASK_MIN", min, 1); else unsetenv("SLURM_ARRAY_TASK_MIN");
  }
  ~SlurmEnv() {
    unsetenv("SLURM_ARRAY_TASK_ID");
    unsetenv("SLURM_ARRAY_TASK_COUNT");
    unsetenv("SLURM_ARRAY_TASK_MIN");
  }
};

TEST(ShardSplit, AutoReadsTheSlurmJobArray) {
  EXPECT_EQ(parse_shard_spec("2/8"), (std::pair<int, int>{2, 8}));
  {
    SlurmEnv env("0", "4", "0");  // sbatch --array=0-3
    EXPECT_EQ(parse_shard_spec("auto"), (std::pair<int, int>{1, 4}));
  }
  {
    SlurmEnv env("4", "4", "1");  // sbatch --array=1-4
    EXPECT_EQ(parse_shard_spec("auto"), (std::pair<int, int>{4, 4}));
  }
  {
    SlurmEnv env("9", "4", "1");  // a sparse array (--array=1,3,5,9) is not a split
    EXPECT_THROW(parse_shard_spec("auto"), Error);
  }
  {
    SlurmEnv env("x", "4", nullptr);
    EXPECT_THROW(parse_shard_spec("auto"), Error);
  }
  EXPECT_THROW(parse_shard_spec("auto"), Error);  // outside a job array
}

}  // namespace
}  // namespace railtab
