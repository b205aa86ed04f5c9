#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# MPI generation end to end (ctest label `mpi`): `mpirun -n 3 railtab generate` gives the same
# datasets as a single-process run; SIGKILL of one rank mid-run leaves no table file and a
# checkpoint from which `--resume` finishes the same datasets.
# Usage: mpi_generate_test.sh RAILTAB SCENE WORKDIR
set -euo pipefail
railtab=$1 scene=$2 work=$3
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1  # CI runs as root
export OMPI_MCA_rmaps_base_oversubscribe=1                        # 3 ranks on 2 cores
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }
# Every dataset and attribute but the root's (`created`, the time of the run, differs by design).
same_datasets() { h5diff --exclude-attribute=/ "$1" "$2"; }

"$railtab" generate "$scene" -o single.h5 --threads 1 --quiet
mpirun -n 3 "$railtab" generate "$scene" -o mpi.h5 --threads 1 --quiet
same_datasets single.h5 mpi.h5 || fail "mpirun -n 3 table differs from the single-process table"
[ ! -e mpi.h5.partial ] || fail "checkpoint left after a complete MPI run"
echo "ok: mpirun -n 3 gives the single-process datasets"

# Kill a worker rank mid-run. Race-free: once rank 0 has created the checkpoint (every rank is past
# MPI_Init), rank 2 is stopped (SIGSTOP); rank 0 cannot finish the table without it, so the run is
# frozen short of completion while ranks 0 and 1 fill the checkpoint; then rank 2 gets SIGKILL.
# The ranks run at the lowest priority so that this script's polls are not starved by them (Open
# MPI's ranks busy-wait) or by other load: on a loaded machine the whole sweep could otherwise pass
# between two polls.
nice -n 19 mpirun -n 3 "$railtab" generate "$scene" -o killed.h5 --threads 1 --quiet > run.log 2>&1 &
launcher=$!
rank_pid() {  # the pid of MPI rank $1 under the launcher
  local pid
  for pid in $(pgrep -P "$launcher"); do
    # grep reads the whole environment (no -q): with pipefail, a grep that exits at the match
    # while tr still writes a large environment fails the pipe (SIGPIPE), and the rank is missed.
    if tr '\0' '\n' < "/proc/$pid/environ" 2>/dev/null | grep -x "OMPI_COMM_WORLD_RANK=$1" > /dev/null; then
      echo "$pid"
      return
    fi
  done
}
for _ in $(seq 1 3000); do [ -e killed.h5.partial ] && break; sleep 0.01; done
# Rank 2 looked up (again) until one is found and stopped: a lookup can miss a rank that is
# still starting, and a pid found early may be gone by the time of the stop.
victim=
for _ in $(seq 1 3000); do
  victim=$(rank_pid 2)
  [ -n "$victim" ] && kill -STOP "$victim" 2> /dev/null && break
  victim=
  [ -e killed.h5 ] && break
  sleep 0.01
done
[ -n "$victim" ] || fail "rank 2 could not be found and stopped under mpirun (did the run end first?)"
[ ! -e killed.h5 ] || fail "the run completed before rank 2 could be stopped; use a larger scene"
for _ in $(seq 1 3000); do
  [ "$(stat -c %s killed.h5.partial 2>/dev/null || echo 0)" -gt 4096 ] && break
  sleep 0.01
done
kill -KILL "$victim"
if wait "$launcher"; then fail "mpirun exited 0 after one of its ranks was killed"; fi
[ ! -e killed.h5 ] || fail "a table file exists after a rank was killed"
ls killed.h5.tmp* > /dev/null 2>&1 && fail "temporary table files left: $(ls killed.h5.tmp*)"
[ -s killed.h5.partial ] || fail "no checkpoint after a rank was killed"
echo "ok: killed rank $victim: no table, checkpoint of $(stat -c %s killed.h5.partial) bytes"

mpirun -n 3 "$railtab" generate "$scene" -o killed.h5 --threads 1 --resume --quiet
same_datasets single.h5 killed.h5 || fail "resumed MPI table differs from the single-process table"
[ ! -e killed.h5.partial ] || fail "checkpoint left after the resumed run completed"
echo "ok: --resume after the kill gives the single-process datasets"
