#include "kinematics/inverse.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "kinematics/forward.hpp"
#include "kinematics/vec3_ops.hpp"

namespace twinpost::kin {

namespace {

// Below this the tool axis is taken to lie on the outer rotary axis (unit vectors: the sine of
// the angle between them). The outer angle's error there is at most ~eps/this in radians.
constexpr double pole_sine = 1e-9;

// The angle (degrees) that turns `from` to `to` about the unit `d`, both taken perpendicular
// to it; nullopt when either has no perpendicular part.
struct angle_and_turn {
  double degrees;
  turn sides;  // its cosine and sine, from the sides atan2 was given
};
std::optional<angle_and_turn> angle_about(const vec3& d, const vec3& from, const vec3& to) {
  const vec3 f = from - dot(d, from) * d;
  const vec3 t = to - dot(d, to) * d;
  if (norm(f) < pole_sine || norm(t) < pole_sine) return std::nullopt;
  const double y = dot(d, cross(f, t)), x = dot(f, t), h = std::sqrt(x * x + y * y);  // |x|, |y| <= 1
  return angle_and_turn{std::atan2(y, x) / deg, {x / h, y / h}};
}

std::string axis_text(const vec3& k) {
  return fmt::format("({}, {}, {})", number_text(k.x), number_text(k.y), number_text(k.z));
}

std::string angles_text(const kinematic_chain& c, const std::array<double, 2>& r) {
  std::string s;
  for (std::size_t i = 0; i < c.rotaries.size(); ++i)
    s += fmt::format("{}{}{}", i ? " " : "", c.rotaries[i].address, number_text(r[i]));
  return s;
}

// The value of axis `a` equivalent to `v` (v + 360k) that a move from `prev` goes to, and the
// length of that move; nullopt when no equivalent lies within the limits.
struct fitted {
  double value, move;
};
std::optional<fitted> fit(const rotary_axis_def& a, double v, double prev) {
  if (a.continuous()) {
    const double d = wrap_180(v - prev);
    if (a.rollover == rotary_rollover::absolute) return fitted{prev + d, std::abs(d)};
    double w = v - 360.0 * std::floor(v / 360.0);
    if (w >= 360.0) w -= 360.0;
    return fitted{w, std::abs(d)};
  }
  // Within the limits and less than half a turn from the previous value: itself (what the
  // search below gives there, k = 0).
  if (v >= *a.min && v <= *a.max && std::abs(prev - v) < 180.0) return fitted{v, std::abs(v - prev)};
  // A value on a limit, give or take the rounding of the solve and of the CL's axis vector: NX
  // prints 7 decimals, which puts B20 at 20.00000018 (review 45, refused before); the value is
  // clamped onto the limit.
  constexpr double slack = 1e-5;
  const double kmin = std::ceil((*a.min - slack - v) / 360.0);
  const double kmax = std::floor((*a.max + slack - v) / 360.0);
  if (kmin > kmax) return std::nullopt;
  const double k = std::clamp(std::round((prev - v) / 360.0), kmin, kmax);
  const double value = std::clamp(v + 360.0 * k, *a.min, *a.max);
  return fitted{value, std::abs(value - prev)};
}

bool meets(preferred_sign p, double v) {
  constexpr double zero = 1e-9;
  return p == preferred_sign::none || (p == preferred_sign::positive ? v >= -zero : v <= zero);
}

}  // namespace

namespace {

// The outer angle of `s` (whose inner rotation is solved): the angle that turns the tool after
// the inner rotation to k, or the previous one at the pole.
void solve_outer(const chain_plan& p, const vec3& k, const joint_values& previous, orientation_solution& s) {
  const kinematic_chain& c = *p.chain;
  const orientation_form& f = p.form;
  const vec3& dout = c.rotaries[f.outer].direction;
  vec3 v = c.tool_direction;
  if (f.inner >= 0) {  // the raw rotation (the sign undone: multiplying by +-1 is exact)
    const turn by{s.turns[f.inner].c, f.inner_sign * s.turns[f.inner].s};
    v = rotate(v, p.steps[f.inner], by);
  }
  if (const std::optional<angle_and_turn> a = angle_about(dout, v, k)) {
    s.rotary[f.outer] = f.outer_sign * a->degrees;
    s.turns[f.outer] = {a->sides.c, f.outer_sign * a->sides.s};
  } else {
    s.rotary[f.outer] = previous.rotary[f.outer];
    s.turns[f.outer] = turn_of(s.rotary[f.outer]);
    s.pole = true;
  }
}

// The inner angles of the (at most two) solutions, their outer angles not yet solved; for a
// chain of two rotary axes only.
two_at_most<orientation_solution> solve_inner(const chain_plan& p, const vec3& k) {
  const kinematic_chain& c = *p.chain;
  const orientation_form& f = p.form;
  two_at_most<orientation_solution> out;
  const vec3& dout = c.rotaries[f.outer].direction;
  // The outer rotation keeps the component along its axis: dout·R(inner, φ)·t0 = dout·k, which
  // by Rodrigues reads a + b·cos φ + c·sin φ = dout·k (its constants: the plan's).
  const inner_equation& eq = p.inner;
  const double a = eq.a, r = eq.r;
  if (r < 1e-12) return out;  // the inner axis cannot change it (rejected by the loader)
  // φ = base ± half with cos half = e / r, e = dout·k - a. Not acos(e / r): near the pole (e ≈ r)
  // it loses half the digits. sin half = sqrt((r - e)(r + e)) / r, with r ∓ e written through
  // 1 ∓ dout·k = |dout × k|² / (1 ± dout·k), which has no cancellation, and the constants
  // a + r - 1 and r - a - 1 of the chain (0 when the tool can reach the outer axis).
  const double dk = dot(dout, k);
  const double across = dot(cross(dout, k), cross(dout, k));
  const double one_minus = dk > 0 ? across / (1 + dk) : 1 - dk;
  const double one_plus = dk < 0 ? across / (1 - dk) : 1 + dk;
  const double r_minus_e = (a + r - 1) + one_minus;
  const double r_plus_e = (r - a - 1) + one_plus;
  // Well beyond the circle the inner axis sweeps: unreachable. Just beyond it (about 0.08°):
  // on its edge, and the forward check holds the result to the chain's angle tolerance.
  if (r_minus_e < -1e-6 || r_plus_e < -1e-6) return out;
  const double sin_half = std::sqrt(std::max(0.0, r_minus_e * r_plus_e)), cos_half = dk - a;
  const double base = eq.base;
  const double half = std::atan2(sin_half, cos_half) / deg;
  // The cosine and sine of base ± half by the sum formulas, from the sides of the two angles
  // (no sincos: an inverse runs once per CL point).
  const double rh = std::sqrt(sin_half * sin_half + cos_half * cos_half);  // both below 3
  const double cb = eq.cos_base, sb = eq.sin_base, ch = rh > 0 ? cos_half / rh : 1,
               sh = rh > 0 ? sin_half / rh : 0;
  for (const double pm : {1.0, -1.0}) {
    const double phi = base + pm * half;
    const turn by{cb * ch - pm * sb * sh, sb * ch + pm * cb * sh};
    orientation_solution s;
    s.rotary[f.inner] = f.inner_sign * wrap_180(phi);
    s.turns[f.inner] = {by.c, f.inner_sign * by.s};
    if (s.rotary[f.inner] == -180.0) s.rotary[f.inner] = 180.0;
    out.push_back(s);
  }
  return out;
}

// Whether two solutions are the same (the closed form's two coincide on the edge of its circle).
bool twins(const orientation_form& f, const orientation_solution& x, const orientation_solution& y) {
  return std::abs(wrap_180(x.rotary[f.inner] - y.rotary[f.inner])) < 1e-12 &&
         std::abs(wrap_180(x.rotary[f.outer] - y.rotary[f.outer])) < 1e-12;
}

}  // namespace

namespace {

two_at_most<orientation_solution> orientation_solutions(const chain_plan& p, const vec3& k,
                                                        const joint_values& previous) {
  const orientation_form& f = p.form;
  two_at_most<orientation_solution> out;
  if (f.outer < 0) {
    out.push_back({});
    return out;
  }
  if (f.inner < 0) {
    orientation_solution s;
    solve_outer(p, k, previous, s);
    out.push_back(s);
    return out;
  }
  for (orientation_solution s : solve_inner(p, k)) {
    solve_outer(p, k, previous, s);
    if (s.rotary[f.outer] == -180.0) s.rotary[f.outer] = 180.0;
    if (out.empty() || !twins(f, out[0], s)) out.push_back(s);
  }
  return out;
}

}  // namespace

two_at_most<orientation_solution> orientation_solutions(const kinematic_chain& c, const vec3& k,
                                                        const joint_values& previous) {
  return orientation_solutions(chain_plan(c), k, previous);
}

joint_values positions(const kinematic_chain& c, const vec3& tip, const joint_values& angles,
                       double tool_length) {
  joint_values j = angles;
  j.linear = {};
  const chain_plan p(c);
  const joint_turns r(p, j);
  j.linear = part_to_machine(p, r, tip) - head_offset(p, r, tool_length);
  return j;
}

ik_result inverse(const kinematic_chain& c, const tool_pose& pose, double tool_length,
                  const joint_values& previous, ik_need need) {
  return inverse(chain_plan(c), pose, tool_length, previous, need);
}

ik_result inverse(const chain_plan& p, const tool_pose& pose, double tool_length,
                  const joint_values& previous, ik_need need) {
  const kinematic_chain& c = *p.chain;
  ik_result r;
  const double len = norm(pose.axis);
  if (!(len > 1e-9) || !std::isfinite(len)) {
    r.error = ik_error::zero_axis;
    r.message = fmt::format("tool axis {} is not a direction", axis_text(pose.axis));
    return r;
  }
  if (!std::isfinite(pose.tip.x) || !std::isfinite(pose.tip.y) || !std::isfinite(pose.tip.z)) {
    r.error = ik_error::bad_tip;
    r.message = fmt::format("tool tip {} is not a point", axis_text(pose.tip));
    return r;
  }
  const vec3 k = (1.0 / len) * pose.axis;
  const tool_pose want{pose.tip, k};

  struct candidate {
    joint_values j;
    bool pole;
    int misses;  // preferred signs not met
    double total, outer;
    double tip_error, axis_error;
    std::array<double, 2> raw{};  // the angles as solved, before placing them within the limits
    std::array<turn, 2> turns{};  // their rotations (whole turns added below change neither)
  };
  // Candidates with an axis beyond its limits, for the message only: formatted when nothing fits.
  struct refused {
    std::array<double, 2> rotary;
    std::array<bool, 2> beyond;
  };
  const orientation_form& f = p.form;
  // Generate, then verify: a candidate the forward transform does not confirm is no solution.
  // The check is made on the candidates in the order they are chosen, and stops at the first
  // that holds (placing the angles below moves them by whole turns only: the same axis).
  const auto axis_error_of = [&](const std::array<double, 2>& rotary) {
    joint_values raw;
    raw.rotary = rotary;
    return angle_between(tool_axis(p, joint_turns(p, raw)), k);
  };
  // Places the angles of `s` within the limits relative to `previous`: false, with `why`,
  // when an axis has no value within them.
  const auto place = [&](const orientation_solution& s, candidate& cand, refused& why) {
    cand = candidate{{}, s.pole, 0, 0, 0, 0, 0};
    cand.raw = s.rotary;
    cand.turns = s.turns;
    cand.j.rotary = s.rotary;
    why = refused{s.rotary, {false, false}};
    for (std::size_t i = 0; i < c.rotaries.size(); ++i) {
      const rotary_axis_def& a = c.rotaries[i];
      const std::optional<fitted> v = fit(a, s.rotary[i], previous.rotary[i]);
      if (!v) {
        why.beyond[i] = true;
        continue;
      }
      cand.j.rotary[i] = v->value;
      cand.total += v->move;
      if (static_cast<int>(i) == f.outer) cand.outer = v->move;
      if (!meets(a.prefer, v->value)) ++cand.misses;
    }
    return !why.beyond[0] && !why.beyond[1];
  };
  // The forward transform's check of a candidate; true (with `r` set) when it holds.
  const auto verify = [&](candidate& cand) {
    const joint_turns turns(cand.turns);
    if (need != ik_need::joints) {
      cand.axis_error = angle_between(tool_axis(p, turns), k);
      if (cand.axis_error > c.angle_tolerance) return false;
    } else {  // the forward transform of the joints below checks the axis too
      // The heads' part of the tip is the same in the solve and in its check: turned once.
      const vec3 offset = head_offset(p, turns, tool_length);
      cand.j.linear = part_to_machine(p, turns, want.tip) - offset;
      const tool_pose got = forward_from_offset(p, cand.j.linear, offset, turns);
      cand.tip_error = distance(got.tip, want.tip);
      cand.axis_error = angle_between(got.axis, k);
      if (cand.tip_error > c.tolerance || cand.axis_error > c.angle_tolerance) return false;
    }
    r.joints = cand.j;
    r.pole = cand.pole;
    r.tip_error = cand.tip_error;
    r.axis_error = cand.axis_error;
    return true;
  };
  // The short way, for two rotary axes whose outer one has no preferred sign: the solution
  // whose inner axis moves less has its outer angle solved; when its whole move is shorter
  // than the other's inner move alone (and the other meets no more preferred signs), the
  // other cannot be chosen before it and its outer angle is not needed: the same choice as
  // below, at one atan2 and one projection less. Anything else goes the whole way.
  if (f.inner >= 0 && c.rotaries[f.outer].prefer == preferred_sign::none) {
    const two_at_most<orientation_solution> in = solve_inner(p, k);
    if (in.size() == 2) {
      const rotary_axis_def& ia = c.rotaries[f.inner];
      const std::optional<fitted> m0 = fit(ia, in[0].rotary[f.inner], previous.rotary[f.inner]);
      const std::optional<fitted> m1 = fit(ia, in[1].rotary[f.inner], previous.rotary[f.inner]);
      if (m0 || m1) {
        const std::size_t first = !m1 || (m0 && m0->move <= m1->move) ? 0 : 1;
        const std::optional<fitted>& other = first == 0 ? m1 : m0;
        orientation_solution s = in[first];
        solve_outer(p, k, previous, s);
        if (s.rotary[f.outer] == -180.0) s.rotary[f.outer] = 180.0;
        candidate cand;
        refused why;
        if (place(s, cand, why)) {
          const int other_misses = other && !meets(ia.prefer, other->value) ? 1 : 0;
          const bool other_later = !other || cand.misses < other_misses ||
                                   (cand.misses == other_misses && cand.total + 1e-6 < other->move);
          if (other_later && verify(cand)) return r;
        }
      }
    }
  }
  // The whole way (the short one above returns before these are needed).
  two_at_most<candidate> fitting;
  two_at_most<refused> beyond;
  for (const orientation_solution& s : orientation_solutions(p, k, previous)) {
    candidate cand;
    refused why;
    if (!place(s, cand, why)) {
      beyond.push_back(why);  // checked below, if it comes to the message
      continue;
    }
    fitting.push_back(cand);
  }
  // Moves that differ by rounding only are equal; on a tie of both, the positive tilt (the
  // inner axis's value) wins, so that a symmetric choice does not depend on the solve's order.
  constexpr double same = 1e-9;
  const int inner = f.inner >= 0 ? f.inner : 0;
  const auto better = [&](const candidate& x, const candidate& y) {
    if (x.misses != y.misses) return x.misses < y.misses;
    if (std::abs(x.total - y.total) > same) return x.total < y.total;
    if (std::abs(x.outer - y.outer) > same) return x.outer < y.outer;
    return x.j.rotary[inner] > y.j.rotary[inner];
  };
  // The positions of the better candidate first, checked by the forward transform; the other
  // only when that one fails (the check is most of an inverse's time).
  std::array<candidate, 2> order{};
  std::size_t n = 0;
  for (const candidate& cand : fitting) order[n++] = cand;
  if (n == 2 && better(order[1], order[0])) std::swap(order[0], order[1]);
  for (std::size_t i = 0; i < n; ++i)
    if (verify(order[i])) return r;
  {  // nothing fits: why (of the candidates beyond a limit, those the forward transform confirms)
    two_at_most<refused> confirmed;
    for (const refused& b : beyond)
      if (axis_error_of(b.rotary) <= c.angle_tolerance) confirmed.push_back(b);
    beyond = confirmed;
    if (beyond.empty()) {
      r.error = ik_error::unreachable;
      if (c.rotaries.empty()) {
        r.message = fmt::format("tool axis {} is not the tool direction {} of a machine without rotary axes",
                                axis_text(k), axis_text(c.tool_direction));
      } else {
        std::string names;
        for (std::size_t i = 0; i < c.rotaries.size(); ++i)
          names += fmt::format("{}{}", i == 0 ? "" : " and ", c.rotaries[i].address);
        r.message = fmt::format("tool axis {} cannot be reached by the rotary {} {}", axis_text(k),
                                c.rotaries.size() == 1 ? "axis" : "axes", names);
      }
    } else {
      r.error = ik_error::beyond_limits;
      // "B30 A0 (B beyond -20..20) or B-150 A180 (B beyond -20..20; A beyond -20..20)"
      std::string list;
      for (std::size_t n = 0; n < beyond.size(); ++n) {
        std::string why;
        for (std::size_t i = 0; i < c.rotaries.size(); ++i)
          if (beyond[n].beyond[i])
            why += fmt::format("{}{} beyond {}..{}", why.empty() ? "" : "; ", c.rotaries[i].address,
                               number_text(*c.rotaries[i].min), number_text(*c.rotaries[i].max));
        list += fmt::format("{}{} ({})", n ? " or " : "", angles_text(c, beyond[n].rotary), why);
      }
      r.message = fmt::format("tool axis {} needs {}", axis_text(k), list);
    }
    return r;
  }
  return r;
}

}  // namespace twinpost::kin
