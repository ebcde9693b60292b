// The cfd executable refuses subsonic scenes and an --out that would wipe
// its input (exit 2, one line), and a failed or interrupted `cfd run`
// leaves the previous case in --out untouched.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

namespace fs = std::filesystem;

namespace {

const std::string kExe = std::string(BIN_DIR) + "/cfd";

struct Result {
  int code = -1;
  std::string err;
};

Result cfd(const std::string& args) {
  Result r;
  FILE* p = popen((kExe + " " + args + " 2>&1 >/dev/null").c_str(), "r");
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), p)) r.err += buf.data();
  const int st = pclose(p);
  r.code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

std::string fresh(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("cfd_refuse_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}

std::string write_scene(const std::string& dir, const std::string& text) {
  const std::string path = dir + "/scene.yaml";
  std::ofstream(path) << text;
  return path;
}

void expect_refusal(const Result& r, const std::string& needle) {
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
}

bool has_temporaries(const std::string& dir) {
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    if (n.find(".staging-") != std::string::npos || n.find(".old-") != std::string::npos)
      return true;
  }
  return false;
}

constexpr const char* kWedge =
    "body: {kind: wedge, angle_deg: 10, length: 1.0}\nfreestream: {mach: 3.0}\n";

}  // namespace

TEST(Refuse, SubsonicSceneIsRefusedBeforeOpenFoam) {
  const std::string dir = fresh("subsonic");
  const std::string s =
      write_scene(dir, "body: {kind: disc, radius: 0.5}\nfreestream: {mach: 0.8}\n");
  expect_refusal(cfd("run " + s + " --mesh " + dir + "/mesh --out " + dir + "/case"),
                 s + ": key 'freestream.mach': cfd run needs a supersonic free stream");
  EXPECT_FALSE(fs::exists(dir + "/case"));
}

TEST(Refuse, OutEqualToOrAroundTheMeshIsRefused) {
  const std::string dir = fresh("overlap");
  const std::string s = write_scene(dir, kWedge);
  fs::create_directories(dir + "/mesh/constant/polyMesh");
  std::ofstream(dir + "/mesh/constant/polyMesh/faces") << "keep me\n";
  expect_refusal(cfd("run " + s + " --mesh " + dir + "/mesh --out " + dir + "/mesh"),
                 "--out " + dir + "/mesh: equals, lies inside or contains the --mesh folder");
  expect_refusal(cfd("run " + s + " --mesh " + dir + "/mesh --out " + dir + "/mesh/case"),
                 "--mesh folder");
  expect_refusal(cfd("run " + s + " --mesh " + dir + "/mesh/ --out " + dir), "--mesh folder");
  EXPECT_TRUE(fs::exists(dir + "/mesh/constant/polyMesh/faces"));
}

TEST(Refuse, InterruptedRunKeepsThePreviousCase) {
  const std::string dir = fresh("interrupt");
  const std::string s =
      write_scene(dir, std::string(kWedge) + "cfd: {end_time: 1000, write_interval: 1}\n");
  ASSERT_EQ(cfd("blockmesh " + s + " --cells 2000 --out " + dir + "/mesh").code, 0);
  const std::string out = dir + "/case";
  fs::create_directories(out);
  std::ofstream(out + "/summary.json") << "{\"previous\": true}\n";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string mesh = dir + "/mesh";
    execl(kExe.c_str(), kExe.c_str(), "run", s.c_str(), "--mesh", mesh.c_str(), "--out",
          out.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  std::this_thread::sleep_for(std::chrono::seconds(4));  // the solver is running by then
  kill(pid, SIGINT);
  int st = 0;
  waitpid(pid, &st, 0);
  ASSERT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), 1);
  std::ifstream is(out + "/summary.json");
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(is)), std::istreambuf_iterator<char>()),
            "{\"previous\": true}\n");
  EXPECT_TRUE(fs::exists(out + ".failed"));
  EXPECT_FALSE(has_temporaries(dir));
}
