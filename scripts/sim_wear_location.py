#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Where the wheelsets ran and where each post-processor's wear sits, for a `railtab simulate` run
(docs/validation/wear-cases.md, "R1500: where the wheelset runs decides the sign").

Usage: sim_wear_location.py OUT/NAME S0 S1 [STEP]
S0, S1: bogie-centre distance range [m] of the trajectory to summarise (e.g. the circular curve).
STEP (default 0): the wear step; its dynamics is shared/step0 for step 0, else the first
post-processor's own run. Prints per counted wheelset the lateral position relative to the rails
(mean, range, standard deviation) and the share of rows with the outer (right) wheel's flange slot
loaded; then per post-processor and wheel (left = inner in the scenes' left curves, right = outer,
both = the wheelset's mean) the depth-weighted centroid u, the share of the depth at u < 0 and at
u < -25 mm, and STRIPES-A (or the second post-processor) minus the first.
"""
import csv
import json
import statistics
import sys


def locate(u, depth):
    total = sum(depth)
    if total <= 0.0:
        return (0.0, 0.0, 0.0)
    return (1e3 * sum(a * b for a, b in zip(u, depth)) / total,
            100.0 * sum(b for a, b in zip(u, depth) if a < 0.0) / total,
            100.0 * sum(b for a, b in zip(u, depth) if a < -0.025) / total)


def main():
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    out, s0, s1 = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
    step = int(sys.argv[4]) if len(sys.argv) == 5 else 0
    try:
        summary = json.load(open(f"{out}/summary.json"))
    except FileNotFoundError:  # a wrong OUT/NAME, or a run that was interrupted (summary.json comes last)
        sys.exit(f"{out}/summary.json: no such file: give OUT/NAME of a finished `railtab simulate` run")
    processors = [m["post_processor"] for m in summary["post_processors"]]
    positions = summary["positions"]
    dynamics = f"{out}/shared/step0" if step == 0 else f"{out}/{processors[0]}/step{step}"
    rows = [r for r in csv.DictReader(open(f"{dynamics}/trajectory.csv")) if s0 <= float(r["s_m"]) <= s1]
    if not rows:
        sys.exit(f"no trajectory rows with {s0} <= s <= {s1} m in {dynamics}")
    for w in positions:
        y = [1e3 * float(r[f"{w}_y_relative_m"]) for r in rows]
        flange = sum(1 for r in rows if float(r[f"{w}_n_right_flange_N"]) > 0.0)
        print(f"{w}: y {statistics.mean(y):+.2f} mm ({min(y):+.2f} to {max(y):+.2f}, sd {statistics.pstdev(y):.2f}); "
              f"right flange slot loaded in {100.0 * flange / len(rows):.0f} % of {len(rows)} rows")
    located = {}
    for p in processors:
        table = list(csv.DictReader(open(f"{out}/{p}/step{step}/wear.csv")))
        u = [float(r["u_m"]) for r in table]
        for w in positions:
            left = [float(r[f"depth_left_{w}_m"]) for r in table]
            right = [float(r[f"depth_right_{w}_m"]) for r in table]
            located[p, w, "left"] = locate(u, left)
            located[p, w, "right"] = locate(u, right)
            located[p, w, "both"] = locate(u, [a + b for a, b in zip(left, right)])
    for w in positions:
        for wheel in ("left", "right", "both"):
            cells = [f"{p} {c:+7.2f} mm {s:5.1f} % {r:5.1f} %" for p in processors
                     for c, s, r in [located[p, w, wheel]]]
            line = f"{w:8s} {wheel:5s} | " + " | ".join(cells)
            if len(processors) > 1:
                other = "stripes-a" if "stripes-a" in processors[1:] else processors[1]
                a, b = located[other, w, wheel], located[processors[0], w, wheel]
                line += f" | {other} - {processors[0]}: {a[0] - b[0]:+.2f} mm {a[1] - b[1]:+.1f} {a[2] - b[2]:+.1f} points"
            print(line)


if __name__ == "__main__":
    main()
