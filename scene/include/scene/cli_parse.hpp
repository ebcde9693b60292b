#pragma once
// Command-line parsing with the contract's exit codes, shared by every
// executable's main (CLI11 is header-only; only mains include this).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

namespace scene {

inline constexpr int kExitUsage = 2;  // contract: bad usage is exit 2

// Parses argv. Returns the exit code to stop with (0 after --help or
// --version, kExitUsage on a usage error, its message printed by CLI11), or
// nullopt to go on.
inline std::optional<int> parse_cli(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
    return std::nullopt;
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line, as the contract asks (CLI11's exit() adds a "Run with
    // --help" line); the message itself names the option.
    std::string msg = e.what();
    for (char& c : msg)
      if (c == '\n') c = ' ';
    const std::string name = std::filesystem::path(app.get_name()).filename().string();
    std::fprintf(stderr, "%s: usage error: %s (see --help)\n", name.c_str(), msg.c_str());
    return kExitUsage;
  }
}

}  // namespace scene
