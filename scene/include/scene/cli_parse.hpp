#pragma once
// Command-line parsing with the contract's exit codes, shared by every
// executable's main (CLI11 is header-only; only mains include this).
#include <CLI/CLI.hpp>

#include <optional>

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
    (void)app.exit(e);
    return kExitUsage;
  }
}

}  // namespace scene
