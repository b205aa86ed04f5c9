// SPDX-License-Identifier: Apache-2.0
// Seed 001 Table 2 (S1002 on UIC60 1:40, 90 kN) and the Sichani et al. 2014 central case: every model on the
// real profiles through the geometry solver. Prints the comparison table (docs/validation/normal.md)
// and writes CSVs under <repo>/build/validation/.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/contact_geometry.hpp"
#include "normal/normal_model.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"

namespace railtab {
namespace {

const NormalModel kModels[] = {NormalModel::hertz, NormalModel::linder,
                               NormalModel::kik_piotrowski, NormalModel::stripes_a,
                               NormalModel::stripes_ab};

ContactGeometrySolver make_solver() {
  const ProfilePtr wheel = make_s1002_profile();
  const ProfilePtr rail = make_uic60_profile();
  return ContactGeometrySolver(wheel, rail, wheel, rail, TrackGeometry{}, WheelsetGeometry{});
}

std::filesystem::path output_dir() {
  const auto dir = std::filesystem::path(RAILTAB_SOURCE_DIR) / "build" / "validation";
  std::filesystem::create_directories(dir);
  return dir;
}

// Block B rows by dy (CONTACT, this project's reference set).
std::map<int, std::pair<double, double>> block_b() {
  std::map<int, std::pair<double, double>> rows;
  const auto file = std::filesystem::path(RAILTAB_SHARED_DIR) / "reference" / "blockB_paper_table.csv";
  std::ifstream in(file);
  if (!in) return rows;
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  {
    std::stringstream ss(line);
    std::string c;
    while (std::getline(ss, c, ',')) header.push_back(c);
  }
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string c;
    std::map<std::string, std::string> r;
    for (const auto& h : header) {
      std::getline(ss, c, ',');
      r[h] = c;
    }
    rows[static_cast<int>(std::lround(std::stod(r["dy_mm"])))] = {std::stod(r["area_mm2"]),
                                                                  std::stod(r["pmax_MPa"])};
  }
  return rows;
}

TEST(S1002Uic60, SeedTable2At90kN) {
  const ContactGeometrySolver solver = make_solver();
  const Material steel{210e9, 0.28};  // CONTACT set-up: G = 82031 MPa, nu = 0.28
  const auto ref = block_b();
  // Seed 001 Table 2: field side 3 mm, neutral, gauge corner 5 mm (right wheel). Reference README:
  // dy > 0 moves the right flange to the gauge corner = wheelset to the right = our y < 0.
  struct Case {
    const char* name;
    int dy;
    double paper[6];  // area elliptic/CONTACT/STRIPES [mm2], pmax elliptic/CONTACT/STRIPES [MPa]
  } cases[] = {{"field side", -3, {129, 151, 149, 1049, 934, 1202}},
               {"neutral", 0, {167, 210, 196, 806, 849, 784}},
               {"gauge corner", 5, {145, 122, 137, 929, 2327, 1539}}};
  std::ofstream csv(output_dir() / "normal_table2.csv");
  csv << "case,dy_mm,y_track_mm,model,area_mm2,pmax_MPa,n_patches,approach_mm,contact_angle_rad,"
         "status,area_contact_blockB_mm2,pmax_contact_blockB_MPa,area_dev_pct,pmax_dev_pct\n";
  std::printf("%-12s %-15s %9s %9s %8s %8s\n", "case", "model", "area", "pmax", "dA%", "dp%");
  for (const auto& c : cases) {
    const double y = -c.dy * 1e-3;
    const WheelContactGeometry g = solver.solve_wheel(Side::right, WheelsetState{y, 0.0});
    ASSERT_FALSE(g.points.empty());
    const bool have_ref = ref.count(c.dy) > 0;
    struct Variant {
      NormalModel model;
      StripesClosure closure;
      const char* label;
    };
    std::vector<Variant> variants;
    for (NormalModel m : kModels) variants.push_back({m, StripesClosure::boussinesq, to_string(m)});
    variants.push_back({NormalModel::stripes_a, StripesClosure::hertz_peak, "stripes-a/hertz-peak"});
    variants.push_back({NormalModel::stripes_ab, StripesClosure::hertz_peak, "stripes-ab/hertz-peak"});
    for (const Variant& var : variants) {
      const NormalModel m = var.model;
      NormalOptions o;
      o.model = m;
      o.stripes_closure = var.closure;
      const WheelNormalResult r = solve_normal_for_load(g, 90e3, steel, o);
      EXPECT_TRUE(r.status & status::kConverged) << c.name << " " << to_string(m);
      double area = 0.0, pmax = 0.0;
      int n = 0;
      for (const auto& p : r.patches) {
        area += p.area;
        pmax = std::max(pmax, p.max_pressure);
        n += p.normal_force > 0.0;
        for (const auto& s : p.strips) ASSERT_TRUE(std::isfinite(s.pressure_peak));
      }
      area *= 1e6;
      pmax *= 1e-6;
      const double ra = have_ref ? ref.at(c.dy).first : c.paper[1];
      const double rp = have_ref ? ref.at(c.dy).second : c.paper[4];
      const double da = 100.0 * (area / ra - 1.0), dp = 100.0 * (pmax / rp - 1.0);
      std::printf("%-12s %-22s %9.1f %9.0f %+8.1f %+8.1f %2d patch(es) angle %+.4f  %s\n", c.name,
                  var.label, area, pmax, da, dp, n, r.patches.at(0).contact_angle,
                  status::describe(r.status).c_str());
      // Block B: CONTACT finds one patch in all three cases (the two rigid minima at dy = 0 and
      // +5 mm lie inside one overlap region).
      EXPECT_EQ(r.patches.size(), 1u) << c.name << " " << var.label;
      EXPECT_EQ(r.point_patch.size(), g.points.size());
      csv << c.name << ',' << c.dy << ',' << -c.dy << ',' << var.label << ',' << area << ','
          << pmax << ',' << n << ',' << r.vertical_approach * 1e3 << ','
          << r.patches[0].contact_angle << ",\"" << status::describe(r.status) << "\"," << ra << ','
          << rp << ',' << da << ',' << dp << '\n';
      // Sanity bounds only (the 15 % aim for STRIPES is reported, not asserted).
      EXPECT_GT(area, 0.3 * ra);
      EXPECT_LT(area, 3.0 * ra);
    }
  }
}

// Seed 000 central case (right wheel, dy = 0, 78.5 kN): pressure along the strip centre lines for
// STRIPES A&B with shifted B versus STRIPES A with clip + smoothing (and the other models).
TEST(S1002Uic60, Seed000PressureProfilesCsv) {
  const ContactGeometrySolver solver = make_solver();
  const Material steel{210e9, 0.28};
  const WheelContactGeometry g = solver.solve_wheel(Side::right, WheelsetState{0.0, 0.0});
  struct Variant {
    const char* label;
    NormalModel model;
    NegativeCurvature treatment;
  } variants[] = {{"stripes-ab-shift", NormalModel::stripes_ab, NegativeCurvature::shift},
                  {"stripes-a-clip-smooth", NormalModel::stripes_a,
                   NegativeCurvature::clip_and_smooth},
                  {"stripes-a-shift", NormalModel::stripes_a, NegativeCurvature::shift},
                  {"stripes-ab-clip-smooth", NormalModel::stripes_ab,
                   NegativeCurvature::clip_and_smooth},
                  {"kik-piotrowski", NormalModel::kik_piotrowski, NegativeCurvature::shift},
                  {"linder", NormalModel::linder, NegativeCurvature::shift},
                  {"hertz", NormalModel::hertz, NegativeCurvature::shift}};
  std::ofstream csv(output_dir() / "normal_pressure_seed000.csv");
  csv << "s_mm,model,pressure_MPa,half_length_mm,rail_u_mm,contact_angle_rad,status\n";  // status quoted
  for (const auto& v : variants) {
    NormalOptions o;
    o.model = v.model;
    o.negative_curvature = v.treatment;
    o.hertz_strips = true;
    const WheelNormalResult r = solve_normal_for_load(g, 78.5e3, steel, o);
    ASSERT_TRUE(r.status & status::kConverged) << v.label;
    double pmax = 0.0;
    for (const auto& p : r.patches) {
      for (const auto& s : p.strips) {
        csv << s.s * 1e3 << ',' << v.label << ',' << s.pressure_peak * 1e-6 << ','
            << s.x_lead * 1e3 << ',' << s.rail_u * 1e3 << ',' << s.contact_angle << ",\""
            << status::describe(p.status) << "\"\n";
        pmax = std::max(pmax, s.pressure_peak);
      }
    }
    std::printf("%-24s pmax %7.0f MPa area %6.1f mm2 %s\n", v.label, pmax * 1e-6,
                r.patches[0].area * 1e6, status::describe(r.patches[0].status).c_str());
    EXPECT_GT(pmax, 0.0);
  }
}

// Seed 000 central case (y = 0, 78.5 kN): two rigid gap minima in one overlap run, the second a
// 1.9 um ripple 10.9 mm towards the flange. STRIPES builds ONE strip set over the run with one
// amplitude (stripes.cpp, stripes_run_patch). Formerly each point built its own ~50 strips with its
// own closure, and the pressure along the strips stepped by 620-730 MPa (neighbouring steps
// < 6 MPa) where the two sets met, at the largest gap between the points (rail y ~ -8.6 mm). The
// pressure must be continuous there: the step across that spot no larger than 4x the steps next to
// it (plus 0.1 % of p_max), the continuity measure of the stability sweeps.
TEST(S1002Uic60, StripesPressureContinuousAcrossRipple) {
  const ContactGeometrySolver solver = make_solver();
  const WheelContactGeometry g = solver.solve_wheel(Side::right, WheelsetState{0.0, 0.0});
  ASSERT_EQ(g.points.size(), 2u);
  const double s0 = std::min(g.points[0].band_s, g.points[1].band_s);
  const double s1 = std::max(g.points[0].band_s, g.points[1].band_s);
  double s_split = s0, gap = -1.0;  // where the per-point strip sets met: the largest gap between
  for (const BandSample& b : g.band)
    if (b.s > s0 && b.s < s1 && b.gap > gap) {
      gap = b.gap;
      s_split = b.s;
    }
  for (NormalModel m : {NormalModel::stripes_a, NormalModel::stripes_ab}) {
    for (NegativeCurvature c : {NegativeCurvature::shift, NegativeCurvature::clip_and_smooth}) {
      SCOPED_TRACE(std::string(to_string(m)) + " " + to_string(c));
      NormalOptions o;
      o.model = m;
      o.negative_curvature = c;
      const WheelNormalResult r = solve_normal_for_load(g, 78.5e3, Material{210e9, 0.28}, o);
      ASSERT_TRUE(r.status & status::kConverged);
      ASSERT_EQ(r.patches.size(), 1u);
      EXPECT_EQ(r.point_patch, (std::vector<int>{0, 0}));
      const std::vector<Strip>& st = r.patches[0].strips;
      ASSERT_EQ(static_cast<int>(st.size()), o.strips);  // one strip set for the run
      ASSERT_LT(st.front().s, s_split);
      ASSERT_GT(st.back().s, s_split);
      std::size_t k = 0;  // strips k, k + 1 enclose the split
      while (st[k + 1].s < s_split) ++k;
      ASSERT_GE(k, 2u);
      ASSERT_LT(k + 3, st.size());
      auto step = [&](std::size_t i) { return std::abs(st[i + 1].pressure_peak - st[i].pressure_peak); };
      const double neighbours = std::max({step(k - 2), step(k - 1), step(k + 1), step(k + 2)});
      EXPECT_LE(step(k), 4.0 * neighbours + 1e-3 * r.patches[0].max_pressure)
          << "pressure " << st[k].pressure_peak << " -> " << st[k + 1].pressure_peak;
      for (const Strip& x : st) EXPECT_TRUE(std::isfinite(x.pressure_peak));
    }
  }
}

// Load sweep 1..150 kN on the central case: the ripple point joins the run's patch on the way
// (one strip set from then on). The approach grows with the load, the load with the approach.
TEST(S1002Uic60, StripesLoadSweepMonotoneAtCentre) {
  const ContactGeometrySolver solver = make_solver();
  const WheelContactGeometry g = solver.solve_wheel(Side::right, WheelsetState{0.0, 0.0});
  const Material steel{210e9, 0.28};
  for (NormalModel m : {NormalModel::stripes_a, NormalModel::stripes_ab}) {
    SCOPED_TRACE(to_string(m));
    NormalOptions o;
    o.model = m;
    double previous = 0.0;
    for (double W = 1e3; W <= 150e3 + 1; W += 1e3) {
      const WheelNormalResult r = solve_normal_for_load(g, W, steel, o);
      ASSERT_TRUE(r.status & status::kConverged) << W;
      EXPECT_NEAR(r.carried_load / W, 1.0, 1e-6);
      EXPECT_GT(r.vertical_approach, previous) << W;
      previous = r.vertical_approach;
    }
    double load = 0.0;
    for (double dz = 1e-6; dz <= 1.2e-4; dz += 0.5e-6) {
      const WheelNormalResult r = solve_normal_for_approach(g, dz, steel, o);
      EXPECT_GT(r.carried_load, load) << dz;
      load = r.carried_load;
    }
  }
}

// On the flange after the jump onto the 70 deg flank (left wheel, y = 6.72 mm) the STRIPES patch
// spans the junction of the straight flank and the flange-root arc, where the lateral curvature
// drops from 38 to 0 1/m within one band cell. The load must still grow with the approach (strip
// A_c averaged over each strip; with centre values N(delta) had bumps and the load control picked
// different roots from one y to the next).
TEST(S1002Uic60, StripesLoadMonotoneOnFlangeRoot) {
  const ContactGeometrySolver solver = make_solver();
  const WheelContactGeometry g = solver.solve_wheel(Side::left, WheelsetState{6.72e-3, 0.0});
  for (NormalModel m : {NormalModel::stripes_a, NormalModel::stripes_ab}) {
    for (NegativeCurvature c : {NegativeCurvature::shift, NegativeCurvature::clip_and_smooth}) {
      NormalOptions o;
      o.model = m;
      o.negative_curvature = c;
      o.strips = 20;
      double previous = 0.0;
      for (double dz = 5.9e-4; dz <= 6.6e-4; dz += 2.5e-6) {
        const WheelNormalResult r = solve_normal_for_approach(g, dz, Material{}, o);
        EXPECT_GT(r.carried_load, previous) << to_string(m) << " " << to_string(c) << " dz " << dz;
        previous = r.carried_load;
      }
    }
  }
}

}  // namespace
}  // namespace railtab
