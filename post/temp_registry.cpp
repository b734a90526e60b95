#include "post/temp_registry.hpp"

#include <atomic>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace twinpost {

namespace {

constexpr int slot_count = 32;
constexpr std::size_t slot_bytes = 8192;

enum : int { free_slot = 0, filling = 1, ready = 2 };

// One run's paths, NUL-separated: the stage, then the made folders outermost first.
struct slot {
  std::atomic<int> state{free_slot};
  int paths = 0;
  char text[slot_bytes];
};

slot slots[slot_count];

// The i-th path of a slot.
const char* path_at(const slot& s, int i) {
  const char* p = s.text;
  for (int k = 0; k < i; ++k) p += std::strlen(p) + 1;
  return p;
}

// Unlinks the files of a flat folder and the folder; only system calls, no allocation.
void remove_flat_dir(const char* dir) noexcept {
  const int fd = ::open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  alignas(8) char buf[4096];
  for (;;) {
    const long n = ::syscall(SYS_getdents64, fd, buf, sizeof buf);
    if (n <= 0) break;
    for (long off = 0; off < n;) {
      const auto* d = reinterpret_cast<const struct dirent64*>(buf + off);
      off += d->d_reclen;
      if (std::strcmp(d->d_name, ".") == 0 || std::strcmp(d->d_name, "..") == 0) continue;
      ::unlinkat(fd, d->d_name, 0);
    }
  }
  ::close(fd);
  ::rmdir(dir);
}

}  // namespace

int register_temp_dirs(const std::string& stage, const std::vector<std::string>& made_dirs) {
  std::size_t need = stage.size() + 1;
  for (const std::string& d : made_dirs) need += d.size() + 1;
  if (need > slot_bytes) return -1;
  for (int i = 0; i < slot_count; ++i) {
    int expected = free_slot;
    if (!slots[i].state.compare_exchange_strong(expected, filling)) continue;
    char* p = slots[i].text;
    std::memcpy(p, stage.c_str(), stage.size() + 1);
    p += stage.size() + 1;
    for (const std::string& d : made_dirs) {
      std::memcpy(p, d.c_str(), d.size() + 1);
      p += d.size() + 1;
    }
    slots[i].paths = 1 + static_cast<int>(made_dirs.size());
    slots[i].state.store(ready);
    return i;
  }
  return -1;
}

void unregister_temp_dirs(int slot_index) {
  if (slot_index >= 0 && slot_index < slot_count) slots[slot_index].state.store(free_slot);
}

void remove_registered_temp_dirs() noexcept {
  for (slot& s : slots) {
    if (s.state.load() != ready) continue;
    remove_flat_dir(s.text);
    for (int i = s.paths - 1; i >= 1; --i) ::rmdir(path_at(s, i));
  }
}

}  // namespace twinpost
