#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Lookup against direct evaluation of the exact half-space model on the FULL default table
# (tables/default.toml), with the metric of tests/table_accuracy (exact-model tables). The test
# suite runs the same check on a reduced table; this one needs the generated default table
# (about 4 min CPU, docs/validation/exact-tables.md "The whole table") and about 400 direct exact
# evaluations of both wheels (a few min CPU).
# Usage: scripts/halfspace_table_accuracy.sh [TABLE.h5]   (build/release; generates TABLE if absent)
set -euo pipefail
cd "$(dirname "$0")/.."
table="${1:-/tmp/default.h5}"
if [[ ! -f "$table" ]]; then
  build/release/generator/railtab generate tables/default.toml -o "$table" --threads 2
fi
RAILTAB_HALFSPACE_TABLE="$table" build/release/tests/test_table_accuracy --gtest_filter='HalfspaceTableAccuracy*'
