// channel_writer: drilling cycles along Z, expanded to moves.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "formats/channel_writer.hpp"

namespace twinpost {

bool channel_writer::cycle_supported(const cycle_event& c, int line) {
  // Drilling is written as plain moves (below): a tap, a bore, a ream or a thread cycle
  // written that way would break the tool or mark the bore, so only what the moves really
  // do is taken, and anything else stops the post at the CYCLE record.
  if (c.type != "DRILL" && c.type != "DEEP") {
    error(line,
          fmt::format("CYCLE/{} is not supported by the post: only DRILL and DEEP are written (as plain "
                      "G0/G1 moves); a tapping, boring or threading cycle cannot be",
                      c.type));
    return false;
  }
  static constexpr std::string_view known[] = {"FEDTO", "DEPTH", "RAPTO", "CLEAR", "STEP",
                                               "MMPR",  "IPR",   "MMPM",  "IPM"};
  for (const auto& [name, value] : c.params) {
    const bool pecks_ignored = name == "STEP" && c.type != "DEEP";  // only DEEP is written in pecks
    if (!pecks_ignored && std::find(std::begin(known), std::end(known), name) != std::end(known)) continue;
    error(line,
          fmt::format("CYCLE/{}: {} is not carried out by the post (it knows FEDTO, DEPTH, RAPTO, CLEAR, "
                      "STEP and the feed)",
                      c.type, name));
    return false;
  }
  if (!c.words.empty() || !c.positional.empty()) {
    error(line,
          fmt::format("CYCLE/{}: {} is not carried out by the post (it knows FEDTO, DEPTH, RAPTO, CLEAR, "
                      "STEP and the feed, each with its value)",
                      c.type,
                      c.words.empty() ? fmt::format("the value {}", c.positional.front()) : c.words.front()));
    return false;
  }
  return true;
}

void channel_writer::cycle_point(const vec3& p, int line) {
  // Drilling along the spindle axis, written as plain moves every control reads: rapid to
  // the clearance plane, feed to depth (in pecks with STEP), rapid back out. The tool axis
  // says which way is into the part: -Z for a tool looking down +Z, +Z for one facing back.
  const cycle_event& c = *cycle_;
  auto param = [&](std::string_view name) -> std::optional<double> {
    for (const auto& [k, v] : c.params)
      if (k == name) return v;
    return std::nullopt;
  };
  // Only along the spindle axis: a radial or tilted tool (cross drilling with a live tool)
  // would be fed along Z, through the side of the part.
  if (std::abs(axis_.z) < 0.9999)
    return error(line,
                 fmt::format("CYCLE/{} with the tool axis ({}, {}, {}): only drilling along Z is written; "
                             "cross and tilted drilling is not supported yet",
                             c.type, axis_.x, axis_.y, axis_.z));
  double into = axis_.z < 0 ? 1.0 : -1.0;  // the direction of drilling along Z
  double clear = p.z - into * param("RAPTO").value_or(param("CLEAR").value_or(0));
  std::optional<double> bottom = param("FEDTO");
  if (!bottom && param("DEPTH")) bottom = p.z + into * *param("DEPTH");
  if (!bottom) return error(line, fmt::format("CYCLE/{} needs FEDTO or DEPTH", c.type));
  // FEDTO is a Z here; a dialect that writes it as a depth below the hole (SolidWorks CAM)
  // puts it behind the clearance plane, and the drill would feed away from the part.
  if ((*bottom - clear) * into <= 0)
    return error(line,
                 fmt::format("CYCLE/{}: the bottom Z {} is not beyond the clearance plane Z {} in the "
                             "drilling direction: the tool would feed away from the part (is FEDTO a depth "
                             "in this CL?)",
                             c.type, *bottom, clear));
  for (const char* unit : {"MMPR", "IPR", "MMPM", "IPM"}) {
    if (auto f = param(unit)) {
      const bool per_rev = std::string_view(unit).back() == 'R';
      const double value = *f * ((unit[0] == 'I') ? 25.4 : 1.0);
      if (!fits('F', value, per_rev ? 4 : 1)) return;
      feed_value_ = value;
      feed_mode(per_rev);
    }
  }
  double step = param("STEP").value_or(0);
  // A peck count past any real hole (a depth of 1e300 or a STEP of 1e-9) would write moves
  // without end: refuse it before the first move.
  constexpr double max_pecks = 10000;
  if (step > 0 && c.type == "DEEP" && !(std::abs(*bottom - clear) / step <= max_pecks))
    return error(line, fmt::format("CYCLE/DEEP: a depth of {} in pecks of STEP {} makes more than {} pecks",
                                   std::abs(*bottom - clear), step, max_pecks));
  linear(true, p.x, p.y, clear, line);
  double z = clear;
  if (step > 0 && c.type == "DEEP") {
    while ((*bottom - (z + into * step)) * into > 0) {
      z += into * step;
      linear(false, p.x, p.y, z, line);
      linear(true, p.x, p.y, clear, line);
      linear(true, p.x, p.y, z - into * 0.5 / scale_, line);  // back down near the last depth
    }
  }
  linear(false, p.x, p.y, *bottom, line);
  linear(true, p.x, p.y, clear, line);
}

}  // namespace twinpost
