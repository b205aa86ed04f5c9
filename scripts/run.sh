#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The main job: sets up, builds, makes the table of a scene and its charts.
# Usage: bash scripts/run.sh [scene.toml] [output dir]      (default: tables/default.toml, out/)
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-tables/default.toml}
out=${2:-out}
name=$(basename "$scene" .toml)
bash scripts/install-deps.sh
cmake --preset release
cmake --build --preset release --parallel "$(nproc)" --target railtab
railtab=./build/release/generator/railtab
mkdir -p "$out"
"$railtab" generate "$scene" -o "$out/$name.h5"
"$railtab" inspect "$out/$name.h5"
"$railtab" chart-geometry --scene "$scene" --out "$out"
"$railtab" chart-stability --scene "$scene" --out "$out"
"$railtab" chart-pressure --scene "$scene" --out "$out" --y 0 --load 78500
"$railtab" chart --scene "$scene" --out "$out"
"$railtab" conicity --scene "$scene" --out "$out"
"$railtab" eval --scene "$scene" --y 0.003 --load 78500 --creepage 0.001,0,0 > "$out/eval_y3mm.txt"
echo "run.sh: table $out/$name.h5, charts and CSV in $out/"
ls -l "$out"
