#pragma once
// The geometry of a kinematic chain (machines/kinematic_chain.hpp): joint values, tool poses,
// which kind of chain it is, and the one product of rotations that gives its tool axis in the
// part frame (docs/kinematics.md, "Frames").
#include <array>
#include <string>
#include <string_view>

#include "kinematics/vec3_ops.hpp"
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

/// One rotary axis as the transforms turn by it: its index in the chain, its direction and
/// point, and the machine axis it lies along (0 x, 1 y, 2 z, `sign` its sense; -1: none), found
/// by the same tests as rotate() makes, so that turning by it gives rotate()'s bits.
struct rotary_step {
  int index = 0;
  int along = -1;
  double sign = 1;
  vec3 direction{}, point{};
};

/// `v` turned by `t` about the axis of `s` (its point aside): rotate(v, s.direction, t), bit for
/// bit, without testing the direction again.
inline vec3 rotate(const vec3& v, const rotary_step& s, const turn& t) {
  switch (s.along) {
    case 0: {
      const double sn = s.sign * t.s;
      return {v.x, t.c * v.y - sn * v.z, sn * v.y + t.c * v.z};
    }
    case 1: {
      const double sn = s.sign * t.s;
      return {t.c * v.x + sn * v.z, v.y, t.c * v.z - sn * v.x};
    }
    case 2: {
      const double sn = s.sign * t.s;
      return {t.c * v.x - sn * v.y, sn * v.x + t.c * v.y, v.z};
    }
    default: return rotate(v, s.direction, t);
  }
}

/// The constants of the inner rotation's equation a + b·cos φ + c·sin φ = dout·k for the axes
/// `dout` (outer), `din` (inner) and the tool direction `t0`: a = (dout·din)(din·t0),
/// b = dout·t0 − a, c = dout·(din × t0), r = |(b, c)|, and the angle of (b, c) with its cosine
/// and sine (kinematics/inverse.cpp solves it). They depend on the chain alone.
struct inner_equation {
  double a = 0, b = 0, c = 0, r = 0, base = 0, cos_base = 1, sin_base = 0;
};

/// What the transforms of a chain need of it, laid out once per chain rather than found again
/// at every point (every CL point runs an inverse and several forward transforms): the
/// orientation form, the heads in the order they turn the tool (the inner one first), the
/// tables in the order they are undone (the first one first).
struct chain_plan {
  const kinematic_chain* chain = nullptr;
  orientation_form form;
  int rotary_count = 0, head_count = 0, table_count = 0;
  std::array<rotary_step, 2> heads{}, tables{};
  std::array<rotary_step, 2> steps{};  ///< every rotary axis, in the chain's order
  inner_equation inner;                ///< with an inner axis (form.inner >= 0)
  chain_plan() = default;
  explicit chain_plan(const kinematic_chain& c);
};

/// A number as twinpost writes it in messages: at most 4 decimals, no trailing zeros ("30",
/// "-0.5", "0.866").
std::string number_text(double v);

}  // namespace twinpost::kin
