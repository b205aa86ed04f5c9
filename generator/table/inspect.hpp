// Human-readable summary of a table file: provenance, axes, and per wheel and part the outputs
// with shapes, sizes and status counts.
#pragma once

#include <ostream>
#include <string>

#include "table/table.hpp"

namespace railtab {

// `file_bytes` is the size of the file on disk [B].
void print_table_summary(const Table& table, const std::string& path, std::uintmax_t file_bytes,
                         bool print_scene, std::ostream& out);

}  // namespace railtab
