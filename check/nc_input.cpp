#include "check/nc_input.hpp"
#include "support/errors.hpp"
#include "support/file_reader.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <map>
#include <utility>

#include <fmt/format.h>

namespace twinpost {

namespace {

[[noreturn]] void cannot_read(const std::string& path, std::string_view why) {
  throw config_error(fmt::format("cannot read '{}': {}", path, why));
}

/// Reads `path` to its end once, into a temporary file that is gone when closed.
std::shared_ptr<std::FILE> copy_once(const std::string& path) {
  const file_ptr in = open_file_ptr(path.c_str(), "rb");
  if (!in) cannot_read(path, std::strerror(errno));
  std::shared_ptr<std::FILE> out(std::tmpfile(), &std::fclose);
  if (!out) cannot_read(path, fmt::format("no temporary file to copy it into ({})", std::strerror(errno)));
  chunk_reader reader(in.get(), std::size_t{1} << 16);  // a pipe gives a few KiB a read anyway
  std::size_t line = 0;                                 // bytes since the last line end
  bool too_long = false;
  for (std::string_view chunk; !too_long && !(chunk = reader.next()).empty();) {
    // The reader stops at a line past its limit: so does the copy (/dev/zero ends here).
    for (std::size_t i = 0; i < chunk.size(); ++i) {
      line = chunk[i] == '\n' || chunk[i] == '\r' ? 0 : line + 1;
      if (line > nc_max_line_bytes) {
        chunk = chunk.substr(0, i + 1);
        too_long = true;
        break;
      }
    }
    if (std::fwrite(chunk.data(), 1, chunk.size(), out.get()) != chunk.size())
      cannot_read(path, fmt::format("cannot copy it to a temporary file ({})", std::strerror(errno)));
  }
  if (!too_long && reader.failed()) cannot_read(path, std::strerror(errno));
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
