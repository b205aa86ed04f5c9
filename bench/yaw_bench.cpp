// SPDX-License-Identifier: Apache-2.0
// Cost of a yaw axis (format 2.4): the STRIPES scene (tables/default_stripes.toml) as it is and with a
// 5-node yaw axis [grid] yaw = [-0.01, -0.005, 0, 0.005, 0.01] (rad), the rest unchanged. The list
// is symmetric, so the table stores 0, 0.005, 0.01 and the lookup reads |yaw| (yaw_symmetry).
// Targets (docs/validation/yaw-tables.md): generation time and table size at most 5x, a lookup
// at most 1.3x the yaw-free table's.
//   BM_Sweep/0, /1            the table sweep (run_sweep: geometry, normal, creep and wear of
//                             every node, both wheels), process CPU time; counter `bytes`: the
//                             table file written by write_table (no contact jumps, no error map:
//                             both tables the same way)
//   BM_Lookup/0, /1           Table::query, one wheel, every output of every slot, at random
//                             states over the table's ranges (yaw too for /1), thread CPU time
//   BM_LookupGeneric/0        the yaw-free table without its fast path (RAILTAB_LOOKUP_NO_FAST_PATH
//                             at load): the generic query the yaw table takes, one axis fewer
//   BM_LookupCoherent/0, /1   as BM_Lookup along a smooth path through the same ranges (a
//                             simulation's consecutive states: neighbouring cells, warm caches)
//   BM_LookupCurving/yaw:Y/coherent:C   as BM_Lookup (C = 0) and BM_LookupCoherent (C = 1) on
//                             the curving scene's own table (tables/curving_r600.toml, yaw +-2 mrad
//                             in 5 nodes, stored 0, 1, 2 mrad) with (Y = 1) and without (Y = 0) its yaw axis
// Run: cmake --build --preset release --target yaw_bench &&
//   build/release/bench/yaw_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// RAILTAB_YAW_BENCH_TABLES=<dir>: the lookup benchmarks keep their four table files in <dir>
// (written by the first run, read by the later ones; delete them after a generator change), so
// that alternated runs of two builds skip the sweeps (about 30 s of CPU per run) and read the
// same tables. BM_Sweep sweeps and measures as always.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "engine/sweep.hpp"
#include "kernel/contact_kernel.hpp"
#include "railtab/lookup.hpp"
#include "scene/scene.hpp"
#include "table/table_io.hpp"

