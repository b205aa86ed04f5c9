// SPDX-License-Identifier: Apache-2.0
// The sweep engine: a kernel over the (y, roll, yaw) grid in parallel, in a deterministic order.
#include "engine/sweep.hpp"

#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <ctime>
#include <limits>
#include <memory>
#include <mutex>
#include <thread>

#include "core/check.hpp"
#include "engine/checkpoint.hpp"
#include "engine/parallel_for.hpp"
#include "engine/sweep_plan.hpp"
#include "table/version.hpp"

namespace railtab {

void ColumnOutput::failure(const std::string& message) {
  if (failures_++ == 0) first_failure_ = message;
}

std::pair<std::size_t, std::size_t> shard_range(std::size_t ny, int index, int count) {
  RAILTAB_CHECK(count >= 1 && index >= 1 && index <= count, "shard {}/{}: need 1 <= I <= N", index, count);
  RAILTAB_CHECK(static_cast<std::size_t>(count) <= ny, "shard {}/{}: the y grid has only {} values to split",
                index, count, ny);
  auto n = static_cast<std::size_t>(count), i = static_cast<std::size_t>(index);
  return {ny * (i - 1) / n, ny * i / n};
}

SweepResult run_sweep(const Scene& scene, const SweepKernel& kernel, const SweepOptions& options) {
  SweepPlan plan(scene, kernel, options);
  const SweepLayout& l = plan.layout();
  SweepResult result;
  SweepSummary& summary = result.summary;
  const std::size_t points_per_block = plan.points_per_block();
  summary.blocks_total = l.ny;
  summary.points_total = l.ny * points_per_block;

  // Resume: blocks already in the checkpoint are loaded, not computed.
  std::vector<char> block_done;
  std::unique_ptr<Checkpoint> checkpoint = plan.resume(options.checkpoint, block_done, summary);

  struct Task {
    std::size_t block;  // local y index
    std::size_t column;  // roll index x nyaw + yaw index
  };
  std::vector<Task> tasks;
  for (std::size_t b = 0; b < l.ny; ++b) {
    if (block_done[b] || !plan.scheduled(b)) continue;  // (a block the mirror fills: with its block +y)
    for (std::size_t c = 0; c < l.columns; ++c) tasks.push_back({b, c});
  }
  const std::size_t points_todo = tasks.size() * kernel.points_per_column;
  summary.threads = effective_threads(options.threads);
  summary.mirrored = plan.mirrored();
  summary.full_sweep_reason = plan.full_sweep_reason();

  std::atomic<std::size_t> points_done{0};
  std::vector<std::atomic<std::size_t>> remaining(l.ny);
  for (auto& r : remaining) r.store(l.columns);
  std::mutex mutex;                      // guards the fields below
  std::condition_variable wake;
  std::vector<std::size_t> finished_blocks;  // complete, not yet checkpointed
  bool worker_finished = false;
  std::exception_ptr fatal;
  std::size_t first_failure_task = std::numeric_limits<std::size_t>::max();

  auto interrupted = [&] { return options.interrupt && options.interrupt->load(std::memory_order_relaxed); };

  auto run_task = [&](std::size_t task_index) {
    const Task& task = tasks[task_index];
    ColumnReport out = plan.compute_column(task.block, task.column);
    points_done.fetch_add(kernel.points_per_column, std::memory_order_relaxed);
    bool block_complete = remaining[task.block].fetch_sub(1) == 1;
    if (out.failures > 0 || block_complete) {
      std::lock_guard lock(mutex);
      summary.failures += out.failures;
      if (out.failures > 0 && task_index < first_failure_task) {
        first_failure_task = task_index;  // lowest column: the same message for any thread count
        summary.first_failure = out.first_failure;
      }
      if (block_complete) finished_blocks.push_back(task.block);
      if (block_complete && plan.mirror_target(task.block) != SweepPlan::kNoBlock)
        finished_blocks.push_back(plan.mirror_target(task.block));
    }
    if (block_complete) wake.notify_one();
  };

  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  std::atomic<bool> abandoned{false};  // set by this thread when it gives up (an exception)
  std::thread worker([&] {
    try {
      // After an interrupt, or a failure of this thread's checkpoint writing, the remaining tasks
      // return at once: the checkpoint keeps what is done.
      parallel_for_index(summary.threads, tasks.size(), [&](std::size_t i) {
        if (!interrupted() && !abandoned) run_task(i);
      });
    } catch (...) {
      std::lock_guard lock(mutex);
      fatal = std::current_exception();
    }
    {
      std::lock_guard lock(mutex);
      worker_finished = true;
    }
    wake.notify_one();
  });

  // This thread alone writes the checkpoint and reports progress.
  try {
    double last_report = -1.0;
    std::unique_lock lock(mutex);
    while (true) {
      wake.wait_for(lock, std::chrono::duration<double>(options.progress_interval),
                    [&] { return worker_finished || !finished_blocks.empty(); });
      std::vector<std::size_t> blocks;
      blocks.swap(finished_blocks);
      bool finished = worker_finished;
      lock.unlock();
      for (std::size_t b : blocks) {
        if (checkpoint) checkpoint->append(b, pack_block(plan.table(), l.ny, b));
        ++summary.blocks_done;
      }
      double now = elapsed();
      if (options.progress && (finished || now - last_report >= options.progress_interval)) {
        options.progress({points_done.load(), points_todo, now});
        last_report = now;
      }
      lock.lock();
      if (finished && finished_blocks.empty()) break;
    }
  } catch (...) {
    abandoned = true;
    worker.join();
    throw;
  }
  worker.join();
  if (fatal) std::rethrow_exception(fatal);

  summary.seconds = elapsed();
  summary.points_computed = points_done.load();
  summary.interrupted = summary.blocks_done < summary.blocks_total;
  RAILTAB_CHECK(summary.interrupted || interrupted() || summary.points_computed == points_todo,
                "sweep: {} of {} points computed", summary.points_computed, points_todo);
  plan.table().set_attribute("created", utc_timestamp());
  result.table = std::move(plan.table());
  return result;
}

}  // namespace railtab
