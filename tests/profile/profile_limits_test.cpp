// SPDX-License-Identifier: Apache-2.0
// Reliability of the profile input (docs/reliability.md: hostile sizes and wrong units): limits
// checked before anything is allocated, only regular files read, and plausibility checks that
// refuse a wrong unit, a wrong orientation, a cut file and a rail that would be canted twice. Each
// test here failed (or crashed, or hung) before these checks existed.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "error_message.hpp"
#include "profile/formats/profile_checks.hpp"
#include "profile/formats/profile_io.hpp"
#include "profile/formats/profile_limits.hpp"
#include "test_profile_files.hpp"

namespace railtab::profile_limits_test {  // own namespace: unity builds compile several test files as one
namespace {

namespace fs = std::filesystem;
using test::error_message;
using test::write_test_file;

fs::path data_file(const std::string& name) {
  return fs::path(RAILTAB_SOURCE_DIR) / "tests" / "data" / "profiles" / name;
}

bool contains(const std::string& s, const std::string& piece) { return s.find(piece) != std::string::npos; }

// ../shared/hostile/profile_1e300.txt: used to crash solve_wheel (SIGSEGV, no contact found).
TEST(ProfileLimits, CoordinatesScaledBy1e300AreRefused) {
  const fs::path f = data_file("profile_1e300.txt");
  const std::string m = error_message([&] { read_profile(f, ProfileKind::wheel); });
  EXPECT_TRUE(contains(m, f.string() + ":1:")) << m;
  EXPECT_TRUE(contains(m, "beyond the coordinate limit")) << m;
}

// ../shared/hostile/profile_wide_1e6.txt: used to allocate 4 GB+ in the geometry tables.
TEST(ProfileLimits, LateralCoordinatesTimes1e6AreRefused) {
  const fs::path f = data_file("profile_wide_1e6.txt");
  const std::string m = error_message([&] { read_profile(f, ProfileKind::wheel); });
  EXPECT_TRUE(contains(m, "beyond the coordinate limit")) << m;
}

TEST(ProfileLimits, DevicesAreRefusedWithoutReading) {
  for (const char* dev : {"/dev/zero", "/dev/urandom"}) {
    if (!fs::exists(dev)) continue;
    const std::string m = error_message([&] { read_profile(dev, ProfileKind::rail); });
    EXPECT_TRUE(contains(m, dev) && contains(m, "not a regular file")) << m;
  }
}

// A FIFO without a writer: opening it must neither block nor read.
TEST(ProfileLimits, FifoIsRefusedWithoutBlocking) {
  const fs::path fifo = fs::temp_directory_path() / ("railtab_test_fifo_" + std::to_string(::getpid()));
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string m = error_message([&] { read_profile(fifo, ProfileKind::rail); });
  fs::remove(fifo);
  EXPECT_TRUE(contains(m, "not a regular file")) << m;
}

TEST(ProfileLimits, OversizedFileIsRefusedBeforeReading) {
  const fs::path f = write_test_file("", ".txt");
  fs::resize_file(f, limits::kMaxProfileFileBytes + 1);  // sparse: costs no disk
  const std::string m = error_message([&] { read_profile(f, ProfileKind::rail); });
  fs::remove(f);
  EXPECT_TRUE(contains(m, "more than the limit")) << m;
}

TEST(ProfileLimits, TooManyPointsAreRefused) {
  std::string text;
  text.reserve(limits::kMaxProfilePoints * 12);
  for (std::size_t i = 0; i <= limits::kMaxProfilePoints; ++i) text += std::to_string(i % 1000) + " 1\n";
  const fs::path f = write_test_file(text, ".txt");
  const std::string m = error_message([&] { read_profile(f, ProfileKind::rail); });
  EXPECT_TRUE(contains(m, "more than 100000 profile points")) << m;
}

// Finding 7: a file cut in the middle of its last number used to read as complete.
TEST(ProfilePlausibility, CutLastLineIsRefused) {
  std::string text = test::columns(test::uic60_points(), 1.0, -1.0);
  text.pop_back();   // the line end
  text.pop_back();   // and the last digit: "... 0.12345678" instead of "... 0.123456789"
  const fs::path f = write_test_file(text, ".txt");
  const std::string m = error_message([&] { read_profile(f, ProfileKind::rail); });
  EXPECT_TRUE(contains(m, "looks cut off")) << m;
  EXPECT_EQ(error_message([&] { read_profile(write_test_file(text + "9\n", ".txt", "_whole"), ProfileKind::rail); }), "");
}

// A SIMPACK wheel written in mm but declared in metres (units.len.f = 1): a 130 m wheel.
TEST(ProfilePlausibility, MillimetresDeclaredAsMetresAreRefused) {
  const std::string points = test::columns(test::s1002_points(), 1.0, -1.0);
  auto prw = [&](const std::string& factor) {
    return "header.begin\n  type = 1\nheader.end\nspline.begin\n  units.len.f = " + factor +
           "\n  point.begin\n" + points + "  point.end\nspline.end\n";
  };
  const std::string m = error_message(
      [&] { read_profile(write_test_file(prw("1.0"), ".prw"), ProfileKind::wheel); });
  EXPECT_TRUE(contains(m, "beyond the coordinate limit") && contains(m, "wrong length unit")) << m;
  // Declared in cm: within the coordinate limit, but a 1.29 m wide wheel.
  const std::string n = error_message(
      [&] { read_profile(write_test_file(prw("100.0"), ".prw", "_cm"), ProfileKind::wheel); });
  EXPECT_TRUE(contains(n, "width 1.29 m is not plausible for a wheel") && contains(n, "wrong length unit")) << n;
  EXPECT_EQ(error_message([&] { read_profile(write_test_file(prw("1000.0"), ".prw", "_mm"), ProfileKind::wheel); }), "");
}

// Two-column wheel written z up (the file's vertical must point down): the flange points up.
TEST(ProfilePlausibility, ZUpWheelIsRefused) {
  const fs::path f = write_test_file(test::columns(test::s1002_points(), 1.0, 1.0), ".txt");
  const std::string m = error_message([&] { read_profile(f, ProfileKind::wheel); });
  EXPECT_TRUE(contains(m, "the flange points up")) << m;
}

// A mirror flag too many: the flange ends up on the field side.
TEST(ProfilePlausibility, MirroredWheelIsRefused) {
  const std::string points = test::columns(test::s1002_points(), 1.0, -1.0);
  const std::string text = "header.begin\n  type = 1\nheader.end\nspline.begin\n  mirror.y = 1\n"
                           "  point.begin\n" + points + "  point.end\nspline.end\n";
  const std::string m = error_message([&] { read_profile(write_test_file(text, ".prw"), ProfileKind::wheel); });
  EXPECT_TRUE(contains(m, "is on the field side of the running circle")) << m;
}

// A wheel whose origin lies near its flange back (60 mm from the running circle; CONTACT's
// worn_high_mileage.prw): the flange is on the correct side, the origin is not.
TEST(ProfilePlausibility, WheelOriginOffTheRunningCircleIsRefused) {
  std::vector<test::Point> pts = test::s1002_points();
  for (test::Point& p : pts) p.y += 60.0;  // u = 0 on the flange back face
  const fs::path f = write_test_file(test::columns(pts, 1.0, -1.0), ".txt");
  const std::string m = error_message([&] { read_profile(f, ProfileKind::wheel); });
  EXPECT_TRUE(contains(m, "the lateral origin is not on the running circle")) << m;
}

TEST(ProfilePlausibility, UpsideDownRailIsRefused) {
  const fs::path f = write_test_file(test::columns(test::uic60_points(), 1.0, 1.0), ".txt");
  const std::string m = error_message([&] { read_profile(f, ProfileKind::rail); });
  EXPECT_TRUE(contains(m, "highest point")) << m;
}

TEST(ProfilePlausibility, RailWithGaugeFaceOnTheFieldSideIsRefused) {
  std::vector<test::Point> pts = test::uic60_points();
  std::erase_if(pts, [](const test::Point& p) { return p.y > 25.0; });  // field side measured short
  const fs::path f = write_test_file(test::columns(pts, -1.0, -1.0), ".txt");  // then mirrored
  const std::string m = error_message([&] { read_profile(f, ProfileKind::rail); });
  EXPECT_TRUE(contains(m, "lateral axis mirrored")) << "[" << m << "]";
}

// The shipped shapes pass every check.
TEST(ProfilePlausibility, RealProfilesPass) {
  EXPECT_EQ(error_message([] { check_plausible_profile(*make_s1002_profile(), "S1002"); }), "");
  EXPECT_EQ(error_message([] { check_plausible_profile(*make_uic60_profile(), "UIC60"); }), "");
}

}  // namespace
}  // namespace railtab::profile_limits_test
