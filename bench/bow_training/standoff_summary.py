#!/usr/bin/env python3
"""Standoff errors of several `standoff_check.sh` outputs, pooled.

    bench/bow_training/standoff_summary.py OUTDIR...

Each OUTDIR holds the runs.txt that standoff_check.sh wrote (one line per
seed: seed, restitution, standoff, half-width, relative error, ...). Prints
each directory's runs and mean, then over all runs: the RMS, the mean with
its 95% interval (Student t over the runs), how many lie within the 5%
target, and how many runs' own intervals hold the gas standoff. The
relative error is against the gas standoff the check was given.
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..'))
from student_t import t95  # noqa: E402

TARGET = 0.05  # the standoff target, relative


def read_runs(outdir):
    path = os.path.join(outdir, 'runs.txt')
    runs = []
    with open(path) as f:
        for line in f:
            cols = line.split()
            if len(cols) < 5:
                sys.exit(f'{path}: a line with fewer than 5 columns: {line.strip()}')
            standoff, half, rel = float(cols[2]), float(cols[3]), float(cols[4])
            gas = standoff / (1.0 + rel)
            runs.append((rel, abs(standoff - gas) <= half))
    if not runs:
        sys.exit(f'{path}: no runs')
    return runs


def main(dirs):
    errors, held = [], 0
    for d in dirs:
        runs = read_runs(d)
        rels = [r for r, _ in runs]
        errors += rels
        held += sum(h for _, h in runs)
        print(f'{d}: ' + ' / '.join(f'{100 * r:+.1f}' for r in rels) +
              f' %, mean {100 * sum(rels) / len(rels):+.1f}%')
    n = len(errors)
    mean = sum(errors) / n
    rms = math.sqrt(sum(e * e for e in errors) / n)
    within = sum(abs(e) <= TARGET for e in errors)
    line = f'{n} runs: RMS {100 * rms:.1f}%, mean {100 * mean:+.1f}%'
    if n > 1:
        sd = math.sqrt(sum((e - mean) ** 2 for e in errors) / (n - 1))
        h = t95(n - 1) * sd / math.sqrt(n)
        line += f' (95% {100 * (mean - h):+.1f} to {100 * (mean + h):+.1f})'
    print(line + f', {within} of {n} within {100 * TARGET:.0f}%, '
          f'the run\'s own interval holding the gas standoff in {held} of {n}')


if __name__ == '__main__':
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
