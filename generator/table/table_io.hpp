// Reading and writing contact-table files (docs/table-format.md, format 1.0) with the HDF5 C API.
// Only one thread may call these at a time (HDF5 is serialised process-wide).
#pragma once

#include <atomic>
#include <filesystem>

#include "table/table.hpp"

namespace railtab {

// Write `table` to `target`: first to `target.tmp.<pid>`, renamed to `target` only once complete
// and closed. Any failure (or `cancel` becoming true between datasets, which throws Interrupted)
// removes the temporary file and leaves an existing `target` untouched.
void write_table(const Table& table, const std::filesystem::path& target,
                 const std::atomic<bool>* cancel = nullptr);

// Read a whole table. Throws railtab::Error naming the file and the problem for: a missing or
// non-HDF5 file, a truncated file, an unknown major format version, missing required groups,
// datasets or attributes, and datasets whose shape disagrees with their axes.
Table read_table(const std::filesystem::path& path);

// Path of the temporary file write_table uses for `target` in this process.
std::filesystem::path temporary_path(const std::filesystem::path& target);

}  // namespace railtab
