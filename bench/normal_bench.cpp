// SPDX-License-Identifier: Apache-2.0
// One load-controlled normal solve per model on the Sichani et al. 2014 central case (S1002 on UIC60 1:40,
// right wheel, y = 0, 78.5 kN). The geometry is solved once outside the timed loop.
// Targets: STRIPES < 20 us per solve (~50 strips), Hertz < 1 us. Every solve includes the patch
// grouping and the reference point of each patch (normal_model.hpp: CONTACT-style for the overlap
// runs; Hertz: the contact point of one ellipse, the centre of force of several). The central case
// has two rigid points in one overlap run (Hertz/Linder weight them: run weights; STRIPES builds
// one strip set over the run). The result is reused across solves.
#include <benchmark/benchmark.h>

#include "geometry/contact_geometry.hpp"
#include "normal/normal_model.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"

namespace {

const railtab::WheelContactGeometry& central_geometry() {
  static const railtab::WheelContactGeometry g = [] {
    const auto wheel = railtab::make_s1002_profile();
    const auto rail = railtab::make_uic60_profile();
    const railtab::ContactGeometrySolver solver(wheel, rail, wheel, rail, railtab::TrackGeometry{},
                                                railtab::WheelsetGeometry{});
    return solver.solve_wheel(railtab::Side::right, railtab::WheelsetState{0.0, 0.0});
  }();
  return g;
}

void BM_NormalSolve(benchmark::State& state, railtab::NormalModel model,
                    railtab::StripesClosure closure = railtab::StripesClosure::boussinesq) {
  const auto& g = central_geometry();
  railtab::NormalOptions o;
  o.model = model;
  o.stripes_closure = closure;
  const railtab::Material steel{210e9, 0.28};
  int iterations = 0;
  // One result reused across solves, as a table sweep does (solve_normal_for_load with `out`).
  railtab::WheelNormalResult r;
  for (auto _ : state) {
    railtab::solve_normal_for_load(g, 78.5e3, steel, o, r);
    iterations = r.iterations;
    benchmark::DoNotOptimize(r);
  }
  state.counters["load_iterations"] = iterations;
}

BENCHMARK_CAPTURE(BM_NormalSolve, hertz, railtab::NormalModel::hertz);
BENCHMARK_CAPTURE(BM_NormalSolve, linder, railtab::NormalModel::linder);
BENCHMARK_CAPTURE(BM_NormalSolve, kik_piotrowski, railtab::NormalModel::kik_piotrowski);
BENCHMARK_CAPTURE(BM_NormalSolve, stripes_a, railtab::NormalModel::stripes_a);
BENCHMARK_CAPTURE(BM_NormalSolve, stripes_ab, railtab::NormalModel::stripes_ab);
BENCHMARK_CAPTURE(BM_NormalSolve, stripes_a_hertz_peak, railtab::NormalModel::stripes_a,
                  railtab::StripesClosure::hertz_peak);
BENCHMARK_CAPTURE(BM_NormalSolve, stripes_ab_hertz_peak, railtab::NormalModel::stripes_ab,
                  railtab::StripesClosure::hertz_peak);

}  // namespace

BENCHMARK_MAIN();
