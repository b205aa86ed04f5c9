// SPDX-License-Identifier: Apache-2.0
// Fuzz target: the profile readers (src/profile/profile_io*). The first byte picks the format
// (SIMPACK .prw/.prr or a two-column file) and the kind; the rest is the file. Any input must end
// in a profile or a railtab::Error, never a crash, a hang or a sanitizer report.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/check.hpp"
#include "profile/formats/profile_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const std::string dir = [] {
    const std::string d = std::filesystem::temp_directory_path() / ("railtab_fuzz_profile_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  static const char* kExtensions[] = {".prw", ".prr", ".txt", ".dat"};
  const std::string path = dir + "/p" + kExtensions[data[0] % 4];
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  const railtab::ProfileKind kind = (data[0] & 4) ? railtab::ProfileKind::rail : railtab::ProfileKind::wheel;
  const double smoothing = (data[0] & 8) ? 0.002 : 0.0;
  try {
    railtab::ProfilePtr p = railtab::read_profile(path, kind, smoothing);
    if (p) {
      (void)p->eval(0.0);  // the spline through the points must be usable
    }
  } catch (const railtab::Error&) {
  }
  return 0;
}
