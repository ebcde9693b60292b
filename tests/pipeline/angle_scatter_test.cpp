// The table's own attached-angle error measured on unseen wedges: the
// formula, the block's round trip, and what `--angle-check-runs` refuses.
#include "pipeline/angle_scatter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "pipeline/calibration.hpp"
#include "pipeline/run.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/scene.hpp"
#include "scratch.hpp"

namespace fs = std::filesystem;

namespace {
const std::string kSource = SOURCE_DIR;
constexpr double kTol = 1e-12;

fs::path fresh(const std::string& name) {
  return test_support::fresh_dir("shockgrain_angle_scatter_" + name);
}

// An angle_check.sh wedge directory: the gas angle and `seeds` granular runs
// at restitution e, each `error` off the gas angle with half-width `hw`.
void write_wedge(const fs::path& dir, double mach, double angle, double e, int seeds, double error,
                 double hw) {
  std::ostringstream n;
  n << "oos_M" << mach << "_" << angle;
  const std::string name = n.str();
  const fs::path w = dir / name;
  fs::create_directories(w / "gas");
  const double gas = 20.0;
  scene::write_json_atomic((w / "gas" / "summary.json").string(),
                           {{"shock", "attached"}, {"shock_angle_deg", gas}});
  for (int k = 0; k < seeds; ++k) {
    const std::string seed = "seed" + std::to_string(k + 1);
    std::ofstream(w / (seed + ".yaml"))
        << "name: " << name << "\nbody: {kind: wedge, angle_deg: " << angle
        << ", length: 1.0}\nfreestream: {mach: " << mach << "}\ngranular: {seed: " << k + 1
        << "}\n";
    fs::create_directories(w / seed);
    const double sign = k % 2 == 0 ? 1.0 : -1.0;
    scene::write_json_atomic(
        (w / seed / "summary.json").string(),
        {{"shock", "attached"},
         {"shock_angle_deg", gas + sign * error},
         {"shock_angle_ci_deg", hw},
         {"details", {{"restitution", e}, {"averaging", {{"flow_throughs", 16.0}}}}}});
  }
}

double table_e(const pipeline::CalibrationTable& t, double mach, double angle) {
  return pipeline::quantised_restitution(*pipeline::interpolate_restitution(t, mach, angle));
}
}  // namespace

TEST(AngleScatter, IsTheRunsErrorLessTheirOwnNoise) {
  // Errors +-0.3 deg, half-widths 1.96 x 0.2: sqrt(0.09 - 0.04).
  std::vector<pipeline::AngleCheckRun> runs;
  for (int k = 0; k < 12; ++k)
    runs.push_back({std::to_string(k / 3), 20.0 + (k % 2 ? 0.3 : -0.3), 1.96 * 0.2, 20.0, 16.0});
  const pipeline::AngleScatter a = pipeline::angle_scatter_of(runs);
  EXPECT_NEAR(a.deg, std::sqrt(0.09 - 0.04), 1e-9);
  EXPECT_NEAR(a.rms_deg, 0.3, 1e-9);
  EXPECT_EQ(a.runs, 12);
  EXPECT_EQ(a.wedges, 4);
  EXPECT_DOUBLE_EQ(a.flow_throughs, 16.0);
  // Noise larger than the error leaves no table error (floored at zero).
  for (auto& r : runs) r.half_width = 1.96;
  EXPECT_DOUBLE_EQ(pipeline::angle_scatter_of(runs).deg, 0.0);
  runs.resize(pipeline::kMinAngleCheckRuns - 1);
  EXPECT_THROW(pipeline::angle_scatter_of(runs), scene::InputError);
}

