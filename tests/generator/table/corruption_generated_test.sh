#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Corruption campaign on a table as `railtab generate` writes it (format 2.3: float32 creep and
# wear outputs, located jumps with one-sided values, the error map), not only on the lookup's format-2.0 fixture:
# single-byte changes, each copy loaded through the C API in a child process and given to
# `railtab inspect` (tests/lookup/corruption_campaign.cpp; docs/reliability.md).
# Usage: corruption_generated_test.sh RAILTAB CAMPAIGN TABLE FLIPS SEED
# TABLE: the STRIPES scene's table (the CTest fixture table.stripes_table); it is only read, the
# changed copies are the campaign's own files.
set -euo pipefail
railtab=$1 campaign=$2 table=$3 flips=$4 seed=$5
info=$("$railtab" inspect "$table")
grep -Eq "format_version +2\.3" <<< "$info" || { echo "FAIL: $table is not a format-2.3 table" >&2; exit 1; }
"$campaign" "$table" --flips "$flips" --seed "$seed" --memory-mib 2048 --inspect "$railtab"
