#pragma once
// OpenFOAM side of meshgen (private): the case files, checkMesh, and the
// gmshToFoam route (gmshToFoam, patch types) the direct polyMesh writer is
// tested against.
// Each application runs through the shared launcher (scene/foam.hpp) and
// logs to CASE/log.<application>, as OpenFOAM's RunFunctions do.
#include <map>
#include <string>

#include "scene/process.hpp"

namespace meshgen {

struct CheckMeshReport {
  bool ok = false;                   // "Mesh OK."
  double max_non_orthogonality = 0;  // degrees
  double max_skewness = 0;
  long cells = 0;
  std::string failures;              // the lines starting with *** when not ok
  // The failed checks that are only mesh-quality warnings (see
  // check_mesh_fatal); empty when ok or when a failure is fatal.
  bool warnings_only = false;
  double cpu_seconds = 0;            // of the checkMesh run (0 from parse_check_mesh)
};

// The FoamFile header of an ASCII OpenFOAM file.
std::string foam_header(const std::string& cls, const std::string& object, const std::string& location);
// Minimal system/{controlDict,fvSchemes,fvSolution}: checkMesh (and
// gmshToFoam) refuse a case without them.
void write_control_dict(const std::string& case_dir);
// CASE/mesh.msh -> CASE/constant/polyMesh. RunError naming the log on failure.
scene::ChildTimes run_gmsh_to_foam(const std::string& case_dir);
// Rewrites constant/polyMesh/boundary with a type (and group) per patch.
// RunError when a patch is missing or an unnamed patch has faces.
void set_patch_types(const std::string& case_dir, const std::map<std::string, std::string>& types);
// Runs checkMesh and parses its log. RunError when checkMesh did not run to
// its verdict (crashed, no log); a failed check is reported, not thrown.
CheckMeshReport run_check_mesh(const std::string& case_dir);
// Parses checkMesh output (exposed for tests).
CheckMeshReport parse_check_mesh(const std::string& log);

}  // namespace meshgen
