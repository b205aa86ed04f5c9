// SPDX-License-Identifier: Apache-2.0
// Loads the table given on the command line through the installed railtab::lookup, queries it
// with both APIs, prints "consumer: ok" on success.
#include <railtab/lookup.hpp>
#include <railtab_lookup.h>

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  try {
    const auto table = railtab::lookup::Table::load(argv[1]);
    railtab::lookup::State s = table.default_state();
    s.y = 0.002;
    const auto r = table.query(railtab::lookup::Wheel::kLeft, s);
    if (r.status != 0 || r.n_slots != 2) return 1;
    railtab_lookup_table* t = nullptr;
    if (railtab_lookup_open(argv[1], RAILTAB_LOOKUP_LINEAR, &t) != RAILTAB_LOOKUP_OK) return 1;
    railtab_lookup_state cs = {s.y, s.roll, s.load, s.xi, s.eta, s.phi, s.yaw};
    railtab_lookup_result cr;
    const int rc = railtab_lookup_query(t, RAILTAB_LOOKUP_LEFT, &cs, &cr);
    railtab_lookup_close(t);
    if (rc != RAILTAB_LOOKUP_OK || cr.contact[0].value[RAILTAB_LOOKUP_FX] != r.contact[0].value[railtab::lookup::kFx])
      return 1;
    // The newer part of the API: status names, introspection, versions.
    if (railtab::lookup::status::describe(railtab::lookup::status::kFailed) != "failed") return 1;
    if (table.axes().empty() || !table.checksums_verified()) return 1;
    std::printf("consumer: ok (fx = %g N, railtab lookup %s)\n",
                r.contact[0].value[railtab::lookup::kFx], railtab_lookup_version());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
