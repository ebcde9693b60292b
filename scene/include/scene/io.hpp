#pragma once
// Atomic output: write to a temporary name in the same directory, then
// rename, so a failed run never leaves a half-written file where a good one was.
#include <functional>
#include <iosfwd>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace scene {

void write_file_atomic(const std::string& path, const std::string& content);
// Calls `fill` with a stream on a temporary file, then renames it to `path`.
void write_stream_atomic(const std::string& path, const std::function<void(std::ostream&)>& fill);
// Pretty JSON, atomic. Non-finite numbers are written as null.
void write_json_atomic(const std::string& path, const nlohmann::json& j);
std::string read_file(const std::string& path);  // InputError if missing
void make_dirs(const std::string& dir);

}  // namespace scene
