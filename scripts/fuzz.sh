#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Builds the libFuzzer targets (fuzz/, clang 14 with ASan+UBSan, in build/asan) and runs each on a
# scratch copy of its seed corpus (fuzz/corpus/<name>/): the profile readers, the scene reader,
# the table loader and the chart titles (scene names and descriptions as gnuplot strings). A fixed -seed and a fixed number of executions (-runs) per target: the same
# amount of work on every run whatever the machine's speed or load, so the verdict does not
# depend on how busy the machine is (the mutated inputs are not exactly the same on every run:
# see the setarch comment below); the seconds are a cap only (sized so the runs finish well inside it on a loaded 2-core machine;
# if the cap cuts a run short the script says so, and that run is not comparable). Every committed input is run first (libFuzzer runs the
# whole corpus before it mutates), so the regression inputs (e.g. fuzz/corpus/table/
# crash_hdf5_vlen_read.h5) are checked on every run. A crash, a sanitizer report, a timeout
# (> 10 s for one input) or an allocation above 2 GB fails the run (exit != 0, CI fails) and
# leaves the input in build/fuzz/artifacts/.
# Usage: bash scripts/fuzz.sh [seconds per target, default 60] [target...]
# Environment: FUZZ_SEED (default 19); FUZZ_RUNS overrides every target's execution count.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(fuzz_profile fuzz_scene fuzz_table_load fuzz_chart_title)
# build/asan: the same clang ASan+UBSan build as scripts/sanitize.sh asan (scripts/asan_build.sh,
# which says why each flag): built once, the fuzz targets only link against it.
bash scripts/asan_build.sh "${targets[@]}"

# Executions per target: ~1/3 of what each did in 45 s with the machine's load average at ~20
# (fuzz_profile 12,800, fuzz_scene 144,340, fuzz_table_load 1,595; docs/ci.md).
declare -A runs=([fuzz_profile]=4000 [fuzz_scene]=40000 [fuzz_table_load]=500 [fuzz_chart_title]=20000)
seed=${FUZZ_SEED:-19}

mkdir -p build/fuzz/artifacts
status=0
for t in "${targets[@]}"; do
  n=${FUZZ_RUNS:-${runs[$t]:-1000}}
  corpus_name=${t#fuzz_}
  [ "$corpus_name" = table_load ] && corpus_name=table
  work=build/fuzz/corpus-run/$corpus_name
  rm -rf "$work" && mkdir -p "$work" && cp fuzz/corpus/"$corpus_name"/* "$work"/
  echo "fuzz: $t: $n executions, seed $seed (cap $seconds s)"
  # detect_leaks=0 for the table loader: libhdf5 (not instrumented) keeps allocations on some
  # error paths until H5close; leaks of railtab's own code are caught by the ASan test run.
  leaks=1
  [ "$t" = fuzz_table_load ] && leaks=0
  # setarch -R for the table loader: no address randomisation, so libhdf5 (pointer-keyed
  # internals) takes the same paths. Measured, 500 runs seed 19: without it two back-to-back runs
  # differed (ft 1500 / 1456), with it two back-to-back runs matched exactly (twice), but runs
  # minutes apart still differed a little (ft 1479 / 1456), as the other targets' do (cov within
  # ~4%, cause not found). So later mutations can differ between runs; the committed inputs
  # (regression inputs included) always run, and the amount of work is fixed.
  norandom=()
  [ "$t" = fuzz_table_load ] && setarch -R true 2> /dev/null && norandom=(setarch -R)
  if ! ASAN_OPTIONS="detect_leaks=$leaks:allocator_may_return_null=1" UBSAN_OPTIONS=print_stacktrace=1 \
      "${norandom[@]}" build/asan/fuzz/"$t" "$work" -seed="$seed" -runs="$n" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
      -malloc_limit_mb=2048 -print_final_stats=1 -artifact_prefix=build/fuzz/artifacts/"$t"- \
      > build/fuzz/"$t".log 2>&1; then
    echo "fuzz: $t FAILED (build/fuzz/$t.log, inputs in build/fuzz/artifacts/):" >&2
    grep -E "ERROR|SUMMARY|==[0-9]+==|Test unit written" build/fuzz/"$t".log | head -20 >&2
    status=1
  fi
  done_runs=$(sed -n 's/^stat::number_of_executed_units: *//p' build/fuzz/"$t".log)
  if [ -n "$done_runs" ] && [ "$done_runs" -lt "$n" ]; then
    echo "fuzz: $t: WARNING: the $seconds s cap stopped it after $done_runs of $n executions (less work than the fixed count)" >&2
  fi
  # Executions per second and coverage (edges) for the record.
  grep -E "stat::number_of_executed_units|stat::average_exec_per_sec|stat::peak_rss_mb" build/fuzz/"$t".log |
    tr '\n' ' ' | sed "s/^/fuzz: $t: /"
  echo
  grep -E "^#[0-9]+.*(DONE|pulse|NEW|REDUCE)" build/fuzz/"$t".log | tail -1 | sed "s/^/fuzz: $t: last: /" || true
done
exit $status
