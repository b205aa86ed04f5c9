// SPDX-License-Identifier: Apache-2.0
// Tests of reading profile files (src/profile/formats/profile_io.hpp).
#include "profile/formats/profile_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/check.hpp"
#include "mbench_files.hpp"
#include "profile/curves/parametric_profile.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/curves/spline_profile.hpp"

namespace railtab {
namespace {

namespace fs = std::filesystem;

// The tests of the file formats use small shapes, not wheels or rails: no plausibility checks.
ProfileReadOptions format_only(double smoothing_length = 0.0) {
  ProfileReadOptions o;
  o.smoothing_length = smoothing_length;
  o.check_plausibility = false;
  return o;
}

// Writes `text` to a fresh file in the temp directory, named after the running test.
fs::path write_temp(const std::string& text, const std::string& extension) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::temp_directory_path() / "railtab_profile_io_test";
  fs::create_directories(dir);
  const fs::path file = dir / (std::string(info->name()) + extension);
  std::ofstream(file) << text;
  return file;
}

// Expects read_profile to throw an Error whose message contains every given piece.
void expect_error(const fs::path& file, ProfileKind kind, std::initializer_list<std::string> pieces) {
  try {
    read_profile(file, kind);
    ADD_FAILURE() << "no error for " << file;
  } catch (const Error& e) {
    const std::string message = e.what();
    for (const std::string& piece : pieces) {
      EXPECT_NE(message.find(piece), std::string::npos) << "'" << piece << "' not in: " << message;
    }
  }
}

// A SIMPACK file around the given option lines and point lines.
std::string simpack(int type, const std::string& options, const std::string& points) {
  return "! test profile\n  header.begin\n    version = 1\n    type = " + std::to_string(type) +
         "  ! 0=rail, 1=wheel\n  header.end\n  spline.begin\n    comment = 'a ! inside quotes'\n" +
         options + "    point.begin\n" + points + "    point.end\n  spline.end\n";
}

// Points of z_down = 0.01 y^2 (mm), y = -6 .. 6 mm, as "y z" lines.
std::string parabola_points(bool descending) {
  std::string s;
  for (int i = 0; i <= 12; ++i) {
    const int y = descending ? 6 - i : i - 6;
    s += std::to_string(y) + "\t" + std::to_string(0.01 * y * y) + "\n";
  }
  return s;
}

TEST(ReadProfile, TwoColumnMmZDownToProfileFrame) {
  const fs::path f = write_temp("# lateral vertical [mm]\n% another comment\n\n" +
                                    parabola_points(false) + "! end\n",
                                ".txt");
  const ProfilePtr p = read_profile(f, ProfileKind::rail, format_only());
  EXPECT_EQ(p->name(), "TwoColumnMmZDownToProfileFrame");
  EXPECT_EQ(p->kind(), ProfileKind::rail);
  EXPECT_NEAR(p->u_min(), -0.006, 1e-15);
  EXPECT_NEAR(p->u_max(), 0.006, 1e-15);
  // z_down = 0.01 y^2 [mm] -> z = -10 u^2 [m]: a crown, exact for the not-a-knot spline.
  EXPECT_NEAR(p->eval(0.0035).z, -10.0 * 0.0035 * 0.0035, 1e-15);
  EXPECT_NEAR(p->eval(0.0035).d2z, -20.0, 1e-8);
}

TEST(ReadProfile, TwoColumnDescendingAndCommasAccepted) {
  std::string text;
  for (int i = 0; i <= 12; ++i) {
    const int y = 6 - i;
    text += std::to_string(y) + ", " + std::to_string(0.5 + 0.02 * y) + "\n";
  }
  const ProfilePtr p = read_profile(write_temp(text, ".csv"), ProfileKind::wheel, format_only());
  EXPECT_NEAR(p->eval(0.001).z, -(0.5 + 0.02) * 1e-3, 1e-15);
  EXPECT_NEAR(p->eval(0.001).dz, -0.02, 1e-12);
}

TEST(ReadProfile, SimpackOptionsApplied) {
  // File y = -u in cm (units.len.f = 100), z up (mirror.z), data given in descending order.
  std::string points;
  for (int i = 0; i <= 10; ++i) {
    const double u_mm = -5.0 + i;  // ascending u
    points += fmt::format("{} {} 1.0\n", -u_mm / 10.0, -(0.02 * u_mm * u_mm) / 10.0);
  }
  const std::string options =
      "    mirror.y = 1\n    mirror.z = 1\n    inversion = 1\n    units.len.f = +1.0e+02\n";
  const ProfilePtr p = read_profile(write_temp(simpack(1, options, points), ".prw"), ProfileKind::wheel,
                                    format_only());
  EXPECT_NEAR(p->u_min(), -0.005, 1e-15);
  EXPECT_NEAR(p->u_max(), 0.005, 1e-15);
  // After mirroring: z_down = 0.02 u^2 [mm] -> z = -20 u^2 [m].
  EXPECT_NEAR(p->eval(0.0025).z, -20.0 * 0.0025 * 0.0025, 1e-15);
}

TEST(ReadProfile, SimpackShiftAndRotate) {
  // A line z_down = 0 shifted by shift.z = 1 mm and rotated by 0.1 rad (given in degrees).
  std::string points;
  for (int i = 0; i <= 8; ++i) points += fmt::format("{} 0\n", -4 + i);
  const std::string options =
      "    shift.z = 1\n    rotate = 5.729577951308232\n    units.ang.f = 57.29577951308232\n";
  const ProfilePtr p = read_profile(write_temp(simpack(0, options, points), ".prr"), ProfileKind::rail,
                                    format_only());
  // SIMPACK rotates (y, z) by [c -s; s c]: z' = s y + c z -> slope dz_down/dy = tan(0.1).
  EXPECT_NEAR(p->eval(0.0).dz, -std::tan(0.1), 1e-12);
  // The shifted line's foot point (0, 1 mm) goes to (-sin, cos) mm.
  EXPECT_NEAR(p->eval(-std::sin(0.1) * 1e-3).z, -std::cos(0.1) * 1e-3, 1e-15);
}

TEST(ReadProfile, SmoothingLengthPassedOn) {
  const fs::path f = write_temp(parabola_points(false), ".txt");
  const auto p = std::dynamic_pointer_cast<const SplineProfile>(read_profile(f, ProfileKind::rail, format_only(0.002)));
  ASSERT_TRUE(p != nullptr);
  EXPECT_EQ(p->smoothing_length(), 0.002);
  EXPECT_EQ(p->eval(p->u_min()).d2z, 0.0);  // natural end of the smoothing spline
}

TEST(ReadProfile, UnreadableFile) {
  const fs::path missing = fs::temp_directory_path() / "railtab_no_such_dir" / "nothing.txt";
  expect_error(missing, ProfileKind::rail, {missing.string(), "cannot open"});
}

TEST(ReadProfile, MalformedNumber) {
  const fs::path f = write_temp("1 2\n2 3\n3 4x\n4 5\n5 6\n", ".txt");
  expect_error(f, ProfileKind::rail, {f.string() + ":3:", "malformed number '4x'"});
}

TEST(ReadProfile, MalformedNumberInSimpackOption) {
  const fs::path f = write_temp(simpack(0, "    mirror.y = yes\n", parabola_points(false)), ".prr");
  expect_error(f, ProfileKind::rail, {f.string() + ":8:", "malformed number 'yes'", "mirror.y"});
}

TEST(ReadProfile, WrongColumnCount) {
  const fs::path f = write_temp("1 2\n2 3\n3 4 5\n4 5\n5 6\n", ".txt");
  expect_error(f, ProfileKind::rail, {f.string() + ":3:", "expected 2 columns", "found 3"});
  const fs::path g = write_temp(simpack(0, "", "1 2\n2 3\n3\n4 5\n5 6\n"), ".prr");
  expect_error(g, ProfileKind::rail, {g.string() + ":11:", "expected 2 or 3 columns", "found 1"});
}

TEST(ReadProfile, NotFinite) {
  const fs::path f = write_temp("1 2\n2 nan\n3 4\n4 5\n5 6\n", ".txt");
  expect_error(f, ProfileKind::rail, {f.string() + ":2:", "not finite"});
  const fs::path g = write_temp("1 2\n2 3\n-inf 4\n4 5\n5 6\n", ".txt");
  expect_error(g, ProfileKind::rail, {g.string() + ":3:", "not finite"});
}

TEST(ReadProfile, TooFewPoints) {
  const fs::path f = write_temp("# three points\n1 2\n2 3\n3 4\n", ".txt");
  expect_error(f, ProfileKind::rail, {f.string() + ":4:", "too few profile points: 3"});
  const fs::path g = write_temp("# nothing\n\n", ".txt");
  expect_error(g, ProfileKind::rail, {g.string(), "too few profile points: 0"});
}

TEST(ReadProfile, NonMonotonicLateralGivesParametricCurve) {
  // An overhang: the lateral coordinate turns back (3 -> 2.5 mm). Read as a curve through the
  // points in their order (it used to be refused as "not monotonic").
  const fs::path f = write_temp("1 2\n2 3\n3 4\n2.5 5\n5 6\n", ".txt");
  const ProfilePtr p = read_profile(f, ProfileKind::rail, format_only());
  ASSERT_TRUE(p->parametric());
  const auto* curve = dynamic_cast<const ParametricProfile*>(p.get());
  ASSERT_TRUE(curve != nullptr);
  const double expected[5][2] = {{1, -2}, {2, -3}, {3, -4}, {2.5, -5}, {5, -6}};
  for (std::size_t i = 0; i < 5; ++i) {
    const CurveSample c = p->curve(curve->knots()[i]);
    EXPECT_NEAR(c.y, expected[i][0] * 1e-3, 1e-15) << i;
    EXPECT_NEAR(c.z, expected[i][1] * 1e-3, 1e-15) << i;
  }
  // A descending file that turns back is reversed first, then kept as a curve.
  const fs::path g = write_temp("5 2\n4 3\n4.5 4\n2 5\n1 6\n", ".txt");
  const ProfilePtr q = read_profile(g, ProfileKind::rail, format_only());
  EXPECT_TRUE(q->parametric());
  EXPECT_NEAR(q->curve(q->t_min()).y, 0.001, 1e-15);
  EXPECT_NEAR(q->curve(q->t_max()).y, 0.005, 1e-15);
}

TEST(ReadProfile, DuplicatePoints) {
  const fs::path f = write_temp("1 2\n2 3\n2 3\n3 4\n4 5\n", ".txt");
  expect_error(f, ProfileKind::rail, {f.string() + ":3:", "duplicate point", "line 2"});
}

TEST(ReadProfile, SimpackStructureErrors) {
  const fs::path wrong_kind = write_temp(simpack(1, "", parabola_points(false)), ".prw");
  expect_error(wrong_kind, ProfileKind::rail, {wrong_kind.string() + ":4:", "type = 1", "wheel"});
  const fs::path unclosed = write_temp("spline.begin\npoint.begin\n1 2\n2 3\n3 4\n4 5\n", ".prr");
  expect_error(unclosed, ProfileKind::rail, {unclosed.string() + ":6:", "not closed"});
  const fs::path stray = write_temp(simpack(0, "    what is this\n", parabola_points(false)), ".prr");
  expect_error(stray, ProfileKind::rail, {stray.string() + ":8:", "unexpected text"});
}

TEST(ReadProfile, MBenchWheelInS1002Orientation) {
  RAILTAB_REQUIRE_MBENCH(file, "MBench_S1002_v3.prw");
  const ProfilePtr p = read_profile(file, ProfileKind::wheel);
  EXPECT_EQ(p->kind(), ProfileKind::wheel);
  // mirror.y and inversion bring the file (y = -S, z = F) to u = S, z = -F: field side end at
  // +60 mm with F(60) = -2.635676 mm, flange back towards -70 mm, flange tip 28 mm down at -55.
  EXPECT_NEAR(p->u_max(), 0.060, 1e-9);
  EXPECT_NEAR(p->u_min(), -0.069612628, 1e-12);  // the file comments out its S = -70 point
  EXPECT_NEAR(p->eval(0.060).z, 2.6356764e-3, 1e-12);
  EXPECT_NEAR(p->eval(-0.055).z, -0.028, 1e-6);
  EXPECT_NEAR(p->eval(0.0).z, 0.0, 1e-6);
  const ProfilePtr s1002 = make_s1002_profile();
  EXPECT_NEAR(p->eval(0.0).dz, s1002->eval(0.0).dz, 1e-4);
}

TEST(ReadProfile, MBenchRailAsCantedInFileFrame) {
  RAILTAB_REQUIRE_MBENCH(file, "MBench_UIC60_v3.prr");
  const ProfilePtr p = read_profile(file, ProfileKind::rail);
  // u = y of the file, z = -z_file: its highest point is (almost) the file origin, the head
  // centre lies about 7.5 mm on the gauge side (u < 0) of it because of the 1:40 cant.
  EXPECT_NEAR(p->u_min(), -0.043704898, 1e-12);
  EXPECT_NEAR(p->u_max(), 0.030595912, 1e-12);
  double u_top = 0.0;
  double z_top = -1.0;
  for (double u = -0.02; u <= 0.02; u += 1e-5) {
    if (p->eval(u).z > z_top) {
      z_top = p->eval(u).z;
      u_top = u;
    }
  }
  EXPECT_NEAR(u_top, 0.0, 0.0005);
  EXPECT_NEAR(z_top, 0.0, 1e-6);
  // The two side faces end at the same depth: the head leans towards u < 0 (gauge side, track
  // centre) and each side face is steep (1:20 -/+ 1:40 from vertical).
  EXPECT_NEAR(p->eval(p->u_min()).z, p->eval(p->u_max()).z, 0.003);
}

}  // namespace
}  // namespace railtab
