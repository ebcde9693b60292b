# Percent-difference field between two fields.vti (a run and the same run
# with a tiny perturbation of the initial state), as PNG data + statistics.
# usage: granular_perturbation.py A.vti B.vti OUT.png
import sys, os, math, subprocess
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import granular_vti as vti
A, B = vti.read(sys.argv[1]), vti.read(sys.argv[2])
na, nb = A['F']['volume_fraction'], B['F']['volume_fraction']
sa, sb = A['F']['volume_fraction_se'], B['F']['volume_fraction_se']
dat = sys.argv[3] + '.dat'
zs, pct, diffs, var = [], [], [], []
with open(dat, 'w') as f:
    for j in range(A['ny']):
        for i in range(A['nx']):
            c = i + A['nx'] * j
            v = 'NaN'
            if all(math.isfinite(x) for x in (na[c], nb[c])) and na[c] > 0:
                p = 100 * (nb[c] - na[c]) / na[c]
                v = '%g' % p
                pct.append(p)
                if math.isfinite(sa[c]) and math.isfinite(sb[c]) and sa[c] + sb[c] > 0:
                    zs.append((nb[c] - na[c]) / math.hypot(sa[c], sb[c]))
                    diffs.append(nb[c] - na[c])
                    var.append(sa[c] ** 2 + sb[c] ** 2)
            f.write('%g %g %s\n' % (A['x0'] + (i + .5) * A['dx'], A['y0'] + (j + .5) * A['dy'], v))
        f.write('\n')
mean = lambda x: sum(x) / len(x)
rms = lambda x: math.sqrt(sum(t * t for t in x) / len(x))
# With 2 replicas each cell's standard error has one degree of freedom, so
# per-cell z-scores are heavy-tailed (Student t, 1 dof): compare the rms
# difference with the pooled standard error instead (1 means: noise only),
# and the mean difference with its own standard error (systematic shift).
pooled = rms(diffs) / math.sqrt(mean(var))
# A uniform shift would show in the domain total: compare the two runs'
# mean disk counts with the spread between replicas of one run.
import json
def counts(vti_path):
    j = json.load(open(os.path.join(os.path.dirname(vti_path), 'summary.json')))
    return [r['particles_mean'] for r in j['per_replica']]
ca, cb = counts(sys.argv[1]), counts(sys.argv[2])
shift = 100 * (mean(cb) - mean(ca)) / mean(ca)
spread = 100 * (max(ca) - min(ca)) / mean(ca)
print('cells %d  mean %% diff %.3f  rms %% diff %.3f  rms diff / pooled se %.3f (1: noise only)  median |z| %.3f  '
      'disk count shift %.2f %% vs replica spread %.2f %%'
      % (len(pct), mean(pct), rms(pct), pooled, sorted(abs(z) for z in zs)[len(zs) // 2], shift, spread))
xr = (A['x0'], A['x0'] + A['nx'] * A['dx']); yr = (A['y0'], A['y0'] + A['ny'] * A['dy'])
ratio = (yr[1] - yr[0]) / (xr[1] - xr[0])
gp = f"""set terminal pngcairo size 900,{int(900*ratio)+80}
set output '{sys.argv[3]}'
set title 'volume fraction: percent difference after a 1e-12 perturbation (mean {mean(pct):.2f}%, rms {rms(pct):.2f}%)'
set xrange [{xr[0]}:{xr[1]}]; set yrange [{yr[0]}:{yr[1]}]
set size ratio -1
set xlabel 'x / L'; set ylabel 'y / L'
set palette defined (-1 'blue', 0 'white', 1 'red')
set cbrange [-15:15]
plot '{dat}' using 1:2:3 with image notitle
"""
subprocess.run(['gnuplot'], input=gp.encode(), check=True)
os.remove(dat)
