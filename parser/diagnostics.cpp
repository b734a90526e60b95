#include "parser/diagnostics.hpp"

#include <fmt/format.h>

namespace twinpost {

namespace {
const char* severity_word(severity s) {
  switch (s) {
    case severity::note: return "note";
    case severity::warning: return "warning";
    case severity::error: return "error";
  }
  return "error";
}
}  // namespace

std::string format_diagnostic(const diagnostic& d) {
  std::string out = d.file;
  if (d.line > 0) out += fmt::format(":{}", d.line);
  if (d.line > 0 && d.column > 0) out += fmt::format(":{}", d.column);
  out += fmt::format(": {}: {}\n", severity_word(d.level), d.message);
  if (!d.source_line.empty()) {
    out += d.source_line;
    out += '\n';
    if (d.column > 0) {
      // Keep tabs in the caret line so the caret lines up under the source column.
      std::string pad;
      for (int i = 0; i + 1 < d.column && i < static_cast<int>(d.source_line.size()); ++i)
        pad += d.source_line[static_cast<std::size_t>(i)] == '\t' ? '\t' : ' ';
      out += pad + "^\n";
    }
  }
  return out;
}

void diagnostic_list::report(diagnostic d) {
  if (d.level == severity::error) ++errors_;
  if (d.level == severity::warning) ++warnings_;
  items_.push_back(std::move(d));
}

}  // namespace twinpost
