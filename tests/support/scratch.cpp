#include "scratch.hpp"

namespace test_support {

namespace fs = std::filesystem;

fs::path scratch_root() {
  const fs::path root(SCRATCH_DIR);
  fs::create_directories(root);
  return root;
}

std::string fresh_dir(const std::string& name) {
  const std::string d = absent_dir(name);
  fs::create_directories(d);
  return d;
}

std::string absent_dir(const std::string& name) {
  const fs::path d = scratch_root() / name;
  fs::remove_all(d);
  return d.string();
}

}  // namespace test_support
