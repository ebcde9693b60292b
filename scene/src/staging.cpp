#include "scene/staging.hpp"

#include <unistd.h>

#include <filesystem>
#include <system_error>

#include "scene/errors.hpp"

namespace scene {

namespace fs = std::filesystem;

namespace {

fs::path normalised(const std::string& p) {
  std::error_code ec;
  fs::path n = fs::weakly_canonical(fs::absolute(p), ec);
  if (ec) n = fs::absolute(p).lexically_normal();
  // "a/b/" and "a/b" are the same folder.
  if (!n.has_filename() && n.has_parent_path()) n = n.parent_path();
  return n;
}

// True when `inner` equals `outer` or lies below it.
bool within(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i)
    if (i == inner.end() || *i != *o) return false;
  return true;
}

}  // namespace

std::string StagedDir::path_for(const std::string& out, long tag) {
  return normalised(out).string() + ".staging-" +
         std::to_string(tag < 0 ? static_cast<long>(::getpid()) : tag);
}

StagedDir::StagedDir(std::string out, long tag) : out_(std::move(out)) {
  const fs::path o = normalised(out_);
  if (o.filename().empty() || o == o.root_path())
    throw InputError(out_ + ": --out must name a folder, not the file-system root");
  std::error_code exists_ec;
  if (fs::exists(o, exists_ec) && !fs::is_directory(o, exists_ec))
    throw InputError(out_ + ": --out exists and is not a folder");
  stage_ = path_for(out_, tag);
  std::error_code ec;
  fs::remove_all(stage_, ec);
  fs::create_directories(stage_, ec);
  if (ec)
    throw InputError(out_ + ": cannot create the staging folder " + stage_ + ": " + ec.message());
}

StagedDir::~StagedDir() {
  if (done_) return;
  std::error_code ec;
  fs::remove_all(stage_, ec);
}

void StagedDir::commit(Leftovers leftovers) {
  const fs::path o = normalised(out_);
  std::error_code ec;
  const bool had_out = fs::exists(o, ec);
  if (had_out && !fs::is_directory(o, ec))
    throw RunError(out_ + ": exists and is not a folder; the results stay in " + stage_);
  if (had_out && leftovers == Leftovers::keep) {
    for (const auto& entry : fs::directory_iterator(o)) {
      const fs::path target = fs::path(stage_) / entry.path().filename();
      if (!fs::exists(target)) fs::rename(entry.path(), target);
    }
  }
  const fs::path old = o.string() + ".old-" + std::to_string(::getpid());
  if (had_out) {
    fs::remove_all(old, ec);
    fs::rename(o, old);
  }
  try {
    fs::rename(stage_, o);
  } catch (...) {
    if (had_out) fs::rename(old, o, ec);  // put the previous results back
    throw;
  }
  done_ = true;
  if (had_out) fs::remove_all(old, ec);
}

std::string StagedDir::keep_as(const std::string& suffix) {
  const std::string target = normalised(out_).string() + suffix;
  std::error_code ec;
  fs::remove_all(target, ec);
  fs::rename(stage_, target);
  done_ = true;
  return target;
}

void refuse_out_overlap(const std::string& out, const std::string& input, const std::string& what) {
  if (out.empty() || input.empty()) return;
  const fs::path o = normalised(out), i = normalised(input);
  if (within(o, i) || within(i, o))
    throw InputError("--out " + out + ": equals, lies inside or contains the " + what + " " +
                     input + " (writing there would replace the input); choose another folder");
}

}  // namespace scene
