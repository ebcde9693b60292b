// End to end with the real executables, gmsh and OpenFOAM, on a small wedge.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "scene/io.hpp"
#include "scratch.hpp"

namespace fs = std::filesystem;

namespace {

constexpr double kAngleTolDeg = 1.0;  // a clustered grid's CFD shock within 1 deg of theta-beta-Mach
const std::string kPipeline = std::string(BIN_DIR) + "/pipeline";
const std::string kData = std::string(SOURCE_DIR) + "/tests/data";

fs::path fresh_dir(const std::string& name) {
  return test_support::absent_dir("pipeline_e2e_" + name);
}

int run(const std::string& args) {
  const int rc = std::system((kPipeline + " " + args).c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

// Every number in the JSON tree is finite (nulls are "does not apply").
void expect_all_finite(const nlohmann::json& j, const std::string& path) {
  if (j.is_number()) {
    EXPECT_TRUE(std::isfinite(j.get<double>())) << path;
  } else if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) expect_all_finite(it.value(), path + "." + it.key());
  } else if (j.is_array()) {
    for (std::size_t k = 0; k < j.size(); ++k) expect_all_finite(j[k], path + "[" + std::to_string(k) + "]");
  }
}

}  // namespace

TEST(EndToEnd, BadSceneFailsBeforeAnyStage) {
  const auto out = fresh_dir("bad");
  EXPECT_EQ(run("run " + kData + "/bad/unknown_key.yaml --out " + out.string() + " 2>/dev/null"), 2);
  EXPECT_FALSE(fs::exists(out / "granular"));
  EXPECT_EQ(run("run /nonexistent.yaml --out " + out.string() + " 2>/dev/null"), 2);
  EXPECT_EQ(run("run 2>/dev/null"), 2);
}

TEST(EndToEnd, SmallWedgeReportsAFiniteVerdict) {
  const auto out = fresh_dir("wedge");
  ASSERT_EQ(run("run " + kData + "/wedge_small.yaml --out " + out.string() + " > /dev/null"), 0);
  ASSERT_TRUE(fs::exists(out / "report.md"));
  // The report says in words what ended the granular stage's averaging.
  EXPECT_NE(scene::read_file((out / "report.md").string())
                .find("(stopped by averaging: the time it was set to average)"),
            std::string::npos);
  const auto j = nlohmann::json::parse(scene::read_file((out / "summary.json").string()));
  expect_all_finite(j, "summary");
  ASSERT_TRUE(j["clustered"].is_object());
  ASSERT_TRUE(j["uniform"].is_object());
  for (const char* k : {"cells", "cfd_wall_seconds", "shock", "steady_state_reached", "shock_angle_deg",
                        "exact_shock_angle_deg", "error"}) {
    EXPECT_TRUE(j["clustered"].contains(k)) << k;
    EXPECT_TRUE(j["uniform"].contains(k)) << k;
  }
  const double exact = j["clustered"]["exact_shock_angle_deg"];
  EXPECT_NEAR(exact, 27.38, 0.01);
  EXPECT_NEAR(j["clustered"]["shock_angle_deg"].get<double>(), exact, kAngleTolDeg);
  // A rerun is served from the cache.
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(run("run " + kData + "/wedge_small.yaml --out " + out.string() + " > /dev/null"), 0);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
            j["total_wall_seconds"].get<double>());
}

TEST(EndToEnd, KilledMidRunThenRerunResumes) {
  const auto out = fresh_dir("resume");
  const std::string scene = kData + "/wedge_small_nocfd.yaml";
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execl(kPipeline.c_str(), "pipeline", "run", scene.c_str(), "--out", out.c_str(), static_cast<char*>(nullptr));
    std::_Exit(127);
  }
  // Interrupt as soon as the granular stage has finished.
  const auto record = out / "granular" / ".stage.json";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(10);
  while (!fs::exists(record) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(fs::exists(record));
  const auto stamp = fs::last_write_time(record);
  const auto fields = fs::last_write_time(out / "granular" / "fields.vti");
  ASSERT_EQ(run("run " + scene + " --out " + out.string() + " > /dev/null"), 0);
  EXPECT_EQ(fs::last_write_time(record), stamp);           // granular not rerun
  EXPECT_EQ(fs::last_write_time(out / "granular" / "fields.vti"), fields);
  EXPECT_TRUE(fs::exists(out / "summary.json"));
  // --force reruns the stage.
  ASSERT_EQ(run("run " + scene + " --out " + out.string() + " --force granular > /dev/null"), 0);
  EXPECT_NE(fs::last_write_time(record), stamp);
}

