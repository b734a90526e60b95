#pragma once
// The CL reader on a thread of its own, a few batches of events ahead of the post.
//
// With two cores, reading and parsing the CL (about a quarter of a lathe post) runs beside
// routing and writing. What comes out is what the reader on the post's own thread gives, in
// the same order: each event, each of the reader's diagnostics just before the event it came
// before (and the last ones at the end), and, for the messages of the later stages, the
// source lines of the record each event comes from (source_line, as cl_reader's).
//
// Memory: a few batches of events and the text of their records (with a look-ahead, twice as
// many: those read and those looked at).
#include <memory>
#include <string_view>

#include "machining/kin_lookahead.hpp"
#include "parser/cl_reader.hpp"
#include "support/diagnostics.hpp"

namespace twinpost {

class reader_thread {
 public:
  /// Reads `src` with a cl_reader of `options` on a new thread. The reader's diagnostics go
  /// to `sink` on the caller's thread, from next(), with their source line already given
  /// (as the reader's record was when it reported them).
  /// `ahead`, when given: a third thread works out each batch's moves with it before the post
  /// takes the batch, and ahead->at() tells it which event the post has (machining/kin_lookahead.hpp).
  reader_thread(byte_source& src, cl_reader_options options, diagnostic_sink& sink,
                kin_lookahead* ahead = nullptr);
  /// Stops the thread (it may be ahead, or waiting for room).
  ~reader_thread();
  reader_thread(const reader_thread&) = delete;
  reader_thread& operator=(const reader_thread&) = delete;

  /// The next event, or nullptr at the end; valid until the next call.
  const event* next();
  /// As cl_reader::source_line for the event returned last (after the end: for the last
  /// record read).
  std::string_view source_line(int line) const;
  /// Bytes read, as far as the events returned so far (by batch).
  std::size_t bytes() const;
  /// Logical records read; complete once next() has returned nullptr.
  std::size_t records() const;

 private:
  struct impl;
  std::unique_ptr<impl> p_;
};

}  // namespace twinpost
