#pragma once
// The words of a CYCLE record as the cycle writers read them (channel_cycles, channel_thread).
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

}  // namespace twinpost
