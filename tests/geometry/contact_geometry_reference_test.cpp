// SPDX-License-Identifier: Apache-2.0
// S1002 on UIC60 1:40 (Manchester set-up) against CONTACT's lateral sweep
// (../shared/reference/blockC_sweep_integer_dy.csv, a_none rows; right wheel, no roll,
// dy = -y). CONTACT reports the reference point of a loaded elastic patch (78.5 kN): the rigid
// contact point is checked only where the patch is stiff (deep flange); the tread is compared
// through overlap_references at CONTACT's approach. Table: docs/validation/geometry.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/contact_geometry.hpp"
#include "geometry/overlap_reference.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"

namespace railtab {
namespace {

constexpr double kDeg = 180.0 / 3.14159265358979323846;

ContactGeometrySolver manchester() {
  ProfilePtr w = make_s1002_profile();
  ProfilePtr r = make_uic60_profile();
  return ContactGeometrySolver(w, r, w, r, TrackGeometry{}, WheelsetGeometry{});
}

struct RefRow {
  double dy_mm;
  double angle_rad;   // CONTACT contact_angle_rad (right wheel: negative towards the flange)
  double r_roll_mm;   // CONTACT r_roll_mm
  double approach_mm; // CONTACT approach_mm
  double ycp_track_mm;
};

// a_none rows of block C, one per dy (the file repeats the dy = -6 row).
std::vector<RefRow> read_reference() {
  const std::filesystem::path path =
      std::filesystem::path(RAILTAB_SHARED_DIR) / "reference" / "blockC_sweep_integer_dy.csv";
  std::vector<RefRow> rows;
  std::ifstream in(path);
  if (!in) return rows;
  std::string line;
  std::getline(in, line);
  std::map<std::string, int> col;
  {
    std::stringstream ss(line);
    std::string name;
    for (int i = 0; std::getline(ss, name, ','); ++i) col[name] = i;
  }
  std::map<double, RefRow> by_dy;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) f.push_back(cell);
    if (f.at(col.at("creep_set")) != "a_none") continue;
    const RefRow r{std::stod(f.at(col.at("dy_mm"))), std::stod(f.at(col.at("contact_angle_rad"))),
                   std::stod(f.at(col.at("r_roll_mm"))), std::stod(f.at(col.at("approach_mm"))),
                   std::stod(f.at(col.at("ycp_track_mm")))};
    by_dy.emplace(r.dy_mm, r);
  }
  for (const auto& [dy, r] : by_dy) rows.push_back(r);
  return rows;
}

#define REQUIRE_REFERENCE(rows)                                        \
  if ((rows).empty()) {                                                \
    GTEST_SKIP() << RAILTAB_SHARED_DIR "/reference/blockC_sweep_integer_dy.csv absent";                      \
  }

ContactPoint primary(const ContactGeometrySolver& s, double dy_mm) {
  return s.solve_wheel(Side::right, {-dy_mm * 1e-3, 0.0}).points.at(0);
}

// The jump into flange contact falls between the same two integer offsets as CONTACT's.
TEST(GeometryReference, FlangeJumpBetweenSameOffsets) {
  const std::vector<RefRow> rows = read_reference();
  REQUIRE_REFERENCE(rows);
  const ContactGeometrySolver s = manchester();
  int ref_jump = -1, our_jump = -1;
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    if (std::abs(rows[i].angle_rad) < 0.6 && std::abs(rows[i + 1].angle_rad) > 1.0) ref_jump = int(i);
    const double a0 = primary(s, rows[i].dy_mm).contact_angle_side;
    const double a1 = primary(s, rows[i + 1].dy_mm).contact_angle_side;
    if (a0 < 0.6 && a1 > 1.0) our_jump = int(i);
  }
  ASSERT_GE(ref_jump, 0);
  EXPECT_EQ(our_jump, ref_jump) << "reference jumps after dy = " << rows[ref_jump].dy_mm << " mm";
  // Flange side of the jump: the flange flank, about 1.1-1.22 rad, like CONTACT's.
  for (const RefRow& r : rows) {
    if (r.dy_mm <= rows[ref_jump].dy_mm) continue;
    const double a = primary(s, r.dy_mm).contact_angle_side;
    EXPECT_GT(a, 1.05) << r.dy_mm;
    EXPECT_LT(a, 1.23) << r.dy_mm;
  }
}

// Deep flange contact is stiff and the elastic patch sits on the rigid point: angle and
// track position agree closely (dy = 9, 10 mm; at dy = 7 CONTACT's row is flagged unreliable,
// at 8 the patch straddles the flank/root joint).
TEST(GeometryReference, DeepFlangeContactMatches) {
  const std::vector<RefRow> rows = read_reference();
  REQUIRE_REFERENCE(rows);
  const ContactGeometrySolver s = manchester();
  for (const RefRow& r : rows) {
    if (r.dy_mm < 9.0) continue;
    const ContactPoint p = primary(s, r.dy_mm);
    EXPECT_NEAR(p.contact_angle, r.angle_rad, 0.1 / kDeg) << r.dy_mm;
    EXPECT_NEAR(-p.y_track * 1e3, r.ycp_track_mm, 0.05) << r.dy_mm;
  }
}

// CONTACT's patch reference, rebuilt from our band at CONTACT's own load (see
// geometry/overlap_reference.hpp for CONTACT's weighting and patch rules). approach_mm is the
// largest NORMAL interpenetration of CONTACT's patch (m_wr_undefdist: pen = -min h); our rigid
// wheel, pushed down by delta_z, overlaps vertically by at most delta_z, i.e. normally by
// delta_z cos(g) near the maximum, so delta_z = approach / cos(angle) with CONTACT's angle (the
// angle difference over the patch changes this by < 1e-3 relative, < 0.1 um).
struct Loaded {
  OverlapReference ref;  // the heaviest reference (CONTACT reports one patch in every row)
  std::size_t count;     // number of references after CONTACT's combination rules
  double delta_z;        // vertical approach fed in [m]
};

