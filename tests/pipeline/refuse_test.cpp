// `pipeline run` refuses before any stage starts: a subsonic scene, a
// --calibration or pipeline.calibration file that does not exist (exit 2,
// one line naming the file).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_run.hpp"

namespace fs = std::filesystem;

namespace {

using test_support::CliRun;
using test_support::expect_refusal;

CliRun pipeline(const std::string& args) {
  return test_support::run_cli(test_support::stage_exe("pipeline"), args);
}

std::string fresh_scene(const std::string& name, const std::string& text) {
  return test_support::write_scene(test_support::fresh_dir("pipeline_refuse_" + name), text);
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
  // `pipeline predict` the same: a named table that is absent never means e = 1.
  expect_refusal(pipeline("predict " + s + " --predictor granular --out " + dir +
                          "/pred --calibration " + dir + "/absent.yaml"),
                 dir + "/absent.yaml: --calibration file not found");
  expect_refusal(pipeline("predict " + k + " --predictor granular --out " + dir + "/pred"),
                 k + ": key 'pipeline.calibration'");
  EXPECT_FALSE(fs::exists(dir + "/pred"));
}

TEST(Refuse, SubsonicSceneIsRefused) {
  const std::string s =
      fresh_scene("subsonic", "body: {kind: disc, radius: 0.5}\nfreestream: {mach: 1.0}\n");
  expect_refusal(pipeline("run " + s + " --out " + fs::path(s).parent_path().string() + "/out"),
                 s + ": key 'freestream.mach': the pipeline needs a supersonic free stream");
}

TEST(Refuse, RejudgingOrReplayingWhatWasNeverRunIsAnInputError) {
  const std::string s = fresh_scene(
      "replay", "name: replay\nbody: {kind: wedge, angle_deg: 10}\nfreestream: {mach: 3}\n");
  const std::string dir = fs::path(s).parent_path().string();
  expect_refusal(pipeline("verdict " + dir + "/none"),
                 dir + "/none/summary.json: no such run summary");
  expect_refusal(pipeline("league " + s + " --out " + dir +
                          "/league --predictor granular --from-runs --docs " + dir + "/league.md"),
                 dir + "/league/replay/summary_granular.json: no recorded summary");
  EXPECT_FALSE(fs::exists(dir + "/league.md"));
}

// A blunt shape's fit needs the training runs and a cache for its sweeps,
// said before any run.
TEST(Refuse, FittingShapesWithoutTrainingRunsOrCacheIsAnInputError) {
  expect_refusal(pipeline("calibrate --fit-shapes --out /nonexistent/cache"),
                 "--fit-shapes needs --bow-shock-runs");
  const std::string dir = test_support::fresh_dir("pipeline_refuse_shapes");
  expect_refusal(pipeline("calibrate --fit-shapes --bow-shock-runs " + dir + "/a " + dir + "/b"),
                 dir + "/a: --bow-shock-runs: no such directory");
}

// --averaging sets the generated training wedges; scenes given with --scene
// carry their own, and a value beyond the check is refused before any run.
TEST(Refuse, TrainingAveragingWithScenesOrOutOfRangeIsRefused) {
  const std::string s = fresh_scene(
      "train_avg", "name: t\nbody: {kind: wedge, angle_deg: 12}\nfreestream: {mach: 9}\n");
  const std::string dir = fs::path(s).parent_path().string();
  expect_refusal(pipeline("calibrate --scene " + s + " --averaging 12 --e 0.94 0.96 --out " + dir +
                          "/cal --table " + dir + "/t.yaml --no-verify"),
                 "--averaging sets generated training wedges");
  EXPECT_FALSE(fs::exists(dir + "/t.yaml"));
  const CliRun r = pipeline("calibrate --averaging 1000 --mach 9 --angle 12 --out " + dir +
                            "/cal2 --table " + dir + "/t2.yaml --no-verify");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("--averaging"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/t2.yaml"));
}
