// SPDX-License-Identifier: Apache-2.0
// Test helper: profile files written from the built-in S1002 and UIC60 shapes, in the formats
// the readers take, so that each test states its file in a few lines.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"

namespace railtab::test {

struct Point {
  double y, z;  // [mm], in whatever frame the test writes
};

// Writes `text` to a fresh file in the temp directory, named after the running test.
inline std::filesystem::path write_test_file(const std::string& text, const std::string& extension,
                                             const std::string& suffix = "") {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "railtab_profile_tests";
  std::filesystem::create_directories(dir);
  const std::filesystem::path file =
      dir / (std::string(info->test_suite_name()) + "_" + info->name() + suffix + extension);
  std::ofstream(file) << text;
  return file;
}

// S1002 in profile frame [mm] (u = S, z = -F), S from -69 to +60 mm in steps of `step`.
inline std::vector<Point> s1002_points(double step = 0.5) {
  const ProfilePtr p = make_s1002_profile();
  std::vector<Point> out;
  for (double s = -69.0; s <= 60.0 + 1e-9; s += step) out.push_back({s, p->eval(s * 1e-3).z * 1e3});
  return out;
}

// UIC60 in profile frame [mm], u from -36.5 to +36.5 mm in steps of `step`.
inline std::vector<Point> uic60_points(double step = 0.5) {
  const ProfilePtr p = make_uic60_profile();
  std::vector<Point> out;
  for (double u = -36.5; u <= 36.5 + 1e-9; u += step) out.push_back({u, p->eval(u * 1e-3).z * 1e3});
  return out;
}

// "a b" lines with a = sy * y, b = sz * z (mm), full precision.
inline std::string columns(const std::vector<Point>& pts, double sy = 1.0, double sz = 1.0) {
  std::string s;
  char buf[96];
  for (const Point& p : pts) {
    std::snprintf(buf, sizeof buf, "%.9f %.9f\n", sy * p.y, sz * p.z);
    s += buf;
  }
  return s;
}

}  // namespace railtab::test
