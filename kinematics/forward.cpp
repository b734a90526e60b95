#include "kinematics/forward.hpp"

namespace twinpost::kin {

namespace {

// Turns `tip` (and `axis`, unless it is null) by the heads, innermost first: H = H1·H2 (the
// first head carries the second). The heads' points are measured from the gauge point,
// `gauge` from the tip at home.
void apply_heads(const kinematic_chain& c, const joint_turns& r, const vec3& gauge, vec3& tip, vec3* axis) {
  for (std::size_t i = c.rotaries.size(); i-- > 0;) {
    const rotary_axis_def& a = c.rotaries[i];
    if (a.kind != rotary_kind::head) continue;
    tip = rotate_about(tip, a.direction, gauge + a.point, r.t[i]);
    if (axis) *axis = rotate(*axis, a.direction, r.t[i]);
  }
}

// Machine frame -> part frame: T^-1 = T2^-1·T1^-1, the first table undone first.
void undo_tables(const kinematic_chain& c, const joint_turns& r, vec3& tip, vec3* axis) {
  for (std::size_t i = 0; i < c.rotaries.size(); ++i) {
    const rotary_axis_def& a = c.rotaries[i];
    if (a.kind != rotary_kind::table) continue;
    tip = rotate_about(tip, a.direction, a.point, reversed(r.t[i]));
    if (axis) *axis = rotate(*axis, a.direction, reversed(r.t[i]));
  }
}

}  // namespace

vec3 head_offset(const kinematic_chain& c, const joint_turns& r, double tool_length) {
  vec3 tip{};
  apply_heads(c, r, tool_length * c.tool_direction, tip, nullptr);
  return tip;
}

vec3 part_to_machine(const kinematic_chain& c, const joint_turns& r, const vec3& p) {
  // T = T1·T2 (the first table carries the second): the second turns the point first.
  vec3 q = p;
  for (std::size_t i = c.rotaries.size(); i-- > 0;) {
    const rotary_axis_def& a = c.rotaries[i];
    if (a.kind == rotary_kind::table) q = rotate_about(q, a.direction, a.point, r.t[i]);
  }
  return q;
}

vec3 tool_axis(const kinematic_chain& c, const joint_values& j) { return tool_axis(c, joint_turns(c, j)); }

vec3 tool_axis(const kinematic_chain& c, const joint_turns& r) {
  vec3 axis = c.tool_direction;
  for (std::size_t i = c.rotaries.size(); i-- > 0;)  // the heads, the inner one first
    if (c.rotaries[i].kind == rotary_kind::head) axis = rotate(axis, c.rotaries[i].direction, r.t[i]);
  for (std::size_t i = 0; i < c.rotaries.size(); ++i)  // the tables undone, the first one first
    if (c.rotaries[i].kind == rotary_kind::table)
      axis = rotate(axis, c.rotaries[i].direction, reversed(r.t[i]));
  return axis;
}

tool_pose forward(const kinematic_chain& c, const joint_values& j, double tool_length, const joint_turns& r) {
  tool_pose p{{0, 0, 0}, c.tool_direction};
  apply_heads(c, r, tool_length * c.tool_direction, p.tip, &p.axis);
  p.tip = p.tip + j.linear;
  undo_tables(c, r, p.tip, &p.axis);
  return p;
}

tool_pose forward(const kinematic_chain& c, const joint_values& j, double tool_length) {
  return forward(c, j, tool_length, joint_turns(c, j));
}

vec3 forward_tip(const kinematic_chain& c, const joint_values& j, double tool_length) {
  return forward_tip(c, j, tool_length, joint_turns(c, j));
}

vec3 forward_tip(const kinematic_chain& c, const joint_values& j, double tool_length, const joint_turns& r) {
  vec3 tip{};
  apply_heads(c, r, tool_length * c.tool_direction, tip, nullptr);
  tip = tip + j.linear;
  undo_tables(c, r, tip, nullptr);
  return tip;
}

}  // namespace twinpost::kin
