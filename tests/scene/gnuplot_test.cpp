// gnuplot_string: hostile labels and file names are drawn, never run. These
// tests need the real gnuplot 5 and fail, naming it, when it is missing.
#include "scene/gnuplot.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/process.hpp"
#include "scratch.hpp"

namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  return test_support::fresh_dir("scene_test_gnuplot_" + std::to_string(::getpid()) + "_" + name);
}

// Each would run a command if gnuplot (or a shell) evaluated it.
const std::vector<std::string> kHostile = {
    "x' . system(\"touch PWNED\") . '",
    "`touch PWNED2`",
    "$(touch PWNED3)",
    "line one\nline two'; system('touch PWNED4')\n",
    "x\\' . system('touch PWNED5') . '\\",
    "@macro \"; system(\"touch PWNED6\") #",
    // Special to gnuplot as file names: an input pipe, an output pipe.
    "< touch PWNED7",
    "|touch PWNED8",
};

// The files the hostile texts would create (the data files named after the
// texts hold "PWNED" too, but never as the whole name).
std::vector<std::string> pwned(const fs::path& d) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(d))
    if (e.path().filename().string().rfind("PWNED", 0) == 0) found.push_back(e.path().string());
  return found;
}

void require_gnuplot() {
  ASSERT_FALSE(scene::find_program("gnuplot").empty())
      << "gnuplot is required for this test (the toolchain draws every PNG with it); install "
         "gnuplot 5";
}

}  // namespace

TEST(Gnuplot, StringLiteralDoublesQuotesAndFlattensControls) {
  EXPECT_EQ(scene::gnuplot_string("plain"), "'plain'");
  EXPECT_EQ(scene::gnuplot_string("it's"), "'it''s'");
  EXPECT_EQ(scene::gnuplot_string("a\nb\tc\r"), "'a b c '");
  EXPECT_EQ(scene::gnuplot_string("`x` $y \\ \"z\""), "'`x` $y \\ \"z\"'");
  EXPECT_EQ(scene::gnuplot_string(""), "''");
}

TEST(Gnuplot, PathsCannotBePipesOrDatablocks) {
  EXPECT_EQ(scene::gnuplot_path("/abs/it's.dat"), "'/abs/it''s.dat'");
  EXPECT_EQ(scene::gnuplot_path("< touch x"), "'./< touch x'");
  EXPECT_EQ(scene::gnuplot_path("|cmd"), "'./|cmd'");
  EXPECT_EQ(scene::gnuplot_path("$block"), "'./$block'");
  EXPECT_EQ(scene::gnuplot_path("-"), "'./-'");
}

TEST(Gnuplot, HostileTextIsDrawnNotRun) {
  require_gnuplot();
  const fs::path d = fresh_dir("hostile");
  int k = 0;
  for (const std::string& text : kHostile) {
    // The text as a data file name too (where a file system allows it).
    std::string file = text;
    for (char& c : file)
      if (c == '\n' || c == '/') c = '_';
    std::ofstream(d / file) << "0 0\n1 1\n";
    // Output named after the text too: '|...' would otherwise be a pipe.
    const std::string png = file + std::to_string(k++) + ".png";
    const std::string label = scene::gnuplot_string(text);
    std::string script = "set terminal pngcairo size 300,200 noenhanced\n";
    script += "set output " + scene::gnuplot_path(png) + "\n";
    script += "set title " + label + "\nset xlabel " + label + "\n";
    script += "set label 1 " + label + " at 0.5,0.5\n";
    script += "plot " + scene::gnuplot_path(file) + " using 1:2 with lines title " + label + "\n";
    script += "unset output\n";
    scene::write_file_atomic((d / "plot.gp").string(), script);
    EXPECT_NO_THROW(scene::run_gnuplot((d / "plot.gp").string(), d.string(), (d / "log").string()))
        << text << "\n"
        << scene::read_file((d / "log").string());
    EXPECT_TRUE(fs::exists(d / png) && fs::file_size(d / png) > 0) << text;
  }
  EXPECT_EQ(pwned(d), std::vector<std::string>{});
  EXPECT_FALSE(fs::exists("PWNED") || fs::exists("PWNED2") || fs::exists("PWNED3"));
  fs::remove_all(d);
}

TEST(Gnuplot, FailureNamesTheLog) {
  require_gnuplot();
  const fs::path d = fresh_dir("fail");
  scene::write_file_atomic((d / "bad.gp").string(), "plot 'no such file' using 1:2\n");
  try {
    scene::run_gnuplot((d / "bad.gp").string(), d.string(), (d / "log").string());
    ADD_FAILURE() << "no error";
  } catch (const scene::RunError& e) {
    EXPECT_NE(std::string(e.what()).find((d / "log").string()), std::string::npos) << e.what();
  }
  fs::remove_all(d);
}
