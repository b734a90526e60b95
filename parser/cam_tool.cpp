#include "parser/cam_tool.hpp"
#include "support/ascii.hpp"

namespace twinpost {

namespace {

// Only the mill and drill forms: a turning TLDATA (TURN, GROOVE, THREAD) gives no length.
bool mill_or_drill(const tool_data_event& t) {
  return t.major == "TLDATA" && !t.words.empty() && (t.words.front() == "MILL" || t.words.front() == "DRILL");
}

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

}  // namespace

std::optional<double> tldata_length(const tool_data_event& t) {
  // The numbers keep their order whatever words stand between them (DRILL's module word).
  if (!mill_or_drill(t) || t.values.size() < 3 || !(t.values[2] > 0)) return std::nullopt;
  return t.values[2];
}

std::optional<double> tldata_diameter(const tool_data_event& t) {
  if (!mill_or_drill(t) || t.values.empty() || !(t.values[0] > 0)) return std::nullopt;
  return t.values[0];
}

std::string_view cam_tool_name(const text_event& t) {
  if (t.kind == text_kind::tprint) return trimmed(t.text);
  if (t.kind != text_kind::toolpath) return {};
  // op,TOOL,name: the operation's name may hold anything but a comma.
  std::string_view s = t.text;
  for (std::size_t at = s.find(','); at != std::string_view::npos; at = s.find(',', at + 1)) {
    const std::size_t end = s.find(',', at + 1);
    if (end == std::string_view::npos) return {};
    if (ascii::iequals(trimmed(s.substr(at + 1, end - at - 1)), "TOOL")) {
      const std::size_t next = s.find(',', end + 1);
      return trimmed(
          s.substr(end + 1, next == std::string_view::npos ? std::string_view::npos : next - end - 1));
    }
  }
  return {};
}

}  // namespace twinpost
