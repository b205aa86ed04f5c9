#!/usr/bin/env bash
# Sets up, builds and runs the main job on the default scene.
# Usage: bash scripts/run.sh [scene.toml] [output dir]
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-tables/default.toml}
out=${2:-out}
bash scripts/install-deps.sh
cmake --preset release
cmake --build --preset release --parallel "$(nproc)" --target railtab
mkdir -p "$out"
./build/release/generator/railtab eval --scene "$scene" --y 0.003 --roll 0 --load 78500
./build/release/generator/railtab chart-geometry --scene "$scene" --out "$out"
echo "run.sh: outputs in $out/"
