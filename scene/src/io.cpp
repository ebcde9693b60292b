#include "scene/io.hpp"

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unistd.h>

#include "scene/errors.hpp"

namespace scene {

namespace fs = std::filesystem;

namespace {
std::string temp_name(const std::string& path) {
  static std::atomic<unsigned> counter{0};  // unique temp names across threads
  return path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
}

nlohmann::json finite_only(const nlohmann::json& j) {
  if (j.is_number_float() && !std::isfinite(j.get<double>())) return nullptr;
  if (j.is_object()) {
    nlohmann::json o = nlohmann::json::object();
    for (auto it = j.begin(); it != j.end(); ++it) o[it.key()] = finite_only(it.value());
    return o;
  }
  if (j.is_array()) {
    nlohmann::json a = nlohmann::json::array();
    for (const auto& v : j) a.push_back(finite_only(v));
    return a;
  }
  return j;
}
}  // namespace

void make_dirs(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir + ": cannot create directory: " + ec.message());
}

void write_stream_atomic(const std::string& path, const std::function<void(std::ostream&)>& fill) {
  const fs::path p(path);
  if (p.has_parent_path()) make_dirs(p.parent_path().string());
  const std::string tmp = temp_name(path);
  try {
    {
      std::ofstream os(tmp, std::ios::binary);
      if (!os) throw RunError(tmp + ": cannot open for writing");
      fill(os);
      os.flush();
      if (!os) throw RunError(tmp + ": write failed");
    }
    fs::rename(tmp, path);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

void write_file_atomic(const std::string& path, const std::string& content) {
  write_stream_atomic(path, [&](std::ostream& os) { os << content; });
}

void write_json_atomic(const std::string& path, const nlohmann::json& j) {
  write_file_atomic(path, finite_only(j).dump(2) + "\n");
}

std::string read_file(const std::string& path) {
  std::ifstream is(path, std::ios::binary);
  if (!is) throw InputError(path + ": cannot open file (missing or unreadable)");
  std::ostringstream ss;
  ss << is.rdbuf();
  return ss.str();
}

}  // namespace scene
