#include "kinematics/chain.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace twinpost::kin {

chain_kind kind_of(const kinematic_chain& c) {
  switch (c.rotaries.size()) {
    case 0: return chain_kind::three_axis;
    case 1: return chain_kind::one_rotary;
    default: break;
  }
  if (c.rotaries[0].kind != c.rotaries[1].kind) return chain_kind::head_table;
  return c.rotaries[0].kind == rotary_kind::head ? chain_kind::head_head : chain_kind::table_table;
}

std::string_view name_of(chain_kind k) {
  switch (k) {
    case chain_kind::three_axis: return "three-axis";
    case chain_kind::one_rotary: return "one rotary";
    case chain_kind::head_head: return "head/head";
    case chain_kind::table_table: return "table/table";
    case chain_kind::head_table: return "head/table";
  }
  return "?";
}

orientation_form orientation_of(const kinematic_chain& c) {
  auto sign = [&](int i) { return c.rotaries[i].kind == rotary_kind::table ? -1.0 : 1.0; };
  orientation_form f;
  switch (kind_of(c)) {
    case chain_kind::three_axis: return f;
    case chain_kind::one_rotary: f.outer = 0; break;
    case chain_kind::head_head: f.outer = 0, f.inner = 1; break;
    // K = R_t2(-θ2)·R_t1(-θ1)·t0: the table that carries the part (the second) is outer.
    case chain_kind::table_table: f.outer = 1, f.inner = 0; break;
    case chain_kind::head_table:
      f.outer = c.rotaries[0].kind == rotary_kind::table ? 0 : 1;
      f.inner = 1 - f.outer;
      break;
  }
  f.outer_sign = sign(f.outer);
  if (f.inner >= 0) f.inner_sign = sign(f.inner);
  return f;
}

chain_plan::chain_plan(const kinematic_chain& c) : chain(&c), form(orientation_of(c)) {
  rotary_count = static_cast<int>(std::min<std::size_t>(c.rotaries.size(), 2));
  const auto step = [&](int i) {
    const rotary_axis_def& a = c.rotaries[i];
    const vec3& d = a.direction;
    rotary_step s{i, -1, 1, d, a.point};
    if (d.y == 0 && d.z == 0 && (d.x == 1 || d.x == -1))
      s.along = 0, s.sign = d.x;
    else if (d.x == 0 && d.z == 0 && (d.y == 1 || d.y == -1))
      s.along = 1, s.sign = d.y;
    else if (d.x == 0 && d.y == 0 && (d.z == 1 || d.z == -1))
      s.along = 2, s.sign = d.z;
    return s;
  };
  for (int i = 0; i < rotary_count; ++i) steps[i] = step(i);
  for (int i = rotary_count; i-- > 0;)
    if (c.rotaries[i].kind == rotary_kind::head) heads[head_count++] = step(i);
  for (int i = 0; i < rotary_count; ++i)
    if (c.rotaries[i].kind == rotary_kind::table) tables[table_count++] = step(i);
  if (form.inner >= 0) {
    const vec3 &dout = c.rotaries[form.outer].direction, &din = c.rotaries[form.inner].direction,
               &t0 = c.tool_direction;
    inner.a = dot(dout, din) * dot(din, t0);
    inner.b = dot(dout, t0) - inner.a;
    inner.c = dot(dout, cross(din, t0));
    inner.r = std::hypot(inner.b, inner.c);
    inner.base = std::atan2(inner.c, inner.b) / deg;
    if (inner.r > 0) inner.cos_base = inner.b / inner.r, inner.sin_base = inner.c / inner.r;
  }
}

std::string number_text(double v) {
  // Past a billion (or not finite) the exponent form: a CL's 1e300 is not 301 digits (attack 45).
  if (!(std::abs(v) < 1e9)) return fmt::format("{:g}", v);
  std::string s = fmt::format("{:.4f}", v);
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

}  // namespace twinpost::kin
