#pragma once
// An exclusive flock(2) on a folder itself (no lock file is left behind), and a guard that
// holds back SIGINT, SIGTERM and SIGHUP while a folder changes.
#include <csignal>
#include <string>

namespace twinpost {

class folder_lock {
 public:
  /// Opens and locks `path`, waiting for other holders. ok() is false (errno kept in
  /// error()) when the folder cannot be opened.
  explicit folder_lock(const std::string& path);
  ~folder_lock();
  folder_lock(const folder_lock&) = delete;
  folder_lock& operator=(const folder_lock&) = delete;

  bool ok() const { return fd_ >= 0; }
  int error() const { return error_; }
  /// True while `path` still names the locked folder (another run may have removed it
  /// between the open and the lock).
  bool still_named(const std::string& path) const;

 private:
  int fd_ = -1;
  int error_ = 0;
};

/// Blocks the interrupting signals for its lifetime (their handlers run afterwards).
class signals_held {
 public:
  signals_held();
  ~signals_held();
  signals_held(const signals_held&) = delete;
  signals_held& operator=(const signals_held&) = delete;

 private:
  sigset_t old_;
};

}  // namespace twinpost
