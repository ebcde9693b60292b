// `pipeline run` refuses before any stage starts: a subsonic scene, a
// --calibration or pipeline.calibration file that does not exist (exit 2,
// one line naming the file).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;

namespace {

struct Result {
  int code = -1;
  std::string err;
};

Result pipeline(const std::string& args) {
  Result r;
  FILE* p = popen((std::string(BIN_DIR) + "/pipeline " + args + " 2>&1 >/dev/null").c_str(), "r");
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), p)) r.err += buf.data();
  const int st = pclose(p);
  r.code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

void expect_refusal(const Result& r, const std::string& needle) {
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
}

std::string fresh_scene(const std::string& name, const std::string& text) {
  const fs::path d = fs::temp_directory_path() / ("pipeline_refuse_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  std::ofstream((d / "scene.yaml").string()) << text;
  return (d / "scene.yaml").string();
}

}  // namespace

TEST(Refuse, MissingCalibrationTableIsAnInputError) {
  const std::string s =
      fresh_scene("calib", "body: {kind: wedge, angle_deg: 10}\nfreestream: {mach: 3}\n");
  const std::string dir = fs::path(s).parent_path().string();
  expect_refusal(
      pipeline("run " + s + " --out " + dir + "/out --calibration " + dir + "/absent.yaml"),
      dir + "/absent.yaml: --calibration file not found");
  const std::string k = fresh_scene("calib_key",
                                    "body: {kind: wedge, angle_deg: 10}\nfreestream: {mach: 3}\n"
                                    "pipeline: {calibration: /nonexistent/table.yaml}\n");
  expect_refusal(pipeline("run " + k + " --out " + dir + "/out"),
                 k + ": key 'pipeline.calibration'");
  EXPECT_FALSE(fs::exists(dir + "/out"));
}

TEST(Refuse, SubsonicSceneIsRefused) {
  const std::string s =
      fresh_scene("subsonic", "body: {kind: disc, radius: 0.5}\nfreestream: {mach: 1.0}\n");
  expect_refusal(pipeline("run " + s + " --out " + fs::path(s).parent_path().string() + "/out"),
                 s + ": key 'freestream.mach': the pipeline needs a supersonic free stream");
}
