#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Sanitizer runs (reliability, docs/reliability.md). Both are CI stages (.ci/run); any report fails.
#   asan: build/asan (clang 14, ASan + UBSan, scripts/asan_build.sh) of all of src/ (profiles,
#         geometry, normal, tangential, wear, half-space, vehicle), the scene and table readers
#         and the lookup, and their unit tests (the list below; HalfspaceReference.* and
#         HalfspaceYawReference.* left out: the CONTACT comparisons repeat the solver the other
#         half-space tests run, 75 solves for the yaw one). Left out for the CI time budget: the sweep, charts, simulate, stability and table
#         accuracy suites; the `debug` preset (gcc ASan+UBSan) runs the whole suite by hand:
#         docs/reliability.md.
#   tsan: build/tsan (clang 14, ThreadSanitizer) of the lookup and the sweep: all of test_lookup
#         (its eight-thread query tests share one Table, as a simulation does) and the sweep's
#         multi-threaded tests (below), with scripts/tsan.supp. The sweep is built with
#         RAILTAB_PLAIN_THREADS: its parallel loops (engine/parallel_for.cpp, the generator's only
#         way to run in parallel) use std::threads there, because Debian's libtbb is not built
#         with TSan and TSan reports races even in a correct 10-line tbb::parallel_for, some in
#         the loop body itself (scripts/tsan.supp, docs/ci.md "ThreadSanitizer and
#         oneTBB"). So the stage checks railtab's own loop bodies and shared state, not oneTBB.
# Usage: bash scripts/sanitize.sh asan|tsan
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:?usage: sanitize.sh asan|tsan}
jobs=$(nproc)
# The table computation's tests that run on two or more threads, per test program (room): the table
# sweep (fast and exact models, load and creep axes), the adaptive grids, the model choice, contact
# jumps, generate, resume.
threaded_tests=(
  "test_generator_engine Sweep.BitIdenticalForAnyThreadCount:Sweep.PreSetInterruptComputesNothing"
  "test_generator_kernel ContactSweep.DefaultProfilesSmallGrid"
  "test_generator_adaptive AdaptiveContact.GridsDoNotDependOnThreads:HalfspaceSelectable.SweepDeterministicAndBalanced"
  "test_generator_generate Generate.ResumeAfterInterruptEqualsFreshRun:ModelChoice.TableRecordsTheChoiceAndIsByteIdenticalForAnyThreadCount"
)
run() {  # program [gtest arguments]: one test program, its name and result printed
  echo "sanitize: $mode: $*"
  "$@" --gtest_brief=1
}
case "$mode" in
  asan)
    tests=(test_core test_profile test_geometry test_normal test_tangential test_wear test_halfspace
           test_vehicle test_generator_scene test_generator_table test_lookup)
    bash scripts/asan_build.sh "${tests[@]}"
    # halt_on_error: the first report ends the program with an error; detect_leaks: a leak too
    # (libhdf5 frees its own at exit). UBSan is built with -fno-sanitize-recover=all.
    export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1
    export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
    # Two programs at a time (2 cores): test_halfspace, about 3/4 of the programs' run time, beside
    # the others one after another. Each program's output is printed when it ends.
    mkdir -p build/asan/test-logs
    run_logged() {  # program: runs it with its output in build/asan/test-logs/, then prints that
      local log=build/asan/test-logs/$1.log rc=0
      run "build/asan/tests/$1" --gtest_filter='-HalfspaceReference.*:HalfspaceYawReference.*' > "$log" 2>&1 || rc=$?
      cat "$log"
      [ $rc -eq 0 ] || echo "sanitize: asan: $1 FAILED (exit $rc)" >&2
      return $rc
    }
    status=0
    run_logged test_halfspace &
    halfspace=$!
    for t in "${tests[@]}"; do
      [ "$t" = test_halfspace ] || run_logged "$t" || status=1
    done
    wait "$halfspace" || status=1
    [ $status -eq 0 ] || exit 1
    ;;
  tsan)
    flags="-fsanitize=thread -fno-omit-frame-pointer -fsized-deallocation"
    mkdir -p build
    if [ ! -f build/tsan/CMakeCache.txt ]; then
      CC=clang-14 CXX=clang++-14 cmake -S . -B build/tsan -G Ninja -DCMAKE_BUILD_TYPE=Debug \
        -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
        -DCMAKE_C_FLAGS_DEBUG="-O1 -gline-tables-only" -DCMAKE_CXX_FLAGS_DEBUG="-O1 -gline-tables-only" \
        -DRAILTAB_BUILD_BENCH=OFF -DRAILTAB_BUILD_PYTHON=OFF -DRAILTAB_MPI=OFF \
        -DRAILTAB_LOOKUP_SHARED=OFF -DRAILTAB_PLAIN_THREADS=ON > build/tsan-configure.log
    fi
    cmake --build build/tsan --parallel "$jobs" --target test_lookup test_generator_engine test_generator_kernel \
      test_generator_adaptive test_generator_generate
    # halt_on_error + exitcode: the first report fails the program (and so CI).
    export TSAN_OPTIONS="halt_on_error=1:exitcode=66:second_deadlock_stack=1:suppressions=$PWD/scripts/tsan.supp"
    run build/tsan/tests/test_lookup
    for entry in "${threaded_tests[@]}"; do
      run "build/tsan/tests/${entry%% *}" --gtest_filter="${entry#* }"
    done
    ;;
  *) echo "sanitize.sh: unknown mode '$mode' (asan or tsan)" >&2; exit 2 ;;
esac
echo "sanitize: $mode: clean"
