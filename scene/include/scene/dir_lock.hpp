#pragma once
// An exclusive lock on an output directory for the life of a run, so two
// runs into the same --out cannot interleave their stages: the second is
// refused at once with the holder's pid. The lock is the kernel's (flock on
// DIR/.lock), so a killed run never leaves a stale lock behind.
#include <string>

namespace scene {

class DirLock {
 public:
  // RunError naming the directory and the holding pid when another process
  // holds it; creates the directory if needed.
  explicit DirLock(const std::string& dir);
  DirLock(const DirLock&) = delete;
  DirLock& operator=(const DirLock&) = delete;
  ~DirLock();

 private:
  int fd_ = -1;
};

}  // namespace scene
