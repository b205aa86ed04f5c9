// SPDX-License-Identifier: Apache-2.0
// The yawed half-space model against CONTACT on the Manchester contact benchmark, case
// (tests/data/contact_a22: 21 cases per wheel, y = 0..10 mm with 2.4 mrad of yaw per mm, 10 kN,
// 0.2 mm elements). Built-in S1002 / UIC60 1:40 (CONTACT used the benchmark's files of them).
// Mapping (tests/data/contact_a22/README.md): y = -Y, roll = ROLL, yaw = -YAW; xi = -cksi,
// eta = ceta, phi = cphi; fx = -FX, fy = FS. Rows with |contact angle| <= 0.35 rad are tread rows
// (targets of blocks A-C), the others flange rows (reported). Prints the tables of
// docs/validation/halfspace-yaw.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "geometry/contact_geometry.hpp"
#include "halfspace/wheel_rail.hpp"
#include "halfspace/wheelset_kinematics.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"
#include "tangential/patch_test_helper.hpp"

namespace railtab::yaw_reference_test {
namespace {

using test::num;

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
double worst(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); }

struct Errors {
  std::vector<double> fn, area, creep, creep_given;  // relative errors, one per row
  std::vector<double> area_one_region;                // area errors of rows with one loaded region
  int rows = 0, multi_patch = 0, two_regions = 0;
};

WheelsetState a22_state(const test::CsvRow& row) {
  WheelsetState s;
  s.y = -1e-3 * num(row, "y_ws_mm");
  s.roll = num(row, "roll_ws_rad");
  s.yaw = -num(row, "yaw_ws_rad");
  return s;
}

// Loaded regions of a patch across the rolling direction: runs of grid rows with pressure,
// separated by unloaded rows.
int loaded_regions(const halfspace::HalfspacePatch& p) {
  int regions = 0;
  bool previous = false;
  for (int j = 0; j < p.grid.ny; ++j) {
    bool loaded = false;
    for (int i = 0; i < p.grid.nx && !loaded; ++i) loaded = p.normal.pressure[p.grid.index(i, j)] > 0.0;
    if (loaded && !previous) ++regions;
    previous = loaded;
  }
  return regions;
}

struct Sums {
  double fn = 0, area = 0, fx = 0, fy = 0;
  int regions = 0;
  const halfspace::HalfspacePatch* main = nullptr;  // the most loaded patch
};

Sums sums(const halfspace::WheelHalfspaceResult& res) {
  Sums t;
  double nmax = -1;
  for (const auto& p : res.patches) {
    t.fn += p.normal.normal_force;
    t.area += p.normal.area;
    t.fx += p.tangential.fx;
    t.fy += p.tangential.fy;
    t.regions += loaded_regions(p);
    if (p.normal.normal_force > nmax) {
      nmax = p.normal.normal_force;
      t.main = &p;
    }
  }
  return t;
}

// One wheel's 21 cases; flange: the flange rows (else the tread rows). The wheelset rolls at
// V = 2 m/s with Omega = -VPITCH; the creepages are those of the yawed kinematics at each patch's
// reference (rigid_creepage), as CONTACT computes its own from the same motion. A second solve
// with CONTACT's printed creepages applied at our reference is reported beside it.
Errors run_wheel(Side side, bool flange_rows) {
  Errors e;
  const char* name = side == Side::left ? "left" : "right";
  const auto rows = test::read_csv(std::string(RAILTAB_SOURCE_DIR) + "/tests/data/contact_a22/mbench_a22_" +
                                   name + ".csv");
  EXPECT_EQ(rows.size(), 21u);
  ProfilePtr w = make_s1002_profile();
  ProfilePtr r = make_uic60_profile();
  const ContactGeometrySolver solver(w, r, w, r, TrackGeometry{}, WheelsetGeometry{});
  Material mat;
  mat.poisson_ratio = 0.28;
  mat.youngs_modulus = 2.0 * 82e9 * 1.28;  // G = 82 GPa, as the .inp files
  halfspace::HalfspaceOptions opt;
  opt.element_size = 0.2e-3;
  halfspace::Workspace ws;
  const double fz = 10000.0, mu = 0.3;
  for (const auto& row : rows) {
    const bool flange = std::abs(num(row, "deltcp_tr_rad")) > 0.35;
    if (flange != flange_rows) continue;
    ++e.rows;
    const WheelContactGeometry g = solver.solve_wheel(side, a22_state(row));
    // The patch's reference comes from the normal layer; the creepages of the motion there.
    const halfspace::WheelHalfspaceResult first = halfspace::solve_halfspace_for_load(g, fz, mat, opt, ws);
    if (first.patches.empty()) {
      ADD_FAILURE() << name << " case " << row.at("case") << ": no contact";
      continue;
    }
    halfspace::WheelsetMotion motion;
    motion.speed = 2.0;
    motion.spin = -num(row, "vpitch_rad_s");
    const Creepage k = halfspace::rigid_creepage(g, *sums(first).main, motion);
    const halfspace::WheelHalfspaceResult res = halfspace::solve_halfspace_rolling(g, fz, k, mu, mat, opt, ws);
    const Sums t = sums(res);
    const Creepage given{-num(row, "cksi"), num(row, "ceta"), 1e3 * num(row, "cphi_rad_per_mm")};
    const Sums tg = sums(halfspace::solve_halfspace_rolling(g, fz, given, mu, mat, opt, ws));
    if (res.patches.size() > 1) ++e.multi_patch;
    const double fn_ref = num(row, "fn_N"), area_ref = num(row, "ncon") * 0.04e-6;
    const double efn = t.fn / fn_ref - 1, earea = t.area / area_ref - 1;
    const double muN = mu * fn_ref;
    const double err = std::hypot(t.fx + num(row, "fx_N"), t.fy - num(row, "fs_N")) / muN;
    const double err_given = std::hypot(tg.fx + num(row, "fx_N"), tg.fy - num(row, "fs_N")) / muN;
    e.fn.push_back(std::abs(efn));
    e.area.push_back(std::abs(earea));
    if (t.regions == 1) e.area_one_region.push_back(std::abs(earea));
    else ++e.two_regions;
    e.creep.push_back(err);
    e.creep_given.push_back(err_given);
    // CONTACT's creepages are per its rolling speed VELOC, ours per V: compared as slip velocities.
    const double vel = 1e-3 * num(row, "veloc_mm_s") / motion.speed;
    std::printf("[table] | %s | %4.1f | %4.1f | %+.3f (%+.3f) | %+6.2f (%+6.2f) | %+6.2f (%+6.2f) | "
                "%+.2f%% | %+.2f%% | %d | %5.0f (%5.0f) | %5.0f (%5.0f) | %.2f%% | "
                "%+.2e (%+.2e) | %+.2e (%+.2e) | %+.3f (%+.3f) | %.2f%% |\n",
                name, num(row, "y_ws_mm"), 1e3 * num(row, "yaw_ws_rad"), t.main->contact_angle,
                num(row, "deltcp_tr_rad"), 1e3 * t.main->x_track, num(row, "xcp_tr_mm"),
                1e3 * t.main->x_wheel, num(row, "xcp_w_mm"), 100 * efn, 100 * earea, t.regions, t.fx,
                -num(row, "fx_N"), t.fy, num(row, "fs_N"), 100 * err, k.xi, -num(row, "cksi") * vel, k.eta,
                num(row, "ceta") * vel, k.phi, 1e3 * num(row, "cphi_rad_per_mm") * vel, 100 * err_given);
  }
  return e;
}

void report(const char* what, const Errors& e) {
  std::printf("[measured] %s: %d rows (%d with several patches, %d with two loaded regions), |fn| "
              "median %.2f%% worst %.2f%%, |area| median %.2f%% worst %.2f%% (one region: worst %.2f%%), "
              "|dF|/muN median %.2f%% worst %.2f%%; with CONTACT's creepages at our reference median "
              "%.2f%% worst %.2f%%\n",
              what, e.rows, e.multi_patch, e.two_regions, 100 * median(e.fn), 100 * worst(e.fn),
              100 * median(e.area), 100 * worst(e.area), 100 * worst(e.area_one_region),
              100 * median(e.creep), 100 * worst(e.creep), 100 * median(e.creep_given),
              100 * worst(e.creep_given));
}

void header() {
  std::printf("[table] | wheel | Y mm | yaw mrad | angle (CONTACT) rad | x_track (XCP(TR)) mm | x_wheel "
              "(XCP(W)) mm | fn | area | regions | fx (CONTACT) N | fy (CONTACT) N | \\|dF\\|/muN | xi "
              "(CONTACT) | eta (CONTACT) | phi (CONTACT) rad/m | \\|dF\\|/muN, CONTACT's creepages |\n");
}

Errors merge(Errors a, const Errors& b) {
  a.rows += b.rows;
  a.multi_patch += b.multi_patch;
  a.two_regions += b.two_regions;
  for (std::vector<double> Errors::*v :
       {&Errors::fn, &Errors::area, &Errors::creep, &Errors::creep_given, &Errors::area_one_region})
    (a.*v).insert((a.*v).end(), (b.*v).begin(), (b.*v).end());
  return a;
}

// Targets of blocks A-C on the tread rows: normal force within 3 %, creep forces within 1.5 % of
// mu N (median) and 4 % (worst); area within 3 % where our contact is one loaded region. Where it
// is two regions 8 mm apart (Y = 5 mm, right wheel: flange root and tread in one patch, as
// CONTACT has them) the area is reported, not asserted: the load split between the regions
// follows 22 micrometres of separation (docs/validation/halfspace-yaw.md).
TEST(HalfspaceYawReference, TreadRowsOfA22) {
  header();
  const Errors left = run_wheel(Side::left, false), right = run_wheel(Side::right, false);
  report("A-2.2 left tread", left);
  report("A-2.2 right tread", right);
  const Errors all = merge(left, right);
  report("A-2.2 tread", all);
  EXPECT_EQ(all.rows, 33);
  EXPECT_LE(all.two_regions, 1);
  for (double v : all.fn) EXPECT_LE(v, 0.03);
  for (double v : all.area_one_region) EXPECT_LE(v, 0.03);
  EXPECT_LE(median(all.creep), 0.015);
  for (double v : all.creep) EXPECT_LE(v, 0.04);
}

TEST(HalfspaceYawReference, FlangeRowsOfA22Reported) {
  header();
  const Errors right = run_wheel(Side::right, true);
  report("A-2.2 right flange", right);
  EXPECT_EQ(right.rows, 9);
}

}  // namespace
}  // namespace railtab::yaw_reference_test
