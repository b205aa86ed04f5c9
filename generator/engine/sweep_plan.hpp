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

// The scene's grid of a state axis ("y", "roll", "yaw", "load", "xi", "eta", "phi").
const std::vector<double>& grid_of(const Scene& scene, const std::string& name);

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

  // Compute column (local y block, column = roll index x nyaw + yaw index) into the table. On a
  // mirrored sweep a block y > 0 also fills the mirror column of its block -y (mirror_target;
  // the report then counts the failures of both), and a block y < 0 whose block +y lies outside
  // this table (a shard) computes that column aside and stores its mirror. Thread-safe for
  // distinct columns of scheduled blocks.
  ColumnReport compute_column(std::size_t block, std::size_t column);

  // The mirror (engine/mirror.hpp): whether this sweep fills its columns y < 0 from y > 0, and if
  // not, why (empty when it does).
  bool mirrored() const { return mirrored_; }
  const std::string& full_sweep_reason() const { return full_sweep_reason_; }
  // Whether an engine computes this block itself: false for a block y < 0 that computing its
  // block +y fills (mirror_target).
  bool scheduled(std::size_t block) const { return !filled_[block]; }
  // The local block that computing `block` fills by the mirror, or kNoBlock.
  static constexpr std::size_t kNoBlock = static_cast<std::size_t>(-1);
  std::size_t mirror_target(std::size_t block) const { return target_[block]; }

  // Resume: open `path` (empty: no checkpoint, returns null), load the blocks it holds into the
  // table and mark them in `block_done` (one flag per y block); counts them in `summary`
  // (blocks_done, points_resumed, checkpoint_discarded). Both engines start this way. On a
  // mirrored sweep a block the mirror fills is done with its block +y: filled here when that one
  // was loaded, computed again with it when not.
  std::unique_ptr<Checkpoint> resume(const std::filesystem::path& path, std::vector<char>& block_done,
                                     SweepSummary& summary);

 private:
  const Scene& scene_;
  const SweepKernel& kernel_;
  SweepLayout layout_;
  Table table_;
  double* equilibrium_roll_ = nullptr;  // root dataset /equilibrium_roll, or null
  bool mirrored_ = false;
  std::string full_sweep_reason_;
  std::vector<std::vector<std::size_t>> mirror_cells_;  // per part (mirror_cells)
  std::vector<std::size_t> target_;  // per local block: the block its computation fills, or kNoBlock
  std::vector<char> filled_;         // per local block: filled by another block's computation

  ColumnState column_state(std::size_t iy, std::size_t column) const;
  ColumnOutput column_output(std::size_t block, std::size_t column);
  ColumnOutput aside_output(std::vector<double>& values, std::vector<StatusBits>& status) const;
  std::size_t mirror_of(std::size_t column) const;  // the column of (-roll, -yaw)
  void set_roll(std::size_t block, double roll);
  void fill_mirror(std::size_t from_block, std::size_t to_block);  // every column
};

}  // namespace railtab
