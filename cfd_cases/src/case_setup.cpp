#include "case_setup.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <stdexcept>

#include <fcntl.h>
#include <sys/stat.h>

#include <fmt/format.h>

#include "cfd/run_case.hpp"
#include "foam_process.hpp"
#include "scene/body_traits.hpp"
#include "scene/errors.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/io.hpp"

#ifndef CFD_TEMPLATE_SOURCE_DIR
#define CFD_TEMPLATE_SOURCE_DIR ""
#endif

namespace cfd {
namespace fs = std::filesystem;
using scene::InputError;

namespace {

// OpenFOAM's universal gas constant RR = 1e3 N_A k (J/(kmol K)) in v1912's
// thermodynamicConstants; molWeight = RR gamma gives R = 1/gamma.
constexpr double kFoamRR = 8314.47;

// OpenFOAM re-reads a modified controlDict only if its time stamp moved by
// more than fileModificationSkew (10 s in v1912's etc/controlDict). Dating
// the instantiated file back by this much lets the monitor's edit be seen
// however soon after the start it comes.
constexpr long kControlDictBackdateSeconds = 3600;

std::string num(double v) { return fmt::format("{:.12g}", v); }

// Allrun is shell text that users run by hand: the bashrc path enters it
// single-quoted, and the scene name (only inside a comment) on one line, so
// that neither can run a command.
std::string shell_quoted(const std::string& text) {
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}
std::string one_line(std::string text) {
  constexpr unsigned char kDelete = 0x7f;
  for (char& c : text)
    if (static_cast<unsigned char>(c) < ' ' || static_cast<unsigned char>(c) == kDelete) c = ' ';
  return text;
}

void backdate(const std::string& path) {
  struct timespec ts[2];
  clock_gettime(CLOCK_REALTIME, &ts[0]);
  ts[0].tv_sec -= kControlDictBackdateSeconds;
  ts[1] = ts[0];
  utimensat(AT_FDCWD, path.c_str(), ts, 0);
}

}  // namespace

namespace {
// Started at rest, a body's flow expands round its shoulders towards a vacuum
// at once. From that impulsive start Kurganov's flux diverged on discs and
// the Apollo capsule on 17 of 25 uniform grids at Mach 5-8 (h 0.025-0.2 body
// lengths, 3 flow-throughs; both shapes from Mach 5) and on none of 12 at
// Mach 3-4; Tadmor's, more dissipative, failed on none of 36
// (docs/reliability.md, "The flux from an impulsive start"). From the
// midpoint up, Tadmor from the start spares the failed attempt and the
// fallback's halved Courant number.
constexpr double kRestStartTadmorMach = 4.5;

bool attached_wedge(const scene::Scene& s) {
  return scene::attached_shock_beta(s).has_value();
}

// Whether gas at rest inside the domain may meet the free stream: below this
// limit the shock facing upstream between them runs out through the inlet.
bool above_rest_start_limit(const scene::Scene& s) {
  return s.freestream.mach >= scene::rest_start_min_mach(s.freestream.gamma);
}
}  // namespace

bool start_at_rest(const scene::Scene& s) {
  if (s.cfd.start != "auto") return s.cfd.start == "rest";
  return s.body && scene::starts_at_rest(*s.body) && above_rest_start_limit(s);
}

std::string initial_state(const scene::Scene& s) {
  if (s.cfd.start == "rest_behind_base") {
    if (!scene::sharp_base_inside_domain(s))
      throw InputError(s.source_file +
                       ": key 'cfd.start': rest_behind_base needs a body with a sharp base inside "
                       "the domain (a wedge whose shock stands off)");
    return "rest_behind_base";
  }
  if (start_at_rest(s)) return "rest";
  // Where the free stream meets the gas at rest, the shock facing upstream
  // runs out through the inlet below the rest-start limit, as in a start at
  // rest (the Mach 1.5, 20 deg wedge: 2.7 L ahead and still going at 10
  // flow-throughs, against 0.36 L steady from the free stream).
  if (s.cfd.start == "auto" && scene::sharp_base_inside_domain(s) && above_rest_start_limit(s))
    return "rest_behind_base";
  return "freestream";
}

std::string initial_velocity_field(const scene::Scene& s, const Mesh2D& mesh) {
  const std::string state = initial_state(s);
  const std::string u = num(s.freestream.mach);
  if (state == "rest") return "uniform (0 0 0)";
  if (state == "freestream") return "uniform (" + u + " 0 0)";
  const double x_base = scene::widest_station_x(s);
  const std::string ahead = "(" + u + " 0 0)\n", behind = "(0 0 0)\n";
  std::string out = fmt::format("nonuniform List<vector> {}\n(\n", mesh.cells());
  for (const scene::Vec2& c : mesh.cell_centre) out += c.x > x_base ? behind : ahead;
  return out + ")";
}

std::string outlet_velocity(const scene::Scene& s) {
  if (!scene::sharp_base_inside_domain(s)) return "type zeroGradient;";
  return "type inletOutlet; inletValue uniform (0 0 0);";
}

bool subsonic_outflow(const scene::Scene& s) {
  return scene::outflow_can_be_subsonic(s);
}

std::string far_field_pressure(const scene::Scene& s) {
  if (!subsonic_outflow(s)) return "type zeroGradient;";
  const Freestream f = freestream(s);
  return fmt::format(
      "type waveTransmissive; field p; phi phi; rho rho; psi thermo:psi; gamma {}; fieldInf {}; lInf {}; "
      "value uniform {};",
      num(f.gamma), num(f.p), num(kFarFieldRelaxationLength * scene::body_length(*s.body)), num(f.p));
}

std::string limiter(const scene::Scene& s) {
  if (s.cfd.limiter != "auto") return s.cfd.limiter;
  return attached_wedge(s) ? "vanLeer" : "Minmod";
}

std::string flux_scheme(const scene::Scene& s) {
  if (s.cfd.flux_scheme != "auto") return s.cfd.flux_scheme;
  // A free-stream start expands round a sharp base corner at once, towards a
  // vacuum: Kurganov's flux diverged there on 5 of the 6 grids of the Mach 2,
  // 30 deg wedge and Tadmor's, more dissipative, held (docs/reliability.md).
  // With the wake started at rest (rest_behind_base) Tadmor stays: under
  // Kurganov's flux the wake behind the Mach 3, 36 deg wedge, started at
  // rest, had not settled after 10 flow-throughs (Tadmor's: 9.4). Bodies
  // started at rest below kRestStartTadmorMach, and attached wedges cut at
  // their base, keep Kurganov.
  const bool rest = start_at_rest(s);
  if (!rest && scene::sharp_base_inside_domain(s)) return "Tadmor";
  if (rest && s.freestream.mach >= kRestStartTadmorMach) return "Tadmor";
  return "Kurganov";
}

bool local_time_stepping(const scene::Scene& s) {
  // auto is time-accurate for every flow. At half max_co LTS costs 1.8-2.6x
  // less CPU at equal error on clustered grids but 0.90-1.45x on uniform
  // ones (a uniform grid's local steps differ only by |U| + c), and three
  // uniform disc grids of eight, started at rest, diverged under it
  // (docs/bench_cfd.md).
  return s.cfd.local_time_stepping.value_or(false);
}

std::string template_dir() {
  std::vector<std::string> c;
  if (const char* e = std::getenv("SHOCKGRAIN_CFD_TEMPLATES")) c.emplace_back(e);
  c.emplace_back(CFD_TEMPLATE_SOURCE_DIR);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) c.push_back((exe.parent_path() / "../share/shockgrain/cfd_cases/templates").string());
  for (const auto& d : c)
    if (!d.empty() && fs::exists(fs::path(d) / "rhoCentralFoam/system/controlDict")) return d;
  throw InputError("cfd case templates not found (set SHOCKGRAIN_CFD_TEMPLATES to cfd_cases/templates)");
}

