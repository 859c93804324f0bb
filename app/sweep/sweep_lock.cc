#include "app/sweep/sweep_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace sortcell::app {

SweepLock::SweepLock(const std::filesystem::path& dir) {
  const std::filesystem::path file = dir / "sweep.lock";
  // Close-on-exec: the workers must not hold it after a killed sweep.
  fd_ = open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    throw std::invalid_argument("sweep folder '" + dir.string() + "': cannot open " + file.string() + ": " +
                                std::strerror(errno));
  }
  if (flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    close(fd_);
    fd_ = -1;
    if (error == EWOULDBLOCK) {
      throw std::invalid_argument("sweep folder '" + dir.string() + "': another sweep is running in it (it holds " +
                                  file.string() + ")");
    }
    throw std::invalid_argument("sweep folder '" + dir.string() + "': cannot lock " + file.string() + ": " +
                                std::strerror(error));
  }
}

SweepLock::~SweepLock() {
  if (fd_ >= 0) close(fd_);  // Closing releases the lock.
}

}  // namespace sortcell::app
