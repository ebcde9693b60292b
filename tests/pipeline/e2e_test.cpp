// End to end with the real executables, gmsh and OpenFOAM, on a small wedge.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
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

// A comparison whose grids would otherwise mix schemes (a grid diverged
// before writing a state and ran robust throughout) is solved on one: the
// grids that ended on the scene's own scheme are solved again robust and
// charged both runs; their first cases stay on disk.
TEST(EndToEnd, StrongObliqueShockComparesGridsOnOneScheme) {
  const auto out = fresh_dir("one_scheme");
  const std::string robust = "Tadmor/Minmod";
  ASSERT_EQ(run("run " + kData + "/wedge_strong_shock.yaml --predictor correlation --np 1 --out " +
                out.string() + " > /dev/null 2>&1"),
            0);
  const auto j = nlohmann::json::parse(scene::read_file((out / "summary.json").string()));
  EXPECT_EQ(j.value("scheme", ""), robust);
  int diverged = 0, solved_again = 0;
  for (const auto& r : j["runs"]) {
    const std::string name = r.value("case", "");
    EXPECT_EQ(r.value("scheme", ""), robust) << name;
    EXPECT_TRUE(r.value("steady_state_reached", false)) << name;
    if (r.value("note", "").rfind("diverged; restarted", 0) == 0) ++diverged;
    const std::string suffix = "_robust";
    if (name.size() <= suffix.size() ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    ++solved_again;
    const fs::path first = out / "cfd" / name.substr(0, name.size() - suffix.size());
    ASSERT_TRUE(fs::exists(first / "summary.json")) << first;
    const auto f = nlohmann::json::parse(scene::read_file((first / "summary.json").string()));
    EXPECT_EQ(f.value("flux_scheme", ""), "Kurganov") << first;
    // Charged both runs: more than the robust run alone and than the first.
    const auto again =
        nlohmann::json::parse(scene::read_file((out / "cfd" / name / "summary.json").string()));
    const double charged = r["cpu_seconds"].get<double>();
    EXPECT_GT(charged, again["cpu_seconds"].get<double>()) << name;
    EXPECT_GT(charged, f["cpu_seconds"].get<double>()) << name;
    EXPECT_NE(r.value("note", "").find("charged too"), std::string::npos) << name;
  }
  // The case this test is for: some grid fell back, and the others followed it.
  ASSERT_GE(diverged, 1) << "no grid diverged: the scene no longer exercises the rule";
  EXPECT_GE(solved_again, 1);
  EXPECT_EQ(diverged + solved_again, static_cast<int>(j["runs"].size()));
  EXPECT_NE(
      scene::read_file((out / "report.md").string()).find("one scheme (flux/limiter): " + robust),
      std::string::npos);
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