TEST(AngleScatter, IsWrittenIntoTheTableAndWidensTheBand) {
  const fs::path d = fresh("write");
  const std::string table = (d / "calibration.yaml").string();
  fs::copy_file(kSource + "/pipeline/calibration.yaml", table);
  pipeline::CalibrationTable t = pipeline::read_calibration(table);
  // The beyond block stands past the inside block's Mach numbers: both go.
  t.angle_scatter.reset();
  t.angle_scatter_beyond.reset();
  pipeline::write_calibration(t, table);
  const double loo = pipeline::table_angle_scatter_deg(t);
  // Four unseen wedges inside the training ranges, three seeds each.
  const fs::path runs = d / "runs";
  const double wedges[4][2] = {{2.7, 12.5}, {3.3, 15.5}, {4.2, 9.5}, {5.3, 18.5}};
  for (const auto& w : wedges) write_wedge(runs, w[0], w[1], table_e(t, w[0], w[1]), 3, 0.3, 0.392);
  const nlohmann::json r = pipeline::calibrate_angle_scatter({runs.string()}, table);
  EXPECT_EQ(r["runs"], 12);
  EXPECT_EQ(r["wedges"], 4);
  const pipeline::CalibrationTable after = pipeline::read_calibration(table);
  ASSERT_TRUE(after.angle_scatter);
  EXPECT_NEAR(after.angle_scatter->deg, std::sqrt(0.09 - 0.04), 1e-9);
  EXPECT_NEAR(pipeline::table_angle_scatter_deg(after), after.angle_scatter->deg, kTol);
  EXPECT_NE(pipeline::table_angle_scatter_deg(after), loo);
  // Everything else stays.
  EXPECT_EQ(after.entries.size(), t.entries.size());
  EXPECT_EQ(after.bow_shock.has_value(), t.bow_shock.has_value());
  EXPECT_EQ(after.fits.size(), t.fits.size());
}

