// generate_mesh: sizes -> gmsh -> OpenFOAM -> checks -> summary, staged in a
// folder beside OUT and swapped in only when complete.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <future>
#include <limits>
#include <optional>

#include "band_strip.hpp"
#include "extruded_layer.hpp"
#include "foam_export.hpp"
#include "gmsh_child.hpp"
#include "gmsh_mesher.hpp"
#include "meshgen/fluid_region.hpp"
#include "meshgen/mesh.hpp"
#include "meshgen/shock_extension.hpp"
#include "meshgen/size_field.hpp"
#include "msh_writer.hpp"
#include "plot.hpp"
#include "poly_mesh.hpp"
#include "scene/body_traits.hpp"
#include "scene/cli.hpp"
#include "scene/cpu_clock.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/staging.hpp"

namespace meshgen {

using scene::Vec2;
namespace fs = std::filesystem;

namespace {

// Target cell count: accepted within kTargetTolerance (10%: a user asking for 100k cells gets 90-110k); a
// retry is made beyond kTargetRetry, up to kMaxTargetAttempts meshes.
constexpr double kTargetTolerance = 0.10;
constexpr double kTargetRetry = 0.05;
constexpr int kMaxTargetAttempts = 4;
// A mesh within this fraction of its estimate leaves nothing to correct: a
// retry would choose the same sizes.
constexpr double kEstimateHeld = 0.01;
// Cells per h^2 of area: gmsh's recombined quad-dominant grids hold 1.5
// (measured / integrated 1.47-1.57 over every uniform, isotropic-band and
// strip grid of the recorded case-study runs, docs/meshgen.md); a triangle
// covers about h^2/2. Starting guesses, corrected from the first mesh when a
// target count is set.
constexpr double kCellsPerH2Quads = 1.5;
constexpr double kCellsPerH2Triangles = 2.0;
// Clipping the shock curve: crossings located to this fraction of h_min.
constexpr double kClipResolutionCells = 0.25;
// Refusals before gmsh starts (InputError, exit 2): gmsh aborts the
// process when it runs out of memory and needs ~1 KB and ~10 us per cell, so
// a grid beyond kMaxCells (minutes, gigabytes) is a typo, not a request; and
// cells below kMinCellSize body lengths meet gmsh's geometric tolerance
// (points closer than 1e-10 body lengths are merged).
constexpr double kMaxCells = 5e6;
constexpr double kMinCellSize = 1e-5;
// Large grids are meshed as pieces between vertical cuts (region_split.hpp),
// one per kCellsPerPiece estimated cells, up to kMaxPieces. gmsh's 2D
// meshing costs more than linearly in a surface's cells: wedge_M3_10 at
// 108k cells, gmsh CPU s (min of 3, loaded host) 9.5 whole, 8.2 in 2
// pieces, 6.6 in 4, 5.2 in 8 (docs/meshgen.md). Grids below 2
// kCellsPerPiece stay whole, as before the cuts. The pieces are meshed one
// after another (kGmshThreads): on two threads gmsh's grid depended on how
// the threads interleaved (the disc's 54k-cell uniform grid came out 54094
// or 54205 cells from one request), and a grid must depend only on its
// request; one thread costs ~2 s of wall time on a 110k-cell grid and no CPU.
constexpr double kCellsPerPiece = 12000.0;
constexpr int kMaxPieces = 8;
constexpr int kGmshThreads = 1;
// Zoom window half-size in cells of h_min (at least kZoomBands band half-widths).
constexpr double kZoomCells = 12.0;
constexpr double kZoomBands = 3.0;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

nlohmann::json domain_json(const scene::Domain& d) {
  return {{"xmin", d.xmin}, {"xmax", d.xmax}, {"ymin", d.ymin}, {"ymax", d.ymax}, {"symmetric", d.symmetric}};
}

double cell_size(const PlaneMesh& m, const std::array<int, 4>& c) {
  const int n = c[3] < 0 ? 3 : 4;
  double sum = 0.0;
  for (int k = 0; k < n; ++k)
    sum += scene::norm(m.nodes[static_cast<std::size_t>(c[static_cast<std::size_t>((k + 1) % n)])] -
                       m.nodes[static_cast<std::size_t>(c[static_cast<std::size_t>(k)])]);
  return sum / n;
}

Vec2 centroid(const PlaneMesh& m, const std::array<int, 4>& c) {
  const int n = c[3] < 0 ? 3 : 4;
  Vec2 s;
  for (int k = 0; k < n; ++k) s += m.nodes[static_cast<std::size_t>(c[static_cast<std::size_t>(k)])];
  return s / n;
}

// Everything that depends on the size scale factor.
struct Sizing {
  double scale = 1.0;
  SizeParams params;
  double uniform_h = 0;
  std::vector<ShockRun> runs;
  double band_min = 0, band_max = 0;
};

struct Plan {
  bool uniform = false;
  SizeParams base;          // clustered sizes at scale 1 (scene coordinates)
  double uniform_h = 0;     // uniform size at scale 1
  std::optional<double> band_width;  // scene coordinates
  std::vector<Vec2> curve;   // as predicted, extended to the region's edge (shock_extension.hpp)
  std::vector<double> ci;
  double extension_start = 0, extension_end = 0;  // scene units added at either end
  std::shared_ptr<const scene::Lattice> size_lattice;  // adapted grids (body lengths)
  std::string size_field_path;                         // where it was read from
  std::optional<double> target;
  double anisotropy = 1.0;  // mesh.anisotropy: > 1 lays shock-aligned strips in the band

