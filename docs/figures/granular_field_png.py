# Render one lattice field of a fields.vti as a PNG with gnuplot.
# usage: granular_field_png.py FIELDS.vti FIELD OUT.png TITLE [GNUPLOT_EXTRA]
# usage: field_png.py FIELDS.vti FIELD OUT.png TITLE
import sys, math, subprocess, os
sys.path.insert(0, os.path.dirname(__file__)); import granular_vti as vti
L = vti.read(sys.argv[1]); F = L['F'][sys.argv[2]]; ins = L['F']['inside_body']
dat = sys.argv[3] + '.dat'
with open(dat, 'w') as f:
    for j in range(L['ny']):
        for i in range(L['nx']):
            c = i + L['nx'] * j
            v = F[c]
            f.write('%g %g %s\n' % (L['x0'] + (i + .5) * L['dx'], L['y0'] + (j + .5) * L['dy'], 'NaN' if (ins[c] == 1 or not math.isfinite(v)) else '%g' % v))
        f.write('\n')
xr = (L['x0'], L['x0'] + L['nx'] * L['dx']); yr = (L['y0'], L['y0'] + L['ny'] * L['dy'])
ratio = (yr[1] - yr[0]) / (xr[1] - xr[0])
gp = f"""set terminal pngcairo size 900,{int(900*ratio)+80}
set termoption noenhanced
set output '{sys.argv[3]}'
set title '{sys.argv[4]}'
set xrange [{xr[0]}:{xr[1]}]; set yrange [{yr[0]}:{yr[1]}]
set size ratio -1
set xlabel 'x / L'; set ylabel 'y / L'
set palette rgbformulae 33,13,10
{sys.argv[5] if len(sys.argv) > 5 else ''}
plot '{dat}' using 1:2:3 with image notitle
"""
subprocess.run(['gnuplot'], input=gp.encode(), check=True)
os.remove(dat)
