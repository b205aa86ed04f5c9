// SPDX-License-Identifier: Apache-2.0
// The generator's one way to run independent work items in parallel: body(i) for every i in
// [0, n) on at most `threads` threads. oneTBB normally; plain std::threads in the ThreadSanitizer
// build (RAILTAB_PLAIN_THREADS), whose synchronisation TSan sees (docs/ci.md).
#pragma once

#include <cstddef>
#include <functional>

namespace railtab {

// The thread count `threads` means: > 0 that many (with oneTBB at most the cores it may use),
// otherwise every core.
int effective_threads(int threads);

// Runs body(i) for i = 0 .. n-1, each index once, in any order and on any of `threads` threads;
// returns when all are done. Callers write each result into its own slot, so the outcome does not
// depend on the thread count. The first exception a body throws is rethrown here (the remaining
// indices may or may not run). Each index is one task (no chunking): bodies here are heavy.
void parallel_for_index(int threads, std::size_t n, const std::function<void(std::size_t)>& body);

}  // namespace railtab
