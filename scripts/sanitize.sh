#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Sanitizer runs of the test suite (issue 19, docs/reliability.md):
#   asan: the `debug` preset (ASan + UBSan, gcc), the whole CTest suite; any report fails the run.
#   tsan: ThreadSanitizer build of the sweep and lookup tests only (the code with threads), run
#         with scripts/tsan.supp (oneTBB's scheduler is not instrumented; see the file).
# Usage: bash scripts/sanitize.sh asan|tsan [extra ctest arguments]
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:?usage: sanitize.sh asan|tsan}
shift
jobs=$(nproc)
case "$mode" in
  asan)
    cmake --preset debug -DRAILTAB_BUILD_BENCH=OFF > /dev/null
    cmake --build --preset debug --parallel "$jobs"
    # halt_on_error: the first report fails the test; detect_leaks: a leak fails it too.
    ASAN_OPTIONS=halt_on_error=1:detect_leaks=1:abort_on_error=0:strict_string_checks=1 \
    UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
      ctest --preset debug --parallel "$jobs" --timeout 1800 "$@"
    ;;
  tsan)
    flags="-fsanitize=thread -O1 -g -fno-omit-frame-pointer"
    cmake -S . -B build/tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRAILTAB_BUILD_BENCH=OFF \
      -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" > /dev/null
    cmake --build build/tsan --parallel "$jobs" --target test_generator_sweep test_lookup
    export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$PWD/scripts/tsan.supp"
    build/tsan/tests/test_generator_sweep
    build/tsan/tests/test_lookup
    ;;
  *) echo "sanitize.sh: unknown mode '$mode' (asan or tsan)" >&2; exit 2 ;;
esac
