#pragma once
// gmsh in a child process (private). gmsh offers no way to interrupt a
// mesh generation and aborts the whole process ("terminate called", or a
// segfault) on some inputs; meshing in a forked child lets meshgen honour
// Ctrl-C within a poll interval (the child is killed) and turns a gmsh crash
// into a RunError instead of taking the caller down.
#include <string>

#include "gmsh_mesher.hpp"

namespace meshgen {

// mesh_with_gmsh in a forked child; the plane mesh comes back through
// `scratch_file` (removed afterwards). RunError when the child crashes, fails
// or is interrupted (scene::interrupted()); the child's InputError and
// RunError messages are passed on as the same kind.
PlaneMesh mesh_with_gmsh_in_child(const FluidRegion& region, const SizeField& size,
                                  const GmshJob& job, const std::string& scratch_file);
PlaneMesh mesh_with_gmsh_in_child(const FluidRegion& region, const SizeFunction& size,
                                  const std::vector<ShockStrip>& strips, const GmshJob& job,
                                  const std::string& scratch_file);

}  // namespace meshgen
