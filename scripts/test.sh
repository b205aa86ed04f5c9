#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Builds railtab (Release) and runs the whole test suite with CTest; prints how long the package
# check, the build and the tests took (wall seconds), so a slow run shows which part grew.
# Usage: bash scripts/test.sh [extra ctest arguments, e.g. -L stability]
set -euo pipefail
cd "$(dirname "$0")/.."
t0=$SECONDS
bash scripts/install-deps.sh
t1=$SECONDS
cmake --preset release
cmake --build --preset release --parallel "$(nproc)"
t2=$SECONDS
status=0
ctest --preset release --parallel "$(nproc)" "$@" || status=$?
t3=$SECONDS
echo "test.sh: packages $((t1 - t0)) s, configure and build $((t2 - t1)) s, ctest $((t3 - t2)) s (exit $status)"
exit $status
