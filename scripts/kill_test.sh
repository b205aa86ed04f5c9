#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Kill test (reliability, docs/reliability.md): sends SIGKILL and SIGTERM to a real `railtab generate`
# at several points of its run and checks what is left: no table or a complete one (identical
# datasets to an uninterrupted run), no temporary after SIGTERM, and `--resume` finishing to
# identical datasets (h5diff) with no temporary and no checkpoint left.
# Usage: bash scripts/kill_test.sh [path/to/railtab]   (default build/release/generator/railtab)
set -euo pipefail
cd "$(dirname "$0")/.."
railtab=$(realpath "${1:-build/release/generator/railtab}")
[ -x "$railtab" ] || { echo "kill_test: $railtab not built" >&2; exit 2; }
work=$(mktemp -d /tmp/railtab_kill.XXXXXX)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "kill_test: FAIL: $*" >&2; fails=$((fails + 1)); }

# The default scene with a finer y grid: a run of a few seconds on one thread.
sed -e '/^y = \[/,/^\]/c y = { start = -0.010, stop = 0.010, step = 0.0002 }' tables/default.toml > "$work/scene.toml"

same_datasets() {  # h5diff of everything but the root attributes (`created` differs by design)
  h5diff --exclude-attribute / "$work/ref.h5" "$1" > "$work/h5diff.txt" 2>&1
}
leftovers() { find "$work" -maxdepth 1 \( -name 'out.h5.tmp.*' -o -name 'out.h5.partial' \) -printf '%f '; }

start=$(date +%s.%N)
"$railtab" generate "$work/scene.toml" -o "$work/ref.h5" --threads 1 --quiet < /dev/null
ref_seconds=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {printf "%.2f", b - a}')
echo "kill_test: reference run $ref_seconds s"

run_and_kill() {  # signal, delay [s], extra generate arguments...
  local sig=$1 delay=$2
  shift 2
  rm -f "$work"/out.h5*
  "$railtab" generate "$work/scene.toml" -o "$work/out.h5" --threads 1 "$@" < /dev/null 2> "$work/stderr.txt" &
  local pid=$!
  sleep "$delay"
  kill -s "$sig" "$pid" 2> /dev/null || true
  local rc=0
  wait "$pid" || rc=$?
  echo "kill_test: SIG$sig after ${delay}s $*: exit $rc, left: $(leftovers)$([ -e "$work/out.h5" ] && echo out.h5)"
  if [ -e "$work/out.h5" ]; then
    same_datasets "$work/out.h5" || fail "SIG$sig after ${delay}s left an incomplete or different out.h5: $(head -3 "$work/h5diff.txt")"
  fi
  case "$sig:$rc" in
    TERM:143 | TERM:0 | KILL:137 | KILL:0) ;;
    *) fail "SIG$sig after ${delay}s: exit status $rc ($(tail -1 "$work/stderr.txt"))" ;;
  esac
  if [ "$sig" = TERM ] && [ -n "$(find "$work" -maxdepth 1 -name 'out.h5.tmp.*')" ]; then
    fail "SIGTERM left a temporary: $(leftovers)"
  fi
  # Handled, not died of it: railtab says it was interrupted (an unhandled SIGTERM also gives 143).
  if [ "$sig" = TERM ] && [ "$rc" = 143 ] && ! grep -q "interrupted" "$work/stderr.txt"; then
    fail "SIGTERM was not handled (no 'interrupted' message)"
  fi
  if [ "$sig" = TERM ] && [ "$rc" = 143 ] && [ -e "$work/out.h5" ]; then
    fail "SIGTERM reported an interruption but out.h5 exists"
  fi
}

resume_and_check() {
  "$railtab" generate "$work/scene.toml" -o "$work/out.h5" --threads 1 --quiet --resume < /dev/null ||
    { fail "--resume failed"; return; }
  same_datasets "$work/out.h5" || fail "--resume gave different datasets: $(head -3 "$work/h5diff.txt")"
  [ -z "$(leftovers)" ] || fail "--resume left $(leftovers)"
}

for sig in KILL TERM; do
  for fraction in 0.1 0.5 0.9 0.98; do
    delay=$(awk -v t="$ref_seconds" -v f="$fraction" 'BEGIN {printf "%.2f", t * f}')
    run_and_kill "$sig" "$delay" --resume
    resume_and_check
  done
done
# Without --resume, SIGTERM writes nothing and removes everything it made.
run_and_kill TERM "$(awk -v t="$ref_seconds" 'BEGIN {printf "%.2f", t * 0.5}')"
[ -z "$(leftovers)" ] || fail "SIGTERM without --resume left $(leftovers)"
# A temporary of a killed run (SIGKILL during the write) is removed by the next run.
echo stale > "$work/out.h5.tmp.999999999"
"$railtab" generate "$work/scene.toml" -o "$work/out.h5" --threads 2 --quiet < /dev/null
[ ! -e "$work/out.h5.tmp.999999999" ] || fail "a stale temporary of a dead process was not removed"

if [ "$fails" -gt 0 ]; then
  echo "kill_test: $fails failure(s)" >&2
  exit 1
fi
echo "kill_test: passed"
