// SPDX-License-Identifier: Apache-2.0
// The MPI sweep engine: rank 0 deals y blocks and collects them; every rank computes.
#include "distributed/mpi_sweep.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <iostream>
#include <limits>
#include <memory>
#include <mutex>
#include <thread>

#include "core/check.hpp"
#include "engine/checkpoint.hpp"
#include "engine/parallel_for.hpp"
#include "engine/sweep_plan.hpp"
#include "table/interrupt.hpp"
#include "table/version.hpp"

namespace railtab {
namespace {

constexpr int kTagRequest = 1;  // worker -> 0: one int, how many blocks it wants
constexpr int kTagAssign = 2;   // 0 -> worker: uint64 block indices; none = stop
constexpr int kTagResult = 3;   // worker -> 0: ResultHeader, failure message, block bytes

struct ResultHeader {
  std::uint64_t block;          // local y block
  std::uint64_t failures;       // points where the core threw
  std::uint64_t first_column;   // block * columns + column of the first failure (ordering key)
  std::uint64_t message_bytes;  // length of the failure message that follows
};

void check_mpi(int code, const char* what) {
  if (code != MPI_SUCCESS) throw Error(fmt::format("MPI: {} failed (error {})", what, code));
}

// One computed block: its failures, ordered like run_sweep orders them (lowest column first).
struct BlockResult {
  std::size_t block = 0;
  std::size_t failures = 0;
  std::size_t first_column = std::numeric_limits<std::size_t>::max();
  std::string first_failure;
};

// Compute the given blocks (every (roll, yaw) column of each) with `threads` threads.
std::vector<BlockResult> compute_blocks(SweepPlan& plan, const std::vector<std::size_t>& blocks, int threads) {
  const std::size_t nroll = plan.layout().columns;  // columns per block
  std::vector<ColumnReport> reports(blocks.size() * nroll);
  parallel_for_index(threads, reports.size(),
                     [&](std::size_t i) { reports[i] = plan.compute_column(blocks[i / nroll], i % nroll); });
  std::vector<BlockResult> results(blocks.size());
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    results[b].block = blocks[b];
    // The block the mirror filled with it goes back too (its failures are counted here).
    if (plan.mirror_target(blocks[b]) != SweepPlan::kNoBlock) {
      BlockResult image;
      image.block = plan.mirror_target(blocks[b]);
      results.push_back(image);
    }
    for (std::size_t r = 0; r < nroll; ++r) {
      const ColumnReport& report = reports[b * nroll + r];
      results[b].failures += report.failures;
      if (report.failures > 0 && results[b].first_column == std::numeric_limits<std::size_t>::max()) {
        results[b].first_column = blocks[b] * nroll + r;
        results[b].first_failure = report.first_failure;
      }
    }
  }
  return results;
}

void send_result(const SweepPlan& plan, const BlockResult& r) {
  ResultHeader header{r.block, r.failures, r.first_column, r.first_failure.size()};
  std::vector<char> message(sizeof header);
  std::memcpy(message.data(), &header, sizeof header);
  message.insert(message.end(), r.first_failure.begin(), r.first_failure.end());
  std::vector<char> bytes = pack_block(plan.table(), plan.layout().ny, r.block);
  message.insert(message.end(), bytes.begin(), bytes.end());
  RAILTAB_CHECK(message.size() <= static_cast<std::size_t>(std::numeric_limits<int>::max()),
                "MPI: one y block of {} bytes is too large for one message", message.size());
  check_mpi(MPI_Send(message.data(), static_cast<int>(message.size()), MPI_BYTE, 0, kTagResult, MPI_COMM_WORLD),
            "send of a result");
}

// Ranks other than 0: ask for blocks, compute them, send them back, until told to stop.
void run_worker(SweepPlan& plan, int threads) {
  while (true) {
    int wanted = threads;
    check_mpi(MPI_Send(&wanted, 1, MPI_INT, 0, kTagRequest, MPI_COMM_WORLD), "send of a request");
    MPI_Status status;
    check_mpi(MPI_Probe(0, kTagAssign, MPI_COMM_WORLD, &status), "probe for an assignment");
    int count = 0;
    MPI_Get_count(&status, MPI_UINT64_T, &count);
    std::vector<std::uint64_t> assigned(static_cast<std::size_t>(count));
    check_mpi(MPI_Recv(assigned.data(), count, MPI_UINT64_T, 0, kTagAssign, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
              "receive of an assignment");
    if (assigned.empty()) return;
    std::vector<std::size_t> blocks(assigned.begin(), assigned.end());
    for (const BlockResult& r : compute_blocks(plan, blocks, threads)) send_result(plan, r);
  }
}

// Rank 0's deal: the blocks still to compute, handed out in ascending order.
class Dealer {
 public:
  explicit Dealer(std::deque<std::size_t> todo) : todo_(std::move(todo)) {}
  std::vector<std::size_t> take(std::size_t n) {
    std::lock_guard lock(mutex_);
    std::vector<std::size_t> out;
    while (out.size() < n && !todo_.empty() && !closed_) {
      out.push_back(todo_.front());
      todo_.pop_front();
    }
    return out;
  }
  void close() {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }

 private:
  std::mutex mutex_;
  std::deque<std::size_t> todo_;
  bool closed_ = false;
};

}  // namespace

MpiSession::MpiSession() {
  int provided = 0;
  check_mpi(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  RAILTAB_CHECK(provided >= MPI_THREAD_FUNNELED, "MPI: the library gives thread level {}, railtab needs FUNNELED",
                provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() { MPI_Finalize(); }

std::optional<SweepResult> run_sweep_mpi(const Scene& scene, const SweepKernel& kernel, const SweepOptions& options) {
  RAILTAB_CHECK(options.shard_count == 1, "--shard and MPI: give one or the other (MPI splits the work itself)");
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  const int threads = effective_threads(options.threads);
  SweepPlan plan(scene, kernel, options);
  if (rank != 0) {
    run_worker(plan, threads);
    return std::nullopt;
  }

  const SweepLayout& l = plan.layout();
  SweepResult result;
  SweepSummary& summary = result.summary;
  summary.blocks_total = l.ny;
  summary.points_total = l.ny * plan.points_per_block();
  summary.threads = threads;
  summary.ranks = ranks;
  summary.mirrored = plan.mirrored();
  summary.full_sweep_reason = plan.full_sweep_reason();

  // Resume: blocks in the checkpoint are loaded, not computed (rank 0 alone touches the file).
  std::vector<char> block_done;
  std::unique_ptr<Checkpoint> checkpoint = plan.resume(options.checkpoint, block_done, summary);
  std::deque<std::size_t> todo;
  for (std::size_t b = 0; b < l.ny; ++b) {
    if (!block_done[b] && plan.scheduled(b)) todo.push_back(b);
  }
  const std::size_t blocks_todo = todo.size();
  Dealer dealer(std::move(todo));

  // Rank 0 computes too, on its own thread; this (main) thread alone calls MPI.
  std::mutex mutex;
  std::deque<BlockResult> local_done;  // guarded by mutex
  bool local_finished = false;         // guarded by mutex
  std::exception_ptr local_fatal;      // guarded by mutex
  std::thread local([&] {
    try {
      while (true) {
        std::vector<std::size_t> blocks = dealer.take(static_cast<std::size_t>(threads));
        if (blocks.empty()) break;
        std::vector<BlockResult> done = compute_blocks(plan, blocks, threads);
        std::lock_guard lock(mutex);
        for (BlockResult& r : done) local_done.push_back(std::move(r));
      }
    } catch (...) {
      std::lock_guard lock(mutex);
      local_fatal = std::current_exception();
    }
    std::lock_guard lock(mutex);
    local_finished = true;
  });

  std::size_t first_column = std::numeric_limits<std::size_t>::max();
  auto record = [&](const BlockResult& r) {
    if (checkpoint) checkpoint->append(r.block, pack_block(plan.table(), l.ny, r.block));
    ++summary.blocks_done;
    summary.failures += r.failures;
    if (r.failures > 0 && r.first_column < first_column) {
      first_column = r.first_column;
      summary.first_failure = r.first_failure;
    }
  };

  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  auto interrupted = [&] { return options.interrupt && options.interrupt->load(std::memory_order_relaxed); };
  int workers_running = ranks - 1;
  std::size_t blocks_computed = 0;
  double last_report = -1.0;
  try {
    while (true) {
      bool busy = false;
      {
        std::deque<BlockResult> done;
        bool finished = false;
        {
          std::lock_guard lock(mutex);
          done.swap(local_done);
          finished = local_finished;
          if (local_fatal) std::rethrow_exception(local_fatal);
        }
        for (const BlockResult& r : done) {
          record(r);
          blocks_computed += plan.scheduled(r.block);
        }
        busy = !done.empty();
        if (finished && workers_running == 0) break;
      }
      if (interrupted()) dealer.close();
      int flag = 0;
      MPI_Status status;
      check_mpi(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status), "probe");
      if (flag) {
        busy = true;
        int bytes = 0;
        MPI_Get_count(&status, MPI_BYTE, &bytes);
        std::vector<char> message(static_cast<std::size_t>(bytes));
        check_mpi(MPI_Recv(message.data(), bytes, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
                           MPI_STATUS_IGNORE),
                  "receive");
        if (status.MPI_TAG == kTagRequest) {
          int wanted = 0;
          RAILTAB_CHECK(message.size() == sizeof wanted, "MPI: malformed request from rank {}", status.MPI_SOURCE);
          std::memcpy(&wanted, message.data(), sizeof wanted);
          std::vector<std::size_t> blocks = dealer.take(static_cast<std::size_t>(std::max(wanted, 1)));
          std::vector<std::uint64_t> assigned(blocks.begin(), blocks.end());
          check_mpi(MPI_Send(assigned.data(), static_cast<int>(assigned.size()), MPI_UINT64_T, status.MPI_SOURCE,
                             kTagAssign, MPI_COMM_WORLD),
                    "send of an assignment");
          if (assigned.empty()) --workers_running;
        } else if (status.MPI_TAG == kTagResult) {
          ResultHeader header{};
          RAILTAB_CHECK(message.size() >= sizeof header, "MPI: malformed result from rank {}", status.MPI_SOURCE);
          std::memcpy(&header, message.data(), sizeof header);
          RAILTAB_CHECK(header.block < l.ny && header.message_bytes <= message.size() - sizeof header,
                        "MPI: malformed result from rank {}", status.MPI_SOURCE);
          const char* text = message.data() + sizeof header;
          std::vector<char> block_bytes(message.begin() + static_cast<std::ptrdiff_t>(sizeof header + header.message_bytes), message.end());
          unpack_block(plan.table(), l.ny, header.block, block_bytes);
          record({header.block, header.failures, header.first_column, std::string(text, header.message_bytes)});
          blocks_computed += plan.scheduled(header.block);
        } else {
          throw Error(fmt::format("MPI: unexpected message tag {} from rank {}", status.MPI_TAG, status.MPI_SOURCE));
        }
      }
      double now = elapsed();
      if (options.progress && now - last_report >= options.progress_interval) {
        options.progress({blocks_computed * plan.points_per_block(), blocks_todo * plan.points_per_block(), now});
        last_report = now;
      }
      // Idle: wait a little instead of spinning, so the compute threads keep the cores.
      if (!busy) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  } catch (...) {
    dealer.close();
    local.join();
    throw;
  }
  local.join();
  if (options.progress) options.progress({blocks_computed * plan.points_per_block(), blocks_todo * plan.points_per_block(), elapsed()});

  summary.seconds = elapsed();
  summary.points_computed = blocks_computed * plan.points_per_block();
  summary.interrupted = summary.blocks_done < summary.blocks_total;
  plan.table().set_attribute("created", utc_timestamp());
  result.table = std::move(plan.table());
  return result;
}

}  // namespace railtab

namespace railtab {

void generate_table_mpi(GenerateOptions options) {
  MpiSession session;
  try {
    if (session.rank() != 0) options.log = nullptr;
    options.engine = run_sweep_mpi;
    options.always_checkpoint = true;
    options.writes_files = session.rank() == 0;
    generate_table(options);
  } catch (const Interrupted&) {
    throw;  // every rank stops the same way; the checkpoint stays
  } catch (const std::exception& e) {
    std::cerr << fmt::format("railtab (MPI rank {} of {}): {}\n", session.rank(), session.size(), e.what())
              << std::flush;
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
}

}  // namespace railtab
