// Lookup speed on a table shaped like the default scene: y 41 x xi 7 x eta 7 x phi 5 x 2 slots
// (creep and wear 4-D, geometry and normal on y only). One query = every output of every slot
// of one wheel; a slot query (`Slot` in the name) = every output of one contact (Table::query_slot).
// Target: < 100 ns per single query of one contact (multilinear).
//   ./lookup_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "../tests/lookup/table_fixture.hpp"
#include "railtab/lookup.hpp"

namespace {

using railtab::lookup::Method;
using railtab::lookup::Query;
using railtab::lookup::Result;
using railtab::lookup::Table;
using railtab::lookup::Wheel;

// The table file is written once per process, loaded once per method.
const Table& table(Method method) {
  static const std::string path = "/tmp/railtab_lookup_bench_" + std::to_string(::getpid()) + ".h5";
  static const bool written = [] {
    railtab::lookup::testing::write_fixture(path, railtab::lookup::testing::default_scene_spec());
    return true;
  }();
  (void)written;
  static std::unique_ptr<Table> tables[3];
  auto& t = tables[static_cast<int>(method)];
  if (!t) t = std::make_unique<Table>(Table::load(path, {method}));
  static const bool removed = (std::atexit([] { std::remove(path.c_str()); }), true);
  (void)removed;
  return *t;
}

// Uniformly random states over the whole table: every query a cache-cold cell.
std::vector<Query> random_queries(const Table& t, std::size_t n) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> y(-0.01, 0.01), c(-0.01, 0.01), phi(-1.0, 1.0);
  std::vector<Query> q(n);
  for (std::size_t k = 0; k < n; ++k) {
    q[k].wheel = static_cast<Wheel>(k % 2);
    q[k].state = t.default_state();
    q[k].state.y = y(rng);
    q[k].state.xi = c(rng);
    q[k].state.eta = c(rng);
    q[k].state.phi = phi(rng);
  }
  return q;
}

// Simulation-like: one wheel's state drifting smoothly over time steps (hunting in y, slowly
// varying creepages), so consecutive queries hit the same or neighbouring cells.
std::vector<Query> coherent_queries(const Table& t, std::size_t n) {
  std::vector<Query> q(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double time = 1e-3 * static_cast<double>(k);  // 1 ms steps
    q[k].wheel = Wheel::kLeft;
    q[k].state = t.default_state();
    q[k].state.y = 0.006 * std::sin(2.0 * M_PI * 1.5 * time);
    q[k].state.xi = 0.004 * std::sin(2.0 * M_PI * 0.3 * time);
    q[k].state.eta = 0.005 * std::cos(2.0 * M_PI * 1.5 * time);
    q[k].state.phi = 0.3 * std::sin(2.0 * M_PI * 1.5 * time + 0.5);
  }
  return q;
}

void run_single(benchmark::State& bench, Method method, bool coherent) {
  const Table& t = table(method);
  const auto q = coherent ? coherent_queries(t, 1 << 14) : random_queries(t, 1 << 14);
  Result r;
  std::size_t k = 0;
  for (auto _ : bench) {
    const Query& item = q[k];
    t.query(item.wheel, item.state, r);
    benchmark::DoNotOptimize(r);
    k = (k + 1) & (q.size() - 1);
  }
  bench.SetItemsProcessed(static_cast<std::int64_t>(bench.iterations()));
}

// One contact per query (the tread, slot 0): what a simulation reads for a one-point contact.
void run_slot(benchmark::State& bench, Method method, bool coherent) {
  const Table& t = table(method);
  const auto q = coherent ? coherent_queries(t, 1 << 14) : random_queries(t, 1 << 14);
  railtab::lookup::Contact c;
  std::size_t k = 0;
  for (auto _ : bench) {
    const Query& item = q[k];
    t.query_slot(item.wheel, item.state, 0, c);
    benchmark::DoNotOptimize(c);
    k = (k + 1) & (q.size() - 1);
  }
  bench.SetItemsProcessed(static_cast<std::int64_t>(bench.iterations()));
}

void BM_LookupSlotLinearRandom(benchmark::State& s) { run_slot(s, Method::kLinear, false); }
void BM_LookupSlotLinearCoherent(benchmark::State& s) { run_slot(s, Method::kLinear, true); }

void BM_LookupLinearRandom(benchmark::State& s) { run_single(s, Method::kLinear, false); }
void BM_LookupLinearCoherent(benchmark::State& s) { run_single(s, Method::kLinear, true); }
void BM_LookupCubicRandom(benchmark::State& s) { run_single(s, Method::kCubic, false); }
void BM_LookupMonotoneCubicRandom(benchmark::State& s) { run_single(s, Method::kMonotoneCubic, false); }

// All wheels of a train evaluated together: range(0) wheels per call.
void BM_LookupLinearBatch(benchmark::State& bench) {
  const Table& t = table(Method::kLinear);
  const std::size_t n = static_cast<std::size_t>(bench.range(0));
  const auto pool = random_queries(t, 1 << 14);
  std::vector<Result> results(n);
  std::size_t k = 0;
  for (auto _ : bench) {
    t.query(std::span<const Query>(pool.data() + k, n), results);
    benchmark::DoNotOptimize(results.data());
    k = (k + n) % (pool.size() - n);
  }
  bench.SetItemsProcessed(static_cast<std::int64_t>(bench.iterations() * n));
}

BENCHMARK(BM_LookupSlotLinearRandom);
BENCHMARK(BM_LookupSlotLinearCoherent);
BENCHMARK(BM_LookupLinearRandom);
BENCHMARK(BM_LookupLinearCoherent);
BENCHMARK(BM_LookupCubicRandom);
BENCHMARK(BM_LookupMonotoneCubicRandom);
BENCHMARK(BM_LookupLinearBatch)->Arg(8)->Arg(64);

}  // namespace

BENCHMARK_MAIN();
