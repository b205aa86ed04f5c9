// SPDX-License-Identifier: Apache-2.0
// One strip-wise FASTSIM solve on a central-case-like non-elliptic patch (S1002/UIC60 tread
// contact, about 78 kN): 50 strips, each with its own local ellipse (STRIPES-like: Kalker
// coefficients evaluated per strip), parabolic pressure, combined creepage with spin.
// Target: < 20 us median per solve. Arguments: strips, per-strip spin (0/1), local ellipses (0/1).
#include <benchmark/benchmark.h>

#include <cmath>

#include "tangential/fastsim.hpp"

namespace {

railtab::ContactPatch central_patch(int strips, bool local_ellipses) {
  railtab::ContactPatch p;
  p.point_index = 0;
  p.model = railtab::NormalModel::stripes_a;
  p.pressure_shape = railtab::StripPressure::parabolic;
  p.normal_force = 78.5e3;
  p.contact_angle = -0.035;
  p.rolling_radius = 0.46;
  const double half_width = 8e-3, width = 2 * half_width / strips;
  for (int j = 0; j < strips; ++j) {
    const double y = -half_width + (j + 0.5) * width;
    const double u = y / half_width;
    railtab::Strip s{};
    s.s = y;
    s.width = width;
    s.wheel_u = -y;
    s.rail_u = y;
    s.contact_angle = -0.035 - y / 0.3;  // curved patch (rail crown 300 mm)
    s.rolling_radius = 0.46 - y * std::sin(0.035);
    // Asymmetric, non-elliptic length: longer towards the field side.
    const double half_len = 5.5e-3 * std::sqrt(std::max(0.0, 1 - u * u)) * (1.0 + 0.25 * u);
    s.x_lead = half_len + 0.2e-3 * u;
    s.x_trail = -half_len + 0.2e-3 * u;
    s.pressure_peak = 1.1e9 * (1 - u * u) * (1.0 + 0.2 * u);
    s.ellipse_a = std::max(half_len, 1e-5);
    s.ellipse_b = 6e-3 + 3e-3 * u * u;  // local ellipse differs per strip
    if (!local_ellipses) {                // Hertz-like: one ellipse for all strips
      s.ellipse_a = 5.5e-3;
      s.ellipse_b = 8e-3;
    }
    p.strips.push_back(s);
  }
  return p;
}

void BM_FastsimStripwise(benchmark::State& state) {
  const railtab::ContactPatch patch =
      central_patch(static_cast<int>(state.range(0)), state.range(2) != 0);
  railtab::Material material;
  railtab::FastsimOptions options;
  options.spin = state.range(1) ? railtab::SpinVariation::per_strip
                                : railtab::SpinVariation::patch_constant;
  railtab::FastsimWorkspace ws;
  const railtab::Creepage creepage{1e-3, 1e-3, 0.05};
  for (auto _ : state) {
    const railtab::FastsimResult r =
        railtab::fastsim_patch(patch, {}, creepage, 0.3, 20.0, material, options, ws);
    benchmark::DoNotOptimize(r);
  }
  state.counters["elements"] = ws.elements();
}
BENCHMARK(BM_FastsimStripwise)
    ->Args({50, 0, 1})  // patch-constant spin, local ellipse per strip (the target case)
    ->Args({50, 1, 1})  // per-strip spin
    ->Args({50, 0, 0})  // one ellipse for all strips (Kalker coefficients evaluated once)
    ->Unit(benchmark::kMicrosecond)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);

}  // namespace

BENCHMARK_MAIN();