TEST(EndToEnd, SweepOverRestitutionRunsInParallelAndOrdersTheAngles) {
  const auto out = fresh_dir("sweep");
  ASSERT_EQ(run("sweep " + kData + "/wedge_small_nocfd.yaml --vary granular.restitution=0.97,1.0 --jobs 2 --out " +
                out.string() + " 2>/dev/null"),
            0);
  const auto rows = nlohmann::json::parse(scene::read_file((out / "sweep.json").string()));
  ASSERT_EQ(rows.size(), 2u);
  for (const auto& r : rows) ASSERT_EQ(r["prediction"].value("shock", ""), "attached") << r.dump();
  // A less dissipative gas stands its shock at a larger angle (calibration
  // sweep, docs/figures/calibration.png: about 24 deg at e = 0.97, 34 at 1).
  EXPECT_GT(rows[1]["prediction"]["shock_angle_deg"].get<double>(),
            rows[0]["prediction"]["shock_angle_deg"].get<double>() + 3.0);
  EXPECT_TRUE(fs::exists(out / "sweep.csv"));
}

// A strong oblique shock: Kurganov diverges on a clustered grid's
// shock-aligned strips before any state is written. The clustered family
// then goes over to the isotropic band (its earlier grids meshed again,
// charged their strip runs, kept on disk), and each family ends on one
// scheme: the robust one only where one of its own grids needed it.
TEST(EndToEnd, StrongObliqueShockMeshesTheClusteredFamilyWithoutStripsAndEachFamilyOnOneScheme) {
  const auto out = fresh_dir("one_scheme");
  const std::string robust = "Tadmor/Minmod";
  ASSERT_EQ(run("run " + kData + "/wedge_strong_shock.yaml --predictor correlation --np 1 --out " +
                out.string() + " > /dev/null 2>&1"),
            0);
  const auto j = nlohmann::json::parse(scene::read_file((out / "summary.json").string()));
  std::map<std::string, std::set<std::string>> schemes;
  std::map<std::string, int> fell_back_robust;
  int remeshed = 0;
  for (const auto& r : j["runs"]) {
    const std::string name = r.value("case", ""), family = r.value("family", "");
    const std::string scheme = r.value("scheme", "");
    schemes[family].insert(scheme);
    EXPECT_TRUE(r.value("steady_state_reached", false)) << name;
    if (r.value("note", "").find("diverged; restarted") != std::string::npos && scheme == robust)
      ++fell_back_robust[family];
    if (family == "uniform") continue;
    // Every clustered grid has the isotropic band, its strip twin kept.
    EXPECT_FALSE(r.value("strips", true)) << name;
    const std::string mesh = r.value("mesh", "");
    const std::string suffix = "_isotropic";
    ASSERT_GT(mesh.size(), suffix.size()) << name;
    ASSERT_EQ(mesh.substr(mesh.size() - suffix.size()), suffix) << name;
    // Levels after the divergence never had strips; those up to it keep theirs.
    const std::string strip_grid = mesh.substr(0, mesh.size() - suffix.size());
    const bool meshed_again =
        r.value("note", "").find("meshed again with the isotropic band") != std::string::npos;
    EXPECT_EQ(fs::exists(out / "cfd" / strip_grid / "summary.json"), meshed_again) << strip_grid;
    if (!meshed_again) continue;
    ++remeshed;
    EXPECT_TRUE(fs::exists(out / "meshgen" / strip_grid / "summary.json")) << strip_grid;
    const auto first = nlohmann::json::parse(
        scene::read_file((out / "cfd" / strip_grid / "summary.json").string()));
    const auto again =
        nlohmann::json::parse(scene::read_file((out / "cfd" / name / "summary.json").string()));
    const double charged = r["cpu_seconds"].get<double>();
    EXPECT_GT(charged, again["cpu_seconds"].get<double>()) << name;
    EXPECT_GT(charged, first["cpu_seconds"].get<double>()) << name;
  }
  // The case this test is for: a strip grid diverged and its family followed it.
  ASSERT_GE(remeshed, 1) << "no strip grid diverged: the scene no longer exercises the rule";
  for (const auto& [family, set] : schemes) {
    ASSERT_EQ(set.size(), 1u) << family << " mixes schemes";
    EXPECT_EQ(*set.begin() == robust, fell_back_robust[family] > 0) << family;
    EXPECT_EQ(j["schemes"].value(family == "uniform" ? "uniform" : "clustered", ""), *set.begin());
  }
  EXPECT_NE(scene::read_file((out / "report.md").string()).find("Schemes (flux/limiter): uniform "),
            std::string::npos);
  // The verdict re-measured from the cases the runs name gives the same errors and verdict.
  ASSERT_EQ(run("verdict " + out.string() + " --remeasure > /dev/null 2>&1"), 0);
  const auto v = nlohmann::json::parse(scene::read_file((out / "verdict.json").string()));
  for (const auto& r : j["runs"]) {
    const auto& e = v["remeasured_errors"][r.value("case", "")];
    ASSERT_TRUE(e.contains("primary_error")) << r.value("case", "") << " " << e.dump();
    EXPECT_DOUBLE_EQ(e["primary_error"].get<double>(), r["primary_error"].get<double>())
        << r.value("case", "");
  }
  EXPECT_EQ(v.value("verdict", ""), j.value("verdict", ""));
}

