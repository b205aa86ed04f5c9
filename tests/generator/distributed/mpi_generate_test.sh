#!/usr/bin/env bash
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

# Kill one rank (not rank 0's process necessarily: any of them) once a block is in the checkpoint.
mpirun -n 3 "$railtab" generate "$scene" -o killed.h5 --threads 1 --quiet > run.log 2>&1 &
launcher=$!
for _ in $(seq 1 1000); do
  [ "$(stat -c %s killed.h5.partial 2>/dev/null || echo 0)" -gt 4096 ] && break
  sleep 0.01
done
ranks=$(pgrep -P "$launcher" -f "railtab generate" || true)
[ -n "$ranks" ] || fail "no rank process found under mpirun (did the run end before the kill?)"
victim=$(echo "$ranks" | tail -n 1)
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
