// SPDX-License-Identifier: Apache-2.0
// One sweep laid out: the table skeleton, the sizes, the run key and the computation of one column
// into it. Shared by the threaded engine (sweep.cpp) and the MPI engine (generator/distributed/), so
// both fill the same bytes in the same places.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "engine/checkpoint.hpp"
#include "engine/sweep.hpp"
#include "table/table.hpp"

namespace railtab {

// Sizes and offsets of one sweep.
struct SweepLayout {
  std::size_t y_begin = 0, y_end = 0;     // shard's range of the full y grid
  std::size_t ny = 0;                     // y values in this table (shard) = blocks
  std::size_t nroll = 1;                  // roll values swept per y (1 with equilibrium roll)
  std::size_t nyaw = 1;                   // yaw values swept per (y, roll) (1 without a yaw axis)
  std::size_t columns = 1;                // columns per y block: nroll x nyaw
  bool y_tabulated = false;               // y is an axis of the file
  bool roll_tabulated = false;            // roll is an axis of the file
  bool yaw_tabulated = false;             // yaw is an axis of the file
  std::vector<std::size_t> cells;         // per part: inner grid x slot elements of one column
  std::vector<std::size_t> first_output;  // per part: index of its first output, plus the total
};

// What computing one column left behind besides its values.
struct ColumnReport {
  std::size_t failures = 0;   // points where the core threw [-]
  std::string first_failure;  // message of the first of them
};

class SweepPlan {
 public:
  // The layout and the table with every dataset allocated (zeros) and every attribute but
  // `created`. Checks the kernel against the scene.
  SweepPlan(const Scene& scene, const SweepKernel& kernel, const SweepOptions& options);

  const SweepLayout& layout() const { return layout_; }
  Table& table() { return table_; }
  const Table& table() const { return table_; }
  std::size_t points_per_block() const { return layout_.columns * kernel_.points_per_column; }
  // Identity of the run for its checkpoint: anything that could change a stored byte.
  std::uint64_t run_key() const;

  // Compute column (local y block, column = roll index x nyaw + yaw index) into the table.
  // Thread-safe for distinct columns.
  ColumnReport compute_column(std::size_t block, std::size_t column);

  // Resume: open `path` (empty: no checkpoint, returns null), load the blocks it holds into the
  // table and mark them in `block_done` (one flag per y block); counts them in `summary`
  // (blocks_done, points_resumed, checkpoint_discarded). Both engines start this way.
  std::unique_ptr<Checkpoint> resume(const std::filesystem::path& path, std::vector<char>& block_done,
                                     SweepSummary& summary);

 private:
  const Scene& scene_;
  const SweepKernel& kernel_;
  SweepLayout layout_;
  Table table_;
  double* equilibrium_roll_ = nullptr;  // root dataset /equilibrium_roll, or null
};

}  // namespace railtab
