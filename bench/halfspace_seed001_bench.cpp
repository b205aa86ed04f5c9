// SPDX-License-Identifier: Apache-2.0
// Seed 001 (Enblom & Berg, Wear 265 (2008)) Tables 2 and 3 computed by railtab: contact area and
// maximum pressure of the elliptic (Hertz), exact half-space and STRIPES (A&B) models beside the
// paper's elliptic / CONTACT / STRIPES columns. Right wheel S1002 on UIC60, no roll, no yaw;
// the paper's lateral displacement dy > 0 moves the flange towards the gauge corner, our track
// y = -dy (docs/validation/normal.md). E = 210 GPa, nu = 0.28 (the CONTACT set-up of this
// project's reference runs). Area: sum over the patches (half-space: elements in contact, as
// CONTACT counts them); maximum pressure: over the patches.
//   Table 2: UIC60 1:40, 90 kN, dy = -3 (field side), 0 (neutral), +5 mm (gauge corner).
//   Table 3: UIC60 1:30, curving cases Tangent / R600 / R400 / R300 at 78 / 99 / 98 / 101 kN and
//            dy = 0 / 5.9 / 6.3 / 6.5 mm (the paper's R300 elliptic area is of two contacts).
// Run: build/release/bench/halfspace_seed001_bench prints the Markdown table (then runs the
// timing benchmarks selected with --benchmark_filter, if any: BM_Seed001Halfspace/<case>).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "core/status.hpp"
#include "geometry/contact_geometry.hpp"
#include "halfspace/wheel_rail.hpp"
#include "normal/normal_model.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"