Freestream freestream(const scene::Scene& s) {
  Freestream f;
  f.mach = s.freestream.mach;
  f.gamma = s.freestream.gamma;
  return f;
}

std::string fill_placeholders(const std::string& text, const std::map<std::string, std::string>& values,
                              const std::string& origin) {
  std::string out = text;
  for (const auto& [k, v] : values) {
    const std::string key = "@" + k + "@";
    for (std::size_t p = out.find(key); p != std::string::npos; p = out.find(key, p + v.size()))
      out.replace(p, key.size(), v);
  }
  static const std::regex left(R"(@[A-Z_]+@)");
  std::smatch m;
  if (std::regex_search(out, m, left))
    throw std::logic_error(origin + ": placeholder " + m.str() + " has no value");
  return out;
}

double free_stream_time_step(const Mesh2D& m, const Freestream& f, double max_co) {
  double dt = std::numeric_limits<double>::infinity();
  const double c = std::sqrt(f.T);  // speed of sound, gamma R T with R = 1/gamma
  for (std::size_t k = 0; k < m.cells(); ++k) {
    double sum = 0;
    for (const auto& [len, n] : m.cell_edges[k]) sum += len * (std::abs(f.mach * n.x) + c);
    if (sum > 0) dt = std::min(dt, 2.0 * max_co * m.cell_area[k] / sum);
  }
  return dt;
}

long lts_steps_per_flow_through(const Mesh2D& m, const Freestream& f, double max_co, double width) {
  const double c = std::sqrt(f.T);
  double area = 0, weighted = 0;
  for (std::size_t k = 0; k < m.cells(); ++k) {
    double sum = 0;
    for (const auto& [len, n] : m.cell_edges[k]) sum += len * (std::abs(f.mach * n.x) + c);
    if (!(sum > 0)) continue;
    const double dt = 2.0 * max_co * m.cell_area[k] / sum;
    area += m.cell_area[k];
    weighted += m.cell_area[k] / dt;
  }
  if (!(area > 0) || !(f.mach > 0)) return 1;
  return std::max(1L, std::lround(width * weighted / (area * f.mach)));
}

