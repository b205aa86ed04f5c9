// SPDX-License-Identifier: Apache-2.0
// The geometry's side of the profile-input reliability checks (hostile sizes, wrong units):
// profiles too large for its tables are refused before any allocation, and a rail file with the
// cant built in is not canted a second time.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "error_message.hpp"
#include "geometry/contact_geometry.hpp"
#include "profile/mbench_files.hpp"
#include "profile/formats/profile_checks.hpp"
#include "profile/formats/profile_io.hpp"
#include "profile/curves/spline_profile.hpp"
#include "profile/test_profile_files.hpp"

namespace railtab {
namespace {

using test::error_message;
using test::write_test_file;

bool contains(const std::string& s, const std::string& piece) { return s.find(piece) != std::string::npos; }

// The same shapes built in code (no reader): the geometry refuses them before any allocation.
TEST(ProfileLimits, GeometryRefusesHugeProfilesBeforeAllocating) {
  std::vector<double> u, z;
  for (int i = 0; i < 200; ++i) {
    u.push_back((-69.0 + i * 0.6) * 1e-3 * 1e6);  // 129 km wide
    z.push_back(1e-3 * std::cos(i * 0.1));
  }
  const ProfilePtr wide = std::make_shared<const SplineProfile>("wide", ProfileKind::wheel, u, z);
  const ProfilePtr rail = make_uic60_profile();
  const std::string m = error_message(
      [&] { ContactGeometrySolver(wide, rail, wide, rail, TrackGeometry{}, WheelsetGeometry{}); });
  EXPECT_TRUE(contains(m, "'wide'") && contains(m, "more than the limit")) << m;
  for (double& x : u) x *= 1e294;  // 1e300-scaled
  for (double& x : z) x *= 1e300;
  const ProfilePtr huge = std::make_shared<const SplineProfile>("huge", ProfileKind::wheel, u, z);
  const std::string n = error_message(
      [&] { ContactGeometrySolver(huge, rail, huge, rail, TrackGeometry{}, WheelsetGeometry{}); });
  EXPECT_TRUE(contains(n, "'huge'")) << n;
}

// A rail file with the 1:40 cant built in, placed with the default 1:40 inclination: canted twice.
TEST(ProfilePlausibility, PreInclinedRailIsFlaggedNotCantedTwice) {
  const double a = std::atan(1.0 / 40.0);
  std::vector<test::Point> canted;
  for (const test::Point& p : test::uic60_points(0.25)) {
    canted.push_back({std::cos(a) * p.y - std::sin(a) * p.z, std::sin(a) * p.y + std::cos(a) * p.z});
  }
  const std::filesystem::path f = write_test_file(test::columns(canted, 1.0, -1.0), ".txt");
  const ProfilePtr rail = read_profile(f, ProfileKind::rail);
  const ApparentCant cant = apparent_cant(*rail);
  EXPECT_NEAR(cant.beta, a, 2e-4);
  const ProfilePtr wheel = make_s1002_profile();
  const std::string m = error_message(
      [&] { ContactGeometrySolver(wheel, rail, wheel, rail, TrackGeometry{}, WheelsetGeometry{}); });
  EXPECT_TRUE(contains(m, "already inclined") && contains(m, "cant it twice")) << m;
  TrackGeometry flat;
  flat.rail_inclination = 0.0;
  EXPECT_EQ(error_message([&] { ContactGeometrySolver(wheel, rail, wheel, rail, flat, WheelsetGeometry{}); }), "");
  // The uninclined head passes with the default cant.
  const ProfilePtr upright = make_uic60_profile();
  EXPECT_NEAR(apparent_cant(*upright).beta, 0.0, 2e-4);
  EXPECT_EQ(error_message([&] { ContactGeometrySolver(wheel, upright, wheel, upright, TrackGeometry{}, WheelsetGeometry{}); }), "");
}

TEST(ProfilePlausibility, MBenchRailRecognisedAsPreInclined) {
  RAILTAB_REQUIRE_MBENCH(file, "MBench_UIC60_v3.prr");
  const ProfilePtr rail = read_profile(file, ProfileKind::rail);
  const ApparentCant cant = apparent_cant(*rail);
  std::cout << "MBench_UIC60_v3.prr: apparent cant " << cant.beta << " rad, asymmetry "
            << cant.asymmetry * 1e3 << " mm (as given " << cant.asymmetry_as_given * 1e3 << " mm)\n";
  EXPECT_NEAR(cant.beta, std::atan(1.0 / 40.0), 5e-4);
  const ProfilePtr wheel = make_s1002_profile();
  const std::string m = error_message(
      [&] { ContactGeometrySolver(wheel, rail, wheel, rail, TrackGeometry{}, WheelsetGeometry{}); });
  EXPECT_TRUE(contains(m, "'MBench_UIC60_v3' is already inclined")) << m;
}

}  // namespace
}  // namespace railtab
