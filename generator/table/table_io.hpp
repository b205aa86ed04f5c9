// SPDX-License-Identifier: Apache-2.0
// Reading and writing contact-table files (docs/table-format.md, format 1.0) with the HDF5 C API.
// Only one thread may call these at a time (HDF5 is serialised process-wide).
#pragma once

#include <atomic>
#include <filesystem>
#include <string>
#include <vector>

#include "table/output_file.hpp"  // temporary_path
#include "table/table.hpp"

namespace railtab {

// What write_table checks in the file it wrote before renaming it over the target.
enum class WrittenCheck {
  lookup,  // the lookup's own loader accepts it (table/loadable_check.hpp): every table railtab ships
  none,    // nothing (tests writing deliberately odd tables for a reader to refuse)
};

// Write `table` to `target` through an OutputFile (table/output_file.hpp): first to
// `target.tmp.<pid>`, synced, loaded by the lookup (`check`), and renamed to `target` only once
// complete, closed and accepted. Refuses a target that is not a regular file or is one of
// `inputs`. Any failure (or `cancel` becoming true between datasets, which throws Interrupted)
// removes the temporary file and leaves an existing `target` untouched.
void write_table(const Table& table, const std::filesystem::path& target,
                 const std::atomic<bool>* cancel = nullptr, const std::vector<std::filesystem::path>& inputs = {},
                 WrittenCheck check = WrittenCheck::lookup);

// Read a whole table. Throws railtab::Error naming the file and the problem for: a missing or
// non-HDF5 file, a truncated file, an unknown major format version, missing required groups,
// datasets or attributes, and datasets whose shape disagrees with their axes.
Table read_table(const std::filesystem::path& path);

// Names of format 2 that the writer and the reader share.
namespace table_format {
// Root attributes whose in-memory text is a JSON object: stored as a group of typed attributes.
inline constexpr const char* kObjectAttributes[] = {"models", "accuracy_targets", "accuracy_achieved"};
// Dimensions that are not axes: list indices without a coordinate (jump list and side of /jumps,
// the y bands of /error_map).
inline bool is_plain_dimension(const std::string& name) { return name == "jump" || name == "side" || name == "band"; }
}  // namespace table_format

}  // namespace railtab
