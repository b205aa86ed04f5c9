// SPDX-License-Identifier: Apache-2.0
// Rigid contact search of one wheel (S1002 on UIC60 1:40, with the gap band the normal models
// read), across y and roll: the geometry every table point and every direct evaluation pays first.
#include <benchmark/benchmark.h>

#include <cmath>

#include "geometry/contact_geometry.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"

namespace {

void BM_SolveWheel(benchmark::State& state) {
  const auto wheel = railtab::make_s1002_profile();
  const auto rail = railtab::make_uic60_profile();
  const railtab::ContactGeometrySolver solver(wheel, rail, wheel, rail, railtab::TrackGeometry{},
                                              railtab::WheelsetGeometry{});
  const int n = 400;  // y from -8 to 8 mm (tread, two-point and flange contact), small rolls
  int i = 0;
  for (auto _ : state) {
    const double y = -8e-3 + 16e-3 * i / (n - 1);
    const railtab::WheelContactGeometry g =
        solver.solve_wheel(railtab::Side::right, railtab::WheelsetState{y, 1e-3 * std::sin(i)});
    benchmark::DoNotOptimize(g.wheel_drop);
    i = (i + 1) % n;
  }
}
BENCHMARK(BM_SolveWheel)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
