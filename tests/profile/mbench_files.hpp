// SPDX-License-Identifier: Apache-2.0
// Shared test helper: the Manchester benchmark profile files in ../shared/profiles.
#pragma once

#include <filesystem>
#include <string>

namespace railtab::test {

inline std::filesystem::path shared_profiles_dir() {
  return std::filesystem::path(RAILTAB_SHARED_DIR) / "profiles";
}

// Path of a benchmark file, or empty when ../shared/profiles is absent (tests then skip).
inline std::filesystem::path mbench_file(const std::string& name) {
  const std::filesystem::path p = shared_profiles_dir() / name;
  return std::filesystem::exists(p) ? p : std::filesystem::path();
}

}  // namespace railtab::test

#define RAILTAB_REQUIRE_MBENCH(var, name)                                                   \
  const std::filesystem::path var = ::railtab::test::mbench_file(name);                    \
  if (var.empty()) {                                                                        \
    GTEST_SKIP() << "../shared/profiles absent: " << ::railtab::test::shared_profiles_dir() \
                 << "/" << name << " not found";                                           \
  }
