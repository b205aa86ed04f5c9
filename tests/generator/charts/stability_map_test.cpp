// SPDX-License-Identifier: Apache-2.0
// Stability map (generator/charts/stability_map.hpp): one row per model variant, wheel and y;
// range checks.
#include "charts/stability_map.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/check.hpp"
#include "core/status.hpp"

namespace railtab::stability_map_test {  // own namespace: unity builds compile several test files as one
namespace {

constexpr const char* kScene = R"(
[scene]
name = "stability"
[profiles]
wheel = "s1002"
rail = "uic60"
[contact]
strips = 20
[grid]
y = [-0.001, 0.0, 0.001]
load = [60e3, 78.5e3, 100e3]
)";

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  bool quoted = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) {
      out.push_back(cell);
      cell.clear();
    } else {
      cell += c;
    }
  }
  out.push_back(cell);
  return out;
}

TEST(StabilityMap, WritesOneRowPerVariantWheelAndY) {
  const Scene scene = parse_scene(kScene, "stability.toml");
  const auto csv = std::filesystem::temp_directory_path() / "railtab_stability_map_test.csv";
  StabilityMapOptions o;
  o.y_min = 5.8e-3;  // across the left wheel's flange onset, right wheel on its tread
  o.y_max = 6.2e-3;
  o.y_step = 0.2e-3;
  write_stability_map_csv(scene, csv, o);

  std::ifstream in(csv);
  ASSERT_TRUE(in.good());
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split(line);
  const std::vector<std::string> expected = {"variant", "model", "negative_curvature", "wheel", "y_m",
                                             "roll_rad", "load_N", "status", "status_names", "patches",
                                             "points", "normal_force_N", "iterations", "error"};
  ASSERT_EQ(header, expected);
  std::map<std::string, int> col;
  for (std::size_t i = 0; i < header.size(); ++i) col[header[i]] = static_cast<int>(i);

  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line)) rows.push_back(split(line));
  ASSERT_EQ(rows.size(), 7u * 2u * 3u);  // 7 variants x 2 wheels x y = 5.8, 6.0, 6.2 mm
  std::set<std::string> variants;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const auto& r = rows[k];
    ASSERT_EQ(r.size(), header.size()) << "row " << k;
    variants.insert(r[col["variant"]]);
    EXPECT_EQ(r[col["wheel"]], (k / 3) % 2 == 0 ? "left" : "right");
    EXPECT_NEAR(std::stod(r[col["y_m"]]), 5.8e-3 + 0.2e-3 * static_cast<double>(k % 3), 1e-12);
    EXPECT_EQ(std::stod(r[col["load_N"]]), 78.5e3);  // middle of the load grid
    EXPECT_EQ(std::stod(r[col["roll_rad"]]), 0.0);   // no equilibrium roll in this scene
    const auto bits = static_cast<StatusBits>(std::stoul(r[col["status"]]));
    std::string names = status::describe(bits);
    std::replace(names.begin(), names.end(), ',', ';');
    EXPECT_EQ(r[col["status_names"]], names);
    // Every point solves: converged, loaded, no failure, the load carried.
    EXPECT_TRUE(bits & status::kConverged) << k;
    EXPECT_FALSE(bits & (status::kFailed | status::kLiftOff | status::kInvalidInput)) << k;
    EXPECT_TRUE(r[col["error"]].empty()) << r[col["error"]];
    const int patches = std::stoi(r[col["patches"]]);
    EXPECT_GE(patches, 1);
    if (patches > 1) {
      EXPECT_TRUE(bits & status::kTwoPoint) << k;
    }
    EXPECT_GE(std::stoi(r[col["points"]]), 1);
    EXPECT_GT(std::stod(r[col["normal_force_N"]]), 78.5e3 * 0.99);
    EXPECT_GE(std::stoi(r[col["iterations"]]), 1);
  }
  EXPECT_EQ(variants, (std::set<std::string>{"hertz", "linder", "kik-piotrowski", "stripes-a/shift",
                                             "stripes-a/clip-and-smooth", "stripes-ab/shift",
                                             "stripes-ab/clip-and-smooth"}));
  // The left wheel reaches its flange in this range (flange bit somewhere), the right does not.
  bool left_flange = false, right_flange = false;
  for (const auto& r : rows) {
    const bool flange = std::stoul(r[col["status"]]) & status::kFlangeContact;
    (r[col["wheel"]] == "left" ? left_flange : right_flange) |= flange;
  }
  EXPECT_TRUE(left_flange);
  EXPECT_FALSE(right_flange);
  std::filesystem::remove(csv);
}

TEST(StabilityMap, RejectsAnInvalidRange) {
  const Scene scene = parse_scene(kScene, "stability.toml");
  StabilityMapOptions o;
  o.y_step = 0.0;
  EXPECT_THROW(write_stability_map_csv(scene, std::filesystem::temp_directory_path() / "x.csv", o), Error);
  o = {};
  o.y_max = std::nan("");
  EXPECT_THROW(write_stability_map_csv(scene, std::filesystem::temp_directory_path() / "x.csv", o), Error);
}

}  // namespace
}  // namespace railtab::stability_map_test
