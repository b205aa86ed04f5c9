// SPDX-License-Identifier: Apache-2.0
// The sweep across MPI ranks: rank 0 deals y blocks out to every rank (itself included) as they
// finish, collects the results, keeps the checkpoint and alone holds the finished table.
#pragma once

#include <optional>

#include "scene/scene.hpp"
#include "generate/generate.hpp"
#include "engine/sweep.hpp"

namespace railtab {

// MPI_Init_thread (funneled: only the main thread calls MPI) for its lifetime, MPI_Finalize after.
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  int rank_ = 0;
  int size_ = 1;
};

// Run `kernel` over the scene's grids on every rank of MPI_COMM_WORLD. Every rank calls it with the
// same scene, kernel and options (options.threads: threads per rank). Work unit: one y block (all
// its roll columns); a rank asks for as many blocks as it has threads and asks again when they are
// done, so slow (flange) blocks do not hold the run. Each block is computed by
// SweepPlan::compute_column exactly as run_sweep computes it, so the datasets are the same bytes
// for any number of ranks and threads. Rank 0 returns the table (as run_sweep does); the other
// ranks return nothing. Shards (options.shard_count > 1) are refused: MPI replaces them.
std::optional<SweepResult> run_sweep_mpi(const Scene& scene, const SweepKernel& kernel, const SweepOptions& options);

// railtab generate on every rank of an MPI launch: generate_table with the MPI engine, the
// checkpoint always kept (a rank that dies leaves it resumable), the log on rank 0 only. An error
// on any rank is printed with the rank and ends the whole run (MPI_Abort): no table is written.
void generate_table_mpi(GenerateOptions options);

}  // namespace railtab
