#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Sanitizer runs (issue 19, docs/reliability.md). Both are CI stages (.ci/run); any report fails.
#   asan: build/asan (clang 14, ASan + UBSan, scripts/asan_build.sh) of the core, the profile
#         readers, the scene reader (and so src/) and the lookup, and their unit tests:
#         test_core, test_profile, test_generator_scene, test_lookup. Left out for the CI time
#         budget: the other layers' tests (geometry, normal, tangential, wear, half-space) and
#         the other generator suites; the `debug` preset (gcc ASan+UBSan) runs the whole suite
#         by hand: docs/reliability.md.
#   tsan: build/tsan (clang 14, ThreadSanitizer) of the lookup and all of test_lookup (its
#         eight-thread query tests share one Table, as a simulation does), with scripts/tsan.supp.
#         NOT the sweep (`railtab generate`): its threads are oneTBB's, and Debian's libtbb is not
#         built with TSan, so TSan reports races even in a correct 10-line parallel_for, some in
#         the loop body itself; no suppression can remove those without hiding races of railtab's
#         own code (scripts/tsan.supp, docs/reliability.md "ThreadSanitizer and oneTBB").
# Usage: bash scripts/sanitize.sh asan|tsan
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:?usage: sanitize.sh asan|tsan}
jobs=$(nproc)
run() {  # program [gtest arguments]: one test program, its name and result printed
  echo "sanitize: $mode: $*"
  "$@" --gtest_brief=1
}
case "$mode" in
  asan)
    tests=(test_core test_profile test_generator_scene test_lookup)
    bash scripts/asan_build.sh "${tests[@]}"
    # halt_on_error: the first report ends the program with an error; detect_leaks: a leak too
    # (libhdf5 frees its own at exit). UBSan is built with -fno-sanitize-recover=all.
    export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1
    export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
    for t in "${tests[@]}"; do run "build/asan/tests/$t"; done
    ;;
  tsan)
    flags="-fsanitize=thread -fno-omit-frame-pointer -fsized-deallocation"
    mkdir -p build
    if [ ! -f build/tsan/CMakeCache.txt ]; then
      CC=clang-14 CXX=clang++-14 cmake -S . -B build/tsan -G Ninja -DCMAKE_BUILD_TYPE=Debug \
        -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
        -DCMAKE_C_FLAGS_DEBUG="-O1 -gline-tables-only" -DCMAKE_CXX_FLAGS_DEBUG="-O1 -gline-tables-only" \
        -DRAILTAB_BUILD_BENCH=OFF -DRAILTAB_BUILD_PYTHON=OFF -DRAILTAB_MPI=OFF \
        -DRAILTAB_LOOKUP_SHARED=OFF > build/tsan-configure.log
    fi
    cmake --build build/tsan --parallel "$jobs" --target test_lookup
    # halt_on_error + exitcode: the first report fails the program (and so CI).
    export TSAN_OPTIONS="halt_on_error=1:exitcode=66:second_deadlock_stack=1:suppressions=$PWD/scripts/tsan.supp"
    run build/tsan/tests/test_lookup
    ;;
  *) echo "sanitize.sh: unknown mode '$mode' (asan or tsan)" >&2; exit 2 ;;
esac
echo "sanitize: $mode: clean"
