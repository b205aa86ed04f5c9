// SPDX-License-Identifier: Apache-2.0
// Checkpoint file of an interrupted sweep (TARGET.partial): a header with a key that identifies the
// run (scene text, build, shard, layout), then one record per finished y block holding that
// block's slice of every dataset, with a checksum. A resumed run loads the valid records and
// computes only the missing blocks; since every value depends only on its grid indices, the result
// equals a fresh run byte for byte. A torn last record (crash mid-write) is dropped.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "table/table.hpp"

namespace railtab {

// FNV-1a 64-bit hash, for checkpoint keys and record checksums.
std::uint64_t fnv1a(std::string_view bytes, std::uint64_t seed = 14695981039346656037ull);

// The slice of every dataset of `table` for y block `block` of `blocks` (y outermost), and back.
std::vector<char> pack_block(const Table& table, std::size_t blocks, std::size_t block);
void unpack_block(Table& table, std::size_t blocks, std::size_t block, const std::vector<char>& bytes);

// The dataset ("/left/creep/fx") holding the first non-finite value in y block `block` of
// `blocks`, or "" when there is none. The sweep stores 0 for every non-finite result (NaN only in
// /equilibrium_roll, by design, not counted), so a resumed record with one was altered.
std::string first_non_finite(const Table& table, std::size_t blocks, std::size_t block);

class Checkpoint {
 public:
  // Open or create `path` for a run identified by `key` whose records hold `record_bytes` bytes.
  // A file with another key (other scene or build) is started afresh: discarded() says so. Throws
  // railtab::Error for a path that is a symbolic link, a hard link, not a regular file, an input
  // of the run or held by another live run (table/output_file.hpp, open_output_to_continue).
  Checkpoint(std::filesystem::path path, std::uint64_t key, std::size_t record_bytes);
  ~Checkpoint();
  Checkpoint(const Checkpoint&) = delete;
  Checkpoint& operator=(const Checkpoint&) = delete;

  // Valid records found on opening, in file order.
  struct Record {
    std::uint64_t block;      // y block index within the table [-]
    std::vector<char> bytes;  // pack_block() payload
  };
  std::vector<Record> take_records() { return std::move(records_); }
  bool discarded() const { return discarded_; }

  // Append one finished block and flush it to disk.
  void append(std::uint64_t block, const std::vector<char>& bytes);

  // Close and delete the file (after the table has been written).
  void remove();

 private:
  std::filesystem::path path_;
  std::uint64_t key_;
  std::size_t record_bytes_;
  int fd_ = -1;  // the checkpoint, open for appending (and locked) while the run lasts
  std::vector<Record> records_;
  bool discarded_ = false;
};

}  // namespace railtab
