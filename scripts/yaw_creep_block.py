#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""How much a yaw table's creep block (the creep and wear parts over y, yaw, load and the normalised
creepage coordinates v) depends on yaw, against the table's own interpolation error (its error map):
the measurement behind docs/validation/yaw-tables.md, "Does the creep block need yaw?".

Usage: yaw_creep_block.py TABLE.h5   (a table with a yaw axis from 0 and normalised creep coordinates)

At every node (y, load, v_xi, v_eta, v_phi, slot) where the slot is loaded at yaw 0 and at the yaw
node, both wheels, the difference of the stored creep block between each yaw node and yaw 0 at the
same node. This is exactly the error a creep block stored at yaw 0 only would make at that yaw
(the scales, and so v at a physical creepage, and the law would still come from the yawed normal
part): fx, fy as F / (mu N) in % of mu N, mz in % of mu N c (c = sqrt(area / pi) of the creep
point), the vertical load share (the creep part's normal_force) in %, slip fraction in %, wear rate in
% of the node's; the status words compared too. Per y band and slot of the table's error map: the
largest difference beside the error map's RMS and maximum of the table against its own model (the
lookup, linear, at off-grid states). Prints one line per quantity and yaw node, then per band.
"""
import sys

import h5py
import numpy as np


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    f = h5py.File(sys.argv[1], "r")
    if "yaw" not in f["axes"] or f["axes/yaw"].shape == () or f["axes/yaw"][0] != 0.0:
        sys.exit(f"{sys.argv[1]}: no yaw axis starting at 0 (/axes/yaw)")
    yaw = f["axes/yaw"][()]
    y = f["axes/y"][()]
    em = f["error_map"]
    band_start, band_end = em["y_band_start"][()], em["y_band_end"][()]
    per_band = {}  # (band, slot) -> largest difference of fx, fy [% of mu N]
    print(f"{sys.argv[1]}: yaw nodes {', '.join(f'{1e3 * v:g}' for v in yaw)} mrad")
    print("yaw [mrad]  quantity             max |diff|   99th pct   median   (nodes loaded at both yaws)")
    for k in range(1, len(yaw)):
        worst = {}
        for wheel in ("left", "right"):
            c, w = f[f"{wheel}/creep"], f[f"{wheel}/wear"]
            share = c["normal_force"][()].astype("f8")  # dims y, yaw, load, xi, eta, phi, slot
            loaded = (share[:, 0] > 0) & (share[:, k] > 0)
            area = c["area"][()].astype("f8")
            cc = np.sqrt(np.maximum(area[:, 0], 1e-30) / np.pi)
            diffs = {
                "fx [% mu N]": 100 * np.abs(c["fx_normalised"][:, k].astype("f8") - c["fx_normalised"][:, 0]),
                "fy [% mu N]": 100 * np.abs(c["fy_normalised"][:, k].astype("f8") - c["fy_normalised"][:, 0]),
                "mz [% mu N c]": 100 * np.abs(c["mz_normalised"][:, k].astype("f8") - c["mz_normalised"][:, 0]) / cc,
                "share N [%]": 100 * np.abs(share[:, k] - share[:, 0]) / np.maximum(share[:, 0], 1e-30),
                "slip fraction [%]": 100 * np.abs(c["slip_fraction"][:, k].astype("f8") - c["slip_fraction"][:, 0]),
                "wear rate [%]": 100 * np.abs(w["wear_rate"][:, k].astype("f8") - w["wear_rate"][:, 0]) /
                np.maximum(np.abs(w["wear_rate"][:, 0].astype("f8")), 1e-30),
            }
            status_changed = (c["status"][:, k] != c["status"][:, 0]) & loaded
            for name, d in diffs.items():
                worst.setdefault(name, []).append(d[loaded])
            worst.setdefault("status", []).append(np.array([status_changed.sum(), loaded.sum()]))
            force = np.maximum(diffs["fx [% mu N]"], diffs["fy [% mu N]"])
            for b in range(len(band_start)):
                in_band = (y >= band_start[b]) & (y <= band_end[b])
                for s in range(share.shape[-1]):
                    sel = force[in_band][..., s][loaded[in_band][..., s]]
                    if sel.size:
                        key = (b, s)
                        per_band[key] = max(per_band.get(key, 0.0), float(sel.max()))
        for name, parts in worst.items():
            if name == "status":
                changed = sum(int(p[0]) for p in parts)
                total = sum(int(p[1]) for p in parts)
                print(f"{1e3 * yaw[k]:9.3g}   status changed       {changed} of {total} loaded nodes")
                continue
            d = np.concatenate(parts)
            print(f"{1e3 * yaw[k]:9.3g}   {name:19s}  {d.max():10.4g}  {np.percentile(d, 99):9.4g}  {np.median(d):8.3g}"
                  f"   ({d.size})")
    print("\nper y band and slot: largest |diff| of fx, fy over every yaw node [% of mu N] against the error map's"
          " table_vs_model (fx, fy) RMS / max [% of mu N]")
    print("band  y [mm]            slot    yaw diff    table RMS   table max")
    tv = em["table_vs_model"]
    for (b, s), v in sorted(per_band.items()):
        rms = max(tv["fx_rms"][b, s], tv["fy_rms"][b, s])
        mx = max(tv["fx_max"][b, s], tv["fy_max"][b, s])
        print(f"{b:4d}  {1e3 * band_start[b]:6.2f} .. {1e3 * band_end[b]:6.2f}  {['tread', 'flange'][s]:6s}  "
              f"{v:9.4g}   {rms:9.4g}   {mx:9.4g}")


if __name__ == "__main__":
    main()
