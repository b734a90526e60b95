#include "check/sync_report.hpp"

#include <fmt/format.h>

namespace twinpost {

namespace {

std::string counted(int n, std::string_view one, std::string_view many) {
  return fmt::format("{} {}", n, n == 1 ? one : many);
}

const char* severity_name(severity s) {
  switch (s) {
    case severity::note: return "note";
    case severity::warning: return "warning";
    case severity::error: return "error";
  }
  return "error";
}

/// Length of the valid UTF-8 sequence at `s[i]`, or 0 when the bytes there are not one.
std::size_t utf8_length(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  std::size_t len = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
  if (len == 0 || i + len > s.size()) return 0;
  for (std::size_t k = 1; k < len; ++k)
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
  // Overlong forms, surrogates and values past U+10FFFF are not valid UTF-8 either.
  if (len == 2 && c < 0xC2) return 0;
  if (len == 3 && ((c == 0xE0 && byte(i + 1) < 0xA0) || (c == 0xED && byte(i + 1) >= 0xA0)))
    return 0;
  if (len == 4 && ((c == 0xF0 && byte(i + 1) < 0x90) || c > 0xF4 ||
                   (c == 0xF4 && byte(i + 1) >= 0x90)))
    return 0;
  return len;
}

}  // namespace

std::string json_quote(std::string_view s) {
  std::string out = "\"";
  for (std::size_t i = 0; i < s.size();) {
    const char c = s[i];
    switch (c) {
      case '"': out += "\\\""; ++i; continue;
      case '\\': out += "\\\\"; ++i; continue;
      case '\n': out += "\\n"; ++i; continue;
      case '\r': out += "\\r"; ++i; continue;
      case '\t': out += "\\t"; ++i; continue;
      case '\b': out += "\\b"; ++i; continue;
      case '\f': out += "\\f"; ++i; continue;
      default: break;
    }
    if (static_cast<unsigned char>(c) < 0x20) {
      out += fmt::format("\\u{:04x}", static_cast<unsigned char>(c));
      ++i;
      continue;
    }
    const std::size_t len = utf8_length(s, i);
    if (len == 0) {
      out += "\\ufffd";  // NC files may be Latin-1 or binary; JSON must stay valid
      ++i;
      continue;
    }
    out.append(s, i, len);
    i += len;
  }
  return out + '"';
}

std::string format_sync_summary(const sync_result& r) {
  std::string line = fmt::format("check: {}, {} paired, {}",
                                 counted(static_cast<int>(r.channels.size()), "channel", "channels"),
                                 counted(r.paired, "wait", "waits"),
                                 counted(r.errors, "error", "errors"));
  if (r.warnings > 0) line += ", " + counted(r.warnings, "warning", "warnings");
  return line;
}

std::string format_sync_text(const sync_result& r) {
  std::string out;
  for (const diagnostic& d : r.diagnostics) out += format_diagnostic(d);
  return out + format_sync_summary(r) + '\n';
}

std::string format_sync_json(const sync_result& r) {
  std::string out = fmt::format("{{\n  \"ok\": {},\n  \"channels\": [", r.ok ? "true" : "false");
  for (std::size_t i = 0; i < r.channels.size(); ++i) {
    const channel_sync_summary& c = r.channels[i];
    out += fmt::format("{}\n    {{\"channel\": {}, \"file\": {}, \"waits\": {}, \"paired\": {}}}",
                       i ? "," : "", c.channel, json_quote(c.file), c.waits, c.paired);
  }
  out += fmt::format("{}],\n  \"paired\": {},\n  \"errors\": {},\n  \"warnings\": {},\n"
                     "  \"problems\": [",
                     r.channels.empty() ? "" : "\n  ", r.paired, r.errors, r.warnings);
  for (std::size_t i = 0; i < r.diagnostics.size(); ++i) {
    const diagnostic& d = r.diagnostics[i];
    out += fmt::format("{}\n    {{\"file\": {}, \"line\": {}, \"column\": {}, \"severity\": "
                       "\"{}\", \"message\": {}}}",
                       i ? "," : "", json_quote(d.file), d.line, d.column,
                       severity_name(d.level), json_quote(d.message));
  }
  return out + (r.diagnostics.empty() ? "]\n}\n" : "\n  ]\n}\n");
}

}  // namespace twinpost
