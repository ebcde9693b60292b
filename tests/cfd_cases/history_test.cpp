// Reading back the case monitor's history.csv: the last finite value of a
// column is where the run stopped.
#include "cfd/history.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scratch.hpp"

namespace {

namespace fs = std::filesystem;

fs::path case_with_history(const std::string& name, const std::string& text) {
  const fs::path d = test_support::scratch_root() / ("shockgrain_history_" + name);
  fs::create_directories(d);
  scene::write_file_atomic((d / "history.csv").string(), text);
  return d;
}

TEST(History, LastFiniteValueOfAColumn) {
  const auto d = case_with_history("last",
                                   "time,flow_throughs,shock_x\n"
                                   "0.1,0.2,-0.70\n"
                                   "0.2,0.4,-0.775\n"
                                   "0.3,0.6,nan\n");
  EXPECT_DOUBLE_EQ(cfd::last_history_value(d.string(), "shock_x"), -0.775);
  EXPECT_DOUBLE_EQ(cfd::last_history_value(d.string(), "time"), 0.3);
}

TEST(History, MissingFileColumnOrValueNamesTheFile) {
  const auto none = test_support::scratch_root() / "shockgrain_history_none";
  fs::remove_all(none);
  EXPECT_THROW(cfd::last_history_value(none.string(), "shock_x"), scene::InputError);
  const auto d = case_with_history("nan", "time,shock_x\n0.1,nan\n0.2,nan\n");
  EXPECT_THROW(cfd::last_history_value(d.string(), "drift"), scene::InputError);
  try {
    cfd::last_history_value(d.string(), "shock_x");
    FAIL() << "no finite shock_x accepted";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("history.csv"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("shock_x"), std::string::npos);
  }
}

}  // namespace
