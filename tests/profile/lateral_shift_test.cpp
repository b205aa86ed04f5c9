// SPDX-License-Identifier: Apache-2.0
// Wheels measured from the flange back (measured worn profiles): CONTACT's testbank wheel
// worn_high_mileage.prw has y = 3.9 .. 143.4 mm with y = 0 at the flange back (CONTACT places it
// with FBPOS = 0) and z = 0 on the tread at y = 70 mm. railtab's wheel frame needs u = 0 on the
// running circle, so the plausibility check refuses it as given; ProfileReadOptions::lateral_shift
// (scene profiles.wheel_shift_y) = -0.070 m places it as railtab expects, without editing the file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/check.hpp"
#include "profile/formats/profile_io.hpp"
#include "test_profile_files.hpp"

namespace railtab {
namespace {

namespace fs = std::filesystem;

// S1002 written as measured from its flange back: two columns (z down), y = S + 70 mm.
fs::path s1002_from_flange_back() {
  std::vector<test::Point> pts = test::s1002_points();
  for (test::Point& p : pts) p = {p.y + 70.0, -p.z};
  return test::write_test_file(test::columns(pts), ".txt");
}

std::string error_of(const fs::path& file, const ProfileReadOptions& o) {
  try {
    read_profile(file, ProfileKind::wheel, o);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(LateralShift, WheelMeasuredFromTheFlangeBackIsRefusedWithTheRemedy) {
  const std::string message = error_of(s1002_from_flange_back(), ProfileReadOptions{});
  EXPECT_NE(message.find("lies outside the wheel's range"), std::string::npos) << message;
  EXPECT_NE(message.find("wheel_shift_y"), std::string::npos) << message;
}

TEST(LateralShift, ShiftPlacesTheRunningCircleAtZero) {
  ProfileReadOptions o;
  o.lateral_shift = -0.070;
  const ProfilePtr shifted = read_profile(s1002_from_flange_back(), ProfileKind::wheel, o);
  const ProfilePtr s1002 = make_s1002_profile();
  EXPECT_NEAR(shifted->u_min(), -0.069, 1e-12);
  for (double u : {-0.060, -0.030, 0.0, 0.020, 0.050})
    EXPECT_NEAR(shifted->eval(u).z, s1002->eval(u).z, 2e-6) << "u = " << u;
}

TEST(LateralShift, NonFiniteOrHugeShiftIsRefused) {
  const fs::path file = s1002_from_flange_back();
  ProfileReadOptions o;
  o.lateral_shift = std::nan("");
  EXPECT_NE(error_of(file, o).find("lateral shift"), std::string::npos);
  o.lateral_shift = 2.0;
  EXPECT_NE(error_of(file, o).find("lateral shift"), std::string::npos);
}

// The file itself (Apache-2.0, CONTACT repository testbank/profiles, commit 6a9d48e): not shipped
// here; found in tests/data/profiles or in $RAILTAB_CONTACT_TESTBANK (CONTACT's testbank/profiles
// directory), skipped when absent.
fs::path worn_high_mileage() {
  const fs::path in_repo = fs::path(RAILTAB_SOURCE_DIR) / "tests" / "data" / "profiles" / "worn_high_mileage.prw";
  if (fs::exists(in_repo)) return in_repo;
  if (const char* dir = std::getenv("RAILTAB_CONTACT_TESTBANK")) {
    const fs::path f = fs::path(dir) / "worn_high_mileage.prw";
    if (fs::exists(f)) return f;
  }
  return {};
}

TEST(LateralShift, ContactTestbankWornHighMileageWheel) {
  const fs::path file = worn_high_mileage();
  if (file.empty()) {
    GTEST_SKIP() << "worn_high_mileage.prw (CONTACT testbank/profiles) not found in tests/data/profiles "
                    "or $RAILTAB_CONTACT_TESTBANK";
  }
  const std::string refused = error_of(file, ProfileReadOptions{});
  EXPECT_NE(refused.find("wheel_shift_y"), std::string::npos) << refused;
  ProfileReadOptions o;
  o.lateral_shift = -0.070;
  const ProfilePtr wheel = read_profile(file, ProfileKind::wheel, o);  // plausibility passes
  EXPECT_NEAR(wheel->u_min(), 3.934136e-3 - 0.070, 1e-9);
  EXPECT_NEAR(wheel->u_max(), 143.440840e-3 - 0.070, 1e-9);
  // The file's tread crosses z = 0 at y = 70.1 mm: the running circle of railtab's frame.
  EXPECT_LT(std::abs(wheel->eval(0.0).z), 0.01e-3);
  // Hollow: the tread rises by 1.0 mm between y = 84 mm (z = 0.33 mm up) and 130.5 mm (1.0 mm
  // down).
  EXPECT_GT(wheel->eval(0.014).z, wheel->eval(0.0).z + 0.3e-3);
}

}  // namespace
}  // namespace railtab
