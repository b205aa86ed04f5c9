// SPDX-License-Identifier: Apache-2.0
// The exact half-space model on the central S1002/UIC60 case (y = 0, no roll, 78.5 kN vertical,
// E = 210 GPa, nu = 0.28, elements 0.3 mm): one wheel's normal problem, and normal plus steady
// rolling at one creepage (block C e_combined: xi 0.003, eta 0.002, phi 0.1 rad/m, mu 0.3).
// Goal (exact model speed): median <= 20 ms for normal + tangential. The workspace (FFT plans, kernel
// spectra) is kept between iterations as in a table sweep; no warm start of the solution.
// Arguments: element size in micrometres. BM_BlockC/*: every case of CONTACT's block C (below).
#include <benchmark/benchmark.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/contact_geometry.hpp"
#include "halfspace/wheel_rail.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"

namespace {

struct Central {
  railtab::WheelContactGeometry geometry;
  railtab::Material material;
  Central() {
    railtab::ProfilePtr w = railtab::make_s1002_profile();
    railtab::ProfilePtr r = railtab::make_uic60_profile();
    const railtab::ContactGeometrySolver solver(w, r, w, r, railtab::TrackGeometry{},
                                                railtab::WheelsetGeometry{});
    geometry = solver.solve_wheel(railtab::Side::right, {0.0, 0.0});
    material.poisson_ratio = 0.28;
  }
};

const Central& central() {
  static const Central c;
  return c;
}

void BM_HalfspaceNormal(benchmark::State& state) {
  const Central& c = central();
  railtab::halfspace::HalfspaceOptions opt;
  opt.element_size = state.range(0) * 1e-6;
  railtab::halfspace::Workspace ws;
  railtab::halfspace::WheelHalfspaceResult r;
  for (auto _ : state) {
    r = railtab::halfspace::solve_halfspace_for_load(c.geometry, 78.5e3, c.material, opt, ws);
    benchmark::DoNotOptimize(r.vertical_approach);
  }
  if (!r.patches.empty()) {
    state.counters["nx"] = r.patches[0].grid.nx;
    state.counters["ny"] = r.patches[0].grid.ny;
    state.counters["bccg_iterations"] = r.patches[0].normal.iterations;
  }
}
BENCHMARK(BM_HalfspaceNormal)->Arg(300)->Unit(benchmark::kMillisecond);

void BM_HalfspaceNormalTangential(benchmark::State& state) {
  const Central& c = central();
  railtab::halfspace::HalfspaceOptions opt;
  opt.element_size = state.range(0) * 1e-6;
  railtab::halfspace::Workspace ws;
  int steps = 0;
  for (auto _ : state) {
    auto r = railtab::halfspace::solve_halfspace_for_load(c.geometry, 78.5e3, c.material, opt, ws);
    railtab::halfspace::solve_halfspace_tangential(r, {0.003, 0.002, 0.1}, 0.3, c.material, opt,
                                                   ws);
    steps = r.patches.empty() ? 0 : r.patches[0].tangential.sweeps;
    benchmark::DoNotOptimize(r.patches.data());
  }
  state.counters["tangential_steps"] = steps;
}
BENCHMARK(BM_HalfspaceNormalTangential)
    ->Arg(600)
    ->Arg(400)
    ->Arg(300)
    ->Arg(200)
    ->Arg(150)
    ->Unit(benchmark::kMillisecond);

// Pure longitudinal creepage 0.001 (partial slip: the slow case of the fixed point).
void BM_HalfspaceNormalTangentialPartialSlip(benchmark::State& state) {
  const Central& c = central();
  railtab::halfspace::HalfspaceOptions opt;
  opt.element_size = state.range(0) * 1e-6;
  railtab::halfspace::Workspace ws;
  for (auto _ : state) {
    auto r = railtab::halfspace::solve_halfspace_for_load(c.geometry, 78.5e3, c.material, opt, ws);
    railtab::halfspace::solve_halfspace_tangential(r, {0.001, 0.0, 0.0}, 0.3, c.material, opt, ws);
    benchmark::DoNotOptimize(r.patches.data());
  }
}
BENCHMARK(BM_HalfspaceNormalTangentialPartialSlip)->Arg(300)->Unit(benchmark::kMillisecond);

// A table column's creepages (the STRIPES scene's 7 x 5 x 3 grid, in the sweep's snake order),
// coupled solves at 78.5 kN on the right wheel at y = 0 (tread) or y = -7 mm (flange contact),
// argument 0 / 7: cold (each solve from scratch, as railtab eval) against warm (each started from
// the previous one, halfspace::RollingState, as the table sweep). Time per column of 105 solves;
// counter solves_per_s.
void creepage_column(benchmark::State& state, bool warm) {
  railtab::ProfilePtr w = railtab::make_s1002_profile();
  railtab::ProfilePtr r = railtab::make_uic60_profile();
  const railtab::ContactGeometrySolver solver(w, r, w, r, railtab::TrackGeometry{}, railtab::WheelsetGeometry{});
  const auto g = solver.solve_wheel(railtab::Side::right, {-1e-3 * static_cast<double>(state.range(0)), 0.0});
  railtab::Material m;
  m.poisson_ratio = 0.28;
  const railtab::halfspace::HalfspaceOptions opt;
  railtab::halfspace::Workspace ws;
  const std::vector<double> xi{-0.004, -0.002, -0.001, 0.0, 0.001, 0.002, 0.004}, eta{-0.004, -0.001, 0.0, 0.001, 0.004},
      phi{-0.3, 0.0, 0.3};
  std::vector<railtab::Creepage> chain;  // the snake order of the sweep (creep_loops.cpp, creepage_chain)
  for (std::size_t ix = 0; ix < xi.size(); ++ix)
    for (std::size_t a = 0; a < eta.size(); ++a)
      for (std::size_t b = 0; b < phi.size(); ++b) {
        const std::size_t ie = ix % 2 == 0 ? a : eta.size() - 1 - a;
        const std::size_t ip = (ix * eta.size() + a) % 2 == 0 ? b : phi.size() - 1 - b;
        chain.push_back({xi[ix], eta[ie], phi[ip]});
      }
  for (auto _ : state) {
    railtab::halfspace::RollingState rolling;
    for (const railtab::Creepage& c : chain) {
      auto res = railtab::halfspace::solve_halfspace_rolling(g, 78.5e3, c, 0.3, m, opt, ws, warm ? &rolling : nullptr);
      benchmark::DoNotOptimize(res.patches.data());
    }
  }
  state.counters["solves_per_s"] =
      benchmark::Counter(static_cast<double>(chain.size()), benchmark::Counter::kIsIterationInvariantRate);
}
void BM_CreepageColumnCold(benchmark::State& state) { creepage_column(state, false); }
void BM_CreepageColumnWarm(benchmark::State& state) { creepage_column(state, true); }
BENCHMARK(BM_CreepageColumnCold)->Arg(0)->Arg(7)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_CreepageColumnWarm)->Arg(0)->Arg(7)->Unit(benchmark::kMillisecond)->Iterations(2);

