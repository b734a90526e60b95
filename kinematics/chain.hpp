#pragma once
// The geometry of a kinematic chain (machines/kinematic_chain.hpp): joint values, tool poses,
// which kind of chain it is, and the one product of rotations that gives its tool axis in the
// part frame (docs/kinematics.md, "Frames").
#include <array>
#include <string>
#include <string_view>

#include "machines/kinematic_chain.hpp"

namespace twinpost::kin {

/// The machine's joint values: the linear axes (mm) and the rotary axes (degrees), the rotary
/// ones in the chain's order (kinematic_chain::rotaries).
struct joint_values {
  vec3 linear;
  std::array<double, 2> rotary{};
};

/// A CL point: the tool tip and the unit tool axis (tip towards spindle), in the part frame.
struct tool_pose {
  vec3 tip;
  vec3 axis{0, 0, 1};
};

enum class chain_kind { three_axis, one_rotary, head_head, table_table, head_table };
chain_kind kind_of(const kinematic_chain& c);
std::string_view name_of(chain_kind k);  ///< "head/head", "table/table", ...

/// The tool axis in the part frame is K = R(outer, φo)·R(inner, φi)·t0, rotations about the
/// axes' home directions. For heads φ is the joint value; a table turns the part, so the tool
/// turns the other way against it: φ = -value. Outer: the first head of a head/head chain, the
/// table that carries the part on a table/table one, the table of a mixed one. Its angle is
/// free when K lies along it (the pole).
struct orientation_form {
  int outer = -1;  ///< index in rotaries, or -1 (no rotary axis)
  int inner = -1;  ///< index in rotaries, or -1 (fewer than two)
  double outer_sign = 1, inner_sign = 1;
};
orientation_form orientation_of(const kinematic_chain& c);

/// A number as twinpost writes it in messages: at most 4 decimals, no trailing zeros ("30",
/// "-0.5", "0.866").
std::string number_text(double v);

}  // namespace twinpost::kin