namespace {

namespace lk = railtab::lookup;

// The scenes: the STRIPES one (tables/default_stripes.toml) with the 5-node yaw axis when `yaw`; the
// curving one (tables/curving_r600.toml, yaw +-2 mrad in 5 nodes) as it is when `yaw`, else
// without its yaw line.
enum Which { kStripes = 0, kCurving = 1 };

railtab::Scene scene(bool yaw, Which which = kStripes) {
  const char* file = which == kStripes ? "default_stripes.toml" : "curving_r600.toml";
  std::ifstream in(std::filesystem::path(RAILTAB_SOURCE_DIR) / "tables" / file);
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  if (which == kStripes && yaw) s.insert(s.find("equilibrium_roll = true"), "yaw = [-0.01, -0.005, 0.0, 0.005, 0.01]\n");
  if (which == kCurving && !yaw) s.erase(s.find("yaw = ["), s.find('\n', s.find("yaw = [")) + 1 - s.find("yaw = ["));
  return railtab::parse_scene(s, std::string(file) + (yaw ? " with yaw" : " without yaw"),
                              std::filesystem::path(RAILTAB_SOURCE_DIR) / "tables");
}

std::string table_name(bool yaw, Which which) {
  return std::string(which == kStripes ? "stripes" : "curving") + (yaw ? "_yaw" : "_free") + ".h5";
}

std::string temp_path(bool yaw, Which which) {
  return (std::filesystem::temp_directory_path() /
          ("railtab_yaw_bench_" + std::to_string(::getpid()) + "_" + table_name(yaw, which)))
      .string();
}

// The kept table file of a scene ($RAILTAB_YAW_BENCH_TABLES), or "" when not asked for.
std::string kept_path(bool yaw, Which which) {
  const char* dir = std::getenv("RAILTAB_YAW_BENCH_TABLES");
  if (!dir || !*dir) return "";
  return (std::filesystem::path(dir) / table_name(yaw, which)).string();
}

// The table file of each scene, swept and written once per process (or read from the kept
// ones); its size [B].
const std::string& table_file(bool yaw, std::uintmax_t* bytes = nullptr, Which which = kStripes) {
  static std::string paths[2][2];
  static std::uintmax_t sizes[2][2] = {};
  std::string& path = paths[which][yaw];
  if (path.empty()) {
    const std::string kept = kept_path(yaw, which);
    if (!kept.empty() && std::filesystem::exists(kept)) {
      path = kept;
    } else {
      const railtab::Scene sc = scene(yaw, which);
      railtab::SweepResult r = railtab::run_sweep(sc, railtab::make_contact_kernel(sc), railtab::SweepOptions{});
      path = kept.empty() ? temp_path(yaw, which) : kept;
      railtab::write_table(r.table, path);
      static bool registered = false;
      if (kept.empty() && !registered) {  // temporary files only
        registered = true;
        std::atexit([] {
          for (const auto& pair : paths)
            for (const std::string& p : pair)
              if (!p.empty()) std::filesystem::remove(p);
        });
      }
    }
    sizes[which][yaw] = std::filesystem::file_size(path);
  }
  if (bytes) *bytes = sizes[which][yaw];
  return path;
}

void BM_Sweep(benchmark::State& st) {
  const bool yaw = st.range(0) != 0;
  const railtab::Scene sc = scene(yaw);
  const railtab::SweepKernel kernel = railtab::make_contact_kernel(sc);
  std::size_t points = 0;
  for (auto _ : st) {
    railtab::SweepResult r = railtab::run_sweep(sc, kernel, railtab::SweepOptions{});
    points = r.summary.points_total;
    benchmark::DoNotOptimize(r.table.groups.data());
  }
  std::uintmax_t bytes = 0;
  table_file(yaw, &bytes);
  st.counters["bytes"] = static_cast<double>(bytes);
  st.counters["points"] = static_cast<double>(points);
}
BENCHMARK(BM_Sweep)->Arg(0)->Arg(1)->Iterations(1)->MeasureProcessCPUTime()->Unit(benchmark::kSecond);

// 4096 random states over the table's ranges (yaw over its axis for the yaw table, 0 otherwise),
// wheels alternating.
std::vector<lk::Query> states(const lk::Table& t, bool yaw) {
  std::mt19937_64 rng(20261129);
  std::vector<lk::Query> q(4096);
  for (std::size_t k = 0; k < q.size(); ++k) {
    lk::State s = t.default_state();
    for (const lk::AxisInfo& a : t.axes()) {
      std::uniform_real_distribution<double> x(a.nodes.front(), a.nodes.back());
      if (a.name == "y") s.y = x(rng);
      if (a.name == "load") s.load = x(rng);
      if (a.name == "xi") s.xi = x(rng);
      if (a.name == "eta") s.eta = x(rng);
      if (a.name == "phi") s.phi = x(rng);
      if (a.name == "yaw" && yaw) s.yaw = x(rng);
    }
    q[k] = {static_cast<lk::Wheel>(k % 2), s};
  }
  return q;
}

// 4096 states along a smooth path through the table's ranges (periods of hundreds of states, as a
// simulation's wheelset moving over 1 ms steps), wheels alternating.
std::vector<lk::Query> path_states(const lk::Table& t, bool yaw) {
  std::vector<lk::Query> q(4096);
  for (std::size_t k = 0; k < q.size(); ++k) {
    lk::State s = t.default_state();
    const double u = 2.0 * M_PI * static_cast<double>(k / 2) / 2048.0;
    for (const lk::AxisInfo& a : t.axes()) {
      const double mid = 0.5 * (a.nodes.front() + a.nodes.back()), half = 0.45 * (a.nodes.back() - a.nodes.front());
      if (a.name == "y") s.y = mid + half * std::sin(3.0 * u);
      if (a.name == "load") s.load = mid + half * std::sin(5.0 * u + 1.0);
      if (a.name == "xi") s.xi = 0.3 * half * std::sin(7.0 * u + 2.0);
      if (a.name == "eta") s.eta = 0.3 * half * std::sin(11.0 * u + 3.0);
      if (a.name == "phi") s.phi = 0.3 * half * std::sin(13.0 * u + 4.0);
      if (a.name == "yaw" && yaw) s.yaw = mid + half * std::sin(2.0 * u + 5.0);
    }
    q[k] = {static_cast<lk::Wheel>(k % 2), s};
  }
  return q;
}

void run_lookup(benchmark::State& st, const lk::Table& t, bool yaw, bool coherent = false) {
  const std::vector<lk::Query> q = coherent ? path_states(t, yaw) : states(t, yaw);
  lk::Result r;
  std::size_t k = 0;
  for (auto _ : st) {
    t.query(q[k].wheel, q[k].state, r);
    benchmark::DoNotOptimize(r.contact[0].value[0]);
    k = (k + 1) & (q.size() - 1);
  }
  st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations()));
}

void BM_Lookup(benchmark::State& st) {
  const bool yaw = st.range(0) != 0;
  static std::unique_ptr<lk::Table> tables[2];
  if (!tables[yaw]) tables[yaw] = std::make_unique<lk::Table>(lk::Table::load(table_file(yaw)));
  run_lookup(st, *tables[yaw], yaw);
}
BENCHMARK(BM_Lookup)->Arg(0)->Arg(1);

void BM_LookupCoherent(benchmark::State& st) {
  const bool yaw = st.range(0) != 0;
  static std::unique_ptr<lk::Table> tables[2];
  if (!tables[yaw]) tables[yaw] = std::make_unique<lk::Table>(lk::Table::load(table_file(yaw)));
  run_lookup(st, *tables[yaw], yaw, true);
}
BENCHMARK(BM_LookupCoherent)->Arg(0)->Arg(1);

// The curving scene's own table with and without its yaw axis (swept at the first run: 14 + 5 s CPU).
void BM_LookupCurving(benchmark::State& st) {
  const bool yaw = st.range(0) != 0, coherent = st.range(1) != 0;
  static std::unique_ptr<lk::Table> tables[2];
  if (!tables[yaw]) tables[yaw] = std::make_unique<lk::Table>(lk::Table::load(table_file(yaw, nullptr, kCurving)));
  run_lookup(st, *tables[yaw], yaw, coherent);
}
BENCHMARK(BM_LookupCurving)->ArgNames({"yaw", "coherent"})->Args({0, 0})->Args({1, 0})->Args({0, 1})->Args({1, 1});

void BM_LookupGeneric(benchmark::State& st) {
  static std::unique_ptr<lk::Table> table;
  if (!table) {
    ::setenv("RAILTAB_LOOKUP_NO_FAST_PATH", "1", 1);  // read at load
    table = std::make_unique<lk::Table>(lk::Table::load(table_file(false)));
    ::unsetenv("RAILTAB_LOOKUP_NO_FAST_PATH");
  }
  run_lookup(st, *table, false);
}
BENCHMARK(BM_LookupGeneric)->Arg(0);

}  // namespace

BENCHMARK_MAIN();