void check_patches(const Mesh2D& m, const std::string& mesh_dir) {
  static const std::vector<std::string> roles{"inlet", "outlet", "top", "bottom", "body"};
  bool has_body = false, has_inlet = false;
  for (const PatchInfo& p : m.patches) {
    if (p.type == "empty" || p.type == "symmetryPlane" || p.type == "symmetry" || p.type == "processor") {
      if (p.name == "body" || p.name == "inlet")
        throw InputError(mesh_dir + "/constant/polyMesh/boundary: patch '" + p.name + "' has type " + p.type);
      continue;
    }
    if (std::find(roles.begin(), roles.end(), p.name) == roles.end())
      throw InputError(mesh_dir + "/constant/polyMesh/boundary: patch '" + p.name +
                       "' is not one of inlet, outlet, top, bottom, body (or an empty/symmetryPlane patch)");
    has_body = has_body || p.name == "body";
    has_inlet = has_inlet || p.name == "inlet";
  }
  if (!has_body || !has_inlet)
    throw InputError(mesh_dir + "/constant/polyMesh/boundary: the mesh needs patches 'inlet' and 'body'");
}

void write_case(const scene::Scene& s, const std::string& mesh_dir, const Mesh2D& mesh,
                const std::string& case_dir, const CaseSettings& cs) {
  const fs::path cd(case_dir);
  if (fs::exists(cd)) {
    const bool is_case = fs::exists(cd / "system/controlDict") || fs::is_empty(cd);
    if (!is_case)
      throw InputError(case_dir + ": exists and is not an OpenFOAM case (no system/controlDict); not replacing it");
    // Keep a mesh that lives inside the case directory itself.
    if (fs::equivalent(fs::path(mesh_dir), cd))
      throw InputError(case_dir + ": the mesh directory must differ from the case directory");
    fs::remove_all(cd);
  }
  scene::make_dirs(case_dir);
  const Freestream f = freestream(s);
  std::map<std::string, std::string> v{
      {"P_INF", num(f.p)},
      {"T_INF", num(f.T)},
      {"MACH", num(f.mach)},
      {"U_INTERNAL", initial_velocity_field(s, mesh)},
      {"OUTLET_U", outlet_velocity(s)},
      {"FAR_FIELD_P", far_field_pressure(s)},
      {"MOL_WEIGHT", num(kFoamRR * f.gamma)},
      {"CP", num(1.0 / (f.gamma - 1.0))},
      {"END_TIME", num(cs.end_time)},
      {"DELTA_T", num(cs.dt_ref)},
      {"WRITE_CONTROL", cs.lts ? "timeStep" : "adjustableRunTime"},
      {"WRITE_INTERVAL", cs.lts ? std::to_string(cs.write_steps) : num(cs.write_interval)},
      {"ADJUST_TIME_STEP", cs.lts ? "no" : "yes"},
      {"MAX_CO", num(cs.max_co)},
      {"RDELTAT_SMOOTHING", num(cs.lts_smoothing)},
      {"MAX_DELTA_T", num(cs.flow_through)},
      {"FLUX_SCHEME", flux_scheme(s)},
      {"DDT_SCHEME", cs.lts ? "localEuler" : "Euler"},
      {"RECONSTRUCT", limiter(s)},
      {"NP", std::to_string(cs.np)},
      {"FOAM_BASHRC", shell_quoted(foam_bashrc())},
      {"SCENE", one_line(s.name)},
  };
  const fs::path tdir = fs::path(template_dir()) / "rhoCentralFoam";
  for (const auto& e : fs::recursive_directory_iterator(tdir)) {
    const fs::path rel = fs::relative(e.path(), tdir);
    if (e.is_directory()) {
      fs::create_directories(cd / rel);
      continue;
    }
    const std::string text = fill_placeholders(scene::read_file(e.path().string()), v, e.path().string());
    scene::write_file_atomic((cd / rel).string(), text);
    if (rel == "Allrun") fs::permissions(cd / rel, fs::perms::owner_exec | fs::perms::group_exec,
                                         fs::perm_options::add);
  }
  scene::write_file_atomic((cd / "scene.yaml").string(), scene::to_yaml(s));
  fs::copy(fs::path(mesh_dir) / "constant/polyMesh", cd / "constant/polyMesh", fs::copy_options::recursive);
  fs::copy(cd / "0.orig", cd / "0", fs::copy_options::recursive);
  backdate((cd / "system/controlDict").string());
}

void set_control(const std::string& case_dir, const std::string& key, const std::string& value) {
  const std::string path = case_dir + "/system/controlDict";
  const std::string text = scene::read_file(path);
  const std::regex re("\\n" + key + "[ \\t]+[^;]*;");
  if (!std::regex_search(text, re)) throw std::logic_error(path + ": no entry " + key);
  scene::write_file_atomic(path, std::regex_replace(text, re, "\n" + key + "    " + value + ";",
                                                    std::regex_constants::format_first_only));
}

}  // namespace cfd
