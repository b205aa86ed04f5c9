#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Corruption campaign (issue #19, docs/reliability.md): 1,000 copies of a small table, each with
# one byte replaced by a different random value; each copy is loaded through the C API in a
# child process under a memory limit (and given to `railtab inspect`), queried at fixed states
# and compared with the pristine table. Pass = 0 crashes, 0 hangs, 0 silent different answers,
# 0 allocations over 2 x the file size (floor: libhdf5's fixed ~515 KB per open file).
#
# Usage: bash scripts/corruption_campaign.sh [FLIPS [SEED [TABLE.h5]]]
#   FLIPS   number of single-byte changes (default 1000)
#   SEED    random seed (default 19)
#   TABLE   table to corrupt (default: the lookup's fixture table, format 2.0, written here)
# Also runs the same changes on a legacy (format 1.0, no checksums) copy of the fixture for
# comparison: those may load with different answers (no checksum to catch them) but must not
# crash. Builds into build/release; exit status 0 when the checksummed campaign passes.
set -euo pipefail
cd "$(dirname "$0")/.."
flips=${1:-1000}
seed=${2:-19}
table=${3:-}
[ -d build/release ] || cmake --preset release
cmake --build --preset release --parallel 2 \
  --target railtab_lookup_corruption railtab_lookup_write_fixture railtab
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if [ -z "$table" ]; then
  table=$work/fixture.h5
  build/release/tests/lookup/railtab_lookup_write_fixture "$table"
fi
build/release/tests/lookup/railtab_lookup_write_fixture "$work/legacy.h5" --legacy
echo "== legacy table (no checksums), for comparison; not part of the pass/fail"
build/release/tests/lookup/railtab_lookup_corruption "$work/legacy.h5" --flips "$flips" \
  --seed "$seed" --memory-mib 2048 | head -3 || true
echo "== checksummed table"
build/release/tests/lookup/railtab_lookup_corruption "$table" --flips "$flips" --seed "$seed" \
  --memory-mib 2048 --inspect build/release/generator/railtab
