// SPDX-License-Identifier: Apache-2.0
// The cost of each y column by which --shard splits (generator/adaptive/column_costs.hpp).
#include "adaptive/column_costs.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace railtab {
namespace {

TEST(ShardSplit, ColumnCostCountsTheLoadedPatches) {
  // The flange scene: one loaded patch per wheel at every y (the tread lifts off as the flange
  // loads), so every column costs 2 and the split is the equal one: measured per-column CPU time
  // on this scene is flat within +-7 % (docs/cluster.md).
  const Scene scene = load_scene(std::filesystem::path(RAILTAB_SOURCE_DIR) / "tables/flange.toml");
  const std::vector<double> costs = column_costs(scene);
  ASSERT_EQ(costs.size(), scene.grids.y.size());
  for (double c : costs) EXPECT_EQ(c, 2.0);
}

}  // namespace
}  // namespace railtab
