// SPDX-License-Identifier: Apache-2.0
// Joining the shards of a table (railtab generate --shard I/N) into the table a single run writes.
#pragma once

#include <filesystem>
#include <functional>
#include <vector>

#include "table/table.hpp"

namespace railtab {

// Checks that `shards` are all N shards of one run (same scene, models, build and layout; every
// I from 1 to N once, in any order) and concatenates them along y. The result carries the root
// attributes of a single run (shard attributes removed, `created` = now); its datasets equal a
// single run's byte for byte. Throws railtab::Error naming the offending shard (by `names`).
Table merge_shards(const std::vector<Table>& shards, const std::vector<std::string>& names);

// What completes a merged table of the contact kernel before it is written (the error map, which
// reads the merged table through the lookup: `written` is the merged table in a stage file).
using MergeFinish = std::function<void(Table& merged, const std::filesystem::path& written)>;

// railtab merge: reads the shard files, merges them and writes `output`; shards of the contact
// kernel (shard_jumps "located") go through `finish` first. Returns the merged table's number of
// y values.
std::size_t merge_table_files(const std::vector<std::string>& inputs, const std::string& output,
                              const MergeFinish& finish = {});

}  // namespace railtab
