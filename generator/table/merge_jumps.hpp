// SPDX-License-Identifier: Apache-2.0
// Joining the shards' contact jumps (group shard_jumps: the jumps of each shard's own y cells)
// into the /jumps group of the table a single run writes.
#pragma once

#include <string>
#include <vector>

#include "table/table.hpp"

namespace railtab {

// Appends to `merged` the groups /jumps and /jumps/<wheel>/<part> joined from the shard_jumps
// groups of `shards` (given in y order; a shard without that group has no jump in its cells):
// per wheel and load node the shards' lists one after the other, padded to the longest with NaN
// positions, 0 kinds and 0 one-sided values, as the single run pads them. Nothing is appended
// when no shard has a jump. Throws railtab::Error naming the shard (by `names`) whose jump data
// are malformed (a non-finite or unordered position, a missing or misshaped dataset).
void join_shard_jumps(const std::vector<const Table*>& shards, const std::vector<std::string>& names, Table& merged);

}  // namespace railtab
