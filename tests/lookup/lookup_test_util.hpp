// SPDX-License-Identifier: Apache-2.0
// Shared helpers of the lookup tests: unique temp file names, output index of (part, output).
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include "railtab/lookup.hpp"

namespace railtab::lookup::testing {

// A file name in the test temp dir, unique per test and process (CTest runs tests in parallel).
inline std::string temp_table(const std::string& stem) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = ::testing::TempDir() + "railtab_lookup_" + info->test_suite_name() + "_" +
                     info->name() + "_" + stem + "_" + std::to_string(::getpid()) + ".h5";
  return name;
}

// Removes the file when the test ends.
struct TempFile {
  std::string path;  // file name
  explicit TempFile(const std::string& stem) : path(temp_table(stem)) {}
  ~TempFile() { std::remove(path.c_str()); }
};

// Output index of output `o` of part `p` (table_fixture's order = the format's order).
inline int output_index(int part, int o) {
  static const int first[kNumParts] = {kContactAngle, kNormalForce, kFx, kWearRate};
  return first[part] + o;
}

inline int part_outputs(int part) {
  static const int n[kNumParts] = {7, 6, 4, 1};
  return n[part];
}

}  // namespace railtab::lookup::testing
