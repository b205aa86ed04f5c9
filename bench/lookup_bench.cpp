// SPDX-License-Identifier: Apache-2.0
// Lookup speed on the default scene's own table (tables/default.toml, the exact half-space model:
// y 65 nodes, non-uniform; load 2; xi, eta and phi 7 nodes each in normalised creep coordinates;
// roll at the equilibrium; 2 slots: creep and wear 5-D, normal over (y, load), geometry over y),
// through the public API (railtab/lookup.hpp).
// One query = every output of every slot of one wheel (Table::query); a slot query (`Slot` in
// the name) = every output of one contact, the tread (Table::query_slot).
//
// The table: $RAILTAB_LOOKUP_BENCH_TABLE if set (any table file, e.g. `railtab generate
// tables/default.toml` made once, or tables/default_stripes.toml's table), else the default scene
// generated here with the generator API (the same bytes as `railtab generate tables/default.toml`;
// about 160 s of CPU, so set the variable when benchmarking repeatedly; the jump benchmarks need
// this in-process table, they read its jumps' positions). Fixture* benchmarks: the synthetic 4-D
// table with uniform axes (tests/lookup/table_fixture.hpp), for comparison with earlier numbers.
// Floor* benchmarks: a plain multilinear kernel over the same table's axes (class Floor below) at
// the same states, the yardstick of the lookup's speed: report lookup / floor from one run.
//   ./lookup_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// CPU time is the benchmark thread's CPU time (Google Benchmark's default).
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "../tests/lookup/table_fixture.hpp"
#include "kernel/contact_kernel.hpp"
#include "adaptive/jump_locator.hpp"
#include "railtab/lookup.hpp"
#include "scene/scene.hpp"
#include "engine/sweep.hpp"
#include "table/table_io.hpp"

