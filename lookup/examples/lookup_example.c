// SPDX-License-Identifier: Apache-2.0
/* Loads a railtab table and queries the left wheel along a lateral sweep, from C.
 * Usage: railtab_lookup_example TABLE.h5          (exit status 0 on success) */
#include <stdio.h>
#include <string.h>

#include "railtab_lookup.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: %s TABLE.h5\n", argv[0]);
    return 2;
  }
  railtab_lookup_table* table = NULL;
  if (railtab_lookup_open(argv[1], RAILTAB_LOOKUP_LINEAR, &table) != RAILTAB_LOOKUP_OK) {
    fprintf(stderr, "%s\n", railtab_lookup_last_error());
    return 1;
  }
  /* What the table holds: its axes (name, units, range) and whether its checksums were verified. */
  railtab_lookup_table_info info;
  railtab_lookup_info(table, &info);
  printf("%s: format %s, %d slots, checksums %s (railtab lookup %s)\n", info.path,
         info.format_version, info.n_slots, info.checksums_verified ? "verified" : "absent",
         railtab_lookup_version());
  /* Untabulated variables (e.g. roll) must sit at the table's fixed values: default_state puts
   * them there. It leaves the tabulated ones at 0, so a simulation sets each one it drives: here
   * y and xi, and the wheel load when the table tabulates it (the default table: 60 .. 100 kN; a
   * load left at 0 would be clamped to 60 kN and flagged out_of_range). */
  railtab_lookup_state state;
  railtab_lookup_default_state(table, &state);
  for (int a = 0; a < info.n_axes; ++a) {
    const char* name;
    const char* units;
    size_t n;
    const double* nodes;
    railtab_lookup_axis(table, a, &name, &units, &n, &nodes);
    printf("  axis %-4s [%s] %zu nodes, %g .. %g\n", name, units, n, nodes[0], nodes[n - 1]);
    if (strcmp(name, "load") == 0) state.load = 0.5 * (nodes[0] + nodes[n - 1]); /* N, mid-range: a simulation's own load */
  }
  printf("load = %g N\n", state.load);
  railtab_lookup_result result;
  for (int k = 0; k <= 4; ++k) {
    state.y = -0.004 + 0.002 * k; /* m */
    state.xi = 0.001;
    if (railtab_lookup_query(table, RAILTAB_LOOKUP_LEFT, &state, &result) != RAILTAB_LOOKUP_OK) {
      fprintf(stderr, "%s\n", railtab_lookup_last_error());
      railtab_lookup_close(table);
      return 1;
    }
    const railtab_lookup_contact* tread = &result.contact[0];
    char status[128]; /* e.g. "converged,out_of_range" */
    railtab_lookup_status_text(tread->status, status, sizeof status);
    printf("y = %+.4f m  fx = %12.4f N  contact_angle = %+.5f rad  status = %s%s\n", state.y,
           tread->value[RAILTAB_LOOKUP_FX], tread->value[RAILTAB_LOOKUP_CONTACT_ANGLE], status,
           (result.status & RAILTAB_LOOKUP_OUT_OF_RANGE) ? " (clamped)" : "");
  }
  /* Both wheels in one call. */
  int wheels[2] = {RAILTAB_LOOKUP_LEFT, RAILTAB_LOOKUP_RIGHT};
  railtab_lookup_state states[2] = {state, state};
  railtab_lookup_result results[2];
  if (railtab_lookup_query_batch_checked(table, 2, wheels, states, results, 2) != RAILTAB_LOOKUP_OK) {
    fprintf(stderr, "%s\n", railtab_lookup_last_error());
    railtab_lookup_close(table);
    return 1;
  }
  printf("batch: left fx = %.4f N, right fx = %.4f N\n", results[0].contact[0].value[RAILTAB_LOOKUP_FX],
         results[1].contact[0].value[RAILTAB_LOOKUP_FX]);
  railtab_lookup_close(table);
  return 0;
}
