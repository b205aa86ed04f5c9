#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Median speed ratio of the half-space model against CONTACT on block C.

Reads the Google Benchmark JSON of (after `cmake --build --preset release --target halfspace_bench`)
    build/release/bench/halfspace_bench --benchmark_filter=BM_BlockC --benchmark_format=json
(a file name as the only argument) and prints the number of cases, our median CPU and wall
time per case, and the medians over the cases of CONTACT's wall_s (the counter contact_wall_s)
divided by our CPU time and by our wall time (docs/validation/halfspace.md, the exact model's speed).
"""
import json
import statistics
import sys

UNIT_MS = {"s": 1e3, "ms": 1.0, "us": 1e-3, "ns": 1e-6}


def main() -> int:
    if len(sys.argv) != 2:
        print("usage: halfspace_speed_ratio.py BENCHMARK_JSON", file=sys.stderr)
        return 2
    with open(sys.argv[1], encoding="utf-8") as f:
        data = json.load(f)
    cases = [b for b in data.get("benchmarks", []) if b.get("name", "").startswith("BM_BlockC/")
             and b.get("run_type", "iteration") == "iteration"]
    if not cases:
        print(f"{sys.argv[1]}: no BM_BlockC results (is ../shared/reference present?)",
              file=sys.stderr)
        return 1
    cpu = [b["cpu_time"] * UNIT_MS[b["time_unit"]] for b in cases]
    wall = [b["real_time"] * UNIT_MS[b["time_unit"]] for b in cases]
    contact = [b["contact_wall_s"] * 1e3 for b in cases]
    print(f"cases {len(cases)}")
    print(f"our median per case: CPU {statistics.median(cpu):.1f} ms, wall "
          f"{statistics.median(wall):.1f} ms; CONTACT median wall {statistics.median(contact):.0f} ms")
    print(f"median ratio CONTACT wall / our CPU: {statistics.median([c / t for c, t in zip(contact, cpu)]):.1f}")
    print(f"median ratio CONTACT wall / our wall: {statistics.median([c / t for c, t in zip(contact, wall)]):.1f}")
    print(f"load average during the run: {data.get('context', {}).get('load_avg')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
