#include "kinematics/linearise.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "kinematics/forward.hpp"
#include "kinematics/vec3_ops.hpp"

namespace twinpost::kin {

joint_values interpolate(const joint_values& a, const joint_values& b, double t) {
  joint_values j;
  j.linear = a.linear + t * (b.linear - a.linear);
  for (std::size_t i = 0; i < j.rotary.size(); ++i)
    j.rotary[i] = a.rotary[i] + t * (b.rotary[i] - a.rotary[i]);
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
  const kinematic_chain& c;
  const tool_pose& from;
  const tool_pose& to;
  double tool_length, tolerance;
  int max_points;
  linearise_result& out;

  // The largest distance from the segment of the tip of the joints between j0 and j1.
  double deviation(const joint_values& j0, const joint_values& j1) const {
    double d = 0;
    for (double t : {0.25, 0.5, 0.75})
      d = std::max(
          d, distance_to_segment(forward(c, interpolate(j0, j1, t), tool_length).tip, from.tip, to.tip));
    return d;
  }

  // Appends the sub-moves from (s0, j0) to (s1, j1); false on an error (in out).
  bool split(double s0, const joint_values& j0, double s1, const joint_values& j1) {
    const double d = deviation(j0, j1);
    if (d <= tolerance) {
      out.deviation = std::max(out.deviation, d);
      out.points.push_back(j1);
      return true;
    }
    if (static_cast<int>(out.points.size()) + 2 > max_points) {
      out.error = ik_error::too_many_points;
      out.message = fmt::format("the move needs more than {} points to keep the tip within {} mm of the line",
                                max_points, number_text(tolerance));
      return false;
    }
    const double sm = (s0 + s1) / 2;
    const tool_pose mid{from.tip + sm * (to.tip - from.tip), slerp(from.axis, to.axis, sm)};
    const ik_result r = inverse(c, mid, tool_length, j0);
    if (!r.ok()) {
      out.error = r.error;
      out.message = r.message;
      return false;
    }
    return split(s0, j0, sm, r.joints) && split(sm, r.joints, s1, j1);
  }
};

}  // namespace

linearise_result linearise(const kinematic_chain& c, const tool_pose& from, const joint_values& from_joints,
                           const tool_pose& to, double tool_length, double tolerance, int max_points) {
  linearise_result out;
  const ik_result end = inverse(c, to, tool_length, from_joints);
  if (!end.ok()) {
    out.error = end.error;
    out.message = end.message;
    return out;
  }
  splitter s{c, from, to, tool_length, tolerance, max_points, out};
  s.split(0, from_joints, 1, end.joints);
  if (!out.ok()) out.points.clear();
  return out;
}

}  // namespace twinpost::kin
