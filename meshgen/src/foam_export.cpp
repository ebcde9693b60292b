#include "foam_export.hpp"

#include <regex>
#include <set>
#include <sstream>

#include "scene/errors.hpp"
#include "scene/foam.hpp"
#include "scene/io.hpp"

namespace meshgen {

namespace {

// The checkMesh failures that only grade the mesh: faces more skewed than
// checkMesh's threshold (4) and cells beyond its aspect-ratio threshold
// (1000) reduce accuracy locally, but the mesh is still a valid
// finite-volume mesh that rhoCentralFoam runs on. Every other failure
// (negative volumes, wrong face pyramids, open cells or boundary,
// non-orthogonality errors beyond 90 degrees) makes the mesh unusable.
// Severe non-orthogonality (> 70 degrees) is a '*' note, not a failed
// check, and is accepted like any other note.
const char* const kQualityWarnings[] = {"highly skew faces", "High aspect ratio cells"};

bool is_quality_warning(const std::string& failure_line) {
  for (const char* w : kQualityWarnings)
    if (failure_line.find(w) != std::string::npos) return true;
  return false;
}

}  // namespace

std::string foam_header(const std::string& cls, const std::string& object, const std::string& location) {
  return "FoamFile\n{\n    version     2.0;\n    format      ascii;\n    class       " + cls +
         ";\n    location    \"" + location + "\";\n    object      " + object + ";\n}\n";
}

void write_control_dict(const std::string& case_dir) {
  scene::make_dirs(case_dir + "/system");
  scene::write_file_atomic(case_dir + "/system/controlDict",
                           foam_header("dictionary", "controlDict", "system") +
                               "// Written by meshgen so that OpenFOAM applications accept the case.\n"
                               "application     checkMesh;\nstartFrom       startTime;\nstartTime       0;\n"
                               "stopAt          endTime;\nendTime         1;\ndeltaT          1;\n"
                               "writeControl    timeStep;\nwriteInterval   1;\nwriteFormat     ascii;\n"
                               // gmshToFoam (the tests' reference route) then writes points exactly.
                               "writePrecision  17;\n");
  // checkMesh builds an fvMesh, which reads these (content irrelevant to it).
  scene::write_file_atomic(case_dir + "/system/fvSchemes",
                           foam_header("dictionary", "fvSchemes", "system") +
                               "ddtSchemes { default Euler; }\ngradSchemes { default Gauss linear; }\n"
                               "divSchemes { default none; }\nlaplacianSchemes { default Gauss linear corrected; }\n"
                               "interpolationSchemes { default linear; }\nsnGradSchemes { default corrected; }\n");
  scene::write_file_atomic(case_dir + "/system/fvSolution", foam_header("dictionary", "fvSolution", "system"));
}

scene::ChildTimes run_gmsh_to_foam(const std::string& case_dir) {
  scene::FoamProcess p(case_dir, "gmshToFoam", {"mesh.msh"});
  const int rc = p.wait();
  if (rc != 0)
    throw scene::RunError("gmshToFoam failed (exit " + std::to_string(rc) + "); see " + p.log_path());
  return p.times();
}

void set_patch_types(const std::string& case_dir, const std::map<std::string, std::string>& types) {
  const std::string path = case_dir + "/constant/polyMesh/boundary";
  std::string text = scene::read_file(path);
  // The patch list follows its entry count: N ( NAME { key value; ... } ... )
  std::smatch list_start;
  if (!std::regex_search(text, list_start, std::regex(R"(\n\d+\s*\n\()")))
    throw scene::RunError(path + ": no patch list");
  const auto list_pos = static_cast<std::size_t>(list_start.position(0));
  const std::regex entry(R"(\n(\s*)(\w+)\s*\n\s*\{([^}]*)\})");
  std::string out;
  std::set<std::string> seen;
  auto it = std::sregex_iterator(text.begin() + static_cast<std::ptrdiff_t>(list_pos), text.end(), entry);
  std::size_t last = 0;
  for (; it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    const std::string name = m[2].str(), indent = m[1].str();
    std::string body = m[3].str();
    const std::regex nfaces(R"(nFaces\s+(\d+)\s*;)");
    std::smatch nf;
    const long faces = std::regex_search(body, nf, nfaces) ? std::stol(nf[1].str()) : 0;
    const std::size_t pos = list_pos + static_cast<std::size_t>(m.position(0));
    out += text.substr(last, pos - last);
    last = pos + static_cast<std::size_t>(m.length(0));
    const auto t = types.find(name);
    if (t == types.end()) {
      if (faces > 0) throw scene::RunError(path + ": unexpected patch '" + name + "' with " + std::to_string(faces) + " faces");
      continue;  // drop empty leftovers such as defaultFaces
    }
    seen.insert(name);
    body = std::regex_replace(body, std::regex(R"(\n\s*(type|physicalType|inGroups)\s+[^;]*;)"), "");
    const std::string in = indent + "    ";
    const std::size_t first = body.find_first_not_of('\n');
    std::ostringstream entry_text;
    entry_text << "\n" << indent << name << "\n" << indent << "{\n" << in << "type            " << t->second << ";\n";
    if (t->second != "patch") entry_text << in << "inGroups        List<word> 1(" << t->second << ");\n";
    entry_text << (first == std::string::npos ? std::string() : body.substr(first)) << "}";
    out += entry_text.str();
  }
  out += text.substr(last);
  for (const auto& [name, type] : types)
    if (!seen.count(name)) throw scene::RunError(path + ": patch '" + name + "' missing after gmshToFoam");
  // The entry count in front of the list must match what is left.
  const std::regex count(R"(\n(\d+)\s*\n\()");
  std::string replacement = "\n";
  replacement += std::to_string(seen.size());
  replacement += "\n(";
  out = std::regex_replace(out, count, replacement, std::regex_constants::format_first_only);
  scene::write_file_atomic(path, out);
}

CheckMeshReport parse_check_mesh(const std::string& log) {
  CheckMeshReport r;
  std::smatch m;
  if (std::regex_search(log, m, std::regex(R"(non-orthogonality Max: ([-+0-9.eE]+))")))
    r.max_non_orthogonality = std::stod(m[1].str());
  if (std::regex_search(log, m, std::regex(R"(Max skewness = ([-+0-9.eE]+))"))) r.max_skewness = std::stod(m[1].str());
  if (std::regex_search(log, m, std::regex(R"(\n\s*cells:\s+(\d+))"))) r.cells = std::stol(m[1].str());
  r.ok = log.find("Mesh OK.") != std::string::npos;
  if (!r.ok) {
    std::istringstream is(log);
    std::string line;
    bool all_quality = true, any = false;
    while (std::getline(is, line)) {
      if (line.find("***") == std::string::npos) continue;
      const std::string failure = line.substr(line.find("***"));
      r.failures += failure + "\n";
      any = true;
      all_quality = all_quality && is_quality_warning(failure);
    }
    r.warnings_only = any && all_quality;
  }
  return r;
}

CheckMeshReport run_check_mesh(const std::string& case_dir) {
  scene::FoamProcess p(case_dir, "checkMesh", {});
  const int rc = p.wait();
  const std::string log = scene::read_file(p.log_path());
  // The verdict is read from the log: "Mesh OK." or "Failed N mesh checks."
  // (its exit code is not the verdict in every OpenFOAM version). A log
  // without either means checkMesh stopped before judging.
  const bool judged = log.find("Mesh OK.") != std::string::npos ||
                      std::regex_search(log, std::regex(R"(Failed \d+ mesh checks)"));
  if (log.find("Checking geometry") == std::string::npos || !judged)
    throw scene::RunError("checkMesh did not complete (exit " + std::to_string(rc) + "); see " + p.log_path());
  CheckMeshReport r = parse_check_mesh(log);
  r.cpu_seconds = p.cpu_seconds();
  return r;
}

}  // namespace meshgen
