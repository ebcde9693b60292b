#pragma once
// Where tests write: a folder of the build tree (SCRATCH_DIR), never the
// shared system temporary folder, so that two checkouts tested at once (a
// clean clone beside a work tree) never share a file.
#include <filesystem>
#include <string>

namespace test_support {

// BUILD/test_scratch, created on first use.
std::filesystem::path scratch_root();
// An empty folder SCRATCH/NAME (whatever was there is removed first).
std::string fresh_dir(const std::string& name);
// SCRATCH/NAME with whatever was there removed and nothing made: for a run
// that makes its own output folder.
std::string absent_dir(const std::string& name);

}  // namespace test_support