// Every case of ../shared/reference/blockC_sweep_integer_dy.csv (when present): normal +
// tangential at CONTACT's creepages (coupled through the vertical load, solve_halfspace_rolling;
// rows without creepage: normal only), 0.3 mm as CONTACT's grid there. Counter contact_wall_s is
// CONTACT's time for the case; the ratio is taken from the JSON output (docs/validation/halfspace.md).
std::vector<std::map<std::string, std::string>> read_block_c() {
  std::vector<std::map<std::string, std::string>> rows;
  std::ifstream in(std::string(RAILTAB_SOURCE_DIR) + "/../shared/reference/blockC_sweep_integer_dy.csv");
  std::string line;
  if (!std::getline(in, line)) return rows;
  std::vector<std::string> names;
  {
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) names.push_back(cell);
  }
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string cell;
    std::map<std::string, std::string> row;
    for (size_t i = 0; std::getline(ss, cell, ',') && i < names.size(); ++i) row[names[i]] = cell;
    rows.push_back(row);
  }
  return rows;
}

void register_block_c() {
  for (const auto& row : read_block_c()) {
    const double dy = std::stod(row.at("dy_mm"));
    const double cksi = std::stod(row.at("cksi")), ceta = std::stod(row.at("ceta"));
    const double cphi = std::stod(row.at("cphi_rad_per_m")), mu = std::stod(row.at("mu"));
    const double wall = std::stod(row.at("wall_s"));
    const std::string name = "BM_BlockC/dy" + row.at("dy_mm") + "/" + row.at("creep_set");
    benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& state) {
      railtab::ProfilePtr w = railtab::make_s1002_profile();
      railtab::ProfilePtr r = railtab::make_uic60_profile();
      const railtab::ContactGeometrySolver solver(w, r, w, r, railtab::TrackGeometry{},
                                                  railtab::WheelsetGeometry{});
      const auto g = solver.solve_wheel(railtab::Side::right, {-dy * 1e-3, 0.0});
      railtab::Material m;
      m.poisson_ratio = 0.28;
      railtab::halfspace::HalfspaceOptions opt;
      railtab::halfspace::Workspace ws;
      const bool creep = std::abs(cksi) > 1e-5 || ceta != 0.0 || std::abs(cphi) > 1e-3;
      for (auto _ : state) {
        if (creep) {  // coupled as CONTACT: the vertical load includes fy sin(angle)
          auto res = railtab::halfspace::solve_halfspace_rolling(g, 78.5e3, {-cksi, ceta, cphi},
                                                                 mu, m, opt, ws);
          benchmark::DoNotOptimize(res.patches.data());
        } else {
          auto res = railtab::halfspace::solve_halfspace_for_load(g, 78.5e3, m, opt, ws);
          benchmark::DoNotOptimize(res.patches.data());
        }
      }
      state.counters["contact_wall_s"] = wall;
    })->Unit(benchmark::kMillisecond)->Iterations(1);
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_block_c();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