  bool strips() const { return anisotropy > 1.0 && !uniform && !size_lattice; }
  Sizing at(double scale, const FluidRegion& region) const {
    Sizing z;
    z.scale = scale;
    z.params = base;
    z.params.h_min *= scale;
    z.params.h_max *= scale;
    z.params.h_body *= scale;
    z.uniform_h = uniform_h * scale;
    std::vector<double> w(curve.size());
    const double base_width = band_half_width(band_width, z.params.h_min);
    for (std::size_t i = 0; i < curve.size(); ++i) {
      double wi = base_width;
      if (i < ci.size() && std::isfinite(ci[i])) wi = std::max(wi, ci[i]);
      w[i] = wi;
    }
    if (!curve.empty()) {
      z.band_min = *std::min_element(w.begin(), w.end());
      z.band_max = *std::max_element(w.begin(), w.end());
    }
    z.runs = clip_shock(curve, w, region, kClipResolutionCells * z.params.h_min);
    return z;
  }
  SizeField field(const Sizing& z, const FluidRegion& region) const {
    if (uniform) return SizeField(z.uniform_h);
    if (size_lattice) return SizeField(z.params, size_lattice, z.scale * region.length_scale, region.body.polyline);
    return SizeField(z.params, z.runs, region.body.polyline);
  }
  StripRule strip_rule(const Sizing& z) const {
    return {z.params.h_min, anisotropy, z.params.h_max, z.params.growth};
  }
  // The cell count of the grid this sizing makes: cells_per_h2 x
  // estimate_cells' sum(dA / h^2); with strips, their cells counted exactly
  // and the isotropic field that grows from their outlines summed round them
  // (the strips laid go to `laid`, when given, for the mesher).
  double cells(const Sizing& z, const FluidRegion& region, double cells_per_h2,
               BandLayout* laid = nullptr) const {
    if (!strips()) return cells_per_h2 * estimate_cells(field(z, region), region);
    BandLayout band = layout_strips(z.runs, region, strip_rule(z));
    const StripGridCount c =
        count_cells(band, BandSize(z.params, band, region.body.polyline), region);
    if (laid) *laid = std::move(band);
    return cells_per_h2 * c.unstructured + c.strip_cells;
  }
};

// Scale factor whose estimated count (times the calibration) hits the target.
double solve_scale(const Plan& plan, const FluidRegion& region, double target, double calibration) {
  double lo = 1e-3, hi = 1e3;  // wide bracket on a monotone (decreasing) count
  for (int it = 0; it < 40; ++it) {
    const double mid = std::sqrt(lo * hi);
    const double n = plan.cells(plan.at(mid, region), region, calibration);
    (n > target ? lo : hi) = mid;
    if (hi / lo < 1.002) break;
  }
  return std::sqrt(lo * hi);
}

std::string fmt_g(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// Refuses a size request before any file is written.
void check_sizes(const std::string& where, double h_min_rel, double h_max_rel, std::optional<double> target) {
  if (!std::isfinite(h_min_rel) || !(h_min_rel > 0) || !std::isfinite(h_max_rel) || !(h_max_rel > 0))
    throw scene::InputError(where + "h_min and h_max must be finite positive numbers (body lengths), got " +
                            fmt_g(h_min_rel) + " and " + fmt_g(h_max_rel));
  if (h_min_rel < kMinCellSize)
    throw scene::InputError(where + "h_min " + fmt_g(h_min_rel) + " is below the smallest cell size meshgen accepts, " +
                            fmt_g(kMinCellSize) + " body lengths");
  if (target && !(std::isfinite(*target) && *target >= 1.0 && *target <= kMaxCells))
    throw scene::InputError(where + "target_cells must be a finite number in [1, " + fmt_g(kMaxCells) + "], got " +
                            fmt_g(*target));
}

void check_estimate(const std::string& where, double estimate, double h_min, double area) {
  if (std::isfinite(estimate) && estimate <= kMaxCells) return;
  throw scene::InputError(where + "the grid would have about " + fmt_g(estimate) + " cells (flow area " + fmt_g(area) +
                          " over h_min^2 = " + fmt_g(h_min * h_min) + " at the finest), above meshgen's limit of " +
                          fmt_g(kMaxCells) + "; raise mesh.h_min / mesh.h_max or lower the target");
}

// Body cell size of a request: the request's h_body, then the scene's.
double body_size(const MeshRequest& r, const scene::MeshParams& mp, const SizeParams& base, double L) {
  const std::optional<double> h_body = r.h_body ? r.h_body : mp.h_body;
  return body_cell_size(h_body ? std::optional<double>(*h_body * L) : std::nullopt, base.h_min, base.h_max);
}

// The plan of a request, refused (InputError) before anything is written
// when the scene is subsonic, a size is not finite or out of range, or the
// estimated cell count is beyond kMaxCells.
struct CheckedPlan {
  Plan plan;
  double estimate = 0;  // cells at the requested sizes (first attempt)
  double scale = 1.0;   // the sizes' scale that meets a target cell count (first attempt)
};

CheckedPlan make_checked_plan(const scene::Scene& s, const MeshRequest& r, const FluidRegion& region,
                              const std::string& where) {
  CheckedPlan c;
  Plan& plan = c.plan;
  const double L = region.length_scale;
  const scene::MeshParams& mp = s.mesh;
  plan.uniform = r.uniform;
  plan.base.h_min = r.h_min.value_or(mp.h_min) * L;
  plan.base.h_max = r.h_max.value_or(mp.h_max) * L;
  check_sizes(where, r.h_min.value_or(mp.h_min), r.h_max.value_or(mp.h_max), r.target_cells);
  if (r.h_body && !(std::isfinite(*r.h_body) && *r.h_body > 0))
    throw scene::InputError(where + "h_body must be a finite positive number (body lengths), got " + fmt_g(*r.h_body));
  if (r.h_min && !r.h_max) plan.base.h_max = std::max(plan.base.h_max, plan.base.h_min);
  if (r.h_max && !r.h_min) plan.base.h_min = std::min(plan.base.h_min, plan.base.h_max);
  if (!(plan.base.h_min > 0) || plan.base.h_min > plan.base.h_max)
    throw scene::InputError(where + "h_min must be positive and not exceed h_max");
  plan.base.h_body = body_size(r, mp, plan.base, L);
  plan.base.growth = mp.growth;
  plan.anisotropy = scene::band_anisotropy(s);
  plan.uniform_h = r.h_min ? *r.h_min * L : mp.h_uniform ? *mp.h_uniform * L : mp.h_min * L;
  if (mp.band_width) plan.band_width = *mp.band_width * L;
  plan.curve = r.shock_curve;
  plan.ci = r.shock_ci;
  if (mp.extend_shock && !plan.curve.empty()) {
    ExtendedShock e = extend_shock_to_boundary(plan.curve, plan.ci, region);
    plan.curve = std::move(e.curve);
    plan.ci = std::move(e.ci);
    plan.extension_start = e.start_length;
    plan.extension_end = e.end_length;
  }
  plan.target = r.target_cells ? r.target_cells : (r.h_min || r.h_max) ? std::nullopt : mp.target_cells;
  plan.size_lattice = r.size_field;
  plan.size_field_path = r.size_field_path;
  if (r.size_field && (r.uniform || !r.shock_curve.empty()))
    throw scene::InputError(where + "a size field is a grid of its own: give it without a shock curve or --uniform");
  if (!r.uniform && r.shock_curve.empty() && !r.size_field)
    throw scene::InputError(where + "a clustered grid needs a shock curve (meshgen --shock shock.csv) or a size "
                            "field (--size-field)");

  if (plan.uniform && plan.uniform_h / L < kMinCellSize)
    throw scene::InputError(where + "uniform cell size " + fmt_g(plan.uniform_h / L) +
                            " is below the smallest cell size meshgen accepts, " + fmt_g(kMinCellSize) +
                            " body lengths");
  if (plan.target && *plan.target > kMaxCells)
    throw scene::InputError(where + "target_cells " + fmt_g(*plan.target) + " is above meshgen's limit of " +
                            fmt_g(kMaxCells) + " cells");
  const double flow_area = region.domain.width() * region.domain.height();
  {
    // The estimate at the requested sizes, before anything is written.
    const double cells_per_h2 = mp.recombine ? kCellsPerH2Quads : kCellsPerH2Triangles;
    c.scale = plan.target ? solve_scale(plan, region, *plan.target, cells_per_h2) : 1.0;
    const Sizing z = plan.at(c.scale, region);
    c.estimate = plan.cells(z, region, cells_per_h2);
    check_estimate(where, c.estimate, plan.uniform ? z.uniform_h : z.params.h_min, flow_area);
  }
  return c;
}

}  // namespace

nlohmann::json MeshResult::summary() const {
  nlohmann::json j = details;
  j["kind"] = kind;
  j["cells"] = cells;
  j["min_cell_size"] = min_cell_size;
  j["max_cell_size"] = max_cell_size;
  j["max_non_orthogonality"] = max_non_orthogonality;
  j["max_skewness"] = max_skewness;
  j["check_mesh_ok"] = check_mesh_ok;
  j["seconds"] = seconds;
  return j;
}

std::string mesh_where(const scene::Scene& s) {
  return (s.source_file.empty() ? s.name : s.source_file) + ": mesh: ";
}

double check_mesh_request(const scene::Scene& s, const MeshRequest& r) {
  scene::require_supersonic(s, "meshgen");
  return make_checked_plan(s, r, make_fluid_region(s), mesh_where(s)).estimate;
}

namespace {

void stop_if_interrupted(const std::string& step, const std::string& out_dir) {
  if (scene::interrupted())
    throw scene::RunError("interrupted " + step + "; " + out_dir + " is unchanged");
}

GmshJob gmsh_job(const scene::MeshParams& mp) {
  GmshJob job;
  job.recombine = mp.recombine;
  job.frontal = mp.algorithm == "frontal";
  job.smoothing = mp.smoothing;
  job.threads = kGmshThreads;
  return job;
}

// What gmsh made of a plan: one mesh, or up to kMaxTargetAttempts when a
// target cell count is set (each attempt corrects the estimate's calibration).
struct Meshed {
  Sizing sizing;
  PlaneMesh mesh;
  double gmsh_seconds = 0.0;  // wall time of the last attempt
  double gmsh_cpu = 0.0;      // CPU time of every attempt
  double estimate = 0.0;      // cells estimated for the last attempt
  int attempts = 0;
  BandLayout band;  // shock-aligned strips (mesh.anisotropy > 1)
  // Why gmsh could not mesh round the strips, when it could not: the band
  // was then meshed isotropically (mesh.anisotropy 1).
  std::optional<std::string> strips_dropped;
};

// gmsh on the plan's field, or round shock-aligned strips when the plan asks
// for them (band_strip.hpp).
PlaneMesh mesh_plan(const Plan& plan, const FluidRegion& region, const SizeField& field,
                    const Meshed& m, const GmshJob& job, const fs::path& stage) {
  const std::string scratch = (stage / "plane_mesh.bin").string();
  if (!plan.strips()) return mesh_with_gmsh_in_child(region, field, job, scratch);
  const SizeParams& p = m.sizing.params;  // m.band: laid when the plan counted its cells
  const BandSize size(p, m.band, region.body.polyline);
  const SizeFunction h = [&size](Vec2 q) { return size(q); };
  return mesh_with_gmsh_in_child(region, h, m.band.strips, job, scratch);
}

// mesh_plan; a strip layout gmsh rejects should not cost the grid: the band
// is then meshed isotropically (the grid the scene had before strips), the
// plan loses its strips for later attempts and `m` records why.
PlaneMesh mesh_or_drop_strips(Plan& plan, const FluidRegion& region, const SizeField& field,
                              Meshed& m, const GmshJob& job, const fs::path& stage,
                              double calibration) {
  try {
    return mesh_plan(plan, region, field, m, job, stage);
  } catch (const scene::RunError& e) {
    if (!plan.strips() || scene::interrupted()) throw;
    m.strips_dropped = e.what();
    plan.anisotropy = 1.0;
    m.band = {};
    m.estimate = plan.cells(m.sizing, region, calibration);
    return mesh_plan(plan, region, field, m, job, stage);
  }
}

Meshed mesh_to_target(const CheckedPlan& checked, const FluidRegion& region, GmshJob& job,
                      const fs::path& stage, const std::string& where, const std::string& out_dir) {
  Plan plan = checked.plan;  // loses its strips if gmsh cannot mesh round them
  const double flow_area = region.domain.width() * region.domain.height();
  double scale = checked.scale,
         calibration = job.recombine ? kCellsPerH2Quads : kCellsPerH2Triangles;
  Meshed m;
  for (;;) {
    ++m.attempts;
    // The first attempt's scale was solved with the plan.
    if (plan.target && m.attempts > 1) scale = solve_scale(plan, region, *plan.target, calibration);
    m.sizing = plan.at(scale, region);
    if (!plan.curve.empty() && m.sizing.runs.empty())
      throw scene::InputError(where + "the shock curve lies wholly outside the flow region (inside the body or "
                              "beyond the domain)");
    const SizeField field = plan.field(m.sizing, region);
    m.estimate = plan.cells(m.sizing, region, calibration, &m.band);
    job.thickness = plan.uniform ? m.sizing.uniform_h : m.sizing.params.h_max;
    job.pieces = static_cast<int>(
        std::clamp(std::floor(m.estimate / kCellsPerPiece), 1.0, static_cast<double>(kMaxPieces)));
    check_estimate(where, m.estimate, plan.uniform ? m.sizing.uniform_h : m.sizing.params.h_min,
                   flow_area);
    stop_if_interrupted("before meshing", out_dir);
    const auto t0 = std::chrono::steady_clock::now();
    const double cpu_before = scene::children_cpu_seconds();
    m.mesh = mesh_or_drop_strips(plan, region, field, m, job, stage, calibration);
    m.gmsh_seconds = seconds_since(t0);
    // The child's CPU time: what gmsh itself cost, whatever the load; every
    // attempt at a target cell count costs.
    m.gmsh_cpu += scene::children_cpu_seconds() - cpu_before;
    if (!plan.target) break;
    const double n = static_cast<double>(m.mesh.cells.size());
    const double miss = std::abs(n / *plan.target - 1.0);
    if (miss <= kTargetRetry) break;
    // The estimate was right, so the count itself jumps near the target (a
    // strip that fits or not): another mesh would land on the same grid.
    const bool estimate_held = std::abs(n / m.estimate - 1.0) <= kEstimateHeld;
    if (m.attempts >= kMaxTargetAttempts || estimate_held) {
      if (miss <= kTargetTolerance) break;
      throw scene::RunError(where + "target_cells " +
                            std::to_string(static_cast<long>(*plan.target)) +
                            " not met within 10% after " + std::to_string(m.attempts) +
                            " meshes (last " + std::to_string(m.mesh.cells.size()) + ")");
    }
    // Strip cells are counted exactly: only the unstructured grid's count
    // per h^2 is corrected, or a grid mostly of strips would over-correct.
    double strip_cells = 0.0;
    for (const ShockStrip& st : m.band.strips) strip_cells += static_cast<double>(st.cells());
    calibration *= std::max(n - strip_cells, 1.0) / std::max(m.estimate - strip_cells, 1.0);
  }
  return m;
}

// Cell sizes over the grid and inside the shock band.
struct CellSizes {
  double min = std::numeric_limits<double>::infinity(), max = 0.0;
  double band_max = 0.0;
  long band_cells = 0;
  BandShape band_shape;
};

CellSizes measure_cell_sizes(const PlaneMesh& mesh, const Sizing& sizing, double growth) {
  CellSizes out;
  // The band as the clustered field defines it (also measured on uniform
  // grids, for comparison), at the sizes actually used.
  SizeParams band_params = sizing.params;
  band_params.h_max = std::max(band_params.h_max, band_params.h_min * growth);
  const SizeField band_field(band_params, sizing.runs, {});
  BandShapeMeter shape(sizing.runs);
  for (const auto& c : mesh.cells) {
    const double h = cell_size(mesh, c);
    out.min = std::min(out.min, h);
    out.max = std::max(out.max, h);
    if (!sizing.runs.empty() && band_field.in_band(centroid(mesh, c))) {
      ++out.band_cells;
      out.band_max = std::max(out.band_max, h);
      std::vector<Vec2> corners;
      for (const int k : c)
        if (k >= 0) corners.push_back(mesh.nodes[static_cast<std::size_t>(k)]);
      shape.add(corners);
    }
  }
  out.band_shape = shape.result();
  return out;
}

// The OpenFOAM case of the staged mesh: constant/polyMesh written directly
// from the plane mesh, then checkMesh. `meanwhile` (what nothing on the way
// reads: mesh.msh, the plots) runs on a second thread while checkMesh runs.
struct FoamCase {
  std::map<std::string, std::string> patch_types;
  CheckMeshReport check;
  double cpu_seconds = 0.0;  // checkMesh
};

FoamCase export_to_foam(const fs::path& stage, const FluidRegion& region, const PlaneMesh& mesh,
                        double thickness, const std::string& out_dir,
                        const std::function<void(const ExtrudedLayer&)>& meanwhile) {
  FoamCase f;
  const std::vector<FoamPatch> patches = foam_patches(region.domain.symmetric);
  for (const FoamPatch& p : patches) f.patch_types[p.name] = p.type;
  const ExtrudedLayer layer = extrude_layer(mesh);
  write_control_dict(stage.string());
  write_poly_mesh(mesh, layer, thickness, patches, stage.string());
  stop_if_interrupted("after writing the OpenFOAM mesh", out_dir);
  auto side = std::async(std::launch::async, [&] { meanwhile(layer); });
  f.check = run_check_mesh(stage.string());
  side.get();
  f.cpu_seconds = f.check.cpu_seconds;
  return f;
}

// The PNGs of the grid and a zoom on the shock; a plotting failure is
// reported in the summary, not fatal.
struct Plots {
  nlohmann::json png = nlohmann::json::array();
  nlohmann::json error = nullptr;
};

Plots plot_grid(const scene::Scene& s, const Meshed& m, const Plan& plan, const FluidRegion& region,
                const std::string& kind, const fs::path& stage) {
  Plots out;
  try {
    const Sizing& sizing = m.sizing;
    PlotWindow zoom;
    zoom.half = std::max(kZoomCells * sizing.params.h_min, kZoomBands * sizing.band_max);
    if (plan.uniform) zoom.half = std::max(kZoomCells * sizing.uniform_h, kZoomBands * sizing.band_max);
    zoom.center = region.body.nose;
    if (!sizing.runs.empty()) {
      const auto& run = *std::max_element(sizing.runs.begin(), sizing.runs.end(),
                                          [](const ShockRun& a, const ShockRun& b) { return a.points.size() < b.points.size(); });
      zoom.center = run.points[run.points.size() / 2];
    }
    for (const std::string& f :
         plot_mesh(m.mesh, sizing.runs, region, zoom, s.name + " " + kind, stage.string()))
      out.png.push_back(f);
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  return out;
}

nlohmann::json mesh_details(const scene::Scene& s, const Plan& plan, const FluidRegion& region,
                            const GmshJob& job, const Meshed& m, const CellSizes& sizes,
                            const FoamCase& foam, const Plots& plots, const scene::CpuStopwatch& cpu) {
  const Sizing& sizing = m.sizing;
  const scene::MeshParams& mp = s.mesh;
  nlohmann::json j;
  j["scene"] = s.name;
  j["length_unit"] = "scene coordinates (sizes below); mesh parameters are in body lengths";
  j["body_length"] = region.length_scale;
  // CPU seconds (load-independent cost): this process and its children
  // (gmsh over all attempts, checkMesh, plotting) from the start.
  j["cpu_seconds"] = cpu.seconds();
  j["gmsh_cpu_seconds"] = m.gmsh_cpu;
  j["foam_cpu_seconds"] = foam.cpu_seconds;
  j["quads"] = m.mesh.quads;
  j["triangles"] = m.mesh.triangles;
  j["hexahedra"] = m.mesh.quads;
  j["prisms"] = m.mesh.triangles;
  j["h_min"] = plan.uniform ? sizing.uniform_h : sizing.params.h_min;
  j["h_max"] = plan.uniform ? sizing.uniform_h : sizing.params.h_max;
  j["h_body"] = plan.uniform ? sizing.uniform_h : sizing.params.h_body;
  j["growth"] = sizing.params.growth;
  j["thickness"] = job.thickness;
  j["band_half_width_min"] = sizing.runs.empty() ? nlohmann::json(nullptr) : nlohmann::json(sizing.band_min);
  j["band_half_width_max"] = sizing.runs.empty() ? nlohmann::json(nullptr) : nlohmann::json(sizing.band_max);
  j["band_cells"] = sizes.band_cells;
  j["band_max_cell_size"] =
      sizes.band_cells ? nlohmann::json(sizes.band_max) : nlohmann::json(nullptr);
  const auto band_figure = [&](double v) {
    return sizes.band_cells ? nlohmann::json(v) : nlohmann::json(nullptr);
  };
  j["anisotropy"] = m.strips_dropped ? 1.0 : plan.anisotropy;
  j["strips_dropped"] =
      m.strips_dropped ? nlohmann::json(*m.strips_dropped) : nlohmann::json(nullptr);
  j["band_max_aspect_ratio"] = band_figure(sizes.band_shape.max_aspect);
  j["band_mean_aspect_ratio"] = band_figure(sizes.band_shape.mean_aspect);
  j["band_max_thickness"] = band_figure(sizes.band_shape.max_thickness);
  long strip_cells = 0;
  for (const ShockStrip& st : m.band.strips) strip_cells += static_cast<long>(st.cells());
  j["band_strips"] = m.band.strips.size();
  j["band_strip_cells"] = strip_cells;
  j["target_cells"] = plan.target ? nlohmann::json(*plan.target) : nlohmann::json(nullptr);
  j["estimated_cells"] = m.estimate;
  j["mesh_attempts"] = m.attempts;
  j["gmsh_pieces"] = m.mesh.pieces;
  j["size_field"] = plan.size_lattice ? nlohmann::json(plan.size_field_path) : nlohmann::json(nullptr);
  j["shock_points"] = plan.curve.size();
  j["shock_extension"] = {plan.extension_start / region.length_scale, plan.extension_end / region.length_scale};
  std::size_t kept = 0;
  for (const ShockRun& run : sizing.runs) kept += run.points.size();
  j["shock_points_clipped"] = kept;
  j["shock_runs"] = sizing.runs.size();
  j["domain"] = domain_json(region.domain);
  j["scene_domain"] = domain_json(region.scene_domain);
  j["outlet_moved"] = region.outlet_moved;
  j["patches"] = foam.patch_types;
  j["recombine"] = mp.recombine;
  j["algorithm"] = mp.algorithm;
  j["smoothing"] = mp.smoothing;
  j["check_mesh_failures"] = foam.check.failures;
  j["png"] = plots.png;
  j["plot_error"] = plots.error;
  return j;
}

// Writes the summary and swaps the finished case into OUT. A failed check
// fails the run; quality warnings alone do not (foam_export.cpp says which).
// A failed mesh is no replacement for a good one: it is kept for inspection
// beside OUT, which stays as it was.
void publish(scene::StagedDir& staged, const MeshResult& res, const CheckMeshReport& check,
             const std::string& out_dir) {
  scene::write_json_atomic((fs::path(staged.path()) / "summary.json").string(), res.summary());
  if (!check.ok && !check.warnings_only) {
    const std::string first = check.failures.substr(0, check.failures.find('\n'));
    const std::string failed_dir = staged.keep_as(".failed");
    throw scene::RunError(failed_dir + "/log.checkMesh: checkMesh failed: " +
                          (first.empty() ? std::string("no verdict") : first) + "; " + out_dir + " is unchanged");
  }
  // Files of OUT this run does not write (e.g. a pipeline cache record) are
  // carried over.
  staged.commit(scene::Leftovers::keep);
}

}  // namespace

MeshResult generate_mesh(const scene::Scene& s, const MeshRequest& r, const std::string& out_dir) {
  const auto t_total = std::chrono::steady_clock::now();
  const scene::CpuStopwatch cpu;
  scene::require_supersonic(s, "meshgen");
  const FluidRegion region = make_fluid_region(s);
  const std::string where = mesh_where(s);
  const CheckedPlan checked = make_checked_plan(s, r, region, where);
  const Plan& plan = checked.plan;

  // Built beside OUT and swapped in only when complete: a failed or
  // interrupted run leaves the previous mesh in OUT as it was.
  scene::StagedDir staged(out_dir);
  const fs::path stage(staged.path());
  GmshJob job = gmsh_job(s.mesh);
  const Meshed m = mesh_to_target(checked, region, job, stage, where, out_dir);

  MeshResult res;
  res.kind = plan.uniform ? "uniform" : plan.size_lattice ? "adapted" : "clustered";
  res.cells = static_cast<long>(m.mesh.cells.size());
  res.seconds = m.gmsh_seconds;
  const CellSizes sizes = measure_cell_sizes(m.mesh, m.sizing, plan.base.growth);
  res.min_cell_size = sizes.min;
  res.max_cell_size = sizes.max;

  stop_if_interrupted("after meshing", out_dir);
  Plots plots;
  const FoamCase foam =
      export_to_foam(stage, region, m.mesh, job.thickness, out_dir, [&](const ExtrudedLayer& layer) {
        write_extruded_msh(m.mesh, layer, job.thickness, (stage / "mesh.msh").string());
        plots = plot_grid(s, m, plan, region, res.kind, stage);
      });
  res.max_non_orthogonality = foam.check.max_non_orthogonality;
  res.max_skewness = foam.check.max_skewness;
  res.check_mesh_ok = foam.check.ok;
  if (foam.check.cells != res.cells)
    throw scene::RunError("checkMesh counts " + std::to_string(foam.check.cells) + " cells, gmsh " +
                          std::to_string(res.cells));

  res.details = mesh_details(s, plan, region, job, m, sizes, foam, plots, cpu);
  stop_if_interrupted("after checkMesh", out_dir);
  res.details["seconds_total"] = seconds_since(t_total);
  publish(staged, res, foam.check, out_dir);
  return res;
}

}  // namespace meshgen
