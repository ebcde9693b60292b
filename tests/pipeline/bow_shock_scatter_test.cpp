// The bow shock's calibration scatter: station errors against the gas's
// shock, pooled per body, stored in the table, and the band it widens.
#include "pipeline/bow_shock_scatter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "pipeline/bow_station_bias.hpp"
#include "pipeline/predictor.hpp"
#include "pipeline/run.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/scene.hpp"
#include "scene/shock_csv.hpp"
#include "scratch.hpp"

namespace fs = std::filesystem;

namespace {
using scene::kNaN;
const std::string kSource = SOURCE_DIR;

fs::path fresh(const std::string& name) {
  return test_support::fresh_dir("shockgrain_bow_" + name);
}

// Stations on the line x = 0 facing -x, the shock at `distance[i]` ahead.
void write_stations(const std::string& path, const std::vector<double>& distance,
                    const std::vector<bool>& accepted, double surface_shift = 0.0) {
  std::vector<scene::ShockCsvRow> rows;
  for (std::size_t i = 0; i < distance.size(); ++i) {
    scene::ShockCsvRow r;
    r.station = static_cast<int>(i);
    r.surface = {0.0, 0.1 * static_cast<double>(i) + surface_shift};
    r.normal = {-1.0, 0.0};
    r.shock = {-distance[i], r.surface.y};
    r.distance = distance[i];
    r.ci = 0.01;
    r.fit_error = 0.0;
    r.accepted = accepted[i];
    rows.push_back(r);
  }
  scene::write_shock_csv(path, rows);
}

// The shipped table copied to `path`, its bow block replaced by one with
// these figures (no shapes); the caller edits it further and writes it.
pipeline::CalibrationTable shipped_table_with_bow_block(const std::string& path, double rms,
                                                        const std::vector<std::string>& bodies) {
  fs::copy_file(kSource + "/pipeline/calibration.yaml", path);
  auto t = pipeline::read_calibration(path);
  t.bow_shock.emplace();
  t.bow_shock->relative_rms = rms;
  t.bow_shock->bodies = bodies;
  return t;
}
}  // namespace

TEST(BowShockScatter, RelativeErrorsOnStationsAcceptedInBoth) {
  const auto d = fresh("stations");
  write_stations((d / "g.csv").string(), {0.55, 0.66, 0.9, 0.40, 0.30},
                 {true, true, true, false, true});
  write_stations((d / "c.csv").string(), {0.50, 0.60, 0.8, 0.50, 0.30},
                 {true, true, false, true, true});
  const auto e = pipeline::station_errors((d / "g.csv").string(), (d / "c.csv").string());
  ASSERT_EQ(e.relative.size(), 3u);  // stations 0, 1, 4
  EXPECT_NEAR(e.relative[0], 0.1, 1e-12);
  EXPECT_NEAR(e.relative[1], 0.1, 1e-12);
  EXPECT_NEAR(e.relative[2], 0.0, 1e-12);
  EXPECT_NEAR(e.rms, std::sqrt(0.02 / 3.0), 1e-12);
  EXPECT_NEAR(e.mean, 0.2 / 3.0, 1e-12);
}

TEST(BowShockScatter, OtherStationsOrTooFewAreInputErrors) {
  const auto d = fresh("bad");
  write_stations((d / "g.csv").string(), {0.5, 0.6, 0.7}, {true, true, true});
  write_stations((d / "moved.csv").string(), {0.5, 0.6, 0.7}, {true, true, true}, 0.05);
  EXPECT_THROW(pipeline::station_errors((d / "g.csv").string(), (d / "moved.csv").string()),
               scene::InputError);
  write_stations((d / "few.csv").string(), {0.5, 0.6, 0.7}, {true, true, false});
  EXPECT_THROW(pipeline::station_errors((d / "g.csv").string(), (d / "few.csv").string()),
               scene::InputError);
}

