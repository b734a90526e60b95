// scripting/confined_file.hpp: open(2) with O_NOFOLLOW | O_NONBLOCK, fstat(2) for a regular
// file, a bounded read.
#include "scripting/confined_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace twinpost::scripting {

namespace {

struct fd_guard {
  int fd;
  ~fd_guard() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

read_refusal read_confined(const std::string& path, std::size_t max_bytes, std::string& out,
                           std::string& why) {
  out.clear();
  why.clear();
  fd_guard f{::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC)};
  if (f.fd < 0) {
    const int e = errno;
    if (e == ENOENT || e == ENOTDIR) return read_refusal::missing;
    if (e == ELOOP) return read_refusal::symlink;
    why = std::strerror(e);
    return read_refusal::other;
  }
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) {
    why = std::strerror(errno);
    return read_refusal::other;
  }
  if (!S_ISREG(st.st_mode)) return read_refusal::not_regular;
  if (static_cast<unsigned long long>(st.st_size) > max_bytes) return read_refusal::too_large;
  out.resize(static_cast<std::size_t>(st.st_size));
  std::size_t got = 0;
  for (;;) {
    if (got == out.size()) {
      if (out.size() > max_bytes) {  // grown since fstat
        out.clear();
        return read_refusal::too_large;
      }
      out.resize(out.size() + 4096);
    }
    const ssize_t n = ::read(f.fd, out.data() + got, out.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      why = std::strerror(errno);
      out.clear();
      return read_refusal::other;
    }
    if (n == 0) break;
    got += static_cast<std::size_t>(n);
  }
  out.resize(got);
  if (got > max_bytes) {
    out.clear();
    return read_refusal::too_large;
  }
  return read_refusal::none;
}

}  // namespace twinpost::scripting
