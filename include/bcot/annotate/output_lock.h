// One writer per annotation directory. Every run that writes an annotation (bcot annotate, its
// `--frames` splice, bcot batch's workers, bcot review's re-annotation) holds an advisory lock
// (flock) on <out>/.bcot.lock from its first write to its end; a second run into the same
// directory, from any process, is refused at once instead of interleaving its files with the
// first's. The kernel drops the lock when its process ends, however it ends (kill -9
// included), so a stale lock file never blocks a later run; the file itself stays (empty).
#pragma once

#include <string>

#include "bcot/core/status.h"

namespace bcot {

inline constexpr const char* kOutputLockFileName = ".bcot.lock";

class OutputLock {
 public:
  // Locks the existing directory `out_dir`. kInvalidInput naming it when another run holds
  // the lock; kIoError when the lock file cannot be created.
  static StatusOr<OutputLock> Acquire(const std::string& out_dir);

  OutputLock(OutputLock&& other) noexcept;
  OutputLock& operator=(OutputLock&& other) noexcept;
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;
  // Releases the lock.
  ~OutputLock();

 private:
  explicit OutputLock(int fd) : fd_(fd) {}
  int fd_ = -1;
};

}  // namespace bcot
