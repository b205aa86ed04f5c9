// SPDX-License-Identifier: Apache-2.0
// The table sweep: a generic engine that runs a kernel over the (y, roll, yaw) grid in parallel
// and fills a Table (docs/table-format.md).
//
// Work unit ("column"): one (y, roll, yaw) grid point, both wheels, all parts. A kernel solves the
// geometry once per column, the normal contact once per load on top of it, and creep/wear per
// creepage on top of each normal result, so no part is ever recomputed. Every value is written
// into a preallocated buffer at an offset computed from the grid indices, so the bytes do not
// depend on the thread count or the scheduling. Per-point failures are status flags (the kernel
// catches them); only fatal errors escape.
//
// Blocks: all columns of one y index. y is the slowest dimension of every dataset, so a block is a
// contiguous slice of each dataset: the unit of the checkpoint (--resume) and of shards (--shard).
#pragma once

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/status.hpp"
#include "scene/scene.hpp"
#include "engine/table_size.hpp"
#include "table/table.hpp"

namespace railtab {

inline constexpr std::size_t kSlots = 2;  // contact slots: 0 tread, 1 flange

struct OutputInfo {
  std::string name;         // dataset name
  std::string units;        // SI units ("1" for dimensionless)
  std::string description;  // one line
  bool odd = false;         // changes sign under the mirror that swaps the wheels (lateral
                            //   quantities: contact angle, fy, mz, ...; docs/conventions.md)
};

// A part of the table (a group per wheel): its state axes beyond (y, roll, yaw) and its float64
// outputs; the engine adds the uint32 `status` dataset.
struct PartSpec {
  std::string name;                     // "geometry", "normal", "creep", "wear"
  std::vector<std::string> inner_axes;  // e.g. {"load"} or {"load", "xi", "eta", "phi"}
  std::vector<OutputInfo> outputs;      // float64 outputs in file order
};

struct ColumnState {
  std::size_t iy = 0;     // index into the scene's full y grid
  std::size_t iroll = 0;  // index into the roll grid (0 with equilibrium roll)
  std::size_t iyaw = 0;   // index into the yaw grid (0 without yaw)
  double y = 0.0;         // lateral displacement [m]
  double roll = 0.0;      // roll angle (grid value or equilibrium roll) [rad]
  double yaw = 0.0;       // yaw angle (grid value; 0 for a scene without yaw) [rad]
  unsigned wheels = 3u;   // wheels the contact kernel computes: bit 0 left, bit 1 right (the
                          //   sweep: both; the one-sided jump values: the jump's wheel only)
};

// Where a kernel writes one column. For part p the column holds the part's inner grid x slot in
// C order (inner_axes in order, slot fastest); values() and status() point at its first element.
class ColumnOutput {
 public:
  ColumnOutput(std::vector<double*> values, std::vector<StatusBits*> status,
               const std::vector<std::size_t>& output_offset, std::size_t parts)
      : values_(std::move(values)), status_(std::move(status)), offset_(output_offset), parts_(parts) {}

  double* values(std::size_t wheel, std::size_t part, std::size_t output) const {
    return values_[wheel * offset_.back() + offset_[part] + output];
  }
  StatusBits* status(std::size_t wheel, std::size_t part) const { return status_[wheel * parts_ + part]; }

  // Record a per-point failure (counted in the summary; the kernel sets the status flags).
  void failure(const std::string& message);
  std::size_t failures() const { return failures_; }
  const std::string& first_failure() const { return first_failure_; }

