// SPDX-License-Identifier: Apache-2.0
// Writes a small table (y 9 x xi 5 x eta 3 x phi 3, 2 slots, all parts) for the C example, the
// install consumer test and the corruption campaign: format 2.0 (fixed variables as compact
// scalar datasets, checksums), or with --format-1.1 the 1.x layout with checksums, or with
// --legacy format 1.0 without checksums (which the lookup refuses), or with --tiny format 2.0 on
// the smallest grid (y 3 x xi 2 x eta 2 x phi 2, 1 slot: fuzz/corpus/table/tiny.h5).
// Usage: railtab_lookup_write_fixture OUT.h5 [--legacy | --format-1.1 | --tiny]
#include <cstdio>
#include <exception>
#include <string>

#include "lookup/table_fixture.hpp"

int main(int argc, char** argv) {
  const std::string option = argc == 3 ? argv[2] : "";
  const bool legacy = option == "--legacy", v11 = option == "--format-1.1", tiny = option == "--tiny";
  if (argc < 2 || argc > 3 || (argc == 3 && !legacy && !v11 && !tiny)) {
    std::fprintf(stderr, "usage: %s OUT.h5 [--legacy | --format-1.1 | --tiny]\n", argv[0]);
    return 2;
  }
  using namespace railtab::lookup::testing;
  FixtureSpec spec = scene_sized_spec();
  spec.axes = {{0, linspace(-0.01, 0.01, 9)},
               {3, linspace(-0.01, 0.01, 5)},
               {4, linspace(-0.01, 0.01, 3)},
               {5, linspace(-1.0, 1.0, 3)}};
  if (tiny) {
    spec.axes = {{0, linspace(-0.01, 0.01, 3)},
                 {3, linspace(-0.01, 0.01, 2)},
                 {4, linspace(-0.01, 0.01, 2)},
                 {5, linspace(-1.0, 1.0, 2)}};
    spec.n_slots = 1;
  }
  spec.checksums = !legacy;
  spec.format_version = legacy ? "1.0" : v11 ? "1.1" : "2.0";
  spec.fixed_as_datasets = !legacy && !v11;
  try {
    write_fixture(argv[1], spec);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
