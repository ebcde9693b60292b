"""Minimal reader of scene::write_vti files (ASCII VTK ImageData, cell data),
for the granular figure scripts (python3 standard library only)."""
import re, sys, math
def read(path):
    s=open(path).read()
    m=re.search(r'WholeExtent="0 (\d+) 0 (\d+)',s); nx,ny=int(m[1]),int(m[2])
    o=re.search(r'Origin="(\S+) (\S+)',s); sp=re.search(r'Spacing="(\S+) (\S+)',s)
    F={}
    for name,body in re.findall(r'Name="(\w+)"[^>]*>(.*?)</DataArray>',s,re.S):
        F[name]=[float(x) for x in body.split()]
    return dict(nx=nx,ny=ny,x0=float(o[1]),y0=float(o[2]),dx=float(sp[1]),dy=float(sp[2]),F=F)
def up(L,name,xmax):
    v=[];F=L['F']
    for j in range(L['ny']):
        for i in range(L['nx']):
            x=L['x0']+(i+.5)*L['dx']; c=i+L['nx']*j
            if x<xmax and F['inside_body'][c]==0 and math.isfinite(F[name][c]): v.append(F[name][c])
    return sum(v)/len(v) if v else float('nan')
def shock(L,thr,xlo,xhi):
    F=L['F']['volume_fraction'];xs=[];ys=[]
    for i in range(L['nx']):
        x=L['x0']+(i+.5)*L['dx']
        if x<xlo or x>xhi: continue
        for j in range(L['ny']-1,0,-1):
            a=F[i+L['nx']*j]; b=F[i+L['nx']*(j-1)]
            if math.isfinite(a) and math.isfinite(b) and a<thr and b>=thr:
                t=(thr-a)/(b-a); xs.append(x); ys.append(L['y0']+(j+.5)*L['dy']-t*L['dy']); break
    n=len(xs); mx=sum(xs)/n; my=sum(ys)/n
    sxx=sum((x-mx)**2 for x in xs); sxy=sum((x-mx)*(y-my) for x,y in zip(xs,ys))
    sl=sxy/sxx; ic=my-sl*mx
    rss=sum((y-ic-sl*x)**2 for x,y in zip(xs,ys)); se=math.sqrt(rss/(n-2)/sxx)
    return math.degrees(math.atan(sl)), math.degrees(se/(1+sl*sl)), n, ic
def smooth_column_shock(L, thr, xlo, xhi, k=1):
    pass
