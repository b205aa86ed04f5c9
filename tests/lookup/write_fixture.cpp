// Writes a small format-1.0 table (y 9 x xi 5 x eta 3 x phi 3, 2 slots, all parts) for the C
// example and the install consumer test. Usage: railtab_lookup_write_fixture OUT.h5
#include <cstdio>
#include <exception>

#include "lookup/table_fixture.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT.h5\n", argv[0]);
    return 2;
  }
  using namespace railtab::lookup::testing;
  FixtureSpec spec = default_scene_spec();
  spec.axes = {{0, linspace(-0.01, 0.01, 9)},
               {3, linspace(-0.01, 0.01, 5)},
               {4, linspace(-0.01, 0.01, 3)},
               {5, linspace(-1.0, 1.0, 3)}};
  try {
    write_fixture(argv[1], spec);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
