#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Compare the creep and wear parts of two railtab tables of the same scene (h5dump, no h5py).

Usage: compare_tables.py A.h5 B.h5 [mu]
Per wheel: the creep part's normal force |N_B/N_A - 1|, the creep forces |F_B - F_A| / (mu N_A)
(F = (fx, fy)), |mz_B - mz_A| / max|mz_A|, wear |w_B - w_A| / max|w_A| and the number of cells
whose status differs; max and 99th percentile over the loaded cells (N_A > 0). mu defaults to 0.3.
"""
import math
import re
import subprocess
import sys



def dataset(path, name):
    text = subprocess.run(['h5dump', '-y', '-w', '0', '-m', '%.12g', '-d', name, path], check=True,
                          capture_output=True, text=True).stdout
    start = text.index('DATA {') + 6
    body = text[start:text.index('}', start)]
    return [float(v) for v in re.split(r'[,\s]+', body.strip()) if v]


def stats(values):
    ordered = sorted(values)
    return f'max {100 * ordered[-1]:.3f} %, p99 {100 * ordered[int(0.99 * (len(ordered) - 1))]:.3f} %'


def main(a, b, mu):
    for wheel in ('left', 'right'):
        get = lambda path, part, name: dataset(path, f'/{wheel}/{part}/{name}')
        n_a, n_b = get(a, 'creep', 'normal_force'), get(b, 'creep', 'normal_force')
        loaded = [i for i, n in enumerate(n_a) if n > 0]
        fx_a, fy_a = get(a, 'creep', 'fx'), get(a, 'creep', 'fy')
        fx_b, fy_b = get(b, 'creep', 'fx'), get(b, 'creep', 'fy')
        force = [math.hypot(fx_b[i] - fx_a[i], fy_b[i] - fy_a[i]) / (mu * n_a[i]) for i in loaded]
        mz_a, mz_b = get(a, 'creep', 'mz'), get(b, 'creep', 'mz')
        mz_scale = max(abs(v) for v in mz_a)
        mz = [abs(mz_b[i] - mz_a[i]) / mz_scale for i in loaded]
        w_a, w_b = get(a, 'wear', 'wear_rate'), get(b, 'wear', 'wear_rate')
        w_scale = max(abs(v) for v in w_a)
        wear = [abs(w_b[i] - w_a[i]) / w_scale for i in loaded]
        s_a, s_b = get(a, 'creep', 'status'), get(b, 'creep', 'status')
        status = sum(1 for x, y in zip(s_a, s_b) if x != y)
        dn = [abs(n_b[i] / n_a[i] - 1) for i in loaded]
        print(f'{wheel}: {len(loaded)} loaded creep cells; |dN|/N {stats(dn)}; '
              f'|dF|/(mu N) {stats(force)}; |dmz|/max|mz| {stats(mz)}; |dwear|/max wear {stats(wear)}; '
              f'status differs in {status} cells')


if __name__ == '__main__':
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], float(sys.argv[3]) if len(sys.argv) == 4 else 0.3)