TEST(BowShockScatter, EachBodyCountsOnce) {
  pipeline::StationErrors a, b;
  a.body = "a";
  a.mach = 3.0;
  b.mach = 6.0;
  a.relative.assign(30, 0.1);
  a.rms = 0.1;
  b.body = "b";
  b.relative.assign(3, 0.3);
  b.rms = 0.3;
  const auto w = pipeline::pooled_scatter({a, b});
  EXPECT_NEAR(w.relative_rms, std::sqrt((0.01 + 0.09) / 2.0), 1e-12);
  EXPECT_EQ(w.stations, 33);
  EXPECT_EQ(w.bodies, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(w.machs, (std::vector<double>{3.0, 6.0}));
}

TEST(BowShockScatter, TableKeepsItAndBluntBodiesGetIt) {
  const std::string path = (fresh("table") / "calibration.yaml").string();
  auto t = shipped_table_with_bow_block(path, 0.1234567890123, {"disc_M3", "disc_M6"});
  t.bow_shock->stations = 67;
  t.bow_shock->cpu_seconds = 500;
  pipeline::write_calibration(t, path);
  const auto back = pipeline::read_calibration(path);
  ASSERT_TRUE(back.bow_shock.has_value());
  EXPECT_EQ(back.bow_shock->relative_rms, 0.1234567890123);
  EXPECT_EQ(back.bow_shock->bodies, t.bow_shock->bodies);
  EXPECT_EQ(back.bow_shock->stations, 67);

  auto disc = scene::parse_scene("body: {kind: disc, radius: 0.5}\nfreestream: {mach: 3.5}\n");
  EXPECT_EQ(pipeline::apply_calibration(disc, path).bow_shock_relative_rms, 0.1234567890123);
  // Every body gets it; the predictor uses it only on a shock it finds detached (an attached
  // wedge's band is the angle's), which near the maximum deflection the granular gas's may be.
  auto wedge = scene::parse_scene("body: {kind: wedge, angle_deg: 12}\nfreestream: {mach: 3.5}\n");
  EXPECT_EQ(pipeline::apply_calibration(wedge, path).bow_shock_relative_rms, 0.1234567890123);
  // A wedge beyond its maximum deflection stands its shock off like a blunt body.
  auto detached = scene::parse_scene("body: {kind: wedge, angle_deg: 30}\nfreestream: {mach: 2}\n");
  EXPECT_EQ(pipeline::apply_calibration(detached, path).bow_shock_relative_rms, 0.1234567890123);
  // The blunt training runs are charged to the bodies whose shock stands off in the gas only.
  const auto cost = [&](const char* text) {
    auto s = scene::parse_scene(text);
    return pipeline::apply_calibration(s, path).cpu_seconds;
  };
  EXPECT_DOUBLE_EQ(cost("body: {kind: wedge, angle_deg: 30}\nfreestream: {mach: 2}\n"),
                   t.cpu_seconds + 500);
  EXPECT_DOUBLE_EQ(cost("body: {kind: disc, radius: 0.5}\nfreestream: {mach: 3.5}\n"),
                   t.cpu_seconds + 500);
  EXPECT_DOUBLE_EQ(cost("body: {kind: wedge, angle_deg: 12}\nfreestream: {mach: 3.5}\n"),
                   t.cpu_seconds);
  // A scene's own restitution owes nothing to the table.
  auto own = scene::parse_scene(
      "body: {kind: disc, radius: 0.5}\nfreestream: {mach: 3.5}\ngranular: {restitution: 0.97}\n");
  EXPECT_TRUE(std::isnan(pipeline::apply_calibration(own, path).bow_shock_relative_rms));

  t.bow_shock.reset();
  pipeline::write_calibration(t, path);
  scene::write_file_atomic(path, scene::read_file(path) + "bow_shock: {relative_rms: -0.1}\n");
  EXPECT_THROW(pipeline::read_calibration(path), scene::InputError);
}

// The scatter is measured on blunt bodies at a few Mach numbers: a bow shock
// beyond them gets the same warning as an e(M) outside its training range,
// an attached wedge (whose band is the angle's) none.
TEST(BowShockScatter, BeyondItsBodiesMachNumbersIsSaid) {
  const std::string path = (fresh("mach_range") / "calibration.yaml").string();
  auto t = shipped_table_with_bow_block(path, 0.17, {"disc_M3", "apollo_M3.5", "disc_M5"});
  t.bow_shock->machs = {3.0, 3.5, 5.0};
  pipeline::write_calibration(t, path);
  const auto back = pipeline::read_calibration(path);
  ASSERT_TRUE(back.bow_shock.has_value());
  EXPECT_EQ(back.bow_shock->machs, t.bow_shock->machs);
  const auto range = pipeline::training_mach_range(*back.bow_shock);
  ASSERT_TRUE(range.has_value());
  EXPECT_EQ(range->low, 3.0);
  EXPECT_EQ(range->high, 5.0);

  const auto applied = [&](const char* text) {
    auto s = scene::parse_scene(text);
    return pipeline::apply_calibration(s, path);
  };
  // Inside the wedge table's Mach range 2.5-6 but below the blunt bodies'.
  const auto slow = applied("body: {kind: disc, radius: 2}\nfreestream: {mach: 2.5}\n");
  EXPECT_TRUE(slow.outside_training_mach);
  EXPECT_NE(slow.note.find("blunt bodies the bow-shock band's scatter was measured on"),
            std::string::npos)
      << slow.note;
  const auto inside = applied("body: {kind: disc, radius: 2}\nfreestream: {mach: 4}\n");
  EXPECT_FALSE(inside.outside_training_mach) << inside.note;
  EXPECT_EQ(inside.note.find("WARNING"), std::string::npos) << inside.note;
  // A detached wedge borrows the scatter, and its warning.
  EXPECT_TRUE(applied("body: {kind: wedge, angle_deg: 40}\nfreestream: {mach: 2.6}\n")
                  .outside_training_mach);
  // An attached wedge's band is the angle's: no bow warning at the same Mach number.
  EXPECT_FALSE(applied("body: {kind: wedge, angle_deg: 10}\nfreestream: {mach: 2.6}\n")
                   .outside_training_mach);

  // A table that does not record its bodies' Mach numbers checks no range.
  t.bow_shock->machs.clear();
  pipeline::write_calibration(t, path);
  EXPECT_FALSE(
      applied("body: {kind: disc, radius: 2}\nfreestream: {mach: 2.6}\n").outside_training_mach);
  // One Mach number per body, or the table is refused naming the key.
  t.bow_shock.reset();
  pipeline::write_calibration(t, path);
  scene::write_file_atomic(
      path,
      scene::read_file(path) + "bow_shock: {relative_rms: 0.1, bodies: [a, b], machs: [3]}\n");
  try {
    pipeline::read_calibration(path);
    FAIL() << "a bow block with too few Mach numbers was read";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bow_shock.machs"), std::string::npos) << e.what();
  }
}

TEST(BowShockScatter, CaseStudiesAreNeverTrainingPoints) {
  const auto d = fresh("case_study");
  fs::copy_file(kSource + "/pipeline/cases/disc_M4.yaml", d / "scene.resolved.yaml");
  scene::write_file_atomic((d / "summary.json").string(),
                           "{\"prediction\": {\"predictor\": \"granular\"}}");
  try {
    pipeline::run_station_errors(d.string());
    FAIL() << "a case study was accepted as training";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("case study"), std::string::npos) << e.what();
  }
}

