// The meshgen executable: exit codes and messages of the contract.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "shock_fixtures.hpp"

namespace {

struct CliRun {
  int code;
  std::string output;
};

CliRun run_meshgen(const std::string& args) {
  const std::string cmd = std::string(BIN_DIR) + "/meshgen " + args + " 2>&1";
  CliRun r{0, ""};
  FILE* p = popen(cmd.c_str(), "r");
  char buf[512];
  while (p && fgets(buf, sizeof buf, p)) r.output += buf;
  const int status = p ? pclose(p) : -1;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace

TEST(Cli, VersionAndHelp) {
  EXPECT_EQ(run_meshgen("--version").code, 0);
  const CliRun h = run_meshgen("--help");
  EXPECT_EQ(h.code, 0);
  EXPECT_NE(h.output.find("--shock"), std::string::npos);
}

TEST(Cli, UsageAndInputErrorsExitTwo) {
  const std::string scene = meshgen_test::case_path("wedge_M3_10");
  const std::string dir = meshgen_test::fresh_dir("cli_err");
  EXPECT_EQ(run_meshgen("--bogus").code, 2);
  const CliRun no_shock = run_meshgen(scene + " --out " + dir);
  EXPECT_EQ(no_shock.code, 2);
  EXPECT_NE(no_shock.output.find("a clustered grid needs --shock shock.csv"), std::string::npos) << no_shock.output;
  const CliRun missing = run_meshgen(scene + " --shock " + dir + "/absent.csv --out " + dir);
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.output.find(dir + "/absent.csv: shock file not found"), std::string::npos) << missing.output;
  const std::string empty = dir + "/empty.csv";
  std::FILE* f = std::fopen(empty.c_str(), "w");
  std::fclose(f);
  const CliRun e = run_meshgen(scene + " --shock " + empty + " --out " + dir);
  EXPECT_EQ(e.code, 2);
  EXPECT_NE(e.output.find("shock file is empty"), std::string::npos) << e.output;
}

TEST(Cli, UniformRunWritesTheCase) {
  const std::string dir = meshgen_test::fresh_dir("cli_ok");
  const CliRun r = run_meshgen(meshgen_test::case_path("wedge_M5_20") + " --uniform --h-min 0.05 --out " + dir);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/summary.json"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/constant/polyMesh/boundary"));
}