namespace {

struct SeedCase {
  const char* table;
  const char* name;
  double inclination;  // tan of the rail cant [-]
  double dy_mm;        // the paper's displacement, + towards the gauge corner [mm]
  double load_kn;      // vertical wheel load [kN]
  double paper[6];     // area elliptic / CONTACT / STRIPES [mm2], p_max the same [MPa]
  const char* note;
};

const SeedCase kCases[] = {
    {"2", "field side", 1.0 / 40, -3.0, 90, {129, 151, 149, 1049, 934, 1202}, ""},
    {"2", "neutral", 1.0 / 40, 0.0, 90, {167, 210, 196, 806, 849, 784}, ""},
    {"2", "gauge corner", 1.0 / 40, 5.0, 90, {145, 122, 137, 929, 2327, 1539}, ""},
    {"3", "Tangent", 1.0 / 30, 0.0, 78, {135, 130, 125, 867, 929, 1229}, ""},
    {"3", "R600", 1.0 / 30, 5.9, 99, {74, 51, 70, 1994, 3242, 2995}, ""},
    {"3", "R400", 1.0 / 30, 6.3, 98, {72, 59, 84, 2038, 2694, 2417}, ""},
    {"3", "R300", 1.0 / 30, 6.5, 101, {77, 77, 155, 2132, 3114, 1782}, "paper elliptic: two contacts"},
};

railtab::Material seed_material() {
  railtab::Material m;
  m.youngs_modulus = 210e9;
  m.poisson_ratio = 0.28;
  return m;
}

railtab::WheelContactGeometry geometry_of(const SeedCase& c) {
  railtab::ProfilePtr w = railtab::make_s1002_profile();
  railtab::ProfilePtr r = railtab::make_uic60_profile();
  railtab::TrackGeometry track;
  track.rail_inclination = c.inclination;
  const railtab::ContactGeometrySolver solver(w, r, w, r, track, railtab::WheelsetGeometry{});
  return solver.solve_wheel(railtab::Side::right, {-c.dy_mm * 1e-3, 0.0});
}

struct AreaPressure {
  double area_mm2 = 0.0, pmax_mpa = 0.0;
  int patches = 0;
  std::string status;
};

AreaPressure fast_model(const railtab::WheelContactGeometry& g, double load,
                        railtab::NormalModel model) {
  railtab::NormalOptions o;
  o.model = model;
  const railtab::WheelNormalResult r = railtab::solve_normal_for_load(g, load, seed_material(), o);
  AreaPressure out;
  for (const auto& p : r.patches) {
    if (!(p.normal_force > 0.0)) continue;
    out.area_mm2 += p.area * 1e6;
    out.pmax_mpa = std::max(out.pmax_mpa, p.max_pressure * 1e-6);
    ++out.patches;
  }
  out.status = railtab::status::describe(r.status);
  return out;
}

AreaPressure halfspace_model(const railtab::WheelContactGeometry& g, double load,
                             railtab::halfspace::Workspace& ws) {
  const railtab::halfspace::WheelHalfspaceResult r = railtab::halfspace::solve_halfspace_for_load(
      g, load, seed_material(), railtab::halfspace::HalfspaceOptions{}, ws);
  AreaPressure out;
  for (const auto& p : r.patches) {
    if (!(p.normal.normal_force > 0.0)) continue;
    out.area_mm2 += p.normal.area * 1e6;
    out.pmax_mpa = std::max(out.pmax_mpa, p.normal.max_pressure * 1e-6);
    ++out.patches;
  }
  out.status = railtab::status::describe(r.status);
  return out;
}

void print_table() {
  std::printf(
      "| table | case | rail | dy [mm] | load [kN] | area elliptic: paper / railtab hertz [mm2] | "
      "area CONTACT paper / railtab half-space [mm2] | area STRIPES: paper / railtab stripes-ab "
      "[mm2] | p_max elliptic: paper / railtab [MPa] | p_max CONTACT paper / half-space [MPa] | "
      "p_max STRIPES: paper / railtab [MPa] | patches hertz / half-space / stripes | half-space "
      "status |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  railtab::halfspace::Workspace ws;
  for (const SeedCase& c : kCases) {
    const railtab::WheelContactGeometry g = geometry_of(c);
    const double load = c.load_kn * 1e3;
    const AreaPressure hz = fast_model(g, load, railtab::NormalModel::hertz);
    const AreaPressure hs = halfspace_model(g, load, ws);
    const AreaPressure st = fast_model(g, load, railtab::NormalModel::stripes_ab);
    std::printf("| %s | %s%s%s | 1:%.0f | %+.1f | %.0f | %.0f / %.1f | %.0f / %.1f | %.0f / %.1f | "
                "%.0f / %.0f | %.0f / %.0f | %.0f / %.0f | %d / %d / %d | %s |\n",
                c.table, c.name, c.note[0] ? " (" : "", c.note[0] ? (std::string(c.note) + ")").c_str() : "",
                1.0 / c.inclination, c.dy_mm, c.load_kn, c.paper[0], hz.area_mm2, c.paper[1],
                hs.area_mm2, c.paper[2], st.area_mm2, c.paper[3], hz.pmax_mpa, c.paper[4],
                hs.pmax_mpa, c.paper[5], st.pmax_mpa, hz.patches, hs.patches, st.patches,
                hs.status.c_str());
  }
  std::fflush(stdout);
}

void register_timings() {
  for (const SeedCase& c : kCases) {
    const std::string name = std::string("BM_Seed001Halfspace/") + c.table + "/" + c.name;
    benchmark::RegisterBenchmark(name.c_str(), [c](benchmark::State& state) {
      const railtab::WheelContactGeometry g = geometry_of(c);
      railtab::halfspace::Workspace ws;
      for (auto _ : state) {
        auto r = railtab::halfspace::solve_halfspace_for_load(
            g, c.load_kn * 1e3, seed_material(), railtab::halfspace::HalfspaceOptions{}, ws);
        benchmark::DoNotOptimize(r.patches.data());
      }
    })->Unit(benchmark::kMillisecond);
  }
}

}  // namespace

int main(int argc, char** argv) {
  // Timings only when asked for (Initialize removes the flags it knows, so look first): the
  // table is what this program is for.
  bool filtered = false;
  for (int i = 1; i < argc; ++i) filtered |= std::string(argv[i]).rfind("--benchmark_filter", 0) == 0;
  print_table();
  register_timings();
  benchmark::Initialize(&argc, argv);
  if (filtered) benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
