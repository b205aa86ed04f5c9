// SPDX-License-Identifier: Apache-2.0
// What a table lookup saves: the direct model evaluation of one contact state against the lookup
// of the same state, in one run (the issue asks for lookup >= 10,000x faster than the models).
//   BM_DirectStripesFastsim: Sichani et al. 2014 central case (S1002 on UIC60 1:40, right wheel, y = 0,
//     78.5 kN), load-controlled STRIPES (default NormalOptions: stripes_ab, 50 strips) and then
//     strip-wise FASTSIM on the loaded tread patch at xi = eta = 1e-3, phi = 0.05 rad/m, mu 0.3,
//     20 m/s. The rigid geometry is solved once outside the timed loop.
//   BM_DirectGeometryStripesFastsim: the same plus the rigid contact search of the state
//     (ContactGeometrySolver::solve_wheel), which a table replaces too.
//   BM_LookupSlotCentralState: Table::query_slot of the same state (slot 0 = tread, all its
//     outputs) on a fixture table of a scene's size (y 41 x xi 7 x eta 7 x phi 5, 2 slots).
// ratio = median(BM_DirectStripesFastsim) / median(BM_LookupSlotCentralState).
//   ./lookup_direct_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "../tests/lookup/table_fixture.hpp"
#include "geometry/contact_geometry.hpp"
#include "normal/normal_model.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"
#include "railtab/lookup.hpp"
#include "tangential/fastsim.hpp"

namespace {

constexpr double kLoad = 78.5e3;                               // N
const railtab::Creepage kCreepage{1e-3, 1e-3, 0.05};          // xi, eta, phi [rad/m]

const railtab::ContactGeometrySolver& central_solver() {
  static const railtab::ContactGeometrySolver solver = [] {
    const auto wheel = railtab::make_s1002_profile();
    const auto rail = railtab::make_uic60_profile();
    return railtab::ContactGeometrySolver(wheel, rail, wheel, rail, railtab::TrackGeometry{},
                                          railtab::WheelsetGeometry{});
  }();
  return solver;
}

// with_geometry: also the rigid contact search of the state inside the loop (what the table's
// geometry part replaces), not only the normal + tangential solves.
void run_direct(benchmark::State& state, bool with_geometry) {
  const railtab::WheelContactGeometry g0 =
      central_solver().solve_wheel(railtab::Side::right, railtab::WheelsetState{0.0, 0.0});
  const railtab::Material steel{210e9, 0.28};
  const railtab::NormalOptions normal_options;  // stripes_ab, 50 strips
  const railtab::FastsimOptions fastsim_options;
  railtab::FastsimWorkspace ws;
  double fx = 0.0;
  for (auto _ : state) {
    railtab::WheelContactGeometry solved;
    if (with_geometry)
      solved = central_solver().solve_wheel(railtab::Side::right, railtab::WheelsetState{0.0, 0.0});
    const railtab::WheelContactGeometry& g = with_geometry ? solved : g0;
    const railtab::WheelNormalResult n =
        railtab::solve_normal_for_load(g, kLoad, steel, normal_options);
    if (n.patches.empty()) {
      state.SkipWithError("no loaded patch in the central case");
      break;
    }
    const auto tread = std::max_element(
        n.patches.begin(), n.patches.end(),
        [](const auto& a, const auto& b) { return a.normal_force < b.normal_force; });
    const railtab::FastsimResult f =
        railtab::fastsim_patch(*tread, railtab::placement_of(g, *tread), kCreepage, 0.3, 20.0,
                               steel, fastsim_options, ws);
    fx = f.fx;
    benchmark::DoNotOptimize(f);
  }
  state.counters["fx_N"] = fx;
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
void BM_DirectStripesFastsim(benchmark::State& s) { run_direct(s, false); }
void BM_DirectGeometryStripesFastsim(benchmark::State& s) { run_direct(s, true); }
BENCHMARK(BM_DirectStripesFastsim)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DirectGeometryStripesFastsim)->Unit(benchmark::kMicrosecond);

const railtab::lookup::Table& scene_sized_table() {
  static const std::string path =
      "/tmp/railtab_lookup_direct_bench_" + std::to_string(::getpid()) + ".h5";
  static const railtab::lookup::Table table = [] {
    railtab::lookup::testing::write_fixture(path, railtab::lookup::testing::scene_sized_spec());
    std::atexit([] { std::remove(path.c_str()); });
    return railtab::lookup::Table::load(path);
  }();
  return table;
}

void BM_LookupSlotCentralState(benchmark::State& state) {
  const auto& t = scene_sized_table();
  railtab::lookup::State s = t.default_state();  // load 78.5 kN, roll 0
  s.y = 0.0;
  s.xi = kCreepage.xi;
  s.eta = kCreepage.eta;
  s.phi = kCreepage.phi;
  railtab::lookup::Contact c;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s);
    t.query_slot(railtab::lookup::Wheel::kRight, s, 0, c);
    benchmark::DoNotOptimize(c);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_LookupSlotCentralState);

}  // namespace

BENCHMARK_MAIN();
