#include "support/diagnostics.hpp"

#include <algorithm>
#include <fmt/format.h>

namespace twinpost {

namespace {
constexpr std::size_t source_window = 200;   // columns of a source line shown at most
constexpr std::size_t message_bytes = 4096;  // of a message shown at most

// The length of the UTF-8 character at text[i] (a byte >= 0x80), or 0 when the bytes there are
// no valid UTF-8 or are a C1 control (U+0080..U+009F: CSI, OSC, ST to a terminal).
std::size_t utf8_printable(std::string_view text, std::size_t i) {
  const auto b = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = b(i);
  const std::size_t len = lead >= 0xC2 && lead <= 0xDF   ? 2
                          : lead >= 0xE0 && lead <= 0xEF ? 3
                          : lead >= 0xF0 && lead <= 0xF4 ? 4
                                                         : 0;
  if (len == 0 || i + len > text.size()) return 0;
  for (std::size_t k = 1; k < len; ++k)
    if ((b(i + k) & 0xC0) != 0x80) return 0;
  if (lead == 0xC2 && b(i + 1) < 0xA0) return 0;  // C1
  return len;
}

// `text` onto `out` with its control bytes but tab as \xHH: a file name or a message that
// carries text from a user's file (a script's error, a name) sends no escape sequence to the
// terminal. A valid UTF-8 character stays (a UTF-8 file name shows as itself, and the §
// of a message); a C1 control in UTF-8 and any byte of no valid UTF-8 (a bare 0x9B, CSI to an
// 8-bit terminal) are written as \xHH.
void append_safe(std::string& out, std::string_view text, std::size_t most) {
  const std::size_t n = std::min(text.size(), most);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x80) {
      if (const std::size_t len = utf8_printable(text.substr(0, n), i); len > 0) {
        out.append(text.substr(i, len));
        i += len - 1;
      } else {
        out += fmt::format("\\x{:02x}", c);
      }
    } else if ((c < 0x20 && c != '\t') || c == 0x7f) {
      out += fmt::format("\\x{:02x}", c);
    } else {
      out += static_cast<char>(c);
    }
  }
  if (n < text.size()) out += fmt::format("... ({} bytes in all)", text.size());
}
}  // namespace

const char* severity_name(severity s) {
  switch (s) {
    case severity::note: return "note";
    case severity::warning: return "warning";
    case severity::error: return "error";
  }
  return "error";
}

std::string format_diagnostic(const diagnostic& d) {
  std::string out;
  append_safe(out, d.file, message_bytes);
  if (d.line > 0) out += fmt::format(":{}", d.line);
  if (d.line > 0 && d.column > 0) out += fmt::format(":{}", d.column);
  if (!out.empty()) out += ": ";  // a diagnostic about the run as a whole has no place
  out += severity_name(d.level);
  out += ": ";
  append_safe(out, d.message, message_bytes);
  out += '\n';
  if (!d.source_line.empty()) {
    // The line as a terminal shows it safely: control and non-ASCII bytes as \xHH, and at
    // most source_window columns around the caret (a 16 MB line echoes 200 columns).
    const std::string_view src = d.source_line;
    const int column = d.column > 0 ? d.column : d.caret;
    const std::size_t caret = column > 0 ? std::min(static_cast<std::size_t>(column - 1), src.size()) : 0;
    std::size_t from = 0, to = src.size();
    if (src.size() > source_window) {
      from = caret > source_window / 2 ? caret - source_window / 2 : 0;
      to = std::min(src.size(), from + source_window);
      from = to - source_window;
    }
    std::string shown, pad;
    if (from > 0) shown += "...", pad += "   ";
    for (std::size_t i = from; i < to; ++i) {
      const auto c = static_cast<unsigned char>(src[i]);
      const std::size_t at = shown.size();
      if (c == '\t' || (c >= 0x20 && c < 0x7f))
        shown += static_cast<char>(c);
      else
        shown += fmt::format("\\x{:02X}", c);
      if (i < caret) pad += c == '\t' ? std::string("\t") : std::string(shown.size() - at, ' ');
    }
    if (to < src.size()) shown += "...";
    out += shown;
    out += '\n';
    // Tabs are kept in the caret line so the caret lines up under the source column.
    if (column > 0) out += pad + "^\n";
  }
  return out;
}

void diagnostic_list::report(diagnostic d) {
  counts_.add(d);
  items_.push_back(std::move(d));
}

}  // namespace twinpost
