"""Reads our outputs with VTK's own readers and checks what a ParaView user
would look for: the granular lattice's arrays, and the OpenFOAM case's
internal fields and boundary patches."""
import math
import sys

try:
    import vtk
except ImportError:
    sys.exit("interop: python3-vtk9 is missing (apt-get install python3-vtk9; .ci/setup.sh does)")

vti_path, case_dir = sys.argv[1], sys.argv[2]
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)


# The granular lattice: an image with point or cell arrays of the flow fields.
r = vtk.vtkXMLImageDataReader()
r.SetFileName(vti_path)
r.Update()
img = r.GetOutput()
dims = img.GetDimensions()
check(dims[0] > 1 and dims[1] > 1, f"{vti_path}: image dimensions {dims}")
data = img.GetCellData() if img.GetCellData().GetNumberOfArrays() else img.GetPointData()
names = {data.GetArrayName(i) for i in range(data.GetNumberOfArrays())}
for need in ("volume_fraction", "u", "v"):
    check(need in names, f"{vti_path}: no array '{need}' (has {sorted(names)})")
if "volume_fraction" in names:
    lo, hi = data.GetArray("volume_fraction").GetRange()
    check(math.isfinite(lo) and math.isfinite(hi) and 0.0 <= lo <= hi < 1.0,
          f"{vti_path}: volume_fraction range {lo}..{hi}")

# The OpenFOAM case, through vtkOpenFOAMReader (the reader ParaView's .foam uses).
foam = case_dir + "/case.foam"
open(foam, "w").close()
# Time 0 is the template's 0.orig, whose "#includeEtc setConstraintTypes"
# VTK 9.1's reader cannot parse (OpenFOAM writes explicit types in every
# later time), so open the solution as a user does: the latest time.
f = vtk.vtkOpenFOAMReader()
f.SetFileName(foam)
f.SkipZeroTimeOn()
f.UpdateInformation()
f.EnableAllPatchArrays()
f.UpdateInformation()
times = f.GetTimeValues()
if times is not None and times.GetNumberOfTuples() > 0:
    f.UpdateTimeStep(times.GetValue(times.GetNumberOfTuples() - 1))
f.Update()
patches = {f.GetPatchArrayName(i) for i in range(f.GetNumberOfPatchArrays())}
for need in ("internalMesh", "patch/inlet", "patch/outlet", "patch/body"):
    check(need in patches, f"{case_dir}: no patch '{need}' (has {sorted(patches)})")
check(times is not None and times.GetNumberOfTuples() >= 2, f"{case_dir}: fewer than two written times")
out = f.GetOutput()
internal = None
it = out.NewIterator()
it.InitTraversal()
while not it.IsDoneWithTraversal():
    block = it.GetCurrentDataObject()
    if block is not None and block.GetNumberOfCells() > 0 and internal is None:
        internal = block
    it.GoToNextItem()
check(internal is not None, f"{case_dir}: no internal mesh block")
if internal is not None:
    cd = internal.GetCellData()
    fields = {cd.GetArrayName(i) for i in range(cd.GetNumberOfArrays())}
    for need in ("rho", "p", "T", "U"):
        check(need in fields, f"{case_dir}: internal mesh has no field '{need}' (has {sorted(fields)})")
    if "p" in fields:
        lo, hi = cd.GetArray("p").GetRange()
        check(0.0 < lo < hi, f"{case_dir}: pressure range {lo}..{hi} is not a shocked flow")

if failures:
    print("interop: " + "; ".join(failures), file=sys.stderr)
    sys.exit(1)
print(f"interop: {vti_path} ({dims[0]}x{dims[1]}, {len(names)} arrays) and {case_dir} "
      f"({len(patches)} patches) read by VTK {vtk.vtkVersion.GetVTKVersion()}")
