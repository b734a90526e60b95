#pragma once
// Test support for kinematics/: one machine file with a channel for each kind of chain, read
// by the machine loader (so the chains the tests use are the ones a machine file gives).
#include <string>

#include "kinematics/chain.hpp"
#include "machines/machine.hpp"
#include "machines/machine_loader.hpp"

namespace twinpost::test {

/// Eight channels, each with X and Z, and one [[kinematics]] each:
/// 1 head/head: B head about Y carrying an A head about X, both through a pivot 300 mm above
///   the gauge point (400 mm to the tip of a 100 mm tool), A and B within ±20°;
/// 2 table/table: an A trunnion about X (axis 80 mm under the work zero, -120..30) carrying a
///   continuous C table about Z whose centre is at x 12.5, y -7;
/// 3 head/table (an Integrex-like upper head): B head about Y, pivot 250 mm above and 5 mm
///   beside the gauge point, -30..210, and a C spindle about Z with rollover "shortest";
/// 4 head/head bridge mill: a continuous C head about Z carrying a B head about Y (-110..110);
/// 5 head/head nutating: a continuous C head about Z carrying a continuous B head about the
///   45° axis (0, -1, 1);
/// 6 one rotary: an A table about X (continuous, axis 50 mm under the work zero);
/// 7 one rotary: a C table about Z, the tool along it (mill/turn C axis);
/// 8 head/table with a horizontal spindle: the tool along +X, a B head about Y (pivot 200 mm
///   behind the gauge point, -90..90) over a continuous C table about Z centred at (3, 4).
inline const std::string kinematics_machine = R"([machine]
name = "kin"
[waits]
first = 100
last = 103
partners = "path_numbers"
[[channel]]
number = 1
axis = [{address = "X"}, {address = "Z"}]
[[channel]]
number = 2
axis = [{address = "X"}, {address = "Z"}]
[[channel]]
number = 3
axis = [{address = "X"}, {address = "Z"}]
[[channel]]
number = 4
axis = [{address = "X"}, {address = "Z"}]
[[channel]]
number = 5
axis = [{address = "X"}, {address = "Z"}]
[[channel]]
number = 6
axis = [{address = "X"}, {address = "Z"}]
[[channel]]
number = 7
axis = [{address = "X"}, {address = "Z"}]
[[channel]]
number = 8
axis = [{address = "X"}, {address = "Z"}]

[[kinematics]]
channel = 1
[[kinematics.rotary]]
address = "B"
kind = "head"
direction = [0, 1, 0]
point = [0, 0, 300]
min = -20
max = 20
[[kinematics.rotary]]
address = "A"
kind = "head"
direction = [1, 0, 0]
point = [0, 0, 300]
min = -20
max = 20

[[kinematics]]
channel = 2
[[kinematics.rotary]]
address = "A"
kind = "table"
direction = [1, 0, 0]
point = [0, 0, -80]
min = -120
max = 30
[[kinematics.rotary]]
address = "C"
kind = "table"
direction = [0, 0, 1]
point = [12.5, -7, 0]
continuous = true

[[kinematics]]
channel = 3
[[kinematics.rotary]]
address = "B"
kind = "head"
direction = [0, 1, 0]
point = [5, 0, 250]
min = -30
max = 210
[[kinematics.rotary]]
address = "C"
kind = "table"
direction = [0, 0, 1]
continuous = true
rollover = "shortest"

[[kinematics]]
channel = 4
[[kinematics.rotary]]
address = "C"
kind = "head"
direction = [0, 0, 1]
point = [0, 0, 350]
continuous = true
[[kinematics.rotary]]
address = "B"
kind = "head"
direction = [0, 1, 0]
point = [0, 0, 350]
min = -110
max = 110

[[kinematics]]
channel = 5
[[kinematics.rotary]]
address = "C"
kind = "head"
direction = [0, 0, 1]
point = [0, 0, 200]
continuous = true
[[kinematics.rotary]]
address = "B"
kind = "head"
direction = [0, -1, 1]
point = [0, 0, 200]
continuous = true

[[kinematics]]
channel = 6
[[kinematics.rotary]]
address = "A"
kind = "table"
direction = [1, 0, 0]
point = [0, 0, -50]
continuous = true

[[kinematics]]
channel = 7
[[kinematics.rotary]]
address = "C"
kind = "table"
direction = [0, 0, 1]
continuous = true

[[kinematics]]
channel = 8
tool_direction = [1, 0, 0]
[[kinematics.rotary]]
address = "B"
kind = "head"
direction = [0, 1, 0]
point = [200, 0, 0]
min = -90
max = 90
[[kinematics.rotary]]
address = "C"
kind = "table"
direction = [0, 0, 1]
point = [3, 4, 0]
continuous = true
)";

/// The chain of channel `n` (1..8) of kinematics_machine.
inline const kinematic_chain& test_chain(int n) {
  static const machine m = parse_machine(kinematics_machine, "kin.toml");
  return m.kinematics.at(n - 1);
}

}  // namespace twinpost::test
