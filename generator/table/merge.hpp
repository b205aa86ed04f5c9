// SPDX-License-Identifier: Apache-2.0
// Joining the shards of a table (railtab generate --shard I/N) into the table a single run writes.
#pragma once

#include <vector>

#include "table/table.hpp"

namespace railtab {

// Checks that `shards` are all N shards of one run (same scene, models, build and layout; every
// I from 1 to N once, in any order) and concatenates them along y. The result carries the root
// attributes of a single run (shard attributes removed, `created` = now); its datasets equal a
// single run's byte for byte. Throws railtab::Error naming the offending shard (by `names`).
Table merge_shards(const std::vector<Table>& shards, const std::vector<std::string>& names);

// railtab merge: reads the shard files, merges them and writes `output`. Returns the merged table's
// number of y values.
std::size_t merge_table_files(const std::vector<std::string>& inputs, const std::string& output);

}  // namespace railtab
