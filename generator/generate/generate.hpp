// SPDX-License-Identifier: Apache-2.0
// railtab generate as a library call: scene -> sweep -> table file, with checkpoint/resume,
// shards, progress and clean interruption. The subcommand (generate_command.cpp) and the tests
// drive this.
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <optional>
#include <ostream>

#include "engine/shard_split.hpp"
#include "engine/sweep.hpp"
#include "scene/scene.hpp"

namespace railtab {

struct GenerateOptions {
  std::filesystem::path scene;               // scene file (TOML)
  std::filesystem::path output;              // table file to write (HDF5)
  int threads = 0;                           // worker threads, 0 = all cores
  bool resume = false;                       // keep/use the checkpoint OUTPUT.partial
  int shard_index = 1;                       // compute shard I of N (1-based, split along y)
  int shard_count = 1;
  const std::atomic<bool>* interrupt = nullptr;  // set = stop; throws Interrupted
  std::ostream* log = nullptr;               // progress and summary; nullptr = silent
  bool terminal = false;                     // log is a terminal: draw a progress bar
  std::function<SweepKernel(const Scene&)> make_kernel;  // default: make_contact_kernel
  // The engine that computes the table: run_sweep (threads of this process) when empty. The MPI
  // engine (generator/distributed/) returns no table on ranks other than 0: they write nothing.
  std::function<std::optional<SweepResult>(const Scene&, const SweepKernel&, const SweepOptions&)> engine;
  // Keep finished blocks in OUTPUT.partial even without `resume` (a fresh run discards an old
  // one): MPI runs always do, so a rank that dies leaves a resumable checkpoint.
  bool always_checkpoint = false;
  // False on MPI ranks other than 0: they neither write the table nor touch the checkpoint (a
  // rank that removed a fresh run's old checkpoint could remove the one rank 0 has just begun).
  bool writes_files = true;
  std::uint64_t max_points = kDefaultMaxPoints;  // refuse a larger table (--max-points) [-]
  std::uint64_t max_bytes = kDefaultMaxBytes;    // refuse a table needing more memory (--max-bytes) [B]
  // A mirror-symmetric scene computes y >= 0 and the left wheel's jumps only (engine/mirror.hpp);
  // false computes everything (the reference of the mirror's tests; the same bytes).
  bool mirror = true;
};

// The checkpoint file of a table: OUTPUT.partial.
std::filesystem::path checkpoint_path(const std::filesystem::path& output);

// True when this process was started by an MPI launcher (mpirun, mpiexec, srun with PMI/PMIx).
bool launched_by_mpi();

// Run the whole generation (on an MPI rank other than 0: compute only, write nothing, return an
// empty summary). On interruption throws Interrupted after removing every temporary
// file: no target is left (an existing target is not touched); with resume the checkpoint stays.
SweepSummary generate_table(const GenerateOptions& options);

}  // namespace railtab
