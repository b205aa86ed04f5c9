// SPDX-License-Identifier: Apache-2.0
// Fuzz target: the table loader (lookup/): railtab::lookup::Table::load on a file holding the
// fuzz input, then one query at the default state. Any input must end in a Table or a
// lookup::LoadError, never a crash, a sanitizer report or an allocation beyond libFuzzer's
// -rss_limit_mb.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include <railtab/lookup.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path =
      std::filesystem::temp_directory_path() / ("railtab_fuzz_table_" + std::to_string(::getpid()) + ".h5");
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  namespace lk = railtab::lookup;
  try {
    const lk::Table table = lk::Table::load(path);
    lk::State s = table.default_state();
    lk::Result r;
    table.query(lk::Wheel::kLeft, s, r);
  } catch (const lk::LoadError&) {
  }
  return 0;
}
