#include "kinematics/forward.hpp"

#include "kinematics/vec3_ops.hpp"

namespace twinpost::kin {

namespace {

// Turns `tip` and `axis` by the heads, innermost first: H = H1·H2 (the first head carries the
// second). The heads' points are measured from the gauge point, `gauge` from the tip at home.
void apply_heads(const kinematic_chain& c, const joint_values& j, const vec3& gauge, vec3& tip, vec3& axis) {
  for (std::size_t i = c.rotaries.size(); i-- > 0;) {
    const rotary_axis_def& a = c.rotaries[i];
    if (a.kind != rotary_kind::head) continue;
    tip = rotate_about(tip, a.direction, gauge + a.point, j.rotary[i]);
    axis = rotate(axis, a.direction, j.rotary[i]);
  }
}

}  // namespace

vec3 head_offset(const kinematic_chain& c, const joint_values& j, double tool_length) {
  vec3 tip{}, axis = c.tool_direction;
  apply_heads(c, j, tool_length * c.tool_direction, tip, axis);
  return tip;
}

vec3 part_to_machine(const kinematic_chain& c, const joint_values& j, const vec3& p) {
  // T = T1·T2 (the first table carries the second): the second turns the point first.
  vec3 q = p;
  for (std::size_t i = c.rotaries.size(); i-- > 0;) {
    const rotary_axis_def& a = c.rotaries[i];
    if (a.kind == rotary_kind::table) q = rotate_about(q, a.direction, a.point, j.rotary[i]);
  }
  return q;
}

vec3 tool_axis(const kinematic_chain& c, const joint_values& j) {
  vec3 axis = c.tool_direction;
  for (std::size_t i = c.rotaries.size(); i-- > 0;)  // the heads, the inner one first
    if (c.rotaries[i].kind == rotary_kind::head) axis = rotate(axis, c.rotaries[i].direction, j.rotary[i]);
  for (std::size_t i = 0; i < c.rotaries.size(); ++i)  // the tables undone, the first one first
    if (c.rotaries[i].kind == rotary_kind::table) axis = rotate(axis, c.rotaries[i].direction, -j.rotary[i]);
  return axis;
}

tool_pose forward(const kinematic_chain& c, const joint_values& j, double tool_length) {
  tool_pose p{{0, 0, 0}, c.tool_direction};
  apply_heads(c, j, tool_length * c.tool_direction, p.tip, p.axis);
  p.tip = p.tip + j.linear;
  // Machine frame -> part frame: T^-1 = T2^-1·T1^-1, the first table undone first.
  for (std::size_t i = 0; i < c.rotaries.size(); ++i) {
    const rotary_axis_def& a = c.rotaries[i];
    if (a.kind != rotary_kind::table) continue;
    p.tip = rotate_about(p.tip, a.direction, a.point, -j.rotary[i]);
    p.axis = rotate(p.axis, a.direction, -j.rotary[i]);
  }
  return p;
}

}  // namespace twinpost::kin
