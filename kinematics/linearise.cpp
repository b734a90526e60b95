#include "kinematics/linearise.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "kinematics/forward.hpp"
#include "kinematics/vec3_ops.hpp"

namespace twinpost::kin {

joint_values interpolate(const kinematic_chain& c, const joint_values& a, const joint_values& b, double t) {
  joint_values j;
  j.linear = a.linear + t * (b.linear - a.linear);
  for (std::size_t i = 0; i < c.rotaries.size(); ++i) {
    double d = b.rotary[i] - a.rotary[i];
    if (c.rotaries[i].rollover == rotary_rollover::shortest) d = wrap_180(d);
    j.rotary[i] = a.rotary[i] + t * d;
  }
  return j;
}

double distance_to_segment(const vec3& p, const vec3& a, const vec3& b) {
  const vec3 ab = b - a;
  const double len2 = dot(ab, ab);
  const double t = len2 > 0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return distance(p, a + t * ab);
}

vec3 slerp(const vec3& a0, const vec3& b0, double t) {
  const vec3 a = (1.0 / norm(a0)) * a0, b = (1.0 / norm(b0)) * b0;
  const double omega = std::atan2(norm(cross(a, b)), dot(a, b));
  if (omega < 1e-9) {
    const vec3 v = a + t * (b - a);
    return (1.0 / norm(v)) * v;
  }
  return (1.0 / std::sin(omega)) * (std::sin((1 - t) * omega) * a + std::sin(t * omega) * b);
}

namespace {

struct splitter {
  const chain_plan& p;
  const tool_pose& from;
  const tool_pose& to;
  double tool_length, tolerance;
  int max_points;
  linearise_result& out;
  const kinematic_chain& c = *p.chain;

  // The CL point a fraction `s` of the way along the segment; the end itself at 1.
  tool_pose at(double s) const { return segment_pose(from, to, s); }

  const vec3 ab = to.tip - from.tip;  // the segment, for distance_to_segment's sums, once
  const double len2 = dot(ab, ab);

  // The largest distance from the segment of the tip of the joints between j0 and j1: the
  // sums of distance_to_segment(), the square root taken once of the largest square.
  // The rotations at the quarters are the start's turned by one, two and three quarters of
  // the move (the sum formulas: one sincos per axis for the start, a series for the quarter
  // when it is small), not a sincos of each interpolated angle.
  double deviation(const joint_values& j0, const joint_values& j1) const {
    const joint_turns start(p, j0);
    std::array<joint_turns, 3> at{start, start, start};
    for (int i = 0; i < p.rotary_count; ++i) {
      double d = j1.rotary[i] - j0.rotary[i];
      if (c.rotaries[i].rollover == rotary_rollover::shortest) d = wrap_180(d);
      const turn q = turn_of_small(d / 4);
      at[0].t[i] = compose(at[0].t[i], q);
      at[1].t[i] = compose(at[0].t[i], q);
      at[2].t[i] = compose(at[1].t[i], q);
    }
    double d2 = 0;
    const vec3 move = j1.linear - j0.linear;
    for (std::size_t n = 0; n < 3; ++n) {
      const double t = 0.25 * static_cast<double>(n + 1);
      // The linear values of interpolate(): the rotations are at[n].
      const vec3 tip = forward_tip(p, j0.linear + t * move, tool_length, at[n]);
      const double s = len2 > 0 ? std::clamp(dot(tip - from.tip, ab) / len2, 0.0, 1.0) : 0.0;
      const vec3 off = tip - (from.tip + s * ab);
      d2 = std::max(d2, dot(off, off));
    }
    return std::sqrt(d2);
  }

  bool fail(ik_error e, std::string message) {
    out.error = e;
    out.message = std::move(message);
    return false;
  }

  // Appends the sub-moves from (s0, j0) to the CL point at s1, whose joints are solved from
  // j0: the joints follow the CL path from the start, so the end is reached the way the path
  // goes (past a pole, the way around it), not by the shortest move from the start.
  bool split(double s0, const joint_values& j0, double s1, int depth) {
    const ik_result end = inverse(p, at(s1), tool_length, j0);
    if (!end.ok()) return fail(end.error, end.message);
    const double d = deviation(j0, end.joints);
    if (d <= tolerance) {
      out.deviation = std::max(out.deviation, d);
      out.points.push_back(end.joints);
      out.fractions.push_back(s1);
      return true;
    }
    if (static_cast<int>(out.points.size()) + 2 > max_points || depth == 60)
      return fail(ik_error::too_many_points,
                  fmt::format("the move needs more than {} points to keep the tip within {} mm of the line",
                              max_points, number_text(tolerance)));
    const double sm = (s0 + s1) / 2;
    if (!split(s0, j0, sm, depth + 1)) return false;
    const joint_values jm = out.points.back();
    return split(sm, jm, s1, depth + 1);
  }
};

}  // namespace

linearise_result linearise(const kinematic_chain& c, const tool_pose& from, const joint_values& from_joints,
                           const tool_pose& to, double tool_length, double tolerance, int max_points) {
  linearise_result out;
  linearise(c, from, from_joints, to, tool_length, tolerance, out, max_points);
  return out;
}

void linearise(const kinematic_chain& c, const tool_pose& from, const joint_values& from_joints,
               const tool_pose& to, double tool_length, double tolerance, linearise_result& out,
               int max_points) {
  linearise(chain_plan(c), from, from_joints, to, tool_length, tolerance, out, max_points);
}

void linearise(const chain_plan& p, const tool_pose& from, const joint_values& from_joints,
               const tool_pose& to, double tool_length, double tolerance, linearise_result& out,
               int max_points) {
  out.error = ik_error::none;
  out.message.clear();
  out.points.clear();
  out.fractions.clear();
  out.deviation = 0;
  splitter s{p, from, to, tool_length, tolerance, max_points, out};
  s.split(0, from_joints, 1, 0);
  if (!out.ok()) {
    out.points.clear();
    out.fractions.clear();
  }
}

tool_pose segment_pose(const tool_pose& from, const tool_pose& to, double s) {
  if (s == 1) return to;
  return {from.tip + s * (to.tip - from.tip), slerp(from.axis, to.axis, s)};
}

}  // namespace twinpost::kin
