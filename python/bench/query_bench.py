# SPDX-License-Identifier: Apache-2.0
"""Python side of the query speed target (docs/lookup.md, "From Python"): ns per state of a
vectorised Table.query of 1e6
uniformly random states over the table's axes (wheels alternating, every output of every slot),
the same work as bench/lookup_vectorised_bench.cpp. Prints JSON: the best of `--repeat` runs, in
process CPU time (as Google Benchmark's CPU column; wall time on a shared machine is noise).

    PYTHONPATH=build/release/python /usr/bin/python3 python/bench/query_bench.py TABLE.h5
"""
import argparse
import json
import time

import numpy as np

import railtab


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("table")
    parser.add_argument("--states", type=int, default=1_000_000)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    table = railtab.Table.load(args.table)
    rng = np.random.default_rng(16)
    n = args.states
    state = {name: rng.uniform(nodes[0], nodes[-1], n) for name, nodes in table.axes.items()}
    wheel = np.arange(n, dtype=np.int32) % 2
    results = {}
    for as_xarray in (False, True):
        best = float("inf")
        for _ in range(args.repeat):
            start = time.process_time()
            r = table.query(wheel, **state, as_xarray=as_xarray)
            best = min(best, time.process_time() - start)
            del r
        results["xarray" if as_xarray else "arrays"] = best / n * 1e9
    print(json.dumps({"table": args.table, "states": n, "ns_per_state": results,
                      "axes": {k: len(v) for k, v in table.axes.items()}, "n_slots": table.n_slots}))


if __name__ == "__main__":
    main()
