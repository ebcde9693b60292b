// shock.csv: round trip through the writer and reader, columns by name,
// comments, and every error naming the file, the line and the column.
#include "scene/shock_csv.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/units.hpp"
#include "scratch.hpp"

namespace fs = std::filesystem;

namespace {

using scene::kNaN;

fs::path fresh_dir(const std::string& name) {
  const fs::path d = test_support::scratch_root() /
                     ("scene_test_shock_csv_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string error_of(const std::string& path) {
  try {
    (void)scene::read_shock_csv(path);
  } catch (const scene::InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(ShockCsvFile, RoundTrip) {
  const fs::path d = fresh_dir("roundtrip");
  const std::string path = (d / "shock.csv").string();
  const std::vector<scene::ShockCsvRow> rows{
      {0, {0.1, 0.0}, {0.0, 1.0}, {0.1, 0.123456789012}, 0.123456789012, 0.01, 1e-3, true},
      {1, {0.2, 0.0}, {0.0, 1.0}, {kNaN, kNaN}, kNaN, kNaN, kNaN, false},
      {2, {0.3, 0.0}, {0.0, 1.0}, {0.3, 0.5}, 0.5, 0.02, 2e-3, true}};
  scene::write_shock_csv(path, rows);
  const std::string text = scene::read_file(path);
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "station,surface_x,surface_y,normal_x,normal_y,shock_x,shock_y,distance,ci,fit_error,"
            "accepted");
  const scene::ShockCsv back = scene::read_shock_csv(path);
  ASSERT_EQ(back.rows.size(), rows.size());
  EXPECT_TRUE(back.has_ci);
  constexpr double kPrinted = 1e-11;  // 12 significant digits
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(back.rows[i].station, rows[i].station);
    EXPECT_EQ(back.rows[i].accepted, rows[i].accepted);
    EXPECT_NEAR(back.rows[i].surface.x, rows[i].surface.x, kPrinted);
    if (rows[i].accepted) {
      EXPECT_NEAR(back.rows[i].shock.y, rows[i].shock.y, kPrinted);
      EXPECT_NEAR(back.rows[i].ci, rows[i].ci, kPrinted);
    } else {
      EXPECT_TRUE(std::isnan(back.rows[i].shock.x));
    }
  }
  fs::remove_all(d);
}

TEST(ShockCsvFile, ColumnsByNameCommentsAndExtraColumns) {
  const fs::path d = fresh_dir("names");
  const std::string path = (d / "shock.csv").string();
  scene::write_file_atomic(
      path,
      "# written by hand\n\"accepted\", extra, shock_y, shock_x\n"
      "1, a, 0.5, 0.25\n# a comment between rows\n1, b, 0.75, \"0.5\"\n0, c, nan, nan\n");
  const scene::ShockCsv csv = scene::read_shock_csv(path);
  ASSERT_EQ(csv.rows.size(), 3u);
  EXPECT_FALSE(csv.has_ci);
  EXPECT_DOUBLE_EQ(csv.rows[0].shock.x, 0.25);
  EXPECT_DOUBLE_EQ(csv.rows[1].shock.x, 0.5);
  EXPECT_EQ(csv.rows[2].station, 2);  // no station column: the row index
  EXPECT_TRUE(std::isnan(csv.rows[0].ci));
  fs::remove_all(d);
}

TEST(ShockCsvFile, EveryErrorNamesFileLineAndColumn) {
  const fs::path d = fresh_dir("errors");
  const std::string path = (d / "shock.csv").string();
  const auto error_for = [&](const std::string& text) {
    scene::write_file_atomic(path, text);
    return error_of(path);
  };
  EXPECT_EQ(error_of((d / "absent.csv").string()),
            (d / "absent.csv").string() + ": shock file not found");
  EXPECT_EQ(error_for("# only a comment\n"),
            path + ": shock file is empty (expected a header row with shock_x, shock_y, accepted)");
  EXPECT_EQ(error_for("# c\nshock_x,accepted\n0,1\n"), path + ":2: missing column 'shock_y'");
  EXPECT_EQ(error_for("shock_x,shock_y,accepted\n"),
            path + ": shock file has a header but no rows");
  EXPECT_EQ(error_for("shock_x,shock_y,accepted\n0,1,1\n0,x1,1\n"),
            path + ":3: column 'shock_y': expected a number, got 'x1'");
  EXPECT_EQ(error_for("shock_x,shock_y,accepted\n0,1\n"),
            path + ":2: no field for column 'accepted' (2 fields, the header has 3)");
  EXPECT_EQ(error_for("shock_x,shock_y,accepted\n0,1,2\n"),
            path + ":2: column 'accepted': expected 1 or 0, got '2'");
  EXPECT_EQ(error_for("shock_x,shock_y,accepted\nnan,1,1\n"),
            path + ":2: accepted row with a non-finite shock_x or shock_y");
  EXPECT_EQ(error_for("shock_x,shock_y,accepted\n0,1,0\n"),
            path + ": no accepted rows (accepted == 1) among 1");
  EXPECT_EQ(error_for("shock_x,shock_y,accepted\n0,1,1\n0,2,0\n"),
            path + ": only 1 accepted row (accepted == 1) among 2; a shock curve needs at least 2");
  fs::remove_all(d);
}
