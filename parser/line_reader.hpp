#pragma once
// Streams CL text as logical records: physical lines are read in large chunks, `$`
// continuations are joined (on `$$->` lines too), trailing `$$` comments are cut off, and
// every offset in a logical record can be mapped back to its physical line and column.
// Memory stays bounded by the longest logical record, never by the file.
#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

namespace twinpost {

/// Where the bytes come from.
class byte_source {
 public:
  virtual ~byte_source() = default;
  /// Reads up to `n` bytes into `dst`; returns 0 at the end.
  virtual std::size_t read(char* dst, std::size_t n) = 0;
};

/// Reads an open stdio file (not owned).
class file_source : public byte_source {
 public:
  explicit file_source(std::FILE* f) : file_(f) {}
  std::size_t read(char* dst, std::size_t n) override;

 private:
  std::FILE* file_;
};

/// Reads from memory (tests, the fuzzer). The text must outlive the source.
class string_source : public byte_source {
 public:
  explicit string_source(std::string_view text) : text_(text) {}
  std::size_t read(char* dst, std::size_t n) override;

 private:
  std::string_view text_;
};

/// A logical record: the data text of one or more physical lines.
struct logical_record {
  std::string_view text;  ///< valid until the next call of line_reader::next
  int line = 0;           ///< first physical line (1-based)
};

/// A physical position of an offset in the current logical record.
struct source_position {
  int line = 0;
  int column = 0;                ///< 1-based, in bytes
  std::string_view source_line;  ///< that physical line, without its line ending
};

class line_reader {
 public:
  explicit line_reader(byte_source& src, std::size_t chunk = 1 << 20);
  line_reader(const line_reader&) = delete;
  line_reader& operator=(const line_reader&) = delete;

  /// The next logical record; false at the end of the input. Blank lines are skipped.
  bool next(logical_record& out);
  /// Up to `n` bytes from the start of the input, for dialect detection (call before next).
  std::string_view peek(std::size_t n);
  /// Maps an offset of the current logical record to its physical line and column.
  source_position locate(std::size_t offset) const;
  /// Bytes consumed so far.
  std::size_t bytes_read() const { return consumed_; }

 private:
  struct segment {
    std::size_t offset;  // where this physical line's text starts in the logical text
    int line;
    std::size_t column0;  // 0-based column of that text in the physical line
    std::string_view physical;
  };
  bool fill();
  bool next_physical(std::string_view& line);

  byte_source& src_;
  std::vector<char> buf_;
  std::size_t begin_ = 0, end_ = 0;
  bool eof_ = false;
  int line_no_ = 0;
  std::size_t consumed_ = 0;
  std::string joined_;                 // logical text of a continued record
  std::vector<std::string> physical_;  // owned copies of a continued record's lines
  std::vector<segment> segments_;
};

}  // namespace twinpost
