#include "check/nc_input.hpp"
#include "support/errors.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <map>
#include <utility>

#include <fmt/format.h>

namespace twinpost {

namespace {

[[noreturn]] void cannot_read(const std::string& path, std::string_view why) {
  throw config_error(fmt::format("twinpost: error: cannot read '{}': {}", path, why));
}

/// Reads `path` to its end once, into a temporary file that is gone when closed.
std::shared_ptr<std::FILE> copy_once(const std::string& path) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> in(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!in) cannot_read(path, std::strerror(errno));
  std::shared_ptr<std::FILE> out(std::tmpfile(), &std::fclose);
  if (!out)
    cannot_read(path, fmt::format("no temporary file to copy it into ({})", std::strerror(errno)));
  constexpr std::size_t chunk_bytes = 1 << 16;
  auto buf = std::make_unique_for_overwrite<char[]>(chunk_bytes);
  std::size_t n, line = 0;  // bytes since the last line end
  bool too_long = false;
  while (!too_long && (n = std::fread(buf.get(), 1, chunk_bytes, in.get())) > 0) {
    // The reader stops at a line past its limit: so does the copy (/dev/zero ends here).
    for (std::size_t i = 0; i < n; ++i) {
      line = buf[i] == '\n' || buf[i] == '\r' ? 0 : line + 1;
      if (line > nc_max_line_bytes) {
        n = i + 1;
        too_long = true;
        break;
      }
    }
    if (std::fwrite(buf.get(), 1, n, out.get()) != n)
      cannot_read(path, fmt::format("cannot copy it to a temporary file ({})", std::strerror(errno)));
  }
  if (!too_long && std::ferror(in.get())) cannot_read(path, std::strerror(errno));
  if (std::fflush(out.get()) != 0)
    cannot_read(path, fmt::format("cannot copy it to a temporary file ({})", std::strerror(errno)));
  return out;
}

}  // namespace

std::vector<nc_source> rereadable(const std::vector<nc_source>& files) {
  std::vector<nc_source> out = files;
  std::map<std::pair<dev_t, ino_t>, std::shared_ptr<std::FILE>> copies;  // one per pipe
  for (nc_source& f : out) {
    if (f.copy || f.path.empty()) continue;
    struct stat st {};
    // stat, not open: opening a FIFO to look at it would take its writer's data away.
    if (::stat(f.path.c_str(), &st) != 0) cannot_read(f.path, std::strerror(errno));
    if (S_ISREG(st.st_mode)) continue;
    if (S_ISDIR(st.st_mode)) cannot_read(f.path, "it is a directory");
    std::shared_ptr<std::FILE>& copy = copies[{st.st_dev, st.st_ino}];
    if (!copy) copy = copy_once(f.path);
    f.copy = copy;
  }
  return out;
}

}  // namespace twinpost
