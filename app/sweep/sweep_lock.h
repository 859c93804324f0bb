#pragma once
/// @file
/// One sweep at a time in an output folder: an exclusive lock (flock) on DIR/sweep.lock, held while the
/// sweep runs and released when it ends or dies. A second sweep started into the folder meanwhile
/// refuses before it touches anything, so two never append to one results.jsonl.

#include <filesystem>

namespace sortcell::app {

class SweepLock {
 public:
  /// @throws std::invalid_argument "sweep folder '<dir>': another sweep is running in it (it holds
  ///         <dir>/sweep.lock)" when the lock is held; "... cannot open <lock file>" when it cannot be made.
  explicit SweepLock(const std::filesystem::path& dir);
  ~SweepLock();
  SweepLock(const SweepLock&) = delete;
  SweepLock& operator=(const SweepLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace sortcell::app
