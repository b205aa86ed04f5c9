// SPDX-License-Identifier: Apache-2.0
// The C++ side of the Python module's speed target (a vectorised query of 1e6 states
// from Python at no more than 2x the C++ cost). One iteration = 1e6 uniformly random states over
// the table's axes (wheels alternating), every output of every slot, through the batch API in
// chunks of 1024 (a reused result buffer, as a C++ caller would); the time of one iteration in ms
// is the cost per state in ns. python/bench/query_bench.py times the same from Python.
//   RAILTAB_BENCH_TABLE=default.h5 ./lookup_vectorised_bench   (without it: a fixture table
//   of a scene's size)
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "../tests/lookup/table_fixture.hpp"
#include "railtab/lookup.hpp"

namespace {

using railtab::lookup::Query;
using railtab::lookup::Result;
using railtab::lookup::Table;
using railtab::lookup::Wheel;

constexpr std::size_t kStates = 1000000;
constexpr std::size_t kChunk = 1024;

const Table& table() {
  static const std::unique_ptr<Table> t = [] {
    if (const char* path = std::getenv("RAILTAB_BENCH_TABLE")) return std::make_unique<Table>(Table::load(path));
    const std::string path = "/tmp/railtab_vectorised_bench_" + std::to_string(::getpid()) + ".h5";
    railtab::lookup::testing::write_fixture(path, railtab::lookup::testing::scene_sized_spec());
    auto loaded = std::make_unique<Table>(Table::load(path));
    std::remove(path.c_str());
    return loaded;
  }();
  return *t;
}

double& variable(railtab::lookup::State& s, const std::string& name) {
  if (name == "y") return s.y;
  if (name == "roll") return s.roll;
  if (name == "load") return s.load;
  if (name == "xi") return s.xi;
  if (name == "eta") return s.eta;
  return s.phi;
}

// Uniform over each tabulated axis's range; fixed variables at their fixed values.
std::vector<Query> random_states(const Table& t) {
  std::mt19937_64 rng(16);
  std::vector<Query> q(kStates);
  for (std::size_t k = 0; k < kStates; ++k) {
    q[k].wheel = static_cast<Wheel>(k % 2);
    q[k].state = t.default_state();
  }
  for (const auto& axis : t.axes()) {
    std::uniform_real_distribution<double> d(axis.nodes.front(), axis.nodes.back());
    for (Query& item : q) variable(item.state, axis.name) = d(rng);
  }
  return q;
}

void BM_LookupMillionStatesBatch(benchmark::State& bench) {
  const Table& t = table();
  const std::vector<Query> q = random_states(t);
  std::vector<Result> results(kChunk);
  for (auto _ : bench) {
    for (std::size_t k = 0; k < kStates; k += kChunk) {
      const std::size_t n = std::min(kChunk, kStates - k);
      t.query(std::span<const Query>(q.data() + k, n), std::span<Result>(results.data(), n));
      benchmark::DoNotOptimize(results.data());
    }
  }
  bench.SetItemsProcessed(static_cast<std::int64_t>(bench.iterations() * kStates));
}

BENCHMARK(BM_LookupMillionStatesBatch)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
