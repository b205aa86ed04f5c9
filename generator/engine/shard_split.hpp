// SPDX-License-Identifier: Apache-2.0
// How --shard splits the y grid: contiguous ranges of about equal estimated cost, so the shards of a
// job array finish together. The cost of each column comes in from the caller (adaptive/column_costs.hpp
// estimates it from the contact patches a column solves).
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace railtab {

// The y index range [begin, end) of shard `index` (1-based) of `count`: contiguous, each as close
// as the columns allow to 1/count of the total cost. Every shard gets at least one column.
std::pair<std::size_t, std::size_t> weighted_shard_range(const std::vector<double>& costs, int index, int count);

// Parse "I/N" (1 <= I <= N) of --shard; throws railtab::Error naming the text.
std::pair<int, int> parse_shard(const std::string& text);

// "I/N" or "auto" (I and N from SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT, with
// SLURM_ARRAY_TASK_MIN as the first id, so 0- and 1-based arrays both work). Throws naming the text
// or the variable.
std::pair<int, int> parse_shard_spec(const std::string& text);

}  // namespace railtab