TEST(AngleScatter, RefusesRunsThatCannotJudgeTheTable) {
  const fs::path d = fresh("refuse");
  const std::string table = (d / "calibration.yaml").string();
  fs::copy_file(kSource + "/pipeline/calibration.yaml", table);
  const pipeline::CalibrationTable t = pipeline::read_calibration(table);
  const std::string before = scene::read_file(table);
  auto refused = [&](const fs::path& runs, const std::string& words) {
    try {
      pipeline::calibrate_angle_scatter({runs.string()}, table);
      ADD_FAILURE() << "accepted " << runs;
    } catch (const scene::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
    EXPECT_EQ(scene::read_file(table), before) << "the table was changed";
  };
  // Another table's e.
  write_wedge(d / "e", 3.3, 15.5, table_e(t, 3.3, 15.5) + 0.001, 12, 0.3, 0.392);
  refused(d / "e", "details.restitution");
  // A training point (Mach 4, 11 deg).
  write_wedge(d / "train", 4.0, 11.0, table_e(t, 4.0, 11.0), 12, 0.3, 0.392);
  refused(d / "train", "training point");
  // A case study (Mach 3, 10 deg).
  write_wedge(d / "case", 3.0, 10.0, table_e(t, 3.0, 10.0), 12, 0.3, 0.392);
  refused(d / "case", "case study");
  // Outside the training deflections (4 deg).
  write_wedge(d / "outside", 4.0, 4.0, table_e(t, 4.0, 4.0), 12, 0.3, 0.392);
  refused(d / "outside", "training deflections");
  // Inside and beyond the training Mach range in one measure.
  write_wedge(d / "mixed", 3.3, 15.5, table_e(t, 3.3, 15.5), 6, 0.3, 0.392);
  const double beyond = pipeline::training_mach_range(t)->high + 1.0;
  write_wedge(d / "mixed", beyond, 12.0, table_e(t, beyond, 12.0), 6, 0.3, 0.392);
  refused(d / "mixed", "different sides");
  // Too few runs.
  write_wedge(d / "few", 3.3, 15.5, table_e(t, 3.3, 15.5), 5, 0.3, 0.392);
  refused(d / "few", "at least");
  refused(d / "missing", "no such directory");
}

// Beyond the training Mach range e(M) is extrapolated: runs there measure the
// extrapolation's error, kept in a block of its own that only wedges on that
// side of the range take, never narrower than the table's own.
TEST(AngleScatter, BeyondTheMachRangeIsMeasuredApartAndTakenThereOnly) {
  const fs::path d = fresh("beyond");
  const std::string table = (d / "calibration.yaml").string();
  fs::copy_file(kSource + "/pipeline/calibration.yaml", table);
  const pipeline::CalibrationTable t = pipeline::read_calibration(table);
  const auto range = pipeline::training_mach_range(t);
  ASSERT_TRUE(range.has_value());
  const double inside = pipeline::table_angle_scatter_deg(t);
  const fs::path runs = d / "runs";
  const double wedges[4][2] = {{range->high + 0.5, 12.5},
                               {range->high + 1.0, 15.5},
                               {range->high + 1.5, 9.5},
                               {range->high + 2.0, 18.5}};
  // Errors +-0.6 deg with half-widths 1.96 x 0.2: sqrt(0.36 - 0.04).
  for (const auto& w : wedges) write_wedge(runs, w[0], w[1], table_e(t, w[0], w[1]), 3, 0.6, 0.392);
  const nlohmann::json r = pipeline::calibrate_angle_scatter({runs.string()}, table);
  EXPECT_EQ(r["block"], "angle_scatter_beyond_mach");
  const pipeline::CalibrationTable after = pipeline::read_calibration(table);
  ASSERT_TRUE(after.angle_scatter_beyond);
  EXPECT_NEAR(after.angle_scatter_beyond->deg, std::sqrt(0.36 - 0.04), 1e-9);
  EXPECT_DOUBLE_EQ(after.angle_scatter_beyond->mach_low, range->high + 0.5);
  EXPECT_DOUBLE_EQ(after.angle_scatter_beyond->mach_high, range->high + 2.0);
  // The inside block is untouched and still serves inside the range and below it.
  ASSERT_TRUE(after.angle_scatter);
  EXPECT_NEAR(after.angle_scatter->deg, t.angle_scatter->deg, kTol);
  EXPECT_NEAR(pipeline::table_angle_scatter_deg(after, 0.5 * (range->low + range->high)), inside,
              kTol);
  EXPECT_NEAR(pipeline::table_angle_scatter_deg(after, range->low - 0.3), inside, kTol);
  // The inside block serves the Mach numbers its runs covered; past them the
  // measured block takes over, inside the training range too (a table
  // extended beyond those runs).
  const auto seen = pipeline::scatter_mach_range(after);
  ASSERT_TRUE(seen.has_value());
  EXPECT_FALSE(pipeline::beyond_scatter_applies(after, seen->high));
  // Above the range, and beyond the runs' own Mach numbers too.
  EXPECT_TRUE(pipeline::beyond_scatter_applies(after, range->high + 0.1));
  EXPECT_NEAR(pipeline::table_angle_scatter_deg(after, range->high + 0.1),
              after.angle_scatter_beyond->deg, kTol);
  EXPECT_NEAR(pipeline::table_angle_scatter_deg(after, range->high + 5.0),
              after.angle_scatter_beyond->deg, kTol);

  // A run there says what its band took, and where that was measured.
  const auto applied = [&](double mach) {
    std::ostringstream text;
    text << "body: {kind: wedge, angle_deg: 12}\nfreestream: {mach: " << mach << "}\n";
    auto s = scene::parse_scene(text.str());
    return pipeline::apply_calibration(s, table);
  };
  const auto measured = applied(range->high + 1.0);
  EXPECT_TRUE(measured.outside_training_mach);
  EXPECT_NEAR(measured.angle_scatter_deg, after.angle_scatter_beyond->deg, kTol);
  EXPECT_NE(measured.note.find("the extrapolation's own angle error"), std::string::npos)
      << measured.note;
  EXPECT_EQ(measured.note.find("unmeasured"), std::string::npos) << measured.note;
  const auto further = applied(range->high + 3.0);  // beyond the runs' own Mach numbers
  EXPECT_NE(further.note.find("not at this Mach number"), std::string::npos) << further.note;
  EXPECT_NEAR(applied(0.5 * (range->low + range->high)).angle_scatter_deg, inside, kTol);
  if (seen->high + 0.05 < range->high) {
    const auto past = applied(seen->high + 0.05);
    EXPECT_FALSE(past.outside_training_mach);
    EXPECT_NEAR(past.angle_scatter_deg, after.angle_scatter_beyond->deg, kTol);
    EXPECT_NE(past.note.find("the table's own angle error"), std::string::npos) << past.note;
  }

  // A block whose runs do not lie beyond the range is refused, naming the key.
  std::string text = scene::read_file(table);
  const std::string low = "mach_low: ";
  const auto at = text.find(low, text.find("\nangle_scatter_beyond_mach:"));
  ASSERT_NE(at, std::string::npos);
  text.replace(at, text.find(',', at) - at, "mach_low: 3");
  scene::write_file_atomic(table, text);
  try {
    pipeline::read_calibration(table);
    ADD_FAILURE() << "a beyond block inside the range was accepted";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("angle_scatter_beyond_mach"), std::string::npos)
        << e.what();
  }
}
