#include "bcot/annotate/output_lock.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <utility>

namespace bcot {

StatusOr<OutputLock> OutputLock::Acquire(const std::string& out_dir) {
  const std::string path = (std::filesystem::path(out_dir) / kOutputLockFileName).string();
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (fd < 0) {
    return Status::IoError(
        fmt::format("{}: cannot create the lock file: {}", path, std::strerror(errno)));
  }
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(fd);
    if (error == EWOULDBLOCK) {
      return Status::InvalidInput(fmt::format(
          "{}: another bcot run is writing this annotation now (it holds {}); wait for it to "
          "end",
          out_dir, kOutputLockFileName));
    }
    return Status::IoError(fmt::format("{}: cannot lock: {}", path, std::strerror(error)));
  }
  return OutputLock(fd);
}

OutputLock::OutputLock(OutputLock&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}

OutputLock& OutputLock::operator=(OutputLock&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

OutputLock::~OutputLock() {
  if (fd_ >= 0) ::close(fd_);  // closing the only descriptor releases the flock
}

}  // namespace bcot
