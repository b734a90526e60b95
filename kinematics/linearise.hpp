#pragma once
// Linearisation: a straight CL move (tip and axis at both ends) on a machine whose control
// interpolates the joints linearly. Between two joint positions the tip leaves the straight
// line; the move is cut at CL points on the segment (tip interpolated linearly, axis along the
// great circle between the two axes), worked along from the start so that the joints follow
// the path, until the tip of each joint interpolation stays within a chordal tolerance of the
// segment (docs/kinematics.md, "Linearisation").
#include <string>
#include <vector>

#include "kinematics/inverse.hpp"

namespace twinpost::kin {

struct linearise_result {
  ik_error error = ik_error::none;
  std::string message;  ///< why not, when error is not none
  /// The joint values at the end of each sub-move, in order; the last one is the CL end point.
  std::vector<joint_values> points;
  /// Where each point lies along the CL segment (0 the start, 1 the end): its CL pose is
  /// segment_pose(from, to, fraction).
  std::vector<double> fractions;
  /// The largest distance from the segment of the tip, measured by the forward transform at
  /// the checked points of the accepted sub-moves (mm).
  double deviation = 0;
  bool ok() const { return error == ik_error::none; }
};

/// The sub-moves from `from` (where the machine is, at `from_joints`) to `to`, each a linear
/// interpolation of the joints whose tip stays within `tolerance` (mm) of the segment at a
/// quarter, half and three quarters of it; at most `max_points` of them.
linearise_result linearise(const kinematic_chain& c, const tool_pose& from, const joint_values& from_joints,
                           const tool_pose& to, double tool_length, double tolerance, int max_points = 10000);

/// The same into `out`, whose vectors keep their memory from one move to the next (the post
/// linearises every feed move: no allocation once they have grown).
void linearise(const kinematic_chain& c, const tool_pose& from, const joint_values& from_joints,
               const tool_pose& to, double tool_length, double tolerance, linearise_result& out,
               int max_points = 10000);
/// The same with the chain's plan made once by the caller.
void linearise(const chain_plan& p, const tool_pose& from, const joint_values& from_joints,
               const tool_pose& to, double tool_length, double tolerance, linearise_result& out,
               int max_points = 10000);

/// The CL pose a fraction `s` of the way along the move: the tip on the line, the axis on the
/// great circle; `to` itself at 1.
tool_pose segment_pose(const tool_pose& from, const tool_pose& to, double s);

/// The joints a fraction `t` of the way from `a` to `b`, as a control interpolates them: a
/// rotary axis with rollover "shortest" the short way round (from 359 to 1 through 360).
joint_values interpolate(const kinematic_chain& c, const joint_values& a, const joint_values& b, double t);

/// The distance of `p` from the segment `a`-`b`.
double distance_to_segment(const vec3& p, const vec3& a, const vec3& b);

/// The unit axis a fraction `t` of the way from `a` to `b` along the great circle.
vec3 slerp(const vec3& a, const vec3& b, double t);

}  // namespace twinpost::kin
