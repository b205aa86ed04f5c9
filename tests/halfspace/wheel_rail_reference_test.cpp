// SPDX-License-Identifier: Apache-2.0
// The half-space model on S1002/UIC60 1:40 against CONTACT (../shared/reference blocks A, B, C;
// right wheel, y = -dy, no roll). Mapping of docs/conventions.md: xi = -cksi, eta = ceta,
// phi = cphi; fx = -fx_N, fy = fs_N. Numbers: docs/validation/halfspace.md. Skips without
// ../shared/reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "geometry/contact_geometry.hpp"
#include "halfspace/wheel_rail.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"
#include "tangential/patch_test_helper.hpp"

namespace railtab {
namespace {

using test::num;

Material reference_material() {  // README: steel, nu = 0.28, E = 210 GPa
  Material m;
  m.poisson_ratio = 0.28;
  return m;
}

ContactGeometrySolver manchester() {
  ProfilePtr w = make_s1002_profile();
  ProfilePtr r = make_uic60_profile();
  return ContactGeometrySolver(w, r, w, r, TrackGeometry{}, WheelsetGeometry{});
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Errors {
  std::vector<double> fn, area, pmax, creep;
  std::vector<double> creep_fn;  // |normal force / CONTACT's - 1| of the creep rows (coupled load)
};

// One block: normal per (dy, load), creep per row. element: CONTACT's grid of the block.
Errors run_block(const std::string& file, double element, bool flange_rows) {
  Errors e;
  const auto rows = test::read_csv(std::string(RAILTAB_SHARED_DIR) + "/reference/" + file);
  if (rows.empty()) return e;
  const ContactGeometrySolver solver = manchester();
  const Material mat = reference_material();
  halfspace::HalfspaceOptions opt;
  opt.element_size = element;
  halfspace::Workspace ws;
  std::map<std::pair<double, double>, halfspace::WheelHalfspaceResult> normal;
  for (const auto& row : rows) {
    const double dy = num(row, "dy_mm"), fz = num(row, "fz_prescribed_N");
    const bool flange = std::abs(num(row, "contact_angle_rad")) > 0.35;
    if (flange != flange_rows) continue;
    auto key = std::make_pair(dy, fz);
    if (!normal.count(key)) {
      const WheelContactGeometry g = solver.solve_wheel(Side::right, {-dy * 1e-3, 0.0});
      normal[key] = halfspace::solve_halfspace_for_load(g, fz, mat, opt, ws);
      const auto& r = normal[key];
      if (r.patches.size() != 1) {
        std::printf("[measured] %s dy %+.1f: %zu patches (CONTACT 1)\n", file.c_str(), dy,
                    r.patches.size());
        continue;
      }
      const auto& p = r.patches[0];
      const double efn = p.normal.normal_force / num(row, "fn_N") - 1;
      const double ea = p.normal.area / (num(row, "area_mm2") * 1e-6) - 1;
      const double ep = p.normal.max_pressure / (num(row, "pmax_MPa") * 1e6) - 1;
      e.fn.push_back(std::abs(efn));
      e.area.push_back(std::abs(ea));
      e.pmax.push_back(std::abs(ep));
      std::printf("[measured] %s dy %+5.1f fz %.0f: fn %+.2f%% area %+.2f%% pmax %+.2f%% angle %.3f"
                  " (CONTACT %.3f) grid %dx%d %s\n", file.c_str(), dy, fz, 100 * efn, 100 * ea,
                  100 * ep, p.contact_angle, num(row, "contact_angle_rad"), p.grid.nx, p.grid.ny,
                  status::describe(p.status).c_str());
    }
    auto& r = normal[key];
    if (r.patches.size() != 1) continue;
    const double cksi = num(row, "cksi"), ceta = num(row, "ceta"), cphi = num(row, "cphi_rad_per_m");
    if (cksi == 0.0 && ceta == 0.0 && std::abs(cphi) < 1e-3 && std::abs(cksi) < 1e-6) continue;
    if (std::abs(cksi) < 1e-5 && ceta == 0.0 && std::abs(cphi) < 1e-3) continue;  // no creepage
    const double mu = num(row, "mu");
    const halfspace::WheelHalfspaceResult rolled = halfspace::solve_halfspace_rolling(
        solver.solve_wheel(Side::right, {-dy * 1e-3, 0.0}), fz, {-cksi, ceta, cphi}, mu, mat, opt,
        ws);
    if (rolled.patches.size() != 1) continue;
    const auto& t = rolled.patches[0].tangential;
    const double muN = mu * num(row, "fn_N");
    const double fx_ref = -num(row, "fx_N"), fy_ref = num(row, "fs_N");
    const double err = std::hypot(t.fx - fx_ref, t.fy - fy_ref) / muN;
    e.creep.push_back(err);
    const double fn_err = rolled.patches[0].normal.normal_force / num(row, "fn_N") - 1;
    e.creep_fn.push_back(std::abs(fn_err));
    std::printf("[measured] %s dy %+5.1f %-12s mu %.1f: fx %8.0f (CONTACT %8.0f) fy %8.0f (%8.0f)"
                " |dF|/muN %.2f%% fn %+.2f%% steps %d %s\n", file.c_str(), dy,
                row.at("creep_set").c_str(), mu, t.fx, fx_ref, t.fy, fy_ref, 100 * err,
                100 * fn_err, t.sweeps, status::describe(rolled.patches[0].status).c_str());
  }
  return e;
}

void report(const char* what, const Errors& e) {
  auto worst = [](const std::vector<double>& v) {
    return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
  };
  std::printf("[measured] %s: %zu normal cases, |fn| worst %.2f%%, |area| worst %.2f%%, |pmax| worst"
              " %.2f%%; %zu creep cases, |dF|/muN median %.2f%% worst %.2f%%\n", what,
              e.fn.size(), 100 * worst(e.fn), 100 * worst(e.area), 100 * worst(e.pmax),
              e.creep.size(), 100 * median(e.creep), 100 * worst(e.creep));
}

Errors merge(const std::vector<Errors>& parts) {
  Errors all;
  for (const Errors& p : parts) {
    all.fn.insert(all.fn.end(), p.fn.begin(), p.fn.end());
    all.area.insert(all.area.end(), p.area.begin(), p.area.end());
    all.pmax.insert(all.pmax.end(), p.pmax.begin(), p.pmax.end());
    all.creep.insert(all.creep.end(), p.creep.begin(), p.creep.end());
  }
  return all;
}

TEST(HalfspaceReference, TreadRowsOfBlocksABC) {
  if (test::read_csv(std::string(RAILTAB_SHARED_DIR) + "/reference/blockC_sweep_integer_dy.csv")
          .empty())
    GTEST_SKIP() << RAILTAB_SHARED_DIR "/reference absent";
  const Errors a = run_block("blockA_seed_spin.csv", 0.2e-3, false);
  const Errors b = run_block("blockB_paper_table.csv", 0.2e-3, false);
  const Errors c = run_block("blockC_sweep_integer_dy.csv", 0.3e-3, false);
  report("block A tread", a);
  report("block B tread", b);
  report("block C tread", c);
  const Errors all = merge({a, b, c});
  report("blocks A-C tread", all);
  for (double v : all.fn) EXPECT_LE(v, 0.03);
  for (double v : all.area) EXPECT_LE(v, 0.03);
  for (double v : all.pmax) EXPECT_LE(v, 0.05);
  EXPECT_LE(median(all.creep), 0.015);
  for (double v : all.creep) EXPECT_LE(v, 0.04);
}

// Flange rows: planar assumption strained (kNotPlanar expected where the angle varies). Creep rows:
// the coupled load balance, N cos g + fy sin g = F_z, amplifies the contact angle's error into N
// (dy = 7 mm b_long0.001: a lateral creep force of 96 kN, N 411 kN at 78.5 kN vertical), so the
// reference must sit where CONTACT puts it, at the solved approach (wheel_rail.hpp). Every creep
// row within 10 % of mu N and its normal force within 5 % of CONTACT's; with the reference at
// STRIPES's approach dy = 7 mm was 22 and 15.5 % off, N 20 and 16 % low.
TEST(HalfspaceReference, FlangeRowsReported) {
  if (test::read_csv(std::string(RAILTAB_SHARED_DIR) + "/reference/blockC_sweep_integer_dy.csv")
          .empty())
    GTEST_SKIP() << RAILTAB_SHARED_DIR "/reference absent";
  const Errors c = run_block("blockC_sweep_integer_dy.csv", 0.3e-3, true);
  report("block C flange", c);
  EXPECT_FALSE(c.fn.empty());
  ASSERT_EQ(c.creep.size(), 25u);
  for (double v : c.creep) EXPECT_LE(v, 0.10);
  for (double v : c.creep_fn) EXPECT_LE(v, 0.05);
  EXPECT_LE(median(c.creep), 0.01);
}

// Grid convergence against CONTACT (block C, 0.3 mm there): three tread cases, two creepage sets,
// element sizes 0.6 to 0.15 mm. Prints the table of docs/validation/halfspace.md; asserts only
// that every case is solved. Run with --gtest_also_run_disabled_tests (about 2 min).
TEST(HalfspaceReference, DISABLED_ElementSizeConvergence) {
  const auto rows = test::read_csv(std::string(RAILTAB_SHARED_DIR) +
                                   "/reference/blockC_sweep_integer_dy.csv");
  if (rows.empty()) GTEST_SKIP() << RAILTAB_SHARED_DIR "/reference absent";
  const ContactGeometrySolver solver = manchester();
  const Material mat = reference_material();
  for (const auto& row : rows) {
    const double dy = num(row, "dy_mm");
    const std::string set = row.at("creep_set");
    if ((dy != -3.0 && dy != 0.0 && dy != 3.0) || (set != "c_lat0.001" && set != "e_combined"))
      continue;
    const WheelContactGeometry g = solver.solve_wheel(Side::right, {-dy * 1e-3, 0.0});
    for (const double h : {0.6e-3, 0.4e-3, 0.3e-3, 0.2e-3, 0.15e-3}) {
      halfspace::HalfspaceOptions opt;
      opt.element_size = h;
      halfspace::Workspace ws;
      const auto r = halfspace::solve_halfspace_rolling(
          g, num(row, "fz_prescribed_N"),
          {-num(row, "cksi"), num(row, "ceta"), num(row, "cphi_rad_per_m")}, num(row, "mu"), mat,
          opt, ws);
      ASSERT_EQ(r.patches.size(), 1u);
      const auto& p = r.patches[0];
      const double muN = num(row, "mu") * num(row, "fn_N");
      const double err = std::hypot(p.tangential.fx + num(row, "fx_N"),
                                    p.tangential.fy - num(row, "fs_N")) / muN;
      std::printf("[measured] convergence dy %+.0f %-11s h %.2f mm: area %+.2f%% pmax %+.2f%%"
                  " |dF|/muN %.2f%% grid %dx%d steps %d\n", dy, set.c_str(), h * 1e3,
                  100 * (p.normal.area / (num(row, "area_mm2") * 1e-6) - 1),
                  100 * (p.normal.max_pressure / (num(row, "pmax_MPa") * 1e6) - 1), 100 * err,
                  p.grid.nx, p.grid.ny, p.tangential.sweeps);
      EXPECT_TRUE(p.status & status::kConverged);
    }
  }
}

}  // namespace
}  // namespace railtab
