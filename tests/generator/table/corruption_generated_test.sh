#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Corruption campaign on a table as `railtab generate` writes it (format 2.3: float32 creep and
# wear outputs, located jumps with one-sided values, the error map), not only on the lookup's format-2.0 fixture:
# single-byte changes, each copy loaded through the C API in a child process and given to
# `railtab inspect` (tests/lookup/corruption_campaign.cpp; docs/reliability.md).
# Usage: corruption_generated_test.sh RAILTAB CAMPAIGN SCENE WORKDIR FLIPS SEED
set -euo pipefail
railtab=$1 campaign=$2 scene=$3 work=$4 flips=$5 seed=$6
rm -rf "$work" && mkdir -p "$work"
"$railtab" generate "$scene" -o "$work/table.h5" --threads 2 --quiet
"$railtab" inspect "$work/table.h5" > "$work/inspect.txt"
grep -Eq "format_version +2\.3" "$work/inspect.txt" || { echo "FAIL: not a format-2.3 table" >&2; exit 1; }
"$campaign" "$work/table.h5" --flips "$flips" --seed "$seed" --memory-mib 2048 --inspect "$railtab"
rm -rf "$work"
