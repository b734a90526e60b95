#pragma once
// The forward transform: joint values -> tool tip and tool axis in the part frame, one product
// of rotations and translations for every chain kind (docs/kinematics.md, "Frames").
#include <array>

#include "kinematics/chain.hpp"
#include "kinematics/vec3_ops.hpp"

namespace twinpost::kin {

/// The rotation of each rotary axis at `j`, its sine and cosine computed once for every
/// transform below that turns by the same values.
struct joint_turns {
  std::array<turn, 2> t{};
  joint_turns(const kinematic_chain& c, const joint_values& j) {
    for (std::size_t i = 0; i < c.rotaries.size() && i < t.size(); ++i) t[i] = turn_of(j.rotary[i]);
  }
  joint_turns(const chain_plan& p, const joint_values& j) {
    for (int i = 0; i < p.rotary_count; ++i) t[i] = turn_of(j.rotary[i]);
  }
  explicit joint_turns(const std::array<turn, 2>& known) : t(known) {}
};

/// Where the tool of length `tool_length` (gauge point to tip, mm) is, and which way it
/// points, in the part frame, with the machine at `j`.
tool_pose forward(const kinematic_chain& c, const joint_values& j, double tool_length);
tool_pose forward(const kinematic_chain& c, const joint_values& j, double tool_length, const joint_turns& r);
tool_pose forward(const chain_plan& p, const joint_values& j, double tool_length);
tool_pose forward(const chain_plan& p, const joint_values& j, double tool_length, const joint_turns& r);
/// The tool tip alone of forward().
vec3 forward_tip(const kinematic_chain& c, const joint_values& j, double tool_length);
vec3 forward_tip(const kinematic_chain& c, const joint_values& j, double tool_length, const joint_turns& r);
/// The same from the linear values alone: the rotations are `r`'s.
vec3 forward_tip(const chain_plan& p, const vec3& linear, double tool_length, const joint_turns& r);

/// forward()'s pose from the heads' part already known (`offset`, head_offset()'s value for
/// these turns and length): the same bits, one turn of the tip by the heads less.
tool_pose forward_from_offset(const chain_plan& p, const vec3& linear, const vec3& offset,
                              const joint_turns& r);

/// The tool axis alone of forward(), in the part frame.
vec3 tool_axis(const kinematic_chain& c, const joint_values& j);
vec3 tool_axis(const kinematic_chain& c, const joint_turns& r);
vec3 tool_axis(const chain_plan& p, const joint_turns& r);

/// The tool tip relative to the linear axes' position, with the heads at `j` (the heads' part
/// of the forward transform): the linear values are the tip's place when every head is at 0.
vec3 head_offset(const kinematic_chain& c, const joint_turns& r, double tool_length);
vec3 head_offset(const chain_plan& p, const joint_turns& r, double tool_length);

/// A point of the part frame in the machine frame with the tables at `j` (the tables' part).
vec3 part_to_machine(const kinematic_chain& c, const joint_turns& r, const vec3& p);
vec3 part_to_machine(const chain_plan& plan, const joint_turns& r, const vec3& p);

}  // namespace twinpost::kin
