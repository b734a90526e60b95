#pragma once
// Writes NC blocks of one channel to a file through a large buffer: sequence numbers,
// comments made safe for the control, block-length limits. One writer per channel.
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "formats/sequence_numbers.hpp"
#include "formats/text_buffer.hpp"
#include "machines/machine.hpp"
#include "support/errors.hpp"

namespace twinpost {

class block_writer {
 public:
  /// What a block_filter does with a block.
  enum class verdict { keep, replace, drop };
  /// Sees each body block before it is written (the machine's script's on_block): keeps it,
  /// replaces it (with `replacement`), or drops it. Blocks it writes itself while it runs go
  /// out as they are.
  class block_filter {
   public:
    virtual ~block_filter() = default;
    virtual verdict filter(std::string_view block, std::string& replacement) = 0;
    /// After filter(): the block as it was written (kept, or the replacement: `replaced`);
    /// not after a drop.
    virtual void block_written(std::string_view block, bool replaced) = 0;
  };

  /// Text around the blocks, as whole lines: `head` is asked for just before the first line
  /// is written (or at close, when there is none), `tail` at close. Empty: nothing. Both
  /// number their blocks from the writer's count (header blocks before the body's, footer
  /// blocks after).
  struct framing {
    std::function<std::string(sequence_numbers&)> head, tail;
    /// The file's name in messages (the program it becomes); empty: the path written.
    std::function<std::string()> name;
  };

  /// Opens `path` for writing; throws config_error when it cannot. `n`: the N word's format.
  block_writer(const std::string& path, const program_format& fmt, framing frame = {},
               const word_format& n = {5, 0});
  ~block_writer();
  block_writer(const block_writer&) = delete;
  block_writer& operator=(const block_writer&) = delete;

  /// Writes one block (words separated by blanks), numbered when the format says so;
  /// `restart`: a restart point (a tool call), numbered also when only those are.
  void block(std::string_view words, bool restart = false);
  /// Starts a block built in place: words appended to the returned buffer (from its current
  /// end, no separator before the first) go straight to the output. end_block() writes it,
  /// drop_block() takes it back. Nothing else may be written in between.
  text_buffer& open_block();
  void end_block();
  void drop_block() { buf_.truncate(open_at_); }
  /// Writes one block past the filter (a block the filter's own script wrote).
  void block_as_is(std::string_view words) {
    const bool was = filtering_;
    filtering_ = true;
    block(words);
    filtering_ = was;
  }
  /// Writes the head now, if it is not written yet (before a filter that must see its blocks
  /// first is called for anything else).
  void begin() {
    if (!started_) start();
  }
  /// Every block of block() and end_block() passes `f` first; nullptr (the default): none.
  void set_filter(block_filter* f) { filter_ = f; }
  /// Whether blocks pass a filter (which may replace them with other words).
  bool has_filter() const { return filter_ != nullptr; }
  /// The program's name in messages (framing::name), or the path written.
  std::string name() const { return frame_.name ? frame_.name() : path_; }
  /// Writes a comment block, made safe: upper case, no parentheses inside, length-limited.
  void comment(std::string_view text);
  /// Writes a line as it is (program frame lines, user INSERT text).
  void raw(std::string_view line);
  /// Flushes and closes; throws config_error on a write error.
  void close();
  long blocks() const { return blocks_; }
  /// Called with every line written between the head and the tail (blocks with their N
  /// number, comments, raw lines), without its line end.
  void set_line_hook(std::function<void(std::string_view)> hook) { hook_ = std::move(hook); }
  /// Another thread that writes the file: the writer hands it each full buffer (and the
  /// last one, the tail's, at close, even when it is empty) instead of writing it, and goes
  /// on in an empty one. The relay writes the pieces to the file in order; it may read them
  /// first (post's self-check on the second core reads the program while it is written).
  class relay {
   public:
    virtual ~relay() = default;
    /// The next piece of the bytes of `f` (`piece.data()[piece.size()]` is a NUL), to be
    /// written to `f` after those passed before it; returns an empty buffer.
    virtual text_buffer pass(text_buffer&& piece, std::FILE* f) = 0;
    /// The errno of a failed write of the pieces passed (0: none so far). `all`: first waits
    /// until every piece passed is written.
    virtual int write_error(bool all) = 0;
  };
  /// Hands the file's bytes to `r` from now on (nullptr: written here, the default).
  void set_relay(std::unique_ptr<relay> r) { relay_ = std::move(r); }
  /// The head written (see framing), "" before the first line.
  const std::string& head_written() const { return head_; }
  /// The bytes of the program written so far, from the first (the head's): those gone to the
  /// file or the relay and those in the buffer. Between blocks it is where the next line
  /// starts: the self-check hands a CL record to the comparison before the block that starts
  /// there (post/concurrent_check; counted from the first byte: attack 66 H1, where records
  /// counted from later were handed 1300 lines early and passed unchecked).
  std::uint64_t bytes_out() const { return out_bytes_ + buf_.size(); }
  /// With a relay: the bytes written so far go to it now, though the buffer is not full.
  void pass_now();

 private:
  void put(std::string_view s);
  /// block() through the filter.
  void filtered(std::string_view words, bool restart);
  void start();
  void flush_if_full();
  /// The buffer to the relay (its NUL after the bytes), and an empty one back.
  void pass_on();
  /// Throws config_error naming the file and the reason (errno of the failed call).
  [[noreturn]] void write_failed(int err) const;
  framing frame_;
  std::string head_;
  bool started_ = false;
  std::size_t open_at_ = 0;
  std::FILE* f_ = nullptr;
  std::string path_;
  const program_format& fmt_;
  text_buffer buf_;
  sequence_numbers seq_;
  long blocks_ = 0;
  std::function<void(std::string_view)> hook_;
  std::unique_ptr<relay> relay_;
  block_filter* filter_ = nullptr;
  bool filtering_ = false;       // inside filter_: the blocks it writes go out as they are
  std::uint64_t out_bytes_ = 0;  // the bytes of the buffers gone out
};

/// `text` as the control accepts it in a comment: upper case, printable ASCII, no comment
/// delimiters, cut to `max` characters (0 = no limit).
std::string safe_comment_text(std::string_view text, const program_format& fmt);

}  // namespace twinpost
