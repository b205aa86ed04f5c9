// SPDX-License-Identifier: Apache-2.0
// How --shard splits the y grid: contiguous ranges of about equal estimated cost, so the shards of a
// job array finish together. A column's cost is estimated by the contact patches it solves (a
// flange column solves tread and flange patches: about 1.5 x a tread column's normal and creep work).
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.hpp"

namespace railtab {

// Estimated relative cost of each y column of the scene: loaded contact patches of both wheels at
// the middle load without creepage (at least 1). Deterministic; 1 for every y where the contact
// chain fails (the column is then cheap anyway).
std::vector<double> column_costs(const Scene& scene);

// The y index range [begin, end) of shard `index` (1-based) of `count`: contiguous, each as close
// as the columns allow to 1/count of the total cost. Every shard gets at least one column.
std::pair<std::size_t, std::size_t> weighted_shard_range(const std::vector<double>& costs, int index, int count);

// "I/N" or "auto" (I and N from SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT, with
// SLURM_ARRAY_TASK_MIN as the first id, so 0- and 1-based arrays both work). Throws naming the text
// or the variable.
std::pair<int, int> parse_shard_spec(const std::string& text);

}  // namespace railtab
