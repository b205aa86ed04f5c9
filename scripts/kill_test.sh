#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Kill test (reliability, docs/reliability.md): sends SIGKILL and SIGTERM to a real `railtab generate`
# in each stage of its run and checks what is left: no table or a complete one (identical datasets
# to an uninterrupted run), no temporary after SIGTERM, and `--resume` finishing to identical
# datasets (h5diff) with no temporary and no checkpoint left.
# The signal is sent when the run shows it has reached the stage (its progress lines on stderr, or
# the file the stage writes), not after a fixed delay: the same points on a fast or a slow, quiet
# or busy machine, and no run needs to be long for a delay to land inside it.
# Usage: bash scripts/kill_test.sh [path/to/railtab]   (default build/release/generator/railtab)
set -euo pipefail
cd "$(dirname "$0")/.."
railtab=$(realpath "${1:-build/release/generator/railtab}")
[ -x "$railtab" ] || { echo "kill_test: $railtab not built" >&2; exit 2; }
work=$(mktemp -d /tmp/railtab_kill.XXXXXX)
trap 'rm -rf "$work"' EXIT
fails=0
fail() { echo "kill_test: FAIL: $*" >&2; fails=$((fails + 1)); }
# The STRIPES scene (the default track, fast models) on a coarser y grid (21 nodes): every stage of a run in a few seconds of CPU.
sed -e '/^y = \[/,/^\]/c y = { start = -0.010, stop = 0.010, step = 0.001 }' tables/default_stripes.toml > "$work/scene.toml"

same_datasets() {  # h5diff of everything but the root attributes (`created` differs by design)
  h5diff --exclude-attribute / "$work/ref.h5" "$1" > "$work/h5diff.txt" 2>&1
}
leftovers() { find "$work" -maxdepth 1 \( -name 'out.h5.tmp.*' -o -name 'out.h5.partial' \) -printf '%f '; }

# The stages of a run, in order, and what shows that the run is in one (stderr.txt: its log):
#   sweep    a quarter of the sweep done (its y blocks are in the checkpoint before the progress
#            line that counts them is printed)
#   jumps    locating the contact jumps (the sweep is complete and checkpointed)
#   sides    computing the one-sided values at the jumps
#   errmap   the error map (out.h5.errmap-stage, the table it reads, is written)
#   write    writing the table (its temporary out.h5.tmp.<pid> exists)
reached() {  # stage: 0 when the running generate's log or files show it
  case "$1" in
    sweep) grep -qE '^progress: +(2[5-9]|[3-9][0-9]|100)\.' "$work/stderr.txt" ;;
    jumps) grep -q '^locating contact jumps:' "$work/stderr.txt" ;;
    sides) grep -q '^one-sided jump values:' "$work/stderr.txt" ;;
    errmap) [ -e "$work/out.h5.errmap-stage" ] ;;
    write) compgen -G "$work/out.h5.tmp.*" > /dev/null ;;
  esac
}

start=$SECONDS
"$railtab" generate "$work/scene.toml" -o "$work/ref.h5" --threads 2 --quiet < /dev/null
echo "kill_test: reference run $((SECONDS - start)) s"

run_and_kill() {  # signal, stage, extra generate arguments...
  local sig=$1 stage=$2
  shift 2
  rm -f "$work"/out.h5*
  "$railtab" generate "$work/scene.toml" -o "$work/out.h5" --threads 2 "$@" < /dev/null 2> "$work/stderr.txt" &
  local pid=$!
  # Poll every 20 ms while the run lasts (bash reaps a finished child, so kill -0 then fails).
  local sent=no
  while kill -0 "$pid" 2> /dev/null; do
    if reached "$stage"; then
      kill -s "$sig" "$pid" 2> /dev/null && sent=yes
      break
    fi
    sleep 0.02
  done
  local rc=0
  { wait "$pid"; } 2> /dev/null || rc=$?  # (bash's own "Killed" line: the exit status says it)
  echo "kill_test: SIG$sig in stage $stage $*: $([ $sent = yes ] && echo sent || echo "NOT sent (the run ended first)"), exit $rc, left: $(leftovers)$([ -e "$work/out.h5" ] && echo out.h5)"
  # The table write is short: a fast machine may finish it before a poll sees its temporary.
  # Every other stage lasts seconds, so a run that ended before it means the log changed.
  [ $sent = yes ] || [ "$stage" = write ] || fail "SIG$sig: the run never showed stage $stage (its log: $(tail -1 "$work/stderr.txt"))"
  if [ -e "$work/out.h5" ]; then
    same_datasets "$work/out.h5" || fail "SIG$sig in stage $stage left an incomplete or different out.h5: $(head -3 "$work/h5diff.txt")"
  fi
  case "$sig:$rc" in
    TERM:143 | TERM:0 | KILL:137 | KILL:0) ;;
    *) fail "SIG$sig in stage $stage: exit status $rc ($(tail -1 "$work/stderr.txt"))" ;;
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
  "$railtab" generate "$work/scene.toml" -o "$work/out.h5" --threads 2 --quiet --resume < /dev/null ||
    { fail "--resume failed"; return; }
  same_datasets "$work/out.h5" || fail "--resume gave different datasets: $(head -3 "$work/h5diff.txt")"
  [ -z "$(leftovers)" ] || fail "--resume left $(leftovers)"
}

for sig in KILL TERM; do
  for stage in sweep jumps sides errmap write; do
    run_and_kill "$sig" "$stage" --resume
    resume_and_check
  done
done
# Without --resume, SIGTERM writes nothing and removes everything it made.
run_and_kill TERM sweep
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
