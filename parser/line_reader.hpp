#pragma once
// Streams CL text as logical records: physical lines are read in large chunks, `$`
// continuations are joined (on `$$->` lines too), trailing `$$` comments are cut off, and
// every offset in a logical record can be mapped back to its physical line and column.
// Memory stays bounded by the longest logical record, never by the file.
#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>
#include <utility>
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

/// Why a logical record cannot be read as it stands; the reader reports it and drops it.
enum class record_problem : unsigned char {
  none,
  too_long,  ///< longer than max_record_bytes: only its start is kept, for the message
  dangling,  ///< ends in a continuation `$` at the end of the input: the job is cut off
};

/// The longest logical record (a physical line, or lines joined by `$`), in bytes. Real CL
/// records are a few hundred bytes; anything longer is not CL, and reading it whole would
/// let one line without a newline take all memory.
inline constexpr std::size_t max_record_bytes = 64 * 1024;

/// A logical record: the data text of one or more physical lines.
struct logical_record {
  std::string_view text;  ///< valid until the next call of line_reader::next
  int line = 0;           ///< first physical line (1-based)
  record_problem problem = record_problem::none;
  int problem_line = 0;             ///< the physical line the problem is at
  int problem_column = 0;           ///< and its column (1-based)
  std::string_view problem_source;  ///< that physical line (its start, when too long)
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
  /// The column of `offset` in its physical line (locate's, without the search when the
  /// record is one line, as nearly all are).
  int column_of(std::size_t offset) const {
    if (segments_.size() == 1) return static_cast<int>(offset) + 1;
    return locate(offset).column;
  }
  /// Physical line `line` when it belongs to the current logical record, else empty.
  std::string_view physical_line(int line) const {
    for (const segment& s : segments_)
      if (s.line == line) return s.physical;
    return {};
  }
  /// The physical lines of the current logical record (physical_line gives each by number).
  std::size_t physical_lines() const { return segments_.size(); }
  /// The i-th of them: its number and text.
  std::pair<int, std::string_view> physical_line_at(std::size_t i) const {
    return {segments_[i].line, segments_[i].physical};
  }
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
  /// Drops the rest of an over-long physical line, up to and including its newline.
  void skip_rest_of_line();

  byte_source& src_;
  std::vector<char> buf_;
  std::size_t begin_ = 0, end_ = 0;
  bool eof_ = false;
  int line_no_ = 0;
  std::size_t consumed_ = 0;
  std::string joined_;    // logical text of a continued record
  std::string physical_;  // owned copies of a continued record's lines, one after another
  std::vector<std::pair<std::size_t, std::size_t>> spans_;  // where each line is in physical_
  std::vector<segment> segments_;
  bool overlong_ = false;      // the physical line just read was cut at max_record_bytes
  std::string overlong_head_;  // its first bytes, kept for the diagnostic
};

}  // namespace twinpost