namespace {

namespace lk = railtab::lookup;
using lk::Method;
using lk::Query;
using lk::Result;
using lk::Table;
using lk::Wheel;

enum class Source { kDefaultScene, kFixture };

std::string temp_path(const char* what) {
  return (std::filesystem::temp_directory_path() /
          ("railtab_lookup_bench_" + std::to_string(::getpid()) + "_" + what + ".h5"))
      .string();
}

void remove_at_exit(const std::string& path) {
  static std::vector<std::string> paths;
  if (paths.empty())
    std::atexit([] {
      for (const auto& p : paths) std::remove(p.c_str());
    });
  paths.push_back(path);
}

// The y of every contact jump of the generated default table (both wheels, every load).
std::vector<double>& jump_y() {
  static std::vector<double> y;
  return y;
}

// Path of the table file for `source`, written at most once per process.
const std::string& table_path(Source source) {
  static std::map<Source, std::string> paths;
  auto it = paths.find(source);
  if (it != paths.end()) return it->second;
  std::string path;
  if (source == Source::kFixture) {
    path = temp_path("fixture");
    lk::testing::write_fixture(path, lk::testing::scene_sized_spec());
    remove_at_exit(path);
  } else if (const char* env = std::getenv("RAILTAB_LOOKUP_BENCH_TABLE"); env && *env) {
    path = env;
  } else {
    const railtab::Scene scene =
        railtab::load_scene(std::filesystem::path(RAILTAB_SOURCE_DIR) / "tables" / "default.toml");
    railtab::SweepResult r =
        railtab::run_sweep(scene, railtab::make_contact_kernel(scene), railtab::SweepOptions{});
    if (r.summary.failures) throw std::runtime_error("default table: " + r.summary.first_failure);
    const railtab::ContactJumps jumps = railtab::locate_jumps(scene);
    railtab::add_jumps(r.table, scene, jumps);  // as `railtab generate` (format 2.1)
    for (const auto& wheel : jumps.wheel)
      for (const auto& list : wheel)
        for (const railtab::ContactJump& j : list) jump_y().push_back(j.y);
    path = temp_path("default");
    railtab::write_table(r.table, path);
    remove_at_exit(path);
  }
  return paths.emplace(source, path).first->second;
}

// Loaded once per (source, method).
const Table& table(Source source, Method method) {
  static std::map<std::pair<Source, Method>, std::unique_ptr<Table>> tables;
  auto& t = tables[{source, method}];
  if (!t) {
    t = std::make_unique<Table>(Table::load(table_path(source), {method}));
    static bool told = false;
    if (source == Source::kDefaultScene && !told) {
      told = true;
      std::fprintf(stderr, "table: %s (scene '%s', %zu bytes of interpolation data)\n",
                   t->path().c_str(), t->scene_name().c_str(), t->memory_bytes());
    }
  }
  return *t;
}

// Sets state variable `name` of `s` to x.
void set_var(lk::State& s, const std::string& name, double x) {
  if (name == "y") s.y = x;
  else if (name == "roll") s.roll = x;
  else if (name == "load") s.load = x;
  else if (name == "xi") s.xi = x;
  else if (name == "eta") s.eta = x;
  else if (name == "phi") s.phi = x;
}

// Uniformly random states over every tabulated axis's range: every query a cache-cold cell.
std::vector<Query> random_queries(const Table& t, std::size_t n) {
  std::mt19937 rng(1);
  std::vector<Query> q(n);
  for (std::size_t k = 0; k < n; ++k) {
    q[k].wheel = static_cast<Wheel>(k % 2);
    q[k].state = t.default_state();
    for (const lk::AxisInfo& a : t.axes()) {
      std::uniform_real_distribution<double> x(a.nodes.front(), a.nodes.back());
      set_var(q[k].state, a.name, x(rng));
    }
  }
  return q;
}

// Random states as random_queries, kept only when y is farther than 0.6 mm from every jump (no
// cell of the default y grid, at most 0.5 mm wide, that holds a jump: the ordinary path, one flag
// test more than before 2.1) or, with `near`, closer than 0.1 mm to one (the one-sided path).
std::vector<Query> random_queries_by_jumps(const Table& t, std::size_t n, bool near) {
  std::vector<Query> pool = random_queries(t, 16 * n), kept;
  for (const Query& q : pool) {
    double d = 1.0;
    for (double y : jump_y()) d = std::min(d, std::abs(q.state.y - y));
    if ((near && d < 1e-4) || (!near && d > 6e-4)) kept.push_back(q);
    if (kept.size() == n) break;
  }
  if (kept.size() != n) throw std::runtime_error("not enough states for the jump benchmark");
  return kept;
}

// Simulation-like: one wheel's state drifting smoothly over 1 ms time steps (hunting in y at
// 1.5 Hz over 90 % of its range, the other variables at their own frequencies over 60-90 % of
// theirs), so consecutive queries hit the same or neighbouring cells.
std::vector<Query> coherent_queries(const Table& t, std::size_t n) {
  std::vector<Query> q(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double time = 1e-3 * static_cast<double>(k);
    q[k].wheel = Wheel::kLeft;
    q[k].state = t.default_state();
    int j = 0;
    for (const lk::AxisInfo& a : t.axes()) {
      const double mid = 0.5 * (a.nodes.front() + a.nodes.back());
      const double half = 0.5 * (a.nodes.back() - a.nodes.front());
      const double amplitude = (j == 0 ? 0.9 : 0.6 + 0.1 * (j % 4)) * half;
      const double frequency = 1.5 / (1.0 + 0.7 * j);
      set_var(q[k].state, a.name, mid + amplitude * std::sin(2.0 * M_PI * frequency * time + j));
      ++j;
    }
  }
  return q;
}

void run_full(benchmark::State& bench, Source source, Method method, bool coherent) {
  const Table& t = table(source, method);
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

// Table::query_derivatives at the states of run_full: values plus every output's partial
// derivatives (target: at most 2.5x the plain query of the same states, BM_LookupLinearRandom).
void run_derivatives(benchmark::State& bench, Method method, bool coherent) {
  const Table& t = table(Source::kDefaultScene, method);
  const auto q = coherent ? coherent_queries(t, 1 << 14) : random_queries(t, 1 << 14);
  Result r;
  lk::Derivatives d;
  std::size_t k = 0;
  for (auto _ : bench) {
    const Query& item = q[k];
    t.query_derivatives(item.wheel, item.state, r, d);
    benchmark::DoNotOptimize(r);
    benchmark::DoNotOptimize(d);
    k = (k + 1) & (q.size() - 1);
  }
  bench.SetItemsProcessed(static_cast<std::int64_t>(bench.iterations()));
}

// One contact per query (the tread, slot 0): what a simulation reads for a one-point contact.
void run_slot(benchmark::State& bench, Source source, Method method, bool coherent) {
  const Table& t = table(source, method);
  const auto q = coherent ? coherent_queries(t, 1 << 14) : random_queries(t, 1 << 14);
  lk::Contact c;
  std::size_t k = 0;
  for (auto _ : bench) {
    const Query& item = q[k];
    t.query_slot(item.wheel, item.state, 0, c);
    benchmark::DoNotOptimize(c);
    k = (k + 1) & (q.size() - 1);
  }
  bench.SetItemsProcessed(static_cast<std::int64_t>(bench.iterations()));
}

// Table::query_slot_derivatives of the tread (slot 0) at the states of run_slot: one contact's
// values and partial derivatives (report against BM_LookupSlot*, the plain one-slot query).
void run_slot_derivatives(benchmark::State& bench, Method method, bool coherent) {
  const Table& t = table(Source::kDefaultScene, method);
  const auto q = coherent ? coherent_queries(t, 1 << 14) : random_queries(t, 1 << 14);
  lk::Contact c;
  lk::SlotDerivatives d;
  std::size_t k = 0;
  for (auto _ : bench) {
    const Query& item = q[k];
    t.query_slot_derivatives(item.wheel, item.state, 0, c, d);
    benchmark::DoNotOptimize(c);
    benchmark::DoNotOptimize(d);
    k = (k + 1) & (q.size() - 1);
  }
  bench.SetItemsProcessed(static_cast<std::int64_t>(bench.iterations()));
}

// One contact, random states away from / near the contact jumps (random_queries_by_jumps).
void run_slot_jumps(benchmark::State& bench, bool near) {
  const Table& t = table(Source::kDefaultScene, Method::kLinear);
  if (jump_y().empty()) {
    bench.SkipWithError("jump benchmarks need the in-process default table (no RAILTAB_LOOKUP_BENCH_TABLE)");
    return;
  }
  const auto q = random_queries_by_jumps(t, 1 << 12, near);
  lk::Contact c;
  std::size_t k = 0;
  for (auto _ : bench) {
    const Query& item = q[k];
    t.query_slot(item.wheel, item.state, 0, c);
    benchmark::DoNotOptimize(c);
    k = (k + 1) & (q.size() - 1);
  }
  bench.SetItemsProcessed(static_cast<std::int64_t>(bench.iterations()));
}

// The floor (a plain multilinear kernel the lookup is measured against): the default table's own
// axes and node vectors (t.axes(): y, load, xi, eta, phi), one record of 8 doubles per node (made-up
// values), one grid per (wheel, slot); per query and slot a binary search on every axis
// (std::upper_bound), the 2^D corner records gathered, then reduced one axis at a time (last axis
// first, 2^D -> 2^(D-1) -> .. -> 1). No statuses, no scales, no jumps: what interpolating the same
// grid costs with nothing else. The states are the lookup benchmarks' own (coherent_queries,
// random_queries), so lookup / floor is a fair ratio when both run in one process.
class Floor {
 public:
  static constexpr int kOut = 8;
  explicit Floor(const Table& t) {
    for (const lk::AxisInfo& a : t.axes()) {
      axes_.push_back(a.nodes);
      var_.push_back(a.name);
    }
    std::size_t nodes = 1;
    for (const auto& a : axes_) nodes *= a.size();
    stride_.assign(axes_.size(), 0);
    std::size_t st = kOut;
    for (std::size_t k = axes_.size(); k-- > 0;) {
      stride_[k] = st;
      st *= axes_[k].size();
    }
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (auto& wheel : grid_)
      for (auto& slot : wheel) {
        slot.resize(nodes * kOut);
        for (double& x : slot) x = u(rng);
      }
  }

  // One slot of one wheel: the 8 outputs at `state`.
  void query_slot(Wheel wheel, const lk::State& state, int slot, double* out) const noexcept {
    const int n = static_cast<int>(axes_.size());
    double t[8];
    std::size_t base = 0;
    for (int k = 0; k < n; ++k) {
      const std::vector<double>& x = axes_[static_cast<std::size_t>(k)];
      const double v = std::min(std::max(value(state, k), x.front()), x.back());
      const std::size_t i =
          static_cast<std::size_t>(std::upper_bound(x.data() + 1, x.data() + x.size() - 1, v) - x.data()) - 1;
      t[k] = (v - x[i]) / (x[i + 1] - x[i]);
      base += i * stride_[static_cast<std::size_t>(k)];
    }
    const double* g = grid_[static_cast<int>(wheel)][slot].data() + base;
    double c[32][kOut];  // 2^n corners, corner bit k = dimension n - 1 - k
    const int corners = 1 << n;
    for (int m = 0; m < corners; ++m) {
      std::size_t off = 0;
      for (int k = 0; k < n; ++k)
        if (m >> (n - 1 - k) & 1) off += stride_[static_cast<std::size_t>(k)];
      for (int o = 0; o < kOut; ++o) c[m][o] = g[off + o];
    }
    for (int k = n - 1, half = corners / 2; k >= 0; --k, half /= 2)
      for (int m = 0; m < half; ++m)
        for (int o = 0; o < kOut; ++o) c[m][o] = c[2 * m][o] + t[k] * (c[2 * m + 1][o] - c[2 * m][o]);
    for (int o = 0; o < kOut; ++o) out[o] = c[0][o];
  }

  int dims() const noexcept { return static_cast<int>(axes_.size()); }

 private:
  double value(const lk::State& s, int k) const noexcept {
    const std::string& name = var_[static_cast<std::size_t>(k)];
    return name == "y" ? s.y : name == "roll" ? s.roll : name == "load" ? s.load
         : name == "xi" ? s.xi : name == "eta" ? s.eta : s.phi;
  }
  std::vector<std::vector<double>> axes_;
  std::vector<std::string> var_;
  std::vector<std::size_t> stride_;     // doubles between neighbouring nodes per axis
  std::vector<double> grid_[2][2];      // [wheel][slot], nodes in C order x 8 doubles
};

// `slots` slots per query (1: the tread, as run_slot; 2: both, as run_full).
void run_floor(benchmark::State& bench, bool coherent, int slots) {
  const Table& t = table(Source::kDefaultScene, Method::kLinear);
  static const Floor floor(t);
  if (floor.dims() > 5) {
    bench.SkipWithError("the floor handles at most 5 axes");
    return;
  }
  const auto q = coherent ? coherent_queries(t, 1 << 14) : random_queries(t, 1 << 14);
  double out[2][Floor::kOut];
  std::size_t k = 0;
  for (auto _ : bench) {
    const Query& item = q[k];
    for (int s = 0; s < slots; ++s) floor.query_slot(item.wheel, item.state, s, out[s]);
    benchmark::DoNotOptimize(out);
    k = (k + 1) & (q.size() - 1);
  }
  bench.SetItemsProcessed(static_cast<std::int64_t>(bench.iterations()));
}

constexpr Source kDefault = Source::kDefaultScene;
void BM_LookupSlotLinearRandomAwayFromJumps(benchmark::State& s) { run_slot_jumps(s, false); }
void BM_LookupSlotLinearRandomNearJumps(benchmark::State& s) { run_slot_jumps(s, true); }
void BM_LookupSlotLinearRandom(benchmark::State& s) { run_slot(s, kDefault, Method::kLinear, false); }
void BM_LookupSlotLinearCoherent(benchmark::State& s) { run_slot(s, kDefault, Method::kLinear, true); }
void BM_LookupLinearRandom(benchmark::State& s) { run_full(s, kDefault, Method::kLinear, false); }
void BM_LookupLinearCoherent(benchmark::State& s) { run_full(s, kDefault, Method::kLinear, true); }
void BM_LookupDerivativesLinearRandom(benchmark::State& s) { run_derivatives(s, Method::kLinear, false); }
void BM_LookupDerivativesLinearCoherent(benchmark::State& s) { run_derivatives(s, Method::kLinear, true); }
void BM_LookupDerivativesCubicRandom(benchmark::State& s) { run_derivatives(s, Method::kCubic, false); }
void BM_LookupDerivativesCubicCoherent(benchmark::State& s) { run_derivatives(s, Method::kCubic, true); }
void BM_LookupSlotDerivativesLinearRandom(benchmark::State& s) { run_slot_derivatives(s, Method::kLinear, false); }
void BM_LookupSlotDerivativesLinearCoherent(benchmark::State& s) { run_slot_derivatives(s, Method::kLinear, true); }
void BM_LookupSlotDerivativesCubicRandom(benchmark::State& s) { run_slot_derivatives(s, Method::kCubic, false); }
void BM_LookupSlotCubicRandom(benchmark::State& s) { run_slot(s, kDefault, Method::kCubic, false); }
void BM_LookupCubicRandom(benchmark::State& s) { run_full(s, kDefault, Method::kCubic, false); }
void BM_LookupCubicCoherent(benchmark::State& s) { run_full(s, kDefault, Method::kCubic, true); }
void BM_FloorSlotRandom(benchmark::State& s) { run_floor(s, false, 1); }
void BM_FloorSlotCoherent(benchmark::State& s) { run_floor(s, true, 1); }
void BM_FloorRandom(benchmark::State& s) { run_floor(s, false, 2); }
void BM_FloorCoherent(benchmark::State& s) { run_floor(s, true, 2); }
void BM_LookupMonotoneCubicRandom(benchmark::State& s) {
  run_full(s, kDefault, Method::kMonotoneCubic, false);
}

// All wheels of a train evaluated together: range(0) wheels per call.
void BM_LookupLinearBatch(benchmark::State& bench) {
  const Table& t = table(kDefault, Method::kLinear);
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

// The synthetic 4-D fixture with uniform axes (the numbers docs/lookup.md quoted before).
void BM_FixtureSlotLinearRandom(benchmark::State& s) {
  run_slot(s, Source::kFixture, Method::kLinear, false);
}
void BM_FixtureLinearRandom(benchmark::State& s) {
  run_full(s, Source::kFixture, Method::kLinear, false);
}

BENCHMARK(BM_FloorSlotRandom);
BENCHMARK(BM_FloorSlotCoherent);
BENCHMARK(BM_FloorRandom);
BENCHMARK(BM_FloorCoherent);
BENCHMARK(BM_LookupSlotLinearRandom);
BENCHMARK(BM_LookupSlotLinearCoherent);
BENCHMARK(BM_LookupSlotLinearRandomAwayFromJumps);
BENCHMARK(BM_LookupSlotLinearRandomNearJumps);
BENCHMARK(BM_LookupLinearRandom);
BENCHMARK(BM_LookupLinearCoherent);
BENCHMARK(BM_LookupDerivativesLinearRandom);
BENCHMARK(BM_LookupDerivativesLinearCoherent);
BENCHMARK(BM_LookupSlotCubicRandom);
BENCHMARK(BM_LookupCubicRandom);
BENCHMARK(BM_LookupCubicCoherent);
BENCHMARK(BM_LookupDerivativesCubicRandom);
BENCHMARK(BM_LookupDerivativesCubicCoherent);
BENCHMARK(BM_LookupSlotDerivativesLinearRandom);
BENCHMARK(BM_LookupSlotDerivativesLinearCoherent);
BENCHMARK(BM_LookupSlotDerivativesCubicRandom);
BENCHMARK(BM_LookupMonotoneCubicRandom);
BENCHMARK(BM_LookupLinearBatch)->Arg(8)->Arg(64);
BENCHMARK(BM_FixtureSlotLinearRandom);
BENCHMARK(BM_FixtureLinearRandom);

}  // namespace

BENCHMARK_MAIN();
