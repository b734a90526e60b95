// libFuzzer target: arbitrary bytes through the whole CL reader (line reader, grammar,
// event builder) and both event renderings, and every line through the fast path for
// numeric statements and the grammar, which must agree. Build and run: fuzz/build.sh (docs/fuzzing.md).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include <cstdlib>

#include "fuzz/fast_path_check.hpp"
#include "fuzz/fuzz_support.hpp"
#include "parser/cl_reader.hpp"
#include "parser/event_text.hpp"

namespace {

// Formats every diagnostic (source line and caret included) and drops it.
class formatting_sink : public twinpost::diagnostic_sink {
 public:
  void report(twinpost::diagnostic d) override { bytes_ += twinpost::format_diagnostic(d).size(); }

 private:
  std::size_t bytes_ = 0;
};

// The fast path for numeric statements must read every record it accepts exactly as the
// X3 grammar does: each line of the input is tried as a record, and a difference aborts.
void check_fast_path(std::string_view text) {
  while (!text.empty()) {
    std::size_t nl = text.find('\n');
    std::string_view line = text.substr(0, nl);
    text = nl == std::string_view::npos ? std::string_view() : text.substr(nl + 1);
    if (!twinpost::fuzz::fast_path_difference(line).empty()) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  check_fast_path(text);
  twinpost::string_source src(text);
  formatting_sink sink;
  twinpost::cl_reader_options options;
  options.file_name = "fuzz.cl";
  options.chunk_size = 64;  // small chunks: lines cross refills and the buffer has to grow
  // An odd first byte forces a dialect: no 64 KiB detection peek, so the small chunks are
  // really refilled. An even one lets the reader detect the dialect as usual.
  if (size > 0 && (data[0] & 1) != 0) {
    static constexpr twinpost::dialect dialects[] = {
        twinpost::dialect::generic, twinpost::dialect::creo,       twinpost::dialect::nx,
        twinpost::dialect::catia,   twinpost::dialect::solidworks, twinpost::dialect::makino};
    options.forced = dialects[(data[0] >> 1) % 6];
  }
  twinpost::cl_reader reader(src, options, sink);
  twinpost::event e;
  std::size_t out = 0;
  while (reader.next(e)) {
    out += twinpost::event_to_text(e).size();
    out += twinpost::event_to_json(e).size();
  }
  return out == static_cast<std::size_t>(-1) ? 1 : 0;  // keep `out` alive
}
