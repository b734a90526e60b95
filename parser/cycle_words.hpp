#pragma once
// The words of a CYCLE record as the cycle writers read them (machining/channel_cycles,
// channel_thread) and the comparison with the CL reads them (analysis/cl_compare).
#include <optional>
#include <string_view>

#include "parser/events.hpp"

namespace twinpost {

/// The value of cycle word `name` (FEDTO, DEPTH, LEAD ...), if the record gives it.
inline std::optional<double> cycle_param(const cycle_event& c, std::string_view name) {
  for (const auto& [k, v] : c.params)
    if (k == name) return v;
  return std::nullopt;
}

/// The bottom of a hole whose top (the GOTO point) is at `top` along the drill, in CL units,
/// from the record's FEDTO read as its dialect reads it (a depth, a distance along the tool
/// axis, or a Z), else its DEPTH; `into` is the sign of the drilling direction along that
/// axis (-1: the tool looks down -Z and drills towards -Z). None without either word.
inline std::optional<double> cycle_bottom(const cycle_event& c, double top, double into) {
  if (const std::optional<double> fedto = cycle_param(c, "FEDTO"))
    return c.meaning.fedto_is_depth     ? top + into * *fedto
           : c.meaning.fedto_along_axis ? top - into * *fedto
                                        : *fedto;
  if (const std::optional<double> depth = cycle_param(c, "DEPTH")) return top + into * *depth;
  return std::nullopt;
}

}  // namespace twinpost
