// SPDX-License-Identifier: Apache-2.0
// parallel_for_index on oneTBB (a capped task arena, one task per index) or, in the TSan build, on
// std::threads sharing an atomic index counter.
#include "engine/parallel_for.hpp"

#ifdef RAILTAB_PLAIN_THREADS
#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>
#else
#include <algorithm>

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/info.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/partitioner.h>
#include <oneapi/tbb/task_arena.h>
#endif

namespace railtab {

#ifdef RAILTAB_PLAIN_THREADS

int effective_threads(int threads) {
  return threads > 0 ? threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

// Debian's libtbb is not built with ThreadSanitizer, which then cannot see oneTBB's spawn and
// join and reports races in correct code; with std::threads every synchronisation is visible, so
// a report is a race in railtab's own bodies (scripts/sanitize.sh tsan).
void parallel_for_index(int threads, std::size_t n, const std::function<void(std::size_t)>& body) {
  std::atomic<std::size_t> next{0};
  std::exception_ptr first_error;
  std::mutex error_mutex;
  auto work = [&] {
    for (std::size_t i = next++; i < n; i = next++) {
      try {
        body(i);
      } catch (...) {
        std::lock_guard lock(error_mutex);
        if (!first_error) first_error = std::current_exception();
        next = n;  // stop handing out indices, as oneTBB cancels the group
      }
    }
  };
  const std::size_t count = std::min<std::size_t>(static_cast<std::size_t>(effective_threads(threads)), n);
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < count; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (first_error) std::rethrow_exception(first_error);
}

#else

// Capped at the cores oneTBB may use: more threads than that gain nothing, and oneTBB answers a
// wider arena with a "TBB Warning: The number of workers is currently limited" on stderr that
// `-q` could not silence (the result is the same for any thread count).
int effective_threads(int threads) {
  const int cores = tbb::info::default_concurrency();
  return threads > 0 ? std::min(threads, cores) : cores;
}

void parallel_for_index(int threads, std::size_t n, const std::function<void(std::size_t)>& body) {
  tbb::task_arena arena(effective_threads(threads));  // caps the threads of this call only
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, n, 1),
        [&](const tbb::blocked_range<std::size_t>& range) {
          for (std::size_t i = range.begin(); i != range.end(); ++i) body(i);
        },
        tbb::simple_partitioner());
  });
}

#endif

}  // namespace railtab