Loaded loaded_reference(const ContactGeometrySolver& s, const RefRow& r) {
  const WheelContactGeometry g = s.solve_wheel(Side::right, {-r.dy_mm * 1e-3, 0.0});
  const double delta_z = r.approach_mm * 1e-3 / std::cos(r.angle_rad);
  const std::vector<OverlapReference> refs = overlap_references(g, delta_z, contact_patch_rules());
  EXPECT_FALSE(refs.empty()) << r.dy_mm;
  if (refs.empty()) return {OverlapReference{}, 0, delta_z};
  const OverlapReference* best = &refs.front();
  for (const OverlapReference& x : refs) {
    if (x.total_weight > best->total_weight) best = &x;
  }
  return {*best, refs.size(), delta_z};
}

// The acceptance check, like with like: on the tread (dy <= 6) the overlap reference at CONTACT's
// approach has CONTACT's contact angle within 0.1 deg and its change of rolling radius (radius
// to the rail surface, CONTACT's r_roll) relative to dy = 0 within 0.05 mm, with one patch.
TEST(GeometryReference, TreadOverlapReferenceMatchesContact) {
  const std::vector<RefRow> rows = read_reference();
  REQUIRE_REFERENCE(rows);
  const ContactGeometrySolver s = manchester();
  double r0_ours = 0.0, r0_ref = 0.0;
  for (const RefRow& r : rows) {
    if (r.dy_mm != 0.0) continue;
    r0_ours = loaded_reference(s, r).ref.loaded_rolling_radius;
    r0_ref = r.r_roll_mm;
  }
  ASSERT_GT(r0_ours, 0.0);
  for (const RefRow& r : rows) {
    if (r.dy_mm > 6.0) continue;
    const Loaded l = loaded_reference(s, r);
    EXPECT_EQ(l.count, 1u) << r.dy_mm;
    EXPECT_FALSE(l.ref.clipped) << r.dy_mm;
    EXPECT_NEAR(l.ref.contact_angle * kDeg, r.angle_rad * kDeg, 0.1) << "dy = " << r.dy_mm;
    EXPECT_NEAR((l.ref.loaded_rolling_radius - r0_ours) * 1e3, r.r_roll_mm - r0_ref, 0.05)
        << "dy = " << r.dy_mm;
  }
}

// The jump into flange contact of the loaded reference falls between the same integer offsets.
TEST(GeometryReference, LoadedFlangeJumpBetweenSameOffsets) {
  const std::vector<RefRow> rows = read_reference();
  REQUIRE_REFERENCE(rows);
  const ContactGeometrySolver s = manchester();
  int ref_jump = -1, our_jump = -1;
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    if (std::abs(rows[i].angle_rad) < 0.6 && std::abs(rows[i + 1].angle_rad) > 1.0) ref_jump = int(i);
    const double a0 = loaded_reference(s, rows[i]).ref.contact_angle_side;
    const double a1 = loaded_reference(s, rows[i + 1]).ref.contact_angle_side;
    if (a0 < 0.6 && a1 > 1.0) our_jump = int(i);
  }
  ASSERT_GE(ref_jump, 0);
  EXPECT_EQ(our_jump, ref_jump) << "reference jumps after dy = " << rows[ref_jump].dy_mm << " mm";
}

// Prints the table of docs/validation/geometry.md:
//   ./build/georef/tests/test_geometry --gtest_also_run_disabled_tests
//       --gtest_filter='GeometryReference.DISABLED_PrintTable'
TEST(GeometryReference, DISABLED_PrintTable) {
  const std::vector<RefRow> rows = read_reference();
  REQUIRE_REFERENCE(rows);
  const ContactGeometrySolver s = manchester();
  double r0_rigid = 0.0, r0_loaded = 0.0, r0_ref = 0.0;
  for (const RefRow& r : rows) {
    if (r.dy_mm != 0.0) continue;
    r0_rigid = primary(s, 0.0).rolling_radius;
    r0_loaded = loaded_reference(s, r).ref.loaded_rolling_radius;
    r0_ref = r.r_roll_mm;
  }
  std::printf("| dy [mm] | angle CONTACT [deg] | rigid [deg] | overlap ref [deg] | diff [deg] | "
              "dr CONTACT [mm] | dr rigid [mm] | dr loaded [mm] | diff [mm] | y_track CONTACT [mm] | "
              "ours [mm] | patches |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const RefRow& r : rows) {
    const ContactPoint p = primary(s, r.dy_mm);
    const Loaded l = loaded_reference(s, r);
    const double dr_ref = r.r_roll_mm - r0_ref;
    const double dr_loaded = (l.ref.loaded_rolling_radius - r0_loaded) * 1e3;
    std::printf("| %.0f | %.3f | %.3f | %.3f | %+.3f | %.4f | %.4f | %.4f | %+.4f | %.3f | %.3f | %zu |\n",
                r.dy_mm, r.angle_rad * kDeg, p.contact_angle * kDeg, l.ref.contact_angle * kDeg,
                (l.ref.contact_angle - r.angle_rad) * kDeg, dr_ref, (p.rolling_radius - r0_rigid) * 1e3,
                dr_loaded, dr_loaded - dr_ref, r.ycp_track_mm, -l.ref.y_track * 1e3, l.count);
  }
}

}  // namespace
}  // namespace railtab
