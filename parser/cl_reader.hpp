#pragma once
// The streaming CL reader: bytes in, typed events out, one at a time. Records are parsed as
// they are read; nothing holds the whole file. Problems go to a diagnostic sink as
// `file:line:col` diagnostics and reading goes on.
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "parser/dialect.hpp"
#include "parser/events.hpp"
#include "parser/line_reader.hpp"
#include "support/diagnostics.hpp"

namespace twinpost {

struct cl_reader_options {
  std::string file_name = "<input>";  ///< used in diagnostics
  std::optional<dialect> forced;      ///< --dialect; detected from the file otherwise
  std::size_t chunk_size = 1 << 20;   ///< bytes read at a time (tests and the fuzzer use small ones)
  /// Reading for a post (`post` sets it): warn when the job does not end with FINI or END
  /// (NX END-OF-PATH, Makino's closing PPRINT), since a job cut off at a line end reads as a
  /// sound one otherwise; and a record the post cannot carry out (an unknown major word) is
  /// an error instead of a passthrough event with a warning.
  bool posting = false;
  /// With `posting`: an unknown major word is a warning, not an error (`post --permissive`).
  /// A known word the post refuses (docs/records.md) stays an error.
  bool permissive = false;
  /// Major words (upper case) the machine file turns into blocks ([[events.record]]): read as
  /// passthrough events with `user` set, never as unknown words.
  std::vector<std::string> user_records;
  /// Major words (upper case) the machine's script takes over ([events] script_records), even
  /// ones the post knows: passthrough events with `user` set, in place of the post's own.
  std::vector<std::string> script_records;
  /// The machine's script has on_record: every unknown major word goes to it (a passthrough
  /// event with `user` set), not an error.
  bool unknown_to_script = false;
};

class cl_reader {
 public:
  cl_reader(byte_source& src, cl_reader_options options, diagnostic_sink& sink);
  ~cl_reader();
  cl_reader(const cl_reader&) = delete;
  cl_reader& operator=(const cl_reader&) = delete;

  /// The next event, or nullptr at the end of the input. The event stays valid until the
  /// next call; nothing is copied (the fast way, for posting).
  const event* next();
  /// The next event copied into `out`; false at the end of the input.
  bool next(event& out);
  /// The dialect in use.
  dialect current_dialect() const;
  /// Source line `line` when it belongs to the record read last (the one whose events are
  /// being handled), else empty: later stages give their diagnostics a source line with it.
  std::string_view source_line(int line) const;
  /// How many physical lines the record read last has (those source_line gives).
  std::size_t source_lines() const;
  /// The i-th physical line of the record read last: its number and text.
  std::pair<int, std::string_view> source_line_at(std::size_t i) const;
  /// Logical records read so far.
  std::size_t records() const;
  /// Bytes read so far.
  std::size_t bytes() const;

 private:
  struct impl;
  std::unique_ptr<impl> impl_;
};

}  // namespace twinpost
