#include "parser/dialect.hpp"

namespace twinpost {

namespace {
bool has(std::string_view s, std::string_view what) { return s.find(what) != std::string_view::npos; }
}  // namespace

dialect detect_dialect(std::string_view head) {
  if (has(head, "Pro/CLfile")) return dialect::creo;
  if (has(head, "$$*CATIA0") || has(head, "CATIA APT")) return dialect::catia;
  if (has(head, "APTCL-SPEC,MAKINO")) return dialect::makino;
  if (has(head, "TOOL PATH/")) return dialect::nx;
  if (has(head, "CSI_SET_") || has(head, "UNIT/MM") || has(head, "OPFEATSTART")) return dialect::solidworks;
  return dialect::generic;
}

std::string_view dialect_name(dialect d) {
  for (const auto& [v, n] : dialect_names)
    if (v == d) return n;
  return "generic";
}

std::optional<dialect> dialect_from_name(std::string_view name) {
  for (const auto& [v, n] : dialect_names)
    if (n == name) return v;
  return std::nullopt;
}

bool circle_is_ccw(dialect d) { return d != dialect::nx && d != dialect::makino; }

}  // namespace twinpost
