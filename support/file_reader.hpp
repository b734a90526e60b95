#pragma once
// Reading a file in large chunks: the one fread loop for inputs that may be far larger than
// memory should hold (CL jobs, NC programs, copies of pipes, program bodies). Each chunk is
// read into the same buffer, so a read costs no allocation.
#include <cstdio>
#include <memory>
#include <string_view>

namespace twinpost {

/// An open C stream, closed when it goes.
using file_ptr = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

/// `path` opened with `mode` (a null file_ptr when it cannot be opened: errno says why).
inline file_ptr open_file_ptr(const char* path, const char* mode) {
  return file_ptr(std::fopen(path, mode), &std::fclose);
}

/// Hands out the bytes of an open stream a chunk at a time, from where the stream stands.
class chunk_reader {
 public:
  /// 1 MiB: a few reads for a long job, one for most NC programs.
  static constexpr std::size_t default_chunk_bytes = std::size_t{1} << 20;

  explicit chunk_reader(std::FILE* file, std::size_t chunk_bytes = default_chunk_bytes)
      : file_(file), chunk_bytes_(chunk_bytes),
        buf_(std::make_unique_for_overwrite<char[]>(chunk_bytes + 1)) {}

  /// The next chunk, at most chunk_bytes long and followed by a NUL (for strcspn). Valid until
  /// the next call. Empty at the end of the stream, or after a read error (failed()).
  std::string_view next() {
    const std::size_t n = std::fread(buf_.get(), 1, chunk_bytes_, file_);
    buf_[n] = '\0';
    return {buf_.get(), n};
  }

  /// The buffer behind the last chunk: a caller may change its bytes (put a NUL after a
  /// prefix, as strcspn wants) until the next call.
  char* data() { return buf_.get(); }

  /// True when a read failed (EIO, a folder) rather than reaching the end: errno says why.
  bool failed() const { return std::ferror(file_) != 0; }

 private:
  std::FILE* file_;
  std::size_t chunk_bytes_;
  std::unique_ptr<char[]> buf_;  // chunk_bytes_ + the NUL; not zeroed: it is overwritten
};

}  // namespace twinpost
