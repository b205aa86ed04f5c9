#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Builds railtab (Release) and runs the whole test suite with CTest.
# Usage: bash scripts/test.sh [extra ctest arguments, e.g. -L stability]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset release
cmake --build --preset release --parallel "$(nproc)"
ctest --preset release --parallel "$(nproc)" "$@"
