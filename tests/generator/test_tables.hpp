// SPDX-License-Identifier: Apache-2.0
// Helpers shared by the generator tests: small tables and scenes, temporary directories, and
// byte-wise comparison of datasets.
#pragma once

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <string>

#include "table/table.hpp"

namespace railtab::testing {

// A fresh empty directory under the system temp dir, removed by the destructor.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() / ("railtab_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  // Names of all files in the directory.
  std::vector<std::string> files() const {
    std::vector<std::string> out;
    for (const auto& e : std::filesystem::directory_iterator(path_)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
  }

 private:
  std::filesystem::path path_;
};

// A contact scene (the real kernel) whose y grid is crossed by contact jumps: flange onset,
// lift-off and rolling-radius steps fall between its 5 y nodes at both loads.
inline constexpr const char* kJumpScene = R"(
[scene]
name = "jumps"
[profiles]
wheel = "s1002"
rail = "uic60"
[contact]
normal_model = "hertz"
[grid]
y = { start = -0.004, stop = 0.004, count = 5 }
equilibrium_roll = true
load = [60e3, 90e3]
xi = [-0.002, 0.0, 0.002]
eta = [-0.001, 0.001]
)";

// A small scene of the exact half-space model: tread contact, 2 y x 2 xi at 78.5 kN (seconds of CPU).
inline constexpr const char* kHalfspaceSmallScene = R"(
[scene]
name = "halfspace-small"
[profiles]
wheel = "s1002"
rail = "uic60"
[track]
rail_inclination = "1:40"
[contact]
normal_model = "halfspace"
friction = 0.3
[grid]
y = [0.0, 0.003]
equilibrium_roll = true
load = [78.5e3]
xi = [0.0, 0.002]
eta = [0.0]
phi = [0.0]
)";

// An adaptive scene on the tread: y and xi refined to the creep force and contact angle targets.
inline constexpr const char* kAdaptiveTreadScene = R"(
[scene]
name = "tread"
[profiles]
wheel = "s1002"
rail = "uic60"
[accuracy]
creep_force = 0.01
contact_angle = 0.002
[grid]
y = {start = -0.002, stop = 0.002, max_step = 0.002, min_step = 2.5e-4}
equilibrium_roll = true
load = 78500
xi = {start = 0.0, stop = 0.008, max_step = 0.004, min_step = 1.25e-4}
)";

// An adaptive scene that chooses the normal model per region (Hertz or Kik-Piotrowski where
// within 3x the targets of STRIPES A&B): tread (|y| <= 3 mm) and flange contact of the left wheel
// (y = 9 mm).
inline constexpr const char* kModelChoiceScene = R"([scene]
name = "choice"
[profiles]
wheel = "s1002"
rail = "uic60"
[contact]
normal_model = "stripes-ab"
[accuracy]
creep_force = 0.02
normal_force = 0.01
models = ["hertz", "kik-piotrowski"]
model_tolerance = 3.0
[grid]
y = [-0.003, 0.0015, 0.003, 0.009]
equilibrium_roll = true
load = [60e3, 100e3]
xi = {start = -0.004, stop = 0.004, max_step = 0.004, min_step = 0.002}
eta = 0.001
phi = 0.05
)";

// One state on the tread (y 1 mm, 60 kN, xi 1e-3) with the default models.
inline constexpr const char* kTreadPointScene = R"(
[scene]
name = "tread"
[profiles]
wheel = "s1002"
rail = "uic60"
[grid]
y = [0.001]
load = [60000]
xi = [0.001]
)";

// Every dataset of `a` exists in `b` with the same shape, axes and identical bytes; same axes.
inline void expect_same_datasets(const Table& a, const Table& b) {
  ASSERT_EQ(a.axes.size(), b.axes.size());
  for (const TableAxis& axis : a.axes) {
    const TableAxis* other = b.axis(axis.name);
    ASSERT_TRUE(other) << axis.name;
    EXPECT_EQ(axis.values, other->values) << axis.name;
  }
  ASSERT_EQ(a.groups.size(), b.groups.size());
  for (const TableGroup& g : a.groups) {
    const TableGroup* other = b.group(g.path);
    ASSERT_TRUE(other) << g.path;
    ASSERT_EQ(g.datasets.size(), other->datasets.size()) << g.path;
    for (const TableDataset& d : g.datasets) {
      const TableDataset* o = other->find(d.name);
      ASSERT_TRUE(o) << g.path << "/" << d.name;
      EXPECT_EQ(d.shape, o->shape) << g.path << "/" << d.name;
      EXPECT_EQ(d.axes, o->axes) << g.path << "/" << d.name;
      ASSERT_EQ(d.values.size(), o->values.size());
      ASSERT_EQ(d.status.size(), o->status.size());
      // memcmp with the null data() of an empty vector is undefined (UBSan, scripts/sanitize.sh).
      EXPECT_TRUE(d.values.empty() ||
                  std::memcmp(d.values.data(), o->values.data(), d.values.size() * sizeof(double)) == 0)
          << g.path << "/" << d.name << " differs";
      EXPECT_EQ(d.status, o->status) << g.path << "/" << d.name;
    }
  }
}

}  // namespace railtab::testing
