#include "post/folder_lock.hpp"

#include <cerrno>
#include <fcntl.h>
#include <pthread.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace twinpost {

folder_lock::folder_lock(const std::string& path) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd_ < 0) {
    error_ = errno;
    return;
  }
  while (::flock(fd_, LOCK_EX) != 0 && errno == EINTR) {
  }
}

folder_lock::~folder_lock() {
  if (fd_ >= 0) ::close(fd_);  // closing releases the lock
}

bool folder_lock::still_named(const std::string& path) const {
  struct stat held {
  }, named{};
  if (fd_ < 0 || ::fstat(fd_, &held) != 0 || ::stat(path.c_str(), &named) != 0) return false;
  return held.st_dev == named.st_dev && held.st_ino == named.st_ino;
}

signals_held::signals_held() {
  sigset_t s;
  sigemptyset(&s);
  sigaddset(&s, SIGINT);
  sigaddset(&s, SIGTERM);
  sigaddset(&s, SIGHUP);
  pthread_sigmask(SIG_BLOCK, &s, &old_);
}

signals_held::~signals_held() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }

}  // namespace twinpost
