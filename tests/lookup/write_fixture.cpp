// Writes a small format-1.0 table (y 9 x xi 5 x eta 3 x phi 3, 2 slots, all parts) for the C
// example, the install consumer test and the corruption campaign.
// Usage: railtab_lookup_write_fixture OUT.h5 [--legacy]   (--legacy: format 1.0, no checksums)
#include <cstdio>
#include <exception>
#include <string>

#include "lookup/table_fixture.hpp"

int main(int argc, char** argv) {
  const bool legacy = argc == 3 && std::string(argv[2]) == "--legacy";
  if (argc != 2 && !legacy) {
    std::fprintf(stderr, "usage: %s OUT.h5 [--legacy]\n", argv[0]);
    return 2;
  }
  using namespace railtab::lookup::testing;
  FixtureSpec spec = default_scene_spec();
  spec.axes = {{0, linspace(-0.01, 0.01, 9)},
               {3, linspace(-0.01, 0.01, 5)},
               {4, linspace(-0.01, 0.01, 3)},
               {5, linspace(-1.0, 1.0, 3)}};
  spec.checksums = !legacy;
  try {
    write_fixture(argv[1], spec);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
