// SPDX-License-Identifier: Apache-2.0
// The fast models on the yawed geometry against CONTACT's Manchester case A-2.2 (the same rows
// as yaw_reference_test.cpp): Hertz, Kik-Piotrowski, Linder, STRIPES A and A&B with FASTSIM,
// the vertical load carried as by the exact model (solve_coupled_load), CONTACT's creepages.
// Reports how far each model is from CONTACT as the yaw grows (docs/validation/halfspace-yaw.md,
// "Fast models"); asserts only that every row is solved.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "geometry/contact_geometry.hpp"
#include "normal/normal_model.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"
#include "tangential/coupled_load.hpp"
#include "tangential/patch_test_helper.hpp"

namespace railtab::yaw_fast_models_test {
namespace {

using test::num;

constexpr NormalModel kModels[] = {NormalModel::hertz, NormalModel::kik_piotrowski, NormalModel::linder,
                                   NormalModel::stripes_a, NormalModel::stripes_ab};
constexpr int kNumModels = 5;

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Bin {
  std::vector<double> creep[kNumModels], area[kNumModels];
};

TEST(FastModelsWithYaw, A22AgainstContactReported) {
  ProfilePtr w = make_s1002_profile();
  ProfilePtr r = make_uic60_profile();
  const ContactGeometrySolver solver(w, r, w, r, TrackGeometry{}, WheelsetGeometry{});
  Material mat;
  mat.poisson_ratio = 0.28;
  mat.youngs_modulus = 2.0 * 82e9 * 1.28;
  const double fz = 10000.0, mu = 0.3;
  // Bins of yaw: up to 6 mrad, 7.2-14.4 mrad, 15.6-24 mrad; tread rows (|angle| <= 0.35) and flange rows.
  Bin tread[3], flange;
  auto bin_of = [](double yaw) { return yaw <= 6.0e-3 ? 0 : yaw <= 14.4e-3 ? 1 : 2; };
  std::printf("[fast] | wheel | Y mm | yaw mrad | Hertz area, \\|dF\\|/muN | KP | Linder | STRIPES A | STRIPES A&B |\n");
  int solved = 0;
  for (const char* name : {"left", "right"}) {
    const Side side = std::string(name) == "left" ? Side::left : Side::right;
    const auto rows = test::read_csv(std::string(RAILTAB_SOURCE_DIR) + "/tests/data/contact_a22/mbench_a22_" +
                                     name + ".csv");
    for (const auto& row : rows) {
      WheelsetState s;
      s.y = -1e-3 * num(row, "y_ws_mm");
      s.roll = num(row, "roll_ws_rad");
      s.yaw = -num(row, "yaw_ws_rad");
      const WheelContactGeometry g = solver.solve_wheel(side, s);
      const Creepage c{-num(row, "cksi"), num(row, "ceta"), 1e3 * num(row, "cphi_rad_per_mm")};
      const bool is_flange = std::abs(num(row, "deltcp_tr_rad")) > 0.35;
      const double muN = mu * num(row, "fn_N"), area_ref = num(row, "ncon") * 0.04e-6;
      std::string line;
      for (int m = 0; m < kNumModels; ++m) {
        NormalOptions no;
        no.model = kModels[m];
        CreepConditions cc;
        cc.friction = mu;
        cc.speed = 2.0;
        FastsimOptions fo;
        FastsimWorkspace fw;
        const WheelNormalResult start = solve_normal_for_load(g, fz, mat, no);
        CoupledLoadResult out;
        solve_coupled_load(g, fz, start, mat, no,
                           fastsim_tangential(g, [&](std::size_t, const ContactPatch&) { return c; }, cc, mat, fo, fw),
                           CoupledLoadOptions{}, out);
        double fx = 0, fy = 0, area = 0;
        for (size_t i = 0; i < out.normal.patches.size(); ++i) {
          fx += out.creep[i].fx;
          fy += out.creep[i].fy;
          area += out.normal.patches[i].area;
        }
        if (!out.normal.patches.empty()) ++solved;
        const double err = std::hypot(fx + num(row, "fx_N"), fy - num(row, "fs_N")) / muN;
        const double earea = area / area_ref - 1;
        Bin& b = is_flange ? flange : tread[bin_of(num(row, "yaw_ws_rad"))];
        b.creep[m].push_back(err);
        b.area[m].push_back(std::abs(earea));
        char cell[64];
        std::snprintf(cell, sizeof cell, " %+.0f%%, %.1f%% |", 100 * earea, 100 * err);
        line += cell;
      }
      std::printf("[fast] | %s | %4.1f | %4.1f |%s\n", name, num(row, "y_ws_mm"), 1e3 * num(row, "yaw_ws_rad"),
                  line.c_str());
    }
  }
  const char* bins[] = {"tread, yaw 0-6 mrad", "tread, yaw 7.2-14.4 mrad", "tread, yaw 15.6-24 mrad"};
  std::printf("[fast-summary] | rows | Hertz | KP | Linder | STRIPES A | STRIPES A&B |\n");
  auto summary = [&](const char* what, const Bin& b) {
    std::string line;
    for (int m = 0; m < kNumModels; ++m) {
      char cell[96];
      std::snprintf(cell, sizeof cell, " %.1f%% (area %.0f%%) |", 100 * median(b.creep[m]), 100 * median(b.area[m]));
      line += cell;
    }
    std::printf("[fast-summary] | %s (%zu) |%s\n", what, b.creep[0].size(), line.c_str());
  };
  for (int k = 0; k < 3; ++k) summary(bins[k], tread[k]);
  summary("flange, yaw 14.4-24 mrad", flange);
  EXPECT_EQ(solved, 42 * kNumModels);
}

}  // namespace
}  // namespace railtab::yaw_fast_models_test
