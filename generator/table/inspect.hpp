// SPDX-License-Identifier: Apache-2.0
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

// The same summary as JSON text (`railtab inspect --json`, stable keys, SI units): "file",
// "file_bytes", "attributes" (JSON-valued ones such as models and fixed_axes as objects, the
// scene as its text), "axes" (name, units, description, size, min, max), "groups" (path, datasets
// with name, units, description, axes, shape, storage_bytes; status datasets also "status_counts":
// cells, no_contact and a count per set bit name), "checksums_verified" (the lookup verified
// the file's Fletcher32 and metadata checksums at load: `checksums_verified`).
std::string table_summary_json(const Table& table, const std::string& path, std::uintmax_t file_bytes,
                               bool checksums_verified);

}  // namespace railtab
