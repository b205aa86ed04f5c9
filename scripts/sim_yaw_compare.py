#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""What reading yaw from the tables changes in a `railtab simulate` run: the same scene run on
yaw-free tables and with `--yaw-nodes` (docs/validation/yaw-tables.md, "Yaw in railtab simulate").

Usage: sim_yaw_compare.py FREE/NAME YAW/NAME S0 S1 [POST_PROCESSOR]
FREE/NAME, YAW/NAME: the two runs' result directories (OUT/<scene name>). S0, S1: bogie-centre
distance range [m] of the trajectory to summarise (the circular curve). POST_PROCESSOR (default:
the first of the runs' summary.json) whose wear is compared.
Prints per wear step: the worn area (mean of wheels and counted wheelsets) and its part at
u < -25 mm (flange root and flange, the flange-contact wear), and the leading wheelset's outer
(right, in the scenes' left curves) wheel's Y/Q over [S0, S1]: mean and largest |Y/Q| (Y the
contact's lateral force on the wheel, Q its vertical load), with the change in per cent, and the
leading wheelset's yaw range there in the yaw run. Step 0 runs on the scene's wheel in both; later
steps on each run's own worn wheel, so they add the profile evolution's response to the change.
"""
import csv
import json
import sys

FLANGE_ROOT_U = -0.025  # [m], simulation_run.hpp kFlangeRootU


def wear(run, processor, step):
    rows = list(csv.DictReader(open(f"{run}/{processor}/step{step}/wear.csv")))
    du = float(rows[1]["u_m"]) - float(rows[0]["u_m"])
    total = sum(float(r["depth_mean_m"]) for r in rows) * du
    flange = sum(float(r["depth_mean_m"]) for r in rows if float(r["u_m"]) < FLANGE_ROOT_U) * du
    return total * 1e6, flange * 1e6  # [mm2]


def leading_outer(run, processor, step, s0, s1):
    dynamics = "shared" if step == 0 else processor
    rows = [r for r in csv.DictReader(open(f"{run}/{dynamics}/step{step}/trajectory.csv"))
            if s0 <= float(r["s_m"]) <= s1]
    if not rows:
        sys.exit(f"{run}: no trajectory rows with s in [{s0}, {s1}] m")
    yq = [float(r["leading_lateral_force_right_N"]) / float(r["leading_load_right_N"]) for r in rows]
    yaw = [float(r["leading_yaw_rad"]) for r in rows]
    return sum(yq) / len(yq), max(abs(v) for v in yq), min(yaw), max(yaw)


def change(a, b):
    return f"{100.0 * (b / a - 1.0):+.2f} %" if a != 0.0 else "n/a"


def main():
    if len(sys.argv) not in (5, 6):
        sys.exit(__doc__)
    free, yawed, s0, s1 = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
    summary = json.load(open(f"{free}/summary.json"))
    processor = sys.argv[5] if len(sys.argv) == 6 else summary["post_processors"][0]["post_processor"]
    if not json.load(open(f"{yawed}/summary.json")).get("yaw_nodes_rad"):
        sys.exit(f"{yawed}/summary.json: not a run with --yaw-nodes")
    for step in range(summary["wear_steps"]):
        a, b = wear(free, processor, step), wear(yawed, processor, step)
        qa, qb = leading_outer(free, processor, step, s0, s1), leading_outer(yawed, processor, step, s0, s1)
        print(f"step {step}: worn area {a[0]:.4f} -> {b[0]:.4f} mm2 ({change(a[0], b[0])}); "
              f"u < -25 mm {a[1]:.4f} -> {b[1]:.4f} mm2 ({change(a[1], b[1])}); "
              f"leading outer wheel Y/Q mean {qa[0]:.5f} -> {qb[0]:.5f} ({change(qa[0], qb[0])}), "
              f"max |Y/Q| {qa[1]:.5f} -> {qb[1]:.5f} ({change(qa[1], qb[1])}); "
              f"leading yaw [{qb[2] * 1e3:.2f}, {qb[3] * 1e3:.2f}] mrad")


if __name__ == "__main__":
    main()
