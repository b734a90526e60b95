#include "kinematics/forward.hpp"

namespace twinpost::kin {

namespace {

// Turns `tip` by the heads, innermost first: H = H1·H2 (the first head carries the second).
// The heads' points are measured from the gauge point, `gauge` from the tip at home.
vec3 heads_tip(const chain_plan& p, const joint_turns& r, const vec3& gauge, vec3 tip) {
  for (int n = 0; n < p.head_count; ++n) {
    const rotary_step& s = p.heads[n];
    const vec3 on = gauge + s.point;
    tip = rotate(tip - on, s, r.t[s.index]) + on;
  }
  return tip;
}

// Machine frame -> part frame: T^-1 = T2^-1·T1^-1, the first table undone first.
vec3 undo_tables(const chain_plan& p, const joint_turns& r, vec3 tip) {
  for (int n = 0; n < p.table_count; ++n) {
    const rotary_step& s = p.tables[n];
    tip = rotate(tip - s.point, s, reversed(r.t[s.index])) + s.point;
  }
  return tip;
}

}  // namespace

vec3 head_offset(const chain_plan& p, const joint_turns& r, double tool_length) {
  return heads_tip(p, r, tool_length * p.chain->tool_direction, vec3{});
}

vec3 head_offset(const kinematic_chain& c, const joint_turns& r, double tool_length) {
  return head_offset(chain_plan(c), r, tool_length);
}

vec3 part_to_machine(const chain_plan& plan, const joint_turns& r, const vec3& p) {
  // T = T1·T2 (the first table carries the second): the second turns the point first.
  vec3 q = p;
  for (int n = plan.table_count; n-- > 0;) {
    const rotary_step& s = plan.tables[n];
    q = rotate(q - s.point, s, r.t[s.index]) + s.point;
  }
  return q;
}

vec3 part_to_machine(const kinematic_chain& c, const joint_turns& r, const vec3& p) {
  return part_to_machine(chain_plan(c), r, p);
}

vec3 tool_axis(const kinematic_chain& c, const joint_values& j) { return tool_axis(c, joint_turns(c, j)); }

vec3 tool_axis(const kinematic_chain& c, const joint_turns& r) { return tool_axis(chain_plan(c), r); }

vec3 tool_axis(const chain_plan& p, const joint_turns& r) {
  vec3 axis = p.chain->tool_direction;
  for (int n = 0; n < p.head_count; ++n)  // the heads, the inner one first
    axis = rotate(axis, p.heads[n], r.t[p.heads[n].index]);
  for (int n = 0; n < p.table_count; ++n)  // the tables undone, the first one first
    axis = rotate(axis, p.tables[n], reversed(r.t[p.tables[n].index]));
  return axis;
}

tool_pose forward_from_offset(const chain_plan& p, const vec3& linear, const vec3& offset,
                              const joint_turns& r) {
  return {undo_tables(p, r, offset + linear), tool_axis(p, r)};
}

tool_pose forward(const chain_plan& p, const joint_values& j, double tool_length, const joint_turns& r) {
  return forward_from_offset(p, j.linear, head_offset(p, r, tool_length), r);
}

tool_pose forward(const chain_plan& p, const joint_values& j, double tool_length) {
  return forward(p, j, tool_length, joint_turns(p, j));
}

tool_pose forward(const kinematic_chain& c, const joint_values& j, double tool_length, const joint_turns& r) {
  return forward(chain_plan(c), j, tool_length, r);
}

tool_pose forward(const kinematic_chain& c, const joint_values& j, double tool_length) {
  return forward(c, j, tool_length, joint_turns(c, j));
}

vec3 forward_tip(const kinematic_chain& c, const joint_values& j, double tool_length) {
  return forward_tip(c, j, tool_length, joint_turns(c, j));
}

vec3 forward_tip(const kinematic_chain& c, const joint_values& j, double tool_length, const joint_turns& r) {
  return forward_tip(chain_plan(c), j.linear, tool_length, r);
}

vec3 forward_tip(const chain_plan& p, const vec3& linear, double tool_length, const joint_turns& r) {
  return undo_tables(p, r, head_offset(p, r, tool_length) + linear);
}

}  // namespace twinpost::kin
