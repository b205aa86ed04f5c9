// SPDX-License-Identifier: Apache-2.0
// `railtab export TABLE --csv`: a table's creep forces in newtons on its own nodes, one CSV row per
// node and slot, for tools that read CSV (docs/lookup.md, "Export to CSV").
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

namespace railtab {

// The CSV text of `table`: a header naming every column with its unit, then one row per wheel,
// creep-part node (y, roll, load, xi, eta, phi as the table tabulates them) and slot, in the file's
// order (left wheel first, slot fastest). Creepages are physical: on a table with normalised creep
// coordinates each node's creepage is its coordinate v mapped with that node's and slot's scale.
// The values are the lookup's (railtab::lookup, linear) at the node's state, so the CSV holds what
// a simulation reading the table gets there; status is the node's own creep-part status. `rows`
// receives the number of data rows. Throws railtab::Error naming the table for a file the lookup
// cannot load or one without a creep part.
std::string table_csv(const std::filesystem::path& table, std::size_t& rows);

// table_csv written to `output` through the safe output path (table/output_file.hpp): the target is
// checked before any work (not a link, not the table, its directory writable). Returns the rows.
std::size_t write_table_csv(const std::filesystem::path& table, const std::filesystem::path& output);

}  // namespace railtab