 private:
  std::vector<double*> values_;              // [wheel][part][output] column pointers
  std::vector<StatusBits*> status_;          // [wheel][part]
  const std::vector<std::size_t>& offset_;   // first output of each part, plus the total
  std::size_t parts_;
  std::size_t failures_ = 0;
  std::string first_failure_;
};

// What the engine runs. compute() must be thread-safe and deterministic (same column in, same
// bytes out) and must not throw for per-point numerical trouble.
struct SweepKernel {
  std::vector<PartSpec> parts;                 // parts with at least one output, in file order
  std::size_t points_per_column = 1;           // grid points one column solves (for progress) [-]
  nlohmann::json models;                       // model names and options, the `models` attribute
  std::function<double(double y)> equilibrium_roll;  // needed when the scene asks for it [rad]
  // Root float64 datasets over y whose values the kernel knows before the sweep (e.g. the normal
  // model chosen per y node); the table stores each shard's slice, axes (y).
  struct PerYOutput {
    OutputInfo info;             // dataset name, units, description
    std::vector<double> values;  // one per node of the scene's full y grid
  };
  std::vector<PerYOutput> per_y;
  // Axes the kernel tabulates in a coordinate of its own instead of the scene's physical grid (the
  // normalised creepages of format 2.1, kernel/creep_map.hpp): each replaces the scene's axis of
  // the same name (same node count).
  std::vector<TableAxis> own_axes;
  // Root attributes the kernel adds (name, JSON text; the creep map of format 2.1), written after
  // `fixed_axes`.
  std::vector<std::pair<std::string, std::string>> attributes;
  PointCost point_cost = kFastPointCost;  // run time per computed grid point, for the size check and the estimate
  // The kernel's model has no side of its own: (y, roll, yaw, eta, phi) -> (-y, -roll, -yaw, -eta,
  // -phi) swaps the wheels exactly, with the `odd` outputs negated (docs/conventions.md, side
  // frame), and equilibrium_roll is exactly odd in y. On a scene whose grids are mirror-symmetric
  // too (engine/mirror.hpp) the sweep then computes the columns y >= 0 and fills y < 0 by the mirror.
  bool mirror_symmetric = false;
  std::function<void(const ColumnState&, ColumnOutput&)> compute;
};

struct SweepProgress {
  std::size_t points_done = 0;     // points computed in this run so far
  std::size_t points_todo = 0;     // points this run computes in total (resumed ones excluded)
  double seconds = 0.0;            // wall time since the start of the computation [s]
};

struct SweepOptions {
  int threads = 0;                          // worker threads; 0 = all cores
  int shard_index = 1;                      // this run computes shard shard_index of shard_count
  int shard_count = 1;                      //   (1-based, contiguous ranges of y)
  std::vector<double> y_costs;              // estimated cost per y of the full grid: shards split
                                            //   by it (shard_split.hpp); empty = equal counts
  std::filesystem::path checkpoint;         // resume file; empty = no checkpoint
  const std::atomic<bool>* interrupt = nullptr;  // polled; set = stop as soon as possible
  std::function<void(const SweepProgress&)> progress;  // called on the calling thread only
  double progress_interval = 0.25;          // seconds between progress calls [s]
  std::uint64_t max_points = kDefaultMaxPoints;  // refuse a larger table (table_size.hpp) [-]
  std::uint64_t max_bytes = kDefaultMaxBytes;    // refuse a table needing more memory [B]
  bool mirror = true;  // false: compute every column even where the mirror could fill it (the
                       //   full sweep, the reference of the mirror's tests)
};

struct SweepSummary {
  std::size_t points_total = 0;     // points of this table (shard) [-]
  std::size_t points_computed = 0;  // computed in this run [-]
  std::size_t points_resumed = 0;   // taken from the checkpoint [-]
  std::size_t blocks_total = 0;     // y blocks of this table (shard) [-]
  std::size_t blocks_done = 0;      // y blocks complete (computed or resumed) [-]
  std::size_t failures = 0;         // columns/points where the core threw (see status) [-]
  std::string first_failure;        // message of the first of them (lowest column)
  int threads = 1;                  // threads used (per rank under MPI) [-]
  int ranks = 1;                    // MPI ranks used [-]
  double seconds = 0.0;             // wall time of the computation [s]
  bool interrupted = false;         // stopped by the interrupt flag: the table is incomplete
  bool checkpoint_discarded = false;  // a checkpoint of another scene/build was found and reset
  bool mirrored = false;            // the columns y < 0 were filled by the mirror of y > 0
  std::string full_sweep_reason;    // why not (empty when mirrored): for the log
};

struct SweepResult {
  Table table;           // complete unless summary.interrupted
  SweepSummary summary;
};

// The y index range [begin, end) of shard `index` (1-based) of `count` over `ny` values.
std::pair<std::size_t, std::size_t> shard_range(std::size_t ny, int index, int count);

// Run `kernel` over the scene's grids (the shard's part of y) and return the filled table with
// all root attributes (format 1.2, docs/table-format.md). With options.checkpoint set, finished blocks are appended to
// that file as they complete and blocks already in it are not recomputed.
SweepResult run_sweep(const Scene& scene, const SweepKernel& kernel, const SweepOptions& options);

}  // namespace railtab
