// Fuzz suite: broken scenes (mutated from the shipped ones), broken .vti
// and shock.csv files and hostile command-line values, run against the
// executables on their early-exit paths (--dry-run, or inputs refused
// before work starts) so that each case takes a fraction of a second.
//
// Every case must exit 0, 1 or 2 with, for 1 and 2, exactly one line on
// stderr naming the input file, the option or the usage error; never die
// on a signal, print "terminate called", hang (per-case time limit), leave
// a temporary file, or lose the output already in --out.
//
// Seed and size: SHOCKGRAIN_FUZZ_SEED (default 20261201) and
// SHOCKGRAIN_FUZZ_CASES (default 300). Counts are printed at the end.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "mutators.hpp"
#include "run_capture.hpp"
#include "scene/cli.hpp"
#include "scene/lattice.hpp"
#include "scene/scene.hpp"
#include "scratch.hpp"

namespace fs = std::filesystem;

namespace {

constexpr std::uint64_t kDefaultSeed = 20261201;
constexpr int kDefaultCases = 300;
// A case that is still running after this many seconds is a hang: the
// early-exit paths take well under a second even on a loaded machine.
constexpr double kCaseTimeout = 30.0;
// Out of every kScenesPerIntermediate cases, one fuzzes a .vti, one a
// shock.csv and one the command-line values.
constexpr int kScenesPerIntermediate = 6;
// Cases run at once: the machine has two cores.
constexpr int kWorkers = 2;

std::uint64_t env_or(const char* name, std::uint64_t def) {
  const char* v = std::getenv(name);
  return v ? std::strtoull(v, nullptr, 10) : def;
}

std::string slurp(const std::string& path) {
  std::ifstream is(path, std::ios::binary);
  std::ostringstream ss;
  ss << is.rdbuf();
  return ss.str();
}

void write(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::string exe(const std::string& name) {
  return std::string(BIN_DIR) + "/" + name;
}

// A small lattice over the wedge M3/10 domain with a density jump: what
// granular writes, minus its size.
std::string base_vti(const std::string& dir, const std::string& scene_path) {
  const scene::Scene s = scene::load_scene(scene_path);
  scene::Lattice lat = scene::domain_lattice(scene::scene_domain(s), 24, 16);
  auto& vf = lat.add("volume_fraction");
  auto& n = lat.add("samples", 50.0);
  for (int j = 0; j < lat.ny; ++j)
    for (int i = 0; i < lat.nx; ++i) vf[lat.index(i, j)] = lat.yc(j) < 0.4 * lat.xc(i) ? 0.2 : 0.1;
  (void)n;
  const std::string path = dir + "/base.vti";
  scene::write_vti(lat, path);
  return slurp(path);
}

std::string base_csv() {
  std::string t = "station,shock_x,shock_y,ci,accepted\n";
  for (int k = 0; k < 10; ++k) {
    const double x = 0.1 + 0.08 * k;
    t += std::to_string(k) + "," + std::to_string(x) + "," + std::to_string(0.45 * x) + ",0.01,1\n";
  }
  return t;
}

struct Tally {
  int tried = 0, clean = 0, crashes = 0, hangs = 0, bad_messages = 0, leftovers = 0, lost = 0;
  std::map<int, int> by_code;
  std::vector<std::string> failures;
};

// Files a run must never leave behind (atomic writes, staging folders).
bool is_temporary(const std::string& name) {
  return name.find(".tmp.") != std::string::npos || name.find(".staging-") != std::string::npos ||
         name.find(".old-") != std::string::npos;
}

// One generated case: its files are written before any case runs, so that
// the cases can run two at a time while staying a function of the seed.
struct Case {
  std::string kind, dir, input, sentinel;
  std::vector<std::string> argv;
};

// Judges one finished case into the tally (under the caller's lock).
void judge(Tally& t, const fuzz::Outcome& o, const std::vector<std::string>& argv,
           const std::string& case_dir, const std::string& sentinel, const std::string& what) {
  ++t.tried;
  std::string problem;
  if (o.hung) {
    ++t.hangs;
    problem = "hang";
  } else if (o.signal != 0 || o.code < 0 || o.code > 2 ||
             o.err.find("terminate called") != std::string::npos) {
    ++t.crashes;
    problem =
        "crash (code " + std::to_string(o.code) + ", signal " + std::to_string(o.signal) + ")";
  } else {
    ++t.by_code[o.code];
    if (o.code != 0) {
      const bool one_line = !o.err.empty() && o.err.find('\n') == o.err.size() - 1;
      // Names an input it was given (a path as written, or with control
      // characters shown as the message shows them), an option, or says
      // it is a usage error.
      bool names =
          o.err.find("usage error") != std::string::npos || o.err.find("--") != std::string::npos;
      for (std::size_t a = 1; a < argv.size() && !names; ++a)
        names = argv[a].size() > 1 && (o.err.find(argv[a]) != std::string::npos ||
                                       o.err.find(scene::one_line(argv[a])) != std::string::npos);
      if (!one_line || !names) {
        ++t.bad_messages;
        problem =
            std::string(one_line ? "message does not name the input" : "not one line on stderr");
      }
    }
  }
  for (const auto& e :
       fs::recursive_directory_iterator(case_dir, fs::directory_options::skip_permission_denied))
    if (is_temporary(e.path().filename().string())) {
      ++t.leftovers;
      problem += " leftover " + e.path().string();
      break;
    }
  if (!fs::exists(sentinel)) {
    ++t.lost;
    problem += " previous output lost";
  }
  if (problem.empty()) {
    ++t.clean;
    return;
  }
  std::string cmd;
  for (const auto& a : argv) cmd += " '" + a + "'";
  t.failures.push_back(what + ": " + problem + ":" + cmd + "\n    stderr: " + o.err.substr(0, 300));
}

}  // namespace

TEST(Fuzz, BrokenInputsAreRefusedCleanly) {
  const std::uint64_t seed = env_or("SHOCKGRAIN_FUZZ_SEED", kDefaultSeed);
  const int cases = static_cast<int>(env_or("SHOCKGRAIN_FUZZ_CASES", kDefaultCases));
  fuzz::Rng rng(seed);
  const fs::path root =
      test_support::scratch_root() / ("shockgrain_fuzz_" + std::to_string(::getpid()));
  // Inputs of failing cases are kept here for replay.
  const fs::path kept = test_support::scratch_root() / "shockgrain_fuzz_failures";
  fs::remove_all(root);
  fs::create_directories(root);

  std::vector<std::string> bases;
  for (const auto& e : fs::directory_iterator(std::string(SOURCE_DIR) + "/pipeline/cases"))
    if (e.path().extension() == ".yaml") bases.push_back(slurp(e.path().string()));
  std::sort(bases.begin(), bases.end());  // directory order is not stable
  ASSERT_FALSE(bases.empty());
  const std::string good_scene = (root / "good.yaml").string();
  write(
      good_scene,
      "name: fuzz_good\nbody: {kind: wedge, angle_deg: 10, length: 1.0}\nfreestream: {mach: 3.0}\n"
      "shockfit: {bootstrap: 10, stations: 8}\n");
  const std::string vti = base_vti(root.string(), good_scene);
  const std::string csv = base_csv();

  std::vector<Case> all;
  for (int k = 0; k < cases; ++k) {
    Case c;
    const fs::path dir = root / ("case_" + std::to_string(k));
    c.dir = dir.string();
    fs::create_directories(dir / "out");
    const std::string out = (dir / "out").string();
    c.sentinel = out + "/previous_result.txt";
    write(c.sentinel, "must survive\n");
    std::string& kind = c.kind;
    std::vector<std::string>& argv = c.argv;
    std::string& input = c.input;
    const int slot = k % kScenesPerIntermediate;
    if (slot == 0) {
      input = (dir / (std::uniform_int_distribution<int>(0, 3)(rng) == 0
                          ? fuzz::hostile_name(rng, ".vti")
                          : "f.vti"))
                  .string();
      write(input, fuzz::mutate_vti(vti, rng, kind));
      argv = {exe("shockfit"), good_scene, "--fields", input, "--out", out};
    } else if (slot == 1) {
      input = (dir / "shock.csv").string();
      write(input, fuzz::mutate_csv(csv, rng, kind));
      argv = {exe("meshgen"), good_scene, "--shock", input, "--out", out, "--dry-run"};
    } else if (slot == 2) {
      const std::string v = fuzz::hostile_value(rng);
      input = good_scene;
      switch (std::uniform_int_distribution<int>(0, 5)(rng)) {
        case 0:
          kind = "cli --h-min";
          argv = {exe("meshgen"), good_scene, "--uniform", "--h-min", v, "--out", out, "--dry-run"};
          break;
        case 1:
          kind = "cli --target-cells";
          argv = {exe("meshgen"), good_scene, "--uniform", "--target-cells", v,
                  "--out",        out,        "--dry-run"};
          break;
        case 2:
          kind = "cli --h-max";
          argv = {exe("meshgen"), good_scene, "--shock", (dir / "none.csv").string(),
                  "--h-max",      v,          "--out",   out};
          break;
        case 3:
          kind = "cli granular --np";
          argv = {exe("granular"), "run", good_scene, "--np", v, "--dry-run"};
          break;
        case 4:
          kind = "cli cfd --np";
          argv = {exe("cfd"), "run", good_scene, "--mesh", (dir / "nomesh").string(),
                  "--np",     v,     "--out",    out};
          break;
        default:
          kind = "cli pipeline --calibration";
          argv = {exe("pipeline"),    "run",  good_scene, "--out",    out, "--calibration",
                  (dir / v).string(), "--np", "1",        "--dry-run"};
          break;
      }
    } else {
      const std::string& base =
          bases[std::uniform_int_distribution<std::size_t>(0, bases.size() - 1)(rng)];
      const bool odd_name = std::uniform_int_distribution<int>(0, 7)(rng) == 0;
      input = (dir / (odd_name ? fuzz::hostile_name(rng, ".yaml") : "scene.yaml")).string();
      write(input, fuzz::mutate_scene(base, rng, kind));
      switch (std::uniform_int_distribution<int>(0, 4)(rng)) {
        case 0:
          argv = {exe("granular"), "run", input, "--dry-run"};
          break;
        case 1:
          argv = {exe("meshgen"), input, "--uniform", "--out", out, "--dry-run"};
          break;
        case 2:
          argv = {exe("pipeline"), "run", input, "--out", out, "--dry-run"};
          break;
        case 3:
          argv = {exe("cfd"), "run", input, "--mesh", (dir / "nomesh").string(), "--out", out};
          break;
        default:
          argv = {exe("shockfit"), input, "--fields", (dir / "absent.vti").string(), "--out", out};
          break;
      }
    }
    all.push_back(std::move(c));
  }

  Tally t;
  std::mutex tally_mutex;
  std::atomic<std::size_t> next{0};
  const auto worker = [&] {
    for (std::size_t k = next++; k < all.size(); k = next++) {
      const Case& c = all[k];
      const fuzz::Outcome o = fuzz::run_capture(c.argv, kCaseTimeout, c.dir + "/stderr.txt");
      fs::remove(c.dir + "/stderr.txt");
      const std::lock_guard<std::mutex> lock(tally_mutex);
      const std::size_t failures_before = t.failures.size();
      judge(t, o, c.argv, c.dir, c.sentinel, "case " + std::to_string(k) + " (" + c.kind + ")");
      if (t.failures.size() != failures_before && fs::is_regular_file(c.input)) {
        fs::create_directories(kept);
        const fs::path copy =
            kept / ("case_" + std::to_string(k) + fs::path(c.input).extension().string());
        fs::copy_file(c.input, copy, fs::copy_options::overwrite_existing);
        t.failures.back() += "\n    input kept in " + copy.string();
      }
      fs::remove_all(c.dir);
    }
  };
  std::vector<std::thread> threads;
  for (int w = 0; w < kWorkers; ++w) threads.emplace_back(worker);
  for (auto& th : threads) th.join();
  fs::remove_all(root);

  std::printf(
      "fuzz: seed %llu, %d cases tried, %d handled cleanly, %d crashes, %d hangs, %d bad messages, "
      "%d leftover temporary files, %d lost outputs; exit codes:",
      static_cast<unsigned long long>(seed), t.tried, t.clean, t.crashes, t.hangs, t.bad_messages,
      t.leftovers, t.lost);
  for (const auto& [code, n] : t.by_code) std::printf(" %d x%d", code, n);
  std::printf("\n");
  for (const auto& f : t.failures) std::printf("  %s\n", f.c_str());
  EXPECT_EQ(t.crashes, 0);
  EXPECT_EQ(t.hangs, 0);
  EXPECT_EQ(t.bad_messages, 0);
  EXPECT_EQ(t.leftovers, 0);
  EXPECT_EQ(t.lost, 0);
  EXPECT_EQ(t.clean, t.tried);
}
