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


def internal_mesh(reader):
    """The first block with cells (the internal mesh) and its cell arrays."""
    out = reader.GetOutput()
    it = out.NewIterator()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        block = it.GetCurrentDataObject()
        if block is not None and block.GetNumberOfCells() > 0:
            cd = block.GetCellData()
            return block, {cd.GetArrayName(i) for i in range(cd.GetNumberOfArrays())}
        it.GoToNextItem()
    return None, set()


# The solution as a user opens it: the latest time.
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
internal, fields = internal_mesh(f)
check(internal is not None, f"{case_dir}: no internal mesh block")
if internal is not None:
    for need in ("rho", "p", "T", "U"):
        check(need in fields, f"{case_dir}: internal mesh has no field '{need}' (has {sorted(fields)})")
    if "p" in fields:
        lo, hi = internal.GetCellData().GetArray("p").GetRange()
        check(0.0 < lo < hi, f"{case_dir}: pressure range {lo}..{hi} is not a shocked flow")

# The initial state opens too (its constraint patch types are written out
# in the template, not included from OpenFOAM's etc): the solver's inputs
# p, T and U, with a uniform free-stream pressure.
f0 = vtk.vtkOpenFOAMReader()
f0.SetFileName(foam)
f0.SkipZeroTimeOff()
f0.UpdateInformation()
times0 = f0.GetTimeValues()
check(times0 is not None and times0.GetNumberOfTuples() > 0 and times0.GetValue(0) == 0.0,
      f"{case_dir}: time 0 is not listed")
f0.UpdateTimeStep(0.0)
f0.Update()
internal0, fields0 = internal_mesh(f0)
check(internal0 is not None, f"{case_dir}: time 0: no internal mesh block")
if internal0 is not None:
    for need in ("p", "T", "U"):
        check(need in fields0, f"{case_dir}: time 0: internal mesh has no field '{need}' (has {sorted(fields0)})")
    if "p" in fields0:
        lo, hi = internal0.GetCellData().GetArray("p").GetRange()
        check(0.0 < lo == hi, f"{case_dir}: time 0: pressure range {lo}..{hi} is not the uniform free stream")

if failures:
    print("interop: " + "; ".join(failures), file=sys.stderr)
    sys.exit(1)
print(f"interop: {vti_path} ({dims[0]}x{dims[1]}, {len(names)} arrays) and {case_dir} "
      f"({len(patches)} patches) read by VTK {vtk.vtkVersion.GetVTKVersion()}")
