// Numerical stability on hard cases (slow, real OpenFOAM):
// a Mach 8 wedge, the Apollo capsule at Mach 5, a strongly skewed band, and
// the near-sonic (Mach 1.3) disc.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "cfd/run_case.hpp"
#include "log_follower.hpp"
#include "meshgen/mesh.hpp"
#include "scene/errors.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/io.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"
#include "steady_state.hpp"
#include "test_util.hpp"

namespace {

using scene::kDeg;
// Mach 8 on ~5k cells smears the strong shock: the wall pressure ratio came
// out 6.5 % high (docs/bench_cfd.md); a broken run is off by far more.
constexpr double kMach8WallTol = 0.10;
// A grid graded 20:1 across the flow still gives the M3/10 wall pressure to 1 %.
constexpr double kSkewedWallTol = 0.01;
constexpr double kSkewGrading = 20.0;

void expect_finite_positive(const scene::Lattice& lat) {
  for (const char* f : {"rho", "p", "T"}) {
    long finite = 0;
    for (const double v : lat.field(f)) {
      if (std::isnan(v)) continue;  // inside the body / outside the mesh
      EXPECT_GT(v, 0.0) << f;
      ++finite;
    }
    EXPECT_GT(finite, 0) << f;
  }
}

// The Apollo capsule impulsively started at Mach 5, on a coarse uniform
// meshgen grid (h = 0.05 D) written to mesh_dir; `cfd` is the scene's cfd section.
constexpr const char* kApolloM5 = "name: apollo\nbody: {kind: apollo, diameter: 1.0}\nfreestream: {mach: 5}\n";
scene::Scene apollo_on_coarse_grid(const std::string& mesh_dir, const std::string& cfd) {
  const scene::Scene s = scene::parse_scene(std::string(kApolloM5) + "cfd: " + cfd + "\n");
  meshgen::MeshRequest req;
  req.uniform = true;
  req.h_min = 0.05;
  meshgen::generate_mesh(s, req, mesh_dir);
  return s;
}

TEST(HardCases, Mach8WedgeStaysStable) {
  // The strong shock's density noise floor is ~0.15 per flow-through: a
  // looser steady tolerance, and a short run.
  const scene::Scene s = cfd_test::wedge_scene(8.0, 15.0, "{end_time: 4, steady_tol: 0.2}");
  const std::string d = cfd_test::scratch_dir();
  cfd::make_wedge_block_mesh(s, 5000, d + "/mesh");
  const cfd::CaseResult r = cfd::run_case(s, d + "/mesh", d + "/case", {});
  const double exact = scene::oblique_pressure_ratio(8.0, *scene::oblique_shock_beta(8.0, 15 * kDeg, 1.4), 1.4);
  EXPECT_NEAR(r.wall_pressure_ratio, exact, kMach8WallTol * exact);
  expect_finite_positive(cfd::resample_to_lattice(s, d + "/case", 80, 60));
}

TEST(HardCases, ApolloMach5OnACoarseMeshgenGrid) {
  // Impulsively started at Mach 5 on a coarse grid (h = 0.05 D), the
  // Kurganov flux drives the afterbody expansion to a negative temperature
  // within a fraction of a flow-through; the more dissipative Tadmor flux
  // (the Apollo case study's setting) runs through. Either way the run must
  // end in a result or a clear RunError, never a hang or a silent NaN.
  const std::string d = cfd_test::scratch_dir();
  {
    const scene::Scene s =
        apollo_on_coarse_grid(d + "/mesh", "{end_time: 3, flux_scheme: Kurganov}");
    try {
      (void)cfd::run_case(s, d + "/mesh", d + "/kurganov", {});
      expect_finite_positive(cfd::resample_to_lattice(s, d + "/kurganov", 80, 80));
    } catch (const scene::RunError& e) {
      EXPECT_NE(std::string(e.what()).find("diverged"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("log.rhoCentralFoam"), std::string::npos) << e.what();
      EXPECT_TRUE(std::filesystem::exists(d + "/kurganov/log.rhoCentralFoam"));  // case kept
    }
  }
  const scene::Scene s = scene::parse_scene(std::string(kApolloM5) + "cfd: {end_time: 3, flux_scheme: Tadmor}\n");
  const cfd::CaseResult r = cfd::run_case(s, d + "/mesh", d + "/tadmor", {});
  EXPECT_GT(r.steps, 0);
  EXPECT_GT(r.sim_time, 0.0);
  expect_finite_positive(cfd::resample_to_lattice(s, d + "/tadmor", 80, 80));
}

TEST(HardCases, StronglySkewedBandKeepsTheWallPressure) {
  const scene::Scene s = cfd_test::wedge_scene(3.0, 10.0);
  const std::string d = cfd_test::scratch_dir();
  cfd::make_wedge_block_mesh(s, 5000, d + "/mesh", kSkewGrading);
  const cfd::CaseResult r = cfd::run_case(s, d + "/mesh", d + "/case", {});
  const double exact = scene::oblique_pressure_ratio(3.0, *scene::oblique_shock_beta(3.0, 10 * kDeg, 1.4), 1.4);
  EXPECT_TRUE(r.steady_state_reached);
  EXPECT_NEAR(r.wall_pressure_ratio, exact, kSkewedWallTol * exact);
}

// The Apollo start above with the Kurganov flux named, which diverges at
// about 1.1 flow-throughs, written every `write_interval` flow-throughs and
// run with the fallback in DIR/case (the scene's grid in DIR/mesh).
struct SceneRun {
  scene::Scene scene;
  cfd::CaseResult result;
};
SceneRun diverging_apollo_run(const std::string& d, const std::string& write_interval) {
  const scene::Scene s = apollo_on_coarse_grid(
      d + "/mesh", "{end_time: 3, flux_scheme: Kurganov, write_interval: " + write_interval + "}");
  return {s, cfd::run_case_with_fallback(s, d + "/mesh", d + "/case", {})};
}

// The fallback's result when the run was made again from the initial state
// with the robust settings throughout.
void expect_robust_from_the_start(const cfd::CaseResult& r) {
  EXPECT_EQ(r.fallback.rfind(
                "flux_scheme Tadmor, limiter Minmod, max_co 0.15 (after: the solution diverged", 0),
            0u)
      << r.fallback;
  EXPECT_EQ(r.flux_scheme, "Tadmor");
}

}  // namespace

TEST(HardCases, DivergingRunRestartsOnceWithTheRobustSettings) {
  // The Kurganov start diverges here before any state is written (one
  // every 1.5 flow-throughs): with no
  // state to bridge from, the fallback restarts it from the initial state
  // with Tadmor, Minmod and half the Courant number, says so in the result
  // and summary.json, and counts the failed attempt's CPU and steps. With
  // cfd.fallback false the divergence is the run's end.
  const std::string d = cfd_test::scratch_dir();
  const auto [s, r] = diverging_apollo_run(d, "1.5");
  expect_robust_from_the_start(r);
  EXPECT_TRUE(std::filesystem::exists(d + "/case/log.rhoCentralFoam.diverged"));
  EXPECT_FALSE(std::filesystem::exists(d + "/case/log.rhoCentralFoam.bridge"));
  EXPECT_GT(r.sim_time, 0.0);
  expect_finite_positive(cfd::resample_to_lattice(s, d + "/case", 80, 80));
  const std::string summary = scene::read_file(d + "/case/summary.json");
  EXPECT_NE(summary.find("\"fallback\": \"flux_scheme Tadmor"), std::string::npos) << summary;

  const scene::Scene strict = scene::parse_scene(
      std::string(kApolloM5) + "cfd: {end_time: 3, fallback: false, flux_scheme: Kurganov}\n");
  EXPECT_THROW((void)cfd::run_case_with_fallback(strict, d + "/mesh", d + "/strict", {}), cfd::Diverged);
}

TEST(HardCases, ABridgeThatDivergesTooEndsInTheRunFromTheInitialState) {
  // The same start written every 0.02 flow-throughs leaves states before it
  // diverges, so the restart first bridges from the one before the last
  // (kBridgeFlowThroughs with the robust settings). Kurganov diverges again
  // after it (Apollo's afterbody at Mach 5: the reason auto picks Tadmor
  // there), and the run is made from the initial state with the robust
  // settings throughout. Every attempt's log and history is kept in the case,
  // its cost counted, and nothing is left beside the case.
  const std::string d = cfd_test::scratch_dir();
  const auto [s, r] = diverging_apollo_run(d, "0.02");
  expect_robust_from_the_start(r);
  for (const char* kept :
       {"log.rhoCentralFoam.diverged", "history.diverged.csv", "log.rhoCentralFoam.bridge",
        "history.bridge.csv", "log.rhoCentralFoam.restart-diverged"})
    EXPECT_TRUE(std::filesystem::exists(d + "/case/" + kept)) << kept;
  EXPECT_FALSE(std::filesystem::exists(d + "/case.restart"));
  // The final run's own steps are those its log counts; the result has more.
  cfd::LogFollower own(d + "/case/log.rhoCentralFoam");
  own.update();
  EXPECT_GT(r.steps, own.steps());
  expect_finite_positive(cfd::resample_to_lattice(s, d + "/case", 80, 80));
}

TEST(HardCases, RobustSettingsAreTadmorMinmodAndHalfTheCourantNumber) {
  scene::CfdParams p;
  p.max_co = 0.4;
  std::string what;
  const scene::CfdParams r = cfd::robust_settings(p, what);
  EXPECT_EQ(r.flux_scheme, "Tadmor");
  EXPECT_EQ(r.limiter, "Minmod");
  EXPECT_DOUBLE_EQ(r.max_co, 0.2);
  EXPECT_EQ(what, "flux_scheme Tadmor, limiter Minmod, max_co 0.2");
}

namespace {
// The scene's uniform grid (its mesh sizes) in DIR/mesh, run with the
// divergence fallback in DIR/case.
cfd::CaseResult run_on_uniform_grid(const scene::Scene& s, const std::string& dir) {
  meshgen::MeshRequest req;
  req.uniform = true;
  meshgen::generate_mesh(s, req, dir + "/mesh");
  return cfd::run_case_with_fallback(s, dir + "/mesh", dir + "/case", {});
}

// A scene's run on its default uniform grid in a fresh scratch directory.
struct UniformRun {
  scene::Scene scene;
  std::string dir;
  cfd::CaseResult result;
};
UniformRun run_scene_on_uniform_grid(const std::string& yaml) {
  UniformRun u{scene::parse_scene(yaml), cfd_test::scratch_dir(), {}};
  u.result = run_on_uniform_grid(u.scene, u.dir);
  return u;
}
}  // namespace

TEST(HardCases, DiscAtMach8FinishesSteadyOnTadmorFromTheStart) {
  // Started at rest with Kurganov the Mach 8 disc diverged on this grid
  // (docs/reliability.md) and finished only through the fallback; the
  // automatic flux is Tadmor there, which must carry it to a measured steady
  // state at the full Courant number, with finite, positive fields.
  const scene::Scene s = scene::parse_scene(
      "name: disc_M8\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 8}\nmesh: {h_min: 0.08, h_max: 0.2}\n");
  const std::string d = cfd_test::scratch_dir();
  const cfd::CaseResult r = run_on_uniform_grid(s, d);
  EXPECT_TRUE(r.steady_state_reached);
  EXPECT_EQ(r.flux_scheme, "Tadmor");
  EXPECT_TRUE(r.fallback.empty()) << r.fallback;
  expect_finite_positive(cfd::resample_to_lattice(s, d + "/case", 80, 80));
}

namespace {
// A steady bow shock's fitted drift on the stagnation line, per
// flow-through, over the gate's tolerance for the scene (the standoff's, at
// least a fraction of the shock's cell): the gate passes a drift within it or
// one insignificant against the shock's flicker between cells, which on these
// coarse grids (cells of 0.1-2 radii) may be larger; kHeldStill bounds both,
// and a shock still approaching as the disc references did (1-3% of the
// standoff on 16-49 cells: 5-15 tolerances) fails.
constexpr double kHeldStill = 5.0;

double drift_over_tolerance(const scene::Scene& s, const std::map<std::string, double>& row) {
  const cfd::SteadyCriteria c = cfd::SteadyCriteria::time_accurate(s.cfd).for_body(s);
  return std::abs(row.at("shock_drift")) /
         c.shock_drift_tolerance(row.at("shock_x"), row.at("shock_cell"));
}

// The last row of a case's history.csv, by column name.
std::map<std::string, double> last_history_row(const std::string& csv) {
  std::ifstream in(csv);
  std::string header, line, last;
  std::getline(in, header);
  while (std::getline(in, line)) last = line;
  std::map<std::string, double> row;
  std::stringstream hs(header), ls(last);
  std::string name, value;
  while (std::getline(hs, name, ',')) {
    if (!std::getline(ls, value, ',')) value.clear();
    row[name] = value.empty() ? scene::kNaN : std::stod(value);
  }
  return row;
}

// The disc at Mach 4 on a coarse uniform grid (h 0.2 = 0.4 radii, the case
// studies' uniform_h10, 559 cells): the shock probe's standoff on the
// stagnation line came out 0.578 R there against Billig's 0.517 R (+12 %);
// the case studies' other disc grids give +13 to +15 %, h 0.1 gives +9 %.
// A correlation fitted to experiments against a coarse inviscid solution:
// 20 % bounds these; a probe off by one sample on the line (0.19 R) does not fit.
constexpr double kDiscM4StandoffTol = 0.2;
}  // namespace

TEST(HardCases, BowShockProbeFindsTheDiscStandoffNearBillig) {
  const scene::Scene s = scene::parse_scene(
      "name: disc_M4\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 4}\nmesh: {h_min: 0.2, "
      "h_max: 0.2}\n");
  const std::string d = cfd_test::scratch_dir();
  const cfd::CaseResult r = run_on_uniform_grid(s, d);
  EXPECT_TRUE(r.steady_state_reached);
  const auto row = last_history_row(r.history_csv);
  const double standoff = (-0.5 - row.at("shock_x")) / 0.5,
               billig = scene::billig_standoff_cylinder(4.0);
  RecordProperty("standoff_radii", std::to_string(standoff));
  EXPECT_NEAR(standoff, billig, kDiscM4StandoffTol * billig) << "standoff " << standoff << " R";
  // Steady means the shock held still too.
  EXPECT_LE(drift_over_tolerance(s, row), kHeldStill);
}

TEST(HardCases, NearSonicDiscSettlesWithoutFallbackInTheTimeItIsGiven) {
  // Before: started at rest, the inflow's reflected shock ran out through the
  // inlet and the run died of a floating-point exception within half a
  // flow-through, fallback included; from the free stream with a
  // zeroGradient outflow, the bow shock drifted upstream without end. Then:
  // free-stream start and a waveTransmissive far-field pressure, no
  // fallback, but at the default end_time of 10 the shock still crept
  // upstream (0.08 R per flow-through) and the run ended not steady. The
  // creep decays: on this grid the drift gate passes at 29 flow-throughs, so
  // a scene whose flow can leave the domain subsonic gets end_time 40 unless
  // it sets one, and the run ends steady.
  const UniformRun u = run_scene_on_uniform_grid(
      "name: disc_M1_3\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 1.3}\nmesh: {h_min: "
      "1.0, h_max: 1.0}\n");
  const scene::Scene& s = u.scene;
  const std::string& d = u.dir;
  const cfd::CaseResult& r = u.result;
  EXPECT_EQ(s.cfd.end_time, 40.0);
  EXPECT_EQ(r.fallback, "");
  EXPECT_EQ(r.start, "freestream");
  EXPECT_EQ(r.outflow, "subsonic");
  EXPECT_TRUE(r.steady_state_reached);
  EXPECT_LT(r.final_density_change_l2, s.cfd.steady_tol);
  EXPECT_LT(r.final_force_change, s.cfd.force_tol);
  const auto row = last_history_row(r.history_csv);
  EXPECT_LE(drift_over_tolerance(s, row), kHeldStill) << "the shock still creeps";
  // A scene that states its end_time keeps it.
  EXPECT_EQ(scene::parse_scene(
                "body: {kind: disc, radius: 0.5}\nfreestream: {mach: 1.3}\ncfd: {end_time: 10}\n")
                .cfd.end_time,
            10.0);
  const scene::Lattice lat = cfd::resample_to_lattice(s, d + "/case", 300, 60);
  expect_finite_positive(lat);
  // The probe's shock against the resampled field's: the first lattice cell
  // from the inflow whose density passes halfway to the normal-shock density
  // (the lattice's cells are 0.09 R, the grid's 2 R).
  const double rho_inf = 1.4,
               mid = 0.5 * rho_inf * (1.0 + scene::oblique_density_ratio(1.3, 0.5 * M_PI, 1.4));
  const auto& rho = lat.field("rho");
  double x_shock = scene::kNaN;
  for (int i = 0; i < lat.nx; ++i)
    if (rho[lat.index(i, 0)] > mid) {
      x_shock = lat.xc(i);
      break;
    }
  RecordProperty("standoff_radii", std::to_string((-0.5 - row.at("shock_x")) / 0.5));
  EXPECT_NEAR(row.at("shock_x"), x_shock, row.at("shock_cell"));
}

TEST(HardCases, NearSonicDiscSettlesOnAGridClusteredAtItsBowShock) {
  // The other family: the grid clustered round Billig's shock (the band the
  // correlation predictor gives, +-10% of the standoff), 826 cells at h_min
  // 1 R. It settles as the uniform grid does (24 flow-throughs in the
  // pipeline's run, docs/reliability.md), within the near-sonic end_time.
  const scene::Scene s = scene::parse_scene(
      "name: disc_M1_3\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 1.3}\n");
  constexpr double kRadius = 0.5, kMach = 1.3, kBandRelative = 0.10;
  const double standoff = scene::billig_standoff_cylinder(kMach) * kRadius;
  const scene::Domain dom = scene::scene_domain(s);
  meshgen::MeshRequest req;
  req.h_min = 1.0;
  req.h_max = 4.0;
  constexpr int kPoints = 40;
  for (int k = 0; k <= kPoints; ++k) {
    const double y = dom.ymax * k / kPoints;
    const double x = -kRadius - standoff + scene::billig_shock_x(kMach, kRadius, y);
    if (x > dom.xmax) break;
    req.shock_curve.push_back({x, y});
    req.shock_ci.push_back(kBandRelative * standoff);
  }
  const std::string d = cfd_test::scratch_dir();
  meshgen::generate_mesh(s, req, d + "/mesh");
  const cfd::CaseResult r = cfd::run_case(s, d + "/mesh", d + "/case", {});
  EXPECT_TRUE(r.fallback.empty()) << r.fallback;
  EXPECT_EQ(r.outflow, "subsonic");
  EXPECT_TRUE(r.steady_state_reached);
  EXPECT_LE(drift_over_tolerance(s, last_history_row(r.history_csv)), kHeldStill);
  expect_finite_positive(cfd::resample_to_lattice(s, d + "/case", 100, 100));
}

namespace {
// A detached wedge's run on the automatic settings: its wake started at rest
// behind the base, Tadmor's flux, no restart, a measured steady state.
void expect_settles_on_the_automatic_start(const UniformRun& u) {
  EXPECT_EQ(u.result.start, "rest_behind_base");
  EXPECT_EQ(u.result.flux_scheme, "Tadmor");
  EXPECT_EQ(u.result.fallback, "") << "the automatic settings should need no restart";
  EXPECT_TRUE(u.result.steady_state_reached);
}
}  // namespace

TEST(HardCases, DetachedWedgeWithItsBaseInsideHoldsItsShockSteady) {
  // Mach 2, 30 deg (maximum deflection 22.97 deg). Cut at the base corner,
  // the flow left subsonic and the bow shock crept upstream without end
  // (0.014-0.033 body lengths per flow-through at 8 flow-throughs). With the
  // base and one base height of wake inside, the flow turns supersonic round
  // the corner and the shock settles: steady by the drift gate, ahead of the
  // apex but well inside the domain. The base's expansion from the
  // free-stream start diverges under Kurganov; the automatic flux is Tadmor
  // there, which holds without the fallback, and the wake starts at rest.
  const UniformRun u = run_scene_on_uniform_grid(
      "name: wedge_M2_30\nbody: {kind: wedge, angle_deg: 30}\nfreestream: {mach: 2}\n"
      "mesh: {h_min: 0.16, h_max: 0.16}\n");
  expect_settles_on_the_automatic_start(u);
  EXPECT_EQ(u.result.outflow, "supersonic");
  EXPECT_NE(scene::read_file(u.dir + "/case/system/fvSchemes").find("fluxScheme      Tadmor;"),
            std::string::npos);
  const auto row = last_history_row(u.result.history_csv);
  EXPECT_LE(drift_over_tolerance(u.scene, row), kHeldStill);
  const double standoff = -row.at("shock_x");  // apex at x = 0, wedge length 1
  RecordProperty("standoff_lengths", std::to_string(standoff));
  EXPECT_GT(standoff, 0.0);
  EXPECT_LT(standoff, -0.5 * scene::scene_domain(u.scene).xmin)
      << "the shock ran towards the inlet";
  expect_finite_positive(cfd::resample_to_lattice(u.scene, u.dir + "/case", 80, 80));
}

TEST(HardCases, DetachedWedgeAtMach3StartsWithItsWakeAtRest) {
  // Mach 3, 36 deg (maximum deflection 34.07 deg). Started in the free
  // stream, the base face moves away from the gas at Mach 3 and the
  // expansion behind it (wall pressure 0.0016 p in one dimension) drove the
  // temperature negative within ~30 steps, with the fallback's settings too;
  // a start at rest sent the bow shock upstream and took 9 flow-throughs to
  // settle. The automatic start keeps the free stream ahead of the base and
  // the gas at rest behind it.
  const UniformRun u = run_scene_on_uniform_grid(
      "name: wedge_M3_36\nbody: {kind: wedge, angle_deg: 36}\nfreestream: {mach: 3}\n"
      "mesh: {h_min: 0.08, h_max: 0.08}\n");
  expect_settles_on_the_automatic_start(u);
  expect_finite_positive(cfd::resample_to_lattice(u.scene, u.dir + "/case", 80, 80));

  scene::Scene freestream = u.scene;
  freestream.cfd.start = "freestream";
  freestream.cfd.fallback = false;
  EXPECT_THROW(
      (void)cfd::run_case_with_fallback(freestream, u.dir + "/mesh", u.dir + "/freestream", {}),
      cfd::Diverged);
}
