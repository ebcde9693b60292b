#pragma once
// Results built beside their destination and swapped in only when complete,
// so that a failed or interrupted run never destroys the previous good
// results in --out, and leaves no half-written folder behind.
#include <string>

namespace scene {

// What happens to entries of an existing OUT that the new run did not write.
enum class Leftovers {
  keep,     // moved into the new OUT (unrelated files, e.g. cache records)
  discard,  // the new OUT is exactly what the run wrote (e.g. solver time folders)
};

class StagedDir {
 public:
  // Creates a fresh OUT.staging-TAG beside `out` (OUT's parent is created);
  // TAG is the process id unless given (MPI ranks share rank 0's).
  explicit StagedDir(std::string out, long tag = -1);
  // The staging folder's name for `out` and `tag`, without creating it.
  static std::string path_for(const std::string& out, long tag);
  ~StagedDir();  // removes the staging folder unless it was committed or kept
  StagedDir(const StagedDir&) = delete;
  StagedDir& operator=(const StagedDir&) = delete;

  const std::string& path() const { return stage_; }
  const std::string& out() const { return out_; }
  // Swaps the staging folder in as OUT (renames; the old OUT is removed only
  // after the new one is in place).
  void commit(Leftovers leftovers);
  // Renames the staging folder to OUT + suffix (e.g. ".partial", ".failed"),
  // replacing an earlier one, and returns that path. OUT is left untouched.
  std::string keep_as(const std::string& suffix);

 private:
  std::string out_, stage_;
  bool done_ = false;
};

// InputError "--out OUT: ..." when OUT equals, lies inside or contains the
// input folder or file `input` (named by `what`, e.g. "--mesh"): writing
// there would replace or wipe the input.
void refuse_out_overlap(const std::string& out, const std::string& input, const std::string& what);

}  // namespace scene
