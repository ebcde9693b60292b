#include "foam_export.hpp"

#include <cstdlib>
#include <regex>
#include <set>
#include <sstream>

#include "scene/errors.hpp"
#include "scene/io.hpp"

namespace meshgen {

namespace {

constexpr const char* kFoamBashrc = "/usr/share/openfoam/etc/bashrc";

std::string quoted(const std::string& s) {
  std::string out = "'";
  for (const char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Runs `app args` in the case directory; returns the exit status.
int run_foam(const std::string& case_dir, const std::string& app, const std::string& args = "") {
  const std::string inner = "source " + std::string(kFoamBashrc) + " >/dev/null 2>&1; cd " + quoted(case_dir) +
                            " && " + app + " " + args + " > log." + app + " 2>&1";
  const std::string cmd = "bash -c " + quoted(inner);
  const int status = std::system(cmd.c_str());
  return status;
}

std::string foam_header(const std::string& cls, const std::string& object, const std::string& location) {
  return "FoamFile\n{\n    version     2.0;\n    format      ascii;\n    class       " + cls +
         ";\n    location    \"" + location + "\";\n    object      " + object + ";\n}\n";
}

}  // namespace

void write_control_dict(const std::string& case_dir) {
  scene::make_dirs(case_dir + "/system");
  scene::write_file_atomic(case_dir + "/system/controlDict",
                           foam_header("dictionary", "controlDict", "system") +
                               "// Written by meshgen so that gmshToFoam and checkMesh accept the case.\n"
                               "application     checkMesh;\nstartFrom       startTime;\nstartTime       0;\n"
                               "stopAt          endTime;\nendTime         1;\ndeltaT          1;\n"
                               "writeControl    timeStep;\nwriteInterval   1;\nwriteFormat     ascii;\n");
  // checkMesh builds an fvMesh, which reads these (content irrelevant to it).
  scene::write_file_atomic(case_dir + "/system/fvSchemes",
                           foam_header("dictionary", "fvSchemes", "system") +
                               "ddtSchemes { default Euler; }\ngradSchemes { default Gauss linear; }\n"
                               "divSchemes { default none; }\nlaplacianSchemes { default Gauss linear corrected; }\n"
                               "interpolationSchemes { default linear; }\nsnGradSchemes { default corrected; }\n");
  scene::write_file_atomic(case_dir + "/system/fvSolution", foam_header("dictionary", "fvSolution", "system"));
}

void run_gmsh_to_foam(const std::string& case_dir) {
  if (run_foam(case_dir, "gmshToFoam", "mesh.msh") != 0)
    throw scene::RunError("gmshToFoam failed; see " + case_dir + "/log.gmshToFoam");
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
    while (std::getline(is, line))
      if (line.find("***") != std::string::npos) r.failures += line.substr(line.find("***")) + "\n";
  }
  return r;
}

CheckMeshReport run_check_mesh(const std::string& case_dir) {
  (void)run_foam(case_dir, "checkMesh");  // non-zero also for a failed check: the log says which
  const std::string log = scene::read_file(case_dir + "/log.checkMesh");
  if (log.find("Checking geometry") == std::string::npos)
    throw scene::RunError("checkMesh did not run; see " + case_dir + "/log.checkMesh");
  return parse_check_mesh(log);
}

}  // namespace meshgen
