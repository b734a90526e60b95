#pragma once
// Test support for the parser tests: read CL text from memory through the real streaming
// reader and keep what came out as text, so tests compare whole lines, never fragments.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <catch2/catch.hpp>

#include "parser/cl_reader.hpp"
#include "parser/event_text.hpp"

namespace twinpost::test {

/// Everything a reader produced for one input.
struct read_result {
  std::vector<std::string> events;  ///< event_to_text of each event, in order
  std::vector<std::string> json;    ///< event_to_json of each event, in order
  std::string diagnostics;          ///< format_diagnostic of each diagnostic, concatenated
  int errors = 0;
  int warnings = 0;
  dialect used = dialect::generic;
};

/// Everything a reader with `options` makes of `src`, read to its end; the JSON form too
/// unless `with_json` is false (long real files).
inline read_result read_source(byte_source& src, const cl_reader_options& options, bool with_json = true) {
  diagnostic_list sink;
  cl_reader reader(src, options, sink);
  read_result r;
  r.used = reader.current_dialect();
  event e;
  while (reader.next(e)) {
    r.events.push_back(event_to_text(e));
    if (with_json) r.json.push_back(event_to_json(e));
  }
  for (const diagnostic& d : sink.all()) r.diagnostics += format_diagnostic(d);
  r.errors = sink.errors();
  r.warnings = sink.warnings();
  return r;
}

/// Reads `text` (named "t.cl" in diagnostics) with an optional forced dialect and chunk size.
inline read_result read_cl(std::string_view text, std::optional<dialect> forced = std::nullopt,
                           std::size_t chunk_size = 1 << 20) {
  string_source src(text);
  cl_reader_options options;
  options.file_name = "t.cl";
  options.forced = forced;
  options.chunk_size = chunk_size;
  return read_source(src, options);
}

using lines = std::vector<std::string>;

/// The event lines of `text` read in `d` (generic APT unless said otherwise); checks on the
/// way that the text gave no diagnostic at all.
inline lines events_of(std::string_view text, dialect d = dialect::generic) {
  read_result r = read_cl(text, d);
  CHECK(r.diagnostics == "");
  return r.events;
}

}  // namespace twinpost::test
