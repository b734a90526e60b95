#include "parser/dialect.hpp"

namespace twinpost {

namespace {
bool has(std::string_view s, std::string_view what) { return s.find(what) != std::string_view::npos; }
}  // namespace

dialect detect_dialect(std::string_view head) {
  if (has(head, "Pro/CLfile")) return dialect::creo;
  if (has(head, "$$*CATIA0") || has(head, "CATIA APT")) return dialect::catia;
  if (has(head, "APTCL-SPEC,MAKINO")) return dialect::makino;
  // NX's record, at the start of a line: the words in a comment or a PPRINT ("$$ ops exported
  // per TOOL PATH/ ...") must not make a generic file NX, whose FEDTO is read another way.
  if (head.starts_with("TOOL PATH/") || has(head, "\nTOOL PATH/")) return dialect::nx;
  // UNIT/ (not UNITS/) is SolidWorks CAM's own spelling, in mm and in inch: an inch job with
  // no CSI_SET_ in its head would otherwise read FEDTO as a Z (a depth of .5 below a top at
  // Z2 drilled to Z.5).
  if (has(head, "CSI_SET_") || has(head, "UNIT/MM") || has(head, "UNIT/IN") || has(head, "OPFEATSTART"))
    return dialect::solidworks;
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

cycle_word_meaning cycle_meaning(dialect d) {
  // SolidWorks CAM: holes at z = 0 drilled with `CYCLE/DRILL,FEDTO,7.85788,...,RAPTO,3.,
  // RTRCTO,25.,DWELL,0` after a rapid to z = 25 (the shared SolidWorks CL files): FEDTO is a
  // depth, RAPTO and RTRCTO heights above the hole's top.
  if (d == dialect::solidworks) return {true, true, true, true};
  // NX: its posts place the cycle's planes from the hole's point along the tool axis,
  // feed_to_pos = pos + mom_cycle_feed_to × axis and the same for rapid_to and retract_to
  // (Siemens' Post Builder posts, Unigraphics/PostBuilder on GitHub: `mom_cycle_feed_to_pos`);
  // NX's CLSF writes those values as FEDTO, RAPTO and RTRCTO (HumMan/CLSFProcessor's samples:
  // `FEDTO,-72`; `RAPTO,3.0000,FEDTO,0.0000` over holes at Z240).
  if (d == dialect::nx) return {.rtrcto_above_top = true, .fedto_along_axis = true};
  // The other dialects keep FEDTO as a Z, and their RTRCTO, DWELL and pecks stay errors until
  // a source says what they mean.
  return {};
}

}  // namespace twinpost
