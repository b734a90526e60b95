#pragma once
// The [timing] table of a machine definition: what the cycle time (analysis/cycle_time.hpp)
// needs of the machine besides its codes. Machine-wide values, overridden per channel by
// [timing.channel.N] (docs/machines.md, "[timing]").
#include <optional>
#include <utility>
#include <vector>

namespace twinpost {

/// The timing figures of one channel, machine-wide values already merged with its override.
struct channel_timing {
  bool given = false;  ///< the machine file has a [timing] table
  /// Rapid rate per axis address, in the axis's unit per minute (mm/min; deg/min for a
  /// rotary axis). X is the slide's own travel (a radius on a diameter-programmed lathe).
  std::vector<std::pair<char, double>> rapid;
  double tool_change = 0;  ///< seconds of a tool call (turret index or tool change)
  double wait = 0;         ///< seconds of a wait code itself, besides the idle at it
  double m_code = 0;       ///< seconds of each other M word (spindle, coolant, ...); 0: none
  /// The rapid rate of axis `address`, or nullopt when the file gives none.
  std::optional<double> rapid_of(char address) const {
    for (const auto& [a, rate] : rapid)
      if (a == address) return rate;
    return std::nullopt;
  }
};

}  // namespace twinpost