// The verdict on three levels per family: CPU costs measured for every run,
// the exact-reference L1 error falling with refinement on uniform grids, the
// speedups as {value, ci_low, ci_high} and a verdict read from them.
TEST(EndToEnd, VerdictFromExactErrorsAndCpuTimes) {
  const auto out = fresh_dir("verdict");
  ASSERT_EQ(run("run " + kData + "/wedge_verdict.yaml --out " + out.string() + " > /dev/null"), 0);
  const auto j = nlohmann::json::parse(scene::read_file((out / "summary.json").string()));
  EXPECT_EQ(j["primary_error"], "l1_density");
  EXPECT_EQ(j["predictor"], "granular");
  for (const char* k : {"speedup_cfd", "speedup_total"}) {
    ASSERT_TRUE(j[k].is_object()) << k;
    for (const char* f : {"value", "ci_low", "ci_high"}) ASSERT_TRUE(j[k].contains(f)) << k << "." << f;
    if (j[k]["value"].is_number() && j[k]["ci_low"].is_number() && j[k]["ci_high"].is_number()) {
      EXPECT_LE(j[k]["ci_low"].get<double>(), j[k]["value"].get<double>()) << k;
      EXPECT_GE(j[k]["ci_high"].get<double>(), j[k]["value"].get<double>()) << k;
    }
  }
  const std::string v = j["verdict"];
  EXPECT_TRUE(v == "faster" || v == "slower" || v == "not distinguishable") << v;
  std::vector<double> uniform_l1;
  for (const auto& r : j["runs"]) {
    EXPECT_GT(r["cpu_seconds"].get<double>(), 0.0) << r.dump();
    EXPECT_GT(r["mesh_cpu_seconds"].get<double>(), 0.0) << r.dump();
    EXPECT_GT(r["steps"].get<long>(), 0) << r.dump();
    EXPECT_TRUE(r.contains("steady_state_reached"));
    // rhoCentralFoam costs ~0.5 us per cell-step; a figure far off means the
    // CPU accounting missed the solver or counted something else.
    EXPECT_GT(r["cpu_us_per_cell_step"].get<double>(), 0.05) << r.dump();
    EXPECT_LT(r["cpu_us_per_cell_step"].get<double>(), 20.0) << r.dump();
    const double l1 = r["l1_density"].get<double>();
    EXPECT_GT(l1, 0.0);
    EXPECT_LT(l1, 0.2) << "an L1 density error above 20% of the free stream is no converged solution";
    if (r["family"] == "uniform") uniform_l1.push_back(l1);
  }
  ASSERT_EQ(uniform_l1.size(), 3u);
  EXPECT_GT(uniform_l1[0], uniform_l1[2]) << "the L1 error must fall from h = 4 to h = 2 x h_min";
  EXPECT_GT(j["granular"]["cpu_seconds"].get<double>(), 0.0);
}
