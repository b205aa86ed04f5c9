// SPDX-License-Identifier: Apache-2.0
// MiniProf reader (src/profile/formats/miniprof.cpp): the three forms of the file (old style with a
// banner, keyed header, plain columns), the automatic orientation and the wheel placement, a
// vertical flange back and an undercut gauge corner kept as parametric curves, and the
// file:line errors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "error_message.hpp"
#include "profile/curves/parametric_profile.hpp"
#include "profile/formats/profile_io.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"
#include "test_profile_files.hpp"

namespace railtab {
namespace {

using test::error_message;
using test::Point;
using test::write_test_file;

bool contains(const std::string& s, const std::string& piece) { return s.find(piece) != std::string::npos; }

// S1002 as a MiniProf wheel: X from the flange back (X = S + 70 mm), Y down, with the vertical
// back face (X = 0) measured from 10 mm above the S = -69 point: a curve, not a function z(u).
std::vector<Point> miniprof_wheel_points() {
  std::vector<Point> pts;
  const std::vector<Point> s = test::s1002_points(1.0);
  const double back_top = -s.front().z - 10.0;  // Y (down) of the highest back-face point
  for (double y = back_top; y < -s.front().z - 1.0; y += 2.0) pts.push_back({0.0, y});
  pts.push_back({0.3, -s.front().z - 0.3});  // round the corner to the S = -69 point
  for (const Point& p : s) pts.push_back({p.y + 70.0, -p.z});
  return pts;
}

// UIC60 with an undercut below the gauge corner (the head overhangs its web side), z up [mm].
std::vector<Point> undercut_rail_points() {
  std::vector<Point> pts = {{-35.2, -34.0}, {-36.2, -33.2}, {-36.9, -31.8}, {-37.0, -30.5}};
  for (const Point& p : test::uic60_points(0.5)) pts.push_back(p);
  return pts;
}

void expect_matches_s1002(const ProfilePtr& p) {
  const ProfilePtr ref = make_s1002_profile();
  for (double u : {-0.060, -0.050, -0.030, -0.010, 0.0, 0.020, 0.050}) {
    EXPECT_NEAR(p->eval(u).z, ref->eval(u).z, 2e-6) << "u = " << u;
  }
}

TEST(MiniProf, OldStyleWheelWithVerticalBackFace) {
  const std::string text = "#MINIWHEELPROF\ntest_T(R).whl\nMINIPROF 2020\nStock.......:\n"
                           "Car Number..:\n\" 32.50 28.00 10.80\n(Sd/Sh/qR)\n\n" +
                           test::columns(miniprof_wheel_points());
  const ProfilePtr p = read_profile(write_test_file(text, ".whl"), ProfileKind::wheel);
  EXPECT_TRUE(p->parametric());  // the back face is vertical
  EXPECT_NEAR(p->u_min(), -0.070, 1e-12);  // flange back placed at u = -70 mm
  EXPECT_NEAR(p->eval(0.0).z, 0.0, 1e-9);  // z = 0 on the running circle
  expect_matches_s1002(p);
  // The curve runs from the top of the back face down and round the flange: its first point is
  // the highest back-face point, at u = -70 mm.
  const CurveSample first = p->curve(p->t_min());
  EXPECT_NEAR(first.y, -0.070, 1e-12);
  EXPECT_GT(first.z, p->curve(p->t_min() + 0.002).z);
}

TEST(MiniProf, KeyedHeaderRailMirroredWithUndercut) {
  // As the instrument writes it: X towards the track (gauge face at +X), Y up, four columns;
  // quoted lines are comments (the quoted ColumnDef must not count), empty values are fine.
  std::string text = "Filename=test.trc\nProgramName=\nMPTypeNo=299\nXYPoints=0\nXOffset=0.0000\n"
                     "Tilt=\n\"RefPoint1=\"\n\"ColumnDef=X,Y,A\"\nUOF1=#title\n"
                     "RefPoint1=0.0000, 0.0000\nColumnDef=X,Y,A,C\n\n";
  const std::vector<Point> pts = undercut_rail_points();
  for (auto it = pts.rbegin(); it != pts.rend(); ++it) {  // file order: field to gauge
    text += fmt::format("{:.6f} {:.6f} 0.0000 -0.0100\n", -it->y, it->z);
  }
  const ProfilePtr p = read_profile(write_test_file(text, ".ban"), ProfileKind::rail);
  EXPECT_TRUE(p->parametric());
  const ProfilePtr ref = make_uic60_profile();
  for (double u : {-0.030, -0.010, 0.0, 0.015, 0.030}) EXPECT_NEAR(p->eval(u).z, ref->eval(u).z, 1e-6) << u;
  // The undercut: the curve starts at its lowest point, inside the gauge corner, going outward.
  const CurveSample start = p->curve(p->t_min());
  EXPECT_NEAR(start.y, -0.0352, 1e-9);
  EXPECT_NEAR(start.z, -0.0340, 1e-9);
  EXPECT_LT(start.dy, 0.0);  // at first towards the track: the overhang
  EXPECT_NEAR(p->u_min(), -0.0370, 1e-9);
}

TEST(MiniProf, PlainColumnsWheelWithYDownAndAutomaticOrientation) {
  // No header at all, the wheel measured from the field side (X towards the track): mirrored
  // and reversed automatically.
  std::string text;
  const std::vector<Point> pts = miniprof_wheel_points();
  for (auto it = pts.rbegin(); it != pts.rend(); ++it) text += fmt::format("{:.9f},{:.9f}\n", 200.0 - it->y, it->z);
  const ProfilePtr p = read_profile(write_test_file(text, ".whl"), ProfileKind::wheel);
  EXPECT_NEAR(p->u_min(), -0.070, 1e-12);
  expect_matches_s1002(p);
}

TEST(MiniProf, ExplicitMirrorKeysOverrideTheAutomatic) {
  const std::string text = test::columns(miniprof_wheel_points());
  const std::filesystem::path f = write_test_file(text, ".whl");
  ProfileReadOptions as_is;
  as_is.mirror_y = AxisMirror::no;
  as_is.mirror_z = AxisMirror::no;  // Y down: already MiniProf's wheel convention
  expect_matches_s1002(read_profile(f, ProfileKind::wheel, as_is));
  ProfileReadOptions wrong = as_is;
  wrong.mirror_y = AxisMirror::yes;  // puts the flange on the field side
  const std::string m = error_message([&] { read_profile(f, ProfileKind::wheel, wrong); });
  EXPECT_TRUE(contains(m, "field side")) << m;
  wrong = as_is;
  wrong.mirror_z = AxisMirror::yes;  // flange up
  const std::string n = error_message([&] { read_profile(f, ProfileKind::wheel, wrong); });
  EXPECT_TRUE(contains(n, "flange points up") || contains(n, "no flange")) << n;
}

TEST(MiniProf, MirrorKeysRefusedForOtherFormats) {
  const std::filesystem::path f = write_test_file(test::columns(test::s1002_points(), 1.0, -1.0), ".txt");
  ProfileReadOptions o;
  o.mirror_y = AxisMirror::yes;
  const std::string m = error_message([&] { read_profile(f, ProfileKind::wheel, o); });
  EXPECT_TRUE(contains(m, "apply to MiniProf files only")) << m;
}

TEST(MiniProf, ErrorsNameFileAndLine) {
  const std::string rail = test::columns(test::uic60_points(1.0), -1.0, 1.0);
  auto message = [](const std::string& text, const std::string& suffix) {
    const std::filesystem::path f = write_test_file(text, ".ban", suffix);
    return std::make_pair(f.string(), error_message([&] { read_profile(f, ProfileKind::rail); }));
  };
  auto [f1, m1] = message("ColumnDef=X,Y,A\n\n1 2 3\n2 3 4\n3 4x 5\n4 5 6\n", "_number");
  EXPECT_TRUE(contains(m1, f1 + ":5:") && contains(m1, "malformed number '4x'")) << m1;
  auto [f2, m2] = message("ColumnDef=X,Y,A\n\n1 2 3\n2 3\n", "_columns");
  EXPECT_TRUE(contains(m2, f2 + ":4:") && contains(m2, "expected 3 columns")) << m2;
  auto [f3, m3] = message("ColumnDef=X,A\n\n1 2\n", "_coldef");
  EXPECT_TRUE(contains(m3, f3 + ":1:") && contains(m3, "names no X and Y")) << m3;
  auto [f4, m4] = message(rail + "Comment=late\n", "_late_key");
  EXPECT_TRUE(contains(m4, "header line 'Comment=late' after the data")) << m4;
  auto [f5, m5] = message("[FileInfo]\nVersion=1\n", "_mpt");
  EXPECT_TRUE(contains(m5, f5 + ":1:") && contains(m5, ".mpt")) << m5;
  // Old style without the blank line that ends the free header: no data at all.
  auto [f6, m6] = message("#MINIPROF\nMINIPROF 2020\n" + rail, "_no_blank");
  EXPECT_TRUE(contains(m6, "too few profile points: 0")) << m6;
}



std::filesystem::path testbank_file(const std::string& name) {
  return std::filesystem::path(RAILTAB_SOURCE_DIR) / "tests" / "data" / "profiles" / name;
}

// CONTACT testbank's avg_HR.BAN as shipped: keyed header, quoted keys, X towards the gauge face,
// Y up, four columns, and one point that steps back by 0.01 mm at the same Y (29.27 -> 29.26):
// noise, dropped, so the rest is a function z(u).
TEST(MiniProf, TestbankRailAvgHrAsShipped) {
  const ProfilePtr p = read_profile(testbank_file("avg_HR.BAN"), ProfileKind::rail);
  EXPECT_FALSE(p->parametric());
  EXPECT_NEAR(p->u_min(), -0.04659, 1e-9);  // the gauge face (file X = +46.59) on the track side
  EXPECT_NEAR(p->u_max(), 0.01173, 1e-9);
  const CurveSample gauge_end = p->curve(p->t_min());
  EXPECT_NEAR(gauge_end.z, -0.02542, 1e-9);  // Y up kept: 25.42 mm below the file origin
  EXPECT_NEAR(p->eval(-0.0036).z, -0.00021, 2e-5);  // the top, near file X = 3.6 mm
}

// CONTACT testbank's Car7216_0001r.whl as shipped: old style, X from the flange back, Y down, a
// vertical back face (X goes back and forth by 0.1 mm) and seven points out of order at the
// flange tip: a curve.
TEST(MiniProf, TestbankWheelCar7216AsShipped) {
  const ProfilePtr p = read_profile(testbank_file("Car7216_0001r.whl"), ProfileKind::wheel);
  ASSERT_TRUE(p->parametric());
  const auto* curve = dynamic_cast<const ParametricProfile*>(p.get());
  ASSERT_TRUE(curve != nullptr);
  // Innermost point X = -0.1571 mm goes to u = -70 mm; the tread at u = 0 (X = 69.8429 mm) has
  // Y = 0.10212 mm, so the flange tip (X = 15.8950, Y = 27.8119, file line 222) is 27.7098 mm down.
  EXPECT_NEAR(p->u_min(), -0.070, 1e-12);
  EXPECT_NEAR(p->eval(0.0).z, 0.0, 1e-7);  // zero on the chord between the points around u = 0
  CurveSample tip = p->curve(curve->knots().front());
  for (double s : curve->knots()) {  // the knot nearest the tip's lateral position
    const CurveSample c = p->curve(s);
    if (std::abs(c.y + 0.0539479) < std::abs(tip.y + 0.0539479)) tip = c;
  }
  EXPECT_NEAR(tip.y, (15.8950 + 0.1571 - 70.0) * 1e-3, 1e-12);
  EXPECT_NEAR(tip.z, -(27.8119 - 0.102116) * 1e-3, 2e-8);
}

}  // namespace
}  // namespace railtab
