#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# Draws docs/validation/halfspace_yaw_models.png: how far the fast models (Hertz, Kik-Piotrowski,
# Linder, STRIPES A and A&B, each with FASTSIM) and the exact half-space model are from CONTACT on
# the Manchester case A-2.2 as the yaw grows, from the rows that test_halfspace's two A-2.2 reports
# print (FastModelsWithYaw*, HalfspaceYawReference*; docs/validation/halfspace-yaw.md). Writes the
# data to docs/validation/halfspace_yaw_models.dat, then runs gnuplot.
# Usage: scripts/halfspace_yaw_chart.sh [BUILD_DIR]   (default build/release, test_halfspace built;
# run from anywhere inside the repository)
set -eu
cd "$(dirname "$0")/.."
build=${1:-build/release}
program="$build/tests/test_halfspace"
if [ ! -x "$program" ]; then
  echo "halfspace_yaw_chart.sh: $program not found: cmake --build --preset release --target test_halfspace" >&2
  exit 1
fi
dat=docs/validation/halfspace_yaw_models.dat
out=$(mktemp)
trap 'rm -f "$out"' EXIT
"$program" --gtest_filter='FastModelsWithYaw*:HalfspaceYawReference*' > "$out"
# [fast] rows: | wheel | Y | yaw | "area, |dF|/muN" per model |; [table] rows (exact model): the
# last column is |dF|/muN at CONTACT's creepages (as the fast models get them), the 4th the
# contact angle (flange contact above 0.35 rad).
awk -F'|' '
  function pct(s) { gsub(/[ %]/, "", s); return s }
  $1 ~ /^\[fast\] / && $3 ~ /[0-9]/ {
    key = $2 $3; order[++n] = key; wheel[key] = $2; y[key] = $3; yaw[key] = $4
    for (m = 5; m <= 9; ++m) { split($m, part, ","); fast[key, m] = pct(part[2]) }
  }
  $1 ~ /^\[table\] / && $3 ~ /[0-9]/ {
    key = $2 $3; exact[key] = pct($17)
    split($5, a, " "); angle = a[1] + 0; flange[key] = (angle > 0.35 || angle < -0.35) ? 1 : 0
  }
  END {
    print "# A-2.2 against CONTACT: |dF| / (mu N) [%] of each model at CONTACT'"'"'s creepages (scripts/halfspace_yaw_chart.sh)"
    print "# wheel Y_mm yaw_mrad flange hertz kik_piotrowski linder stripes_a stripes_ab exact"
    for (k = 1; k <= n; ++k) {
      key = order[k]
      if (!(key in exact)) { print "no exact-model row for" wheel[key] y[key] > "/dev/stderr"; exit 1 }
      w = wheel[key]; gsub(/ /, "", w)
      printf "%s %s %s %d %s %s %s %s %s %s\n", w, y[key] + 0, yaw[key] + 0, flange[key],
             fast[key, 5], fast[key, 6], fast[key, 7], fast[key, 8], fast[key, 9], exact[key]
    }
  }' "$out" > "$dat"
exec gnuplot scripts/halfspace_yaw_models.gp
