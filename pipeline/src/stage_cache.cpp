#include "pipeline/stage_cache.hpp"

#include <cstdint>
#include <cstdio>
#include <filesystem>

#include "scene/cli.hpp"
#include "scene/io.hpp"

namespace pipeline {

namespace fs = std::filesystem;

namespace {
constexpr const char* kRecord = "/.stage.json";
}

std::string fingerprint(const std::vector<std::string>& parts) {
  std::uint64_t h = 1469598103934665603ull;  // FNV offset basis
  auto mix = [&](const std::string& s) {
    for (const unsigned char c : s) {
      h ^= c;
      h *= 1099511628211ull;  // FNV prime
    }
    h ^= 0xff;  // separator, so ("ab","c") != ("a","bc")
    h *= 1099511628211ull;
  };
  mix(scene::version_string());
  for (const auto& p : parts) mix(p);
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

bool StageCache::fresh(const std::string& stage, const std::string& fp) const {
  const std::string path = dir(stage) + kRecord;
  if (!fs::exists(path)) return false;
  try {
    const auto j = nlohmann::json::parse(scene::read_file(path));
    return j.value("fingerprint", "") == fp;
  } catch (const std::exception&) {
    return false;  // unreadable record: rerun the stage
  }
}

nlohmann::json StageCache::result(const std::string& stage) const {
  try {
    const auto j = nlohmann::json::parse(scene::read_file(dir(stage) + kRecord));
    return j.value("result", nlohmann::json::object());
  } catch (const std::exception&) {
    return nlohmann::json::object();
  }
}

void StageCache::mark_done(const std::string& stage, const std::string& fp,
                           const nlohmann::json& result) const {
  scene::write_json_atomic(dir(stage) + kRecord, {{"fingerprint", fp}, {"result", result}});
}

void StageCache::invalidate(const std::string& stage) const {
  std::error_code ec;
  fs::remove(dir(stage) + kRecord, ec);
}

}  // namespace pipeline
