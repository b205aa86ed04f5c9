#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Load coupling acceptance numbers from two `railtab chart` runs (docs/validation.md, flange load).

Usage: flange_load_metrics.py BEFORE/speed_accuracy_states.csv AFTER/speed_accuracy_states.csv
BEFORE is the chart of a scene with `load_coupling = false` in [contact], AFTER the same scene
coupled. Per model (chart label): the flange rows' (dy >= 7 mm) normal force against CONTACT's,
and the creep force error |F - F_CONTACT| / (mu N_CONTACT) on the flange creep rows (set != a_none),
median and worst, before and after. mu = 0.3 (block C).
"""
import csv
import math
import statistics
import sys

MU = 0.3


def load(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith('#')))


def creep_error(r):
    f = float
    return math.hypot(f(r['fx_N']) - f(r['ref_fx_N']), f(r['fy_N']) - f(r['ref_fy_N'])) / (MU * f(r['ref_fn_N']))


def main(before_path, after_path):
    before, after = load(before_path), load(after_path)
    key = lambda r: (r['label'], r['dy_mm'], r['creep_set'])
    before_by_key = {key(r): r for r in before}
    labels = list(dict.fromkeys(r['label'] for r in after))
    print('# normal force N/N_CONTACT - 1 [%] on the flange rows, after (before)')
    for label in labels:
        cells = []
        for r in after:
            if r['label'] != label or float(r['dy_mm']) < 7:
                continue
            b = before_by_key[key(r)]
            ref = float(r['ref_fn_N'])
            cells.append(f"dy{float(r['dy_mm']):.0f} {r['creep_set']} {100 * (float(r['fn_N']) / ref - 1):+.1f} "
                         f"({100 * (float(b['fn_N']) / ref - 1):+.1f})")
        print(f'{label}: ' + '; '.join(cells))
    print()
    print('# flange creep rows: |F - F_CONTACT| / (mu N_CONTACT) [%], median / worst; '
          'in brackets without dy = 7 b_long0.001')
    print('model | before | after')
    for label in labels:
        errors = {'before': [], 'after': [], 'before_x': [], 'after_x': []}
        for r in after:
            if r['label'] != label or float(r['dy_mm']) < 7 or r['creep_set'] == 'a_none':
                continue
            b = before_by_key[key(r)]
            odd = float(r['dy_mm']) == 7 and r['creep_set'] == 'b_long0.001'
            for name, row in (('before', b), ('after', r)):
                errors[name].append(creep_error(row))
                if not odd:
                    errors[name + '_x'].append(creep_error(row))
        cell = lambda n: (f"{100 * statistics.median(errors[n]):.1f} / {100 * max(errors[n]):.1f} "
                          f"({100 * statistics.median(errors[n + '_x']):.1f} / {100 * max(errors[n + '_x']):.1f})")
        print(f"{label} | {cell('before')} | {cell('after')}")


if __name__ == '__main__':
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
