// SPDX-License-Identifier: Apache-2.0
// The SIMPACK profile text (src/profile/formats/simpack_writer.hpp): read back by read_profile, kind
// and file name checks, bad input refused.
#include "profile/formats/simpack_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "error_message.hpp"
#include "core/check.hpp"
#include "profile/formats/profile_io.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/curves/spline_profile.hpp"
#include "profile/standard/uic60.hpp"

namespace railtab {
namespace {

namespace fs = std::filesystem;
using test::error_message;

fs::path temp_dir() {
  const fs::path dir = fs::temp_directory_path() / "railtab_simpack_writer_test";
  fs::create_directories(dir);
  return dir;
}

// The file as the Python binding and railtab simulate write it (there through the generator's safe
// output file; src/ writes no file).
void write_simpack_profile(const fs::path& file, ProfileKind kind, const std::vector<double>& u,
                           const std::vector<double>& z, std::string_view comment = {}) {
  check_simpack_file_name(file, kind);
  std::ofstream(file, std::ios::binary) << simpack_profile_text(kind, u, z, comment);
}

struct Points {
  std::vector<double> u, z;
};

// A profile sampled every `step` over its whole range.
Points sample(const Profile& p, double step) {
  Points s;
  const int n = static_cast<int>(std::floor((p.u_max() - p.u_min()) / step));
  for (int i = 0; i <= n; ++i) {
    const double u = p.u_min() + step * i;
    s.u.push_back(u);
    s.z.push_back(p.eval(u).z);
  }
  return s;
}

// Written then read with read_profile: the same points come back, and the interpolating spline
// through them is the one through the original points (so the shape survives the file).
void expect_round_trip(const Profile& original, ProfileKind kind, const fs::path& file) {
  const Points s = sample(original, 0.0005);
  write_simpack_profile(file, kind, s.u, s.z, "round trip 'test'");
  const ProfilePtr back = read_profile(file, kind);
  EXPECT_EQ(back->kind(), kind);
  EXPECT_NEAR(back->u_min(), s.u.front(), 1e-15);
  EXPECT_NEAR(back->u_max(), s.u.back(), 1e-15);
  double worst = 0.0;
  for (std::size_t i = 0; i < s.u.size(); ++i) worst = std::max(worst, std::abs(back->eval(s.u[i]).z - s.z[i]));
  EXPECT_LT(worst, 1e-15) << "largest point difference " << worst << " m";
  // Between the points: the read profile is the spline through the written points (the file
  // carries the profile itself, not only its points).
  const SplineProfile direct("direct", kind, s.u, s.z, 0.0);
  double between = 0.0;
  for (std::size_t i = 0; i + 1 < s.u.size(); ++i) {
    const double u = 0.5 * (s.u[i] + s.u[i + 1]);
    between = std::max(between, std::abs(back->eval(u).z - direct.eval(u).z));
  }
  EXPECT_LT(between, 1e-12) << "largest mid-point difference " << between << " m";
}

TEST(SimpackWriter, WheelRoundTrip) {
  expect_round_trip(*make_s1002_profile(), ProfileKind::wheel, temp_dir() / "s1002.prw");
}

TEST(SimpackWriter, RailRoundTrip) {
  expect_round_trip(*make_uic60_profile(), ProfileKind::rail, temp_dir() / "uic60.prr");
}

TEST(SimpackWriter, HeaderTypeAndNeutralOptions) {
  const std::vector<double> u{-0.01, 0.0, 0.01, 0.02}, z{0.001, 0.0, -0.0005, -0.002};
  const std::string wheel = simpack_profile_text(ProfileKind::wheel, u, z, "it's");
  EXPECT_NE(wheel.find("type           =  1"), std::string::npos);
  EXPECT_NE(wheel.find("comment        = 'it s'"), std::string::npos) << "quotes replaced";
  EXPECT_NE(wheel.find("mirror.y       =  0"), std::string::npos);
  EXPECT_NE(wheel.find("units.len.f    = +1.000000000000000e+03"), std::string::npos);
  // z up 0.001 m -> z down -1 mm in the file; u in mm.
  EXPECT_NE(wheel.find("-1.0000000000000000e+01 -1.0000000000000000e+00"), std::string::npos) << wheel;
  const std::string rail = simpack_profile_text(ProfileKind::rail, u, z);
  EXPECT_NE(rail.find("type           =  0"), std::string::npos);
  EXPECT_EQ(wheel.find("Date"), std::string::npos) << "no dates: the same profile gives the same bytes";
}

TEST(SimpackWriter, KindMismatchRefusedOnRead) {
  const Points s = sample(*make_s1002_profile(), 0.001);
  const fs::path file = temp_dir() / "as_wheel.prw";
  write_simpack_profile(file, ProfileKind::wheel, s.u, s.z);
  EXPECT_THROW(read_profile(file, ProfileKind::rail), Error);
}

TEST(SimpackWriter, BadInputRefusedAndNothingWritten) {
  const std::vector<double> u{0.0, 0.001, 0.002, 0.003}, z{0.0, 0.0, 0.0, 0.0};
  const fs::path wrong_ext = temp_dir() / "wheel.prr";
  fs::remove(wrong_ext);
  EXPECT_NE(error_message([&] { write_simpack_profile(wrong_ext, ProfileKind::wheel, u, z); }).find(".prw"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(wrong_ext));
  const std::vector<double> three{0.0, 0.001, 0.002};
  EXPECT_NE(error_message([&] { simpack_profile_text(ProfileKind::wheel, three, three); }).find("at least 4"),
            std::string::npos);
  const std::vector<double> back{0.0, 0.002, 0.001, 0.003};
  EXPECT_NE(error_message([&] { simpack_profile_text(ProfileKind::wheel, back, z); }).find("not increasing"),
            std::string::npos);
  const std::vector<double> nan{0.0, std::nan(""), 0.0, 0.0};
  EXPECT_NE(error_message([&] { simpack_profile_text(ProfileKind::wheel, u, nan); }).find("not finite"),
            std::string::npos);
}

}  // namespace
}  // namespace railtab
