#include "cli_run.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace test_support {

namespace fs = std::filesystem;

std::string stage_exe(const std::string& name) {
  return std::string(BIN_DIR) + "/" + name;
}

CliRun run_cli(const std::string& exe, const std::string& args) {
  CliRun r;
  const auto t0 = std::chrono::steady_clock::now();
  FILE* p = popen((exe + " " + args + " 2>&1 >/dev/null").c_str(), "r");
  std::array<char, 4096> buf{};
  while (p && std::fgets(buf.data(), buf.size(), p)) r.err += buf.data();
  const int st = p ? pclose(p) : -1;
  r.code = p && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

std::string write_scene(const std::string& dir, const std::string& text) {
  const std::string path = dir + "/scene.yaml";
  std::ofstream(path) << text;
  return path;
}

void expect_refusal(const CliRun& r, const std::string& needle) {
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
}

bool has_temporaries(const std::string& dir) {
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    if (n.find(".staging-") != std::string::npos || n.find(".old-") != std::string::npos ||
        n.find(".tmp.") != std::string::npos)
      return true;
  }
  return false;
}

}  // namespace test_support
