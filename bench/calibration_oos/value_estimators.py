#!/usr/bin/env python3
"""Candidate values of an attached shock's angle, refitted offline from recorded runs.

For each run's shockfit summary.json (interval_group_values, group_own_angles_deg):
  P   the pooled fit's angle (shock_angle_pooled_deg where present) and the reported interval,
  G   the mean of the groups refitted on the pooled stations, Student's t x standard error
      (at least the own fits' half-width),
  O   the mean of the groups' own fits (outliers beyond 3.5 robust sigmas left out), t x SE,
  OG  O's value with the larger of the two half-widths (what shockfit reports since the
      groups' own fits' mean became the angle).
Prints per candidate: error against the gas angle (RMS / max / mean), the within-wedge sd,
the median half-width and how many same-wedge pairs differ by less than their combined
half-widths (docs/shockfit.md, "The groups' mean standoff"). With --scatter DEG first, also
how many runs' prediction bands (hypot(half-width, 1.96 DEG), pipeline::band_angle_half_width_deg
with the table's scatter DEG) hold the gas angle.

  bench/calibration_oos/value_estimators.py [--scatter DEG] ANGLE_CHECK_OUTDIR...
      (directories written by angle_check.sh)
  bench/calibration_oos/value_estimators.py --coverage GAS_ANGLE_DEG COVERAGE_OUTDIR
      (a directory written by bench/coverage/coverage.sh)
"""
import glob
import json
import math
import os
import statistics as st
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..'))
from student_t import t95  # noqa: E402

OUTLIER_SIGMAS = 3.5


def near_median(v):
    # shockfit::near_median: the median (mean of the middle two), the upper middle distance
    m = st.median(v)
    s = 1.4826 * sorted(abs(x - m) for x in v)[len(v) // 2]
    return [x for x in v if abs(x - m) <= OUTLIER_SIGMAS * s] if s > 0 else v


def mean_and_half(v):
    v = [x for x in v if x is not None and math.isfinite(x)]
    if len(v) < 4:
        return float('nan'), float('nan')
    return st.mean(v), t95(len(v) - 1) * st.stdev(v) / math.sqrt(len(v))


def candidates(summary, gas):
    g = [x for x in summary['interval_group_values'] if x is not None]
    o = [x for x in summary['group_own_angles_deg'] if x is not None]
    mg, hg = mean_and_half(g)
    mo, ho = mean_and_half(near_median(o) if len(o) >= 4 else o)
    both = max(hg, ho) if math.isfinite(ho) else hg
    # Since the groups' own fits' mean is the reported angle, the pooled line's is kept aside.
    pooled = summary.get('shock_angle_pooled_deg')
    if pooled is None:
        pooled = summary['shock_angle_deg']
    return dict(gas=gas, P=(pooled, summary['shock_angle_ci_deg']),
                G=(mg, both), O=(mo, ho), OG=(mo, both))


def load(path):
    with open(path) as f:
        return json.load(f)


def angle_check_runs(dirs):
    out = {}
    for d in dirs:
        for w in sorted(glob.glob(d + '/oos_*')):
            if not os.path.exists(w + '/gas/summary.json'):
                continue
            gas = load(w + '/gas/summary.json')['shock_angle_deg']
            for s in sorted(glob.glob(w + '/seed*/shockfit/summary.json')):
                j = load(s)
                if j['shock'] == 'attached':
                    out.setdefault(os.path.basename(w), []).append(candidates(j, gas))
    return out


def report(groups, scatter=None):
    for k in ('P', 'G', 'O', 'OG'):
        errs, var, hws, pairs, npairs, band = [], [], [], 0, 0, 0
        for rs in groups.values():
            vals = [r[k][0] for r in rs]
            errs += [r[k][0] - r['gas'] for r in rs]
            hws += [r[k][1] for r in rs]
            if scatter is not None:
                band += sum(abs(r[k][0] - r['gas']) <= math.hypot(r[k][1], 1.96 * scatter) for r in rs)
            if len(vals) > 1:
                var.append(st.variance(vals))
            for i in range(len(rs)):
                for j in range(i + 1, len(rs)):
                    npairs += 1
                    pairs += abs(rs[i][k][0] - rs[j][k][0]) <= math.hypot(rs[i][k][1], rs[j][k][1])
        rms = math.sqrt(sum(e * e for e in errs) / len(errs))
        print('%-3s runs %d  error RMS %.3f max %.2f mean %+.3f  within sd %.3f  median half-width %.3f'
              '  pairs %d/%d' % (k, len(errs), rms, max(abs(e) for e in errs), st.mean(errs),
                                 math.sqrt(st.mean(var)) if var else float('nan'), st.median(hws),
                                 pairs, npairs) +
              ('  band holds gas %d/%d' % (band, len(errs)) if scatter is not None else ''))


if __name__ == '__main__':
    if len(sys.argv) >= 2 and sys.argv[1] == '--coverage':
        gas = float(sys.argv[2])
        runs = [candidates(j, gas) for j in (load(p) for p in
                sorted(glob.glob(sys.argv[3] + '/s*/s/summary.json'))) if j['shock'] == 'attached']
        report({'all': runs})
    elif len(sys.argv) >= 4 and sys.argv[1] == '--scatter':
        report(angle_check_runs(sys.argv[3:]), float(sys.argv[2]))
    elif len(sys.argv) >= 2:
        report(angle_check_runs(sys.argv[1:]))
    else:
        sys.exit(__doc__)