TEST(BowShockScatter, BandCombinesTheIntervalWithTheRelativeScatter) {
  EXPECT_NEAR(pipeline::band_bow_half_width(0.01, 0.5, 0.2), std::hypot(0.01, 1.96 * 0.2 * 0.5),
              1e-15);
  EXPECT_EQ(pipeline::band_bow_half_width(0.01, 0.5, kNaN),
            0.01);  // no scatter: the interval alone
  EXPECT_NEAR(pipeline::band_bow_half_width(kNaN, 0.5, 0.2), 1.96 * 0.1, 1e-15);
}

// The granular predictor's bow shock as meshgen gets it: the accepted
// stations, each band widened by the scatter at its own distance, and a
// fingerprint that changes with the scatter.
TEST(BowShockScatter, GranularBowShockBandCoversTheScatter) {
  const auto s = scene::load_scene(kSource + "/tests/data/disc_small.yaml");
  const auto dir = fresh("granular");
  const auto p = pipeline::predict_shock(s, "granular", dir.string(), 1);
  ASSERT_EQ(p.kind, scene::ShockKind::detached);
  constexpr double kRel = 0.2;
  const auto wide = pipeline::predict_shock(s, "granular", dir.string(), 1, false, kNaN, kRel);
  EXPECT_NE(wide.fingerprint, p.fingerprint);
  EXPECT_NE(wide.shock_csv, p.shock_csv);
  const auto rows = scene::read_shock_csv(p.shock_csv).rows;
  std::size_t k = 0;
  for (const auto& r : rows) {
    if (!r.accepted) continue;
    ASSERT_LT(k, wide.curve.size());
    EXPECT_EQ(wide.curve[k].x, r.shock.x);
    EXPECT_NEAR(wide.half_width[k], std::hypot(r.ci, 1.96 * kRel * r.distance), 1e-9);
    EXPECT_GT(wide.half_width[k], p.half_width[k]);
    ++k;
  }
  EXPECT_EQ(k, wide.curve.size());
  // The band keeps shockfit's station layout (every station, its surface
  // point and normal), each accepted station's ci the band's half-width.
  const auto back = scene::read_shock_csv(wide.shock_csv).rows;
  ASSERT_EQ(back.size(), rows.size());
  k = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(back[i].surface, rows[i].surface);
    EXPECT_EQ(back[i].accepted, rows[i].accepted);
    if (back[i].accepted) {
      EXPECT_NEAR(back[i].ci, wide.half_width[k++], 1e-9);
    }
  }

  // A shape's station bias moves every station along its normal by its fold
  // and the standoff with it; the band then takes the bias's own scatter.
  pipeline::BowStationBias bias;
  bias.shape = "disc";
  bias.model = "inclination";
  bias.coefficients = {0.2, -0.4};
  bias.relative_rms = 0.05;
  bias.mach_low = 3;
  bias.mach_high = 6;
  const auto folded =
      pipeline::predict_shock(s, "granular", dir.string(), 1, false, kNaN, 0.05, &bias);
  EXPECT_NE(folded.fingerprint, p.fingerprint);
  EXPECT_NEAR(folded.standoff, p.standoff / 1.2, 1e-12);
  EXPECT_NEAR(folded.details.at("standoff_granular").get<double>(), p.standoff, 1e-12);
  const auto moved = scene::read_shock_csv(folded.shock_csv).rows;
  ASSERT_EQ(moved.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (!rows[i].accepted) continue;
    const double r =
        bias.relative_error(s.freestream.mach, pipeline::inclination_deg(rows[i].normal));
    EXPECT_NEAR(moved[i].distance, rows[i].distance / (1.0 + r), 1e-9);
    EXPECT_NEAR(moved[i].shock.x, rows[i].surface.x + moved[i].distance * rows[i].normal.x, 1e-9);
    EXPECT_NEAR(moved[i].ci, std::hypot(rows[i].ci / (1.0 + r), 1.96 * 0.05 * moved[i].distance),
                1e-9);
  }

  // The standoff's own term divides the standoff once more and leaves the
  // stations where the fold put them; the prediction says which term it took.
  auto termed = bias;
  termed.standoff_model = "constant";
  termed.standoff_coefficients = {0.05};
  const auto with_term =
      pipeline::predict_shock(s, "granular", dir.string(), 1, false, kNaN, 0.05, &termed);
  EXPECT_NE(with_term.fingerprint, folded.fingerprint);
  EXPECT_NEAR(with_term.standoff, p.standoff / (1.2 * 1.05), 1e-12);
  EXPECT_NEAR(with_term.standoff_ci, p.standoff_ci / (1.2 * 1.05), 1e-12);
  EXPECT_EQ(with_term.details.at("station_bias").at("standoff_model"), "constant");
  EXPECT_EQ(with_term.curve, folded.curve);
}

// The scatter belongs to the table's e(M): a run with another restitution
// is refused before anything is written.
TEST(BowShockScatter, RunsWithAnotherRestitutionAreRefused) {
  const auto d = fresh("other_e");
  const std::string table = (d / "calibration.yaml").string();
  fs::copy_file(kSource + "/pipeline/calibration.yaml", table);
  const std::string before = scene::read_file(table);
  for (const char* name : {"a", "b"}) {
    fs::create_directories(d / name);
    scene::write_file_atomic(
        (d / name / "scene.resolved.yaml").string(),
        "name: other\nbody: {kind: disc, radius: 0.5}\nfreestream: {mach: 3.3}\n"
        "granular: {restitution: 0.9}\n");
  }
  try {
    pipeline::calibrate_bow_shocks({(d / "a").string(), (d / "b").string()}, table);
    FAIL() << "a run at its own restitution was accepted";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("granular.restitution"), std::string::npos) << e.what();
  }
  EXPECT_EQ(scene::read_file(table), before);
  try {
    pipeline::calibrate_bow_shocks({(d / "missing").string(), (d / "a").string()}, table);
    FAIL() << "a missing run directory was accepted";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no such directory"), std::string::npos) << e.what();
  }
}
