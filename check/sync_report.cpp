#include "check/sync_report.hpp"

#include <fmt/format.h>

#include "support/json.hpp"

namespace twinpost {

namespace {

std::string counted(int n, std::string_view one, std::string_view many) {
  return fmt::format("{} {}", n, n == 1 ? one : many);
}

}  // namespace

std::string format_sync_summary(const sync_result& r) {
  std::string line = fmt::format("check: {}, {} paired, {}",
                                 counted(static_cast<int>(r.channels.size()), "channel", "channels"),
                                 counted(r.paired, "wait", "waits"), counted(r.errors, "error", "errors"));
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
  out += fmt::format(
      "{}],\n  \"paired\": {},\n  \"errors\": {},\n  \"warnings\": {},\n"
      "  \"problems\": [",
      r.channels.empty() ? "" : "\n  ", r.paired, r.errors, r.warnings);
  for (std::size_t i = 0; i < r.diagnostics.size(); ++i) {
    const diagnostic& d = r.diagnostics[i];
    out += fmt::format(
        "{}\n    {{\"file\": {}, \"line\": {}, \"column\": {}, \"severity\": "
        "\"{}\", \"message\": {}}}",
        i ? "," : "", json_quote(d.file), d.line, d.column, severity_name(d.level), json_quote(d.message));
  }
  return out + (r.diagnostics.empty() ? "]\n}\n" : "\n  ]\n}\n");
}

}  // namespace twinpost
