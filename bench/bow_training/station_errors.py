#!/usr/bin/env python3
"""One bow shock's stations against another's, station by station.

    bench/bow_training/station_errors.py GRANULAR.csv GAS.csv

Both files in shockfit's station layout (scene/shock_csv.hpp columns; a
prediction's shock_band.csv keeps it). Prints the number of stations accepted
in both, the mean and the RMS of (d_granular - d_gas) / d_gas: the measure of
`pipeline calibrate --bow-shock-runs` (bow_shock_scatter.cpp).
"""
import csv
import math
import sys


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith('#')))


def main(granular, gas):
    rel = []
    for g, c in zip(rows(granular), rows(gas)):
        if g['accepted'].strip() != '1' or c['accepted'].strip() != '1':
            continue
        dg, dc = float(g['distance']), float(c['distance'])
        if dc > 0 and math.isfinite(dg):
            rel.append(dg / dc - 1.0)
    if not rel:
        sys.exit(f'{granular} and {gas}: no station accepted in both')
    n = len(rel)
    print(f'{n} {sum(rel) / n:+.4f} {math.sqrt(sum(r * r for r in rel) / n):.4f}')


if __name__ == '__main__':
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
