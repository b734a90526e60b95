#pragma once
// The inverse transform: a CL point (tip and tool axis in the part frame) -> joint values.
// Orientation by the closed form of two rotations about known axes, with both solutions;
// positions from the forward transform's pieces; every candidate checked by the forward
// transform; one chosen by limits, preferred tilt sign and the shortest move from the
// previous joint values (docs/kinematics.md, "Choosing a solution").
#include <array>
#include <string>

#include "kinematics/chain.hpp"
#include "kinematics/vec3_ops.hpp"

namespace twinpost::kin {

/// The rotary angles of one orientation solution, in (-180, 180], before limits and unwinding.
struct orientation_solution {
  std::array<double, 2> rotary{};
  bool pole = false;  ///< the axis lay on the outer rotary axis: its angle was kept from `previous`
  /// Each axis's rotation as solved (the cosine and sine of its value), from the sides of the
  /// solve's angles: the transforms of the candidate need no sincos of their own.
  std::array<turn, 2> turns{};
};

/// At most two values, without allocation (an inverse runs once per CL point).
template <class T>
class two_at_most {
 public:
  void push_back(const T& v) { items_[count_++] = v; }
  std::size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  const T& operator[](std::size_t i) const { return items_[i]; }
  const T* begin() const { return items_.data(); }
  const T* end() const { return items_.data() + count_; }

 private:
  std::array<T, 2> items_{};
  std::size_t count_ = 0;
};

/// The solutions of R(outer)·R(inner)·t0 = `axis` (two, one where they coincide, none when no
/// rotation of the axes reaches it). Not yet checked by the forward transform. At the pole the
/// outer angle is `previous`'s.
two_at_most<orientation_solution> orientation_solutions(const kinematic_chain& c, const vec3& axis,
                                                        const joint_values& previous);

/// The linear joint values that put the tip of a tool of `tool_length` on `tip` with the
/// rotary axes at `angles` (`angles.linear` is ignored).
joint_values positions(const kinematic_chain& c, const vec3& tip, const joint_values& angles,
                       double tool_length);

enum class ik_error {
  none,
  zero_axis,        ///< the tool axis is not a direction (length 0, or not finite)
  bad_tip,          ///< the tool tip is not a point (not finite)
  unreachable,      ///< no rotation of the axes turns the tool to it
  beyond_limits,    ///< every solution has an axis outside its limits
  too_many_points,  ///< linearisation: the move needs more sub-moves than allowed
};

struct ik_result {
  ik_error error = ik_error::none;
  joint_values joints;  ///< the chosen solution, when error is none
  bool pole = false;    ///< the outer axis kept its previous angle
  /// The forward transform of `joints` against the request: tip (mm) and axis (degrees).
  double tip_error = 0, axis_error = 0;
  std::string message;  ///< why not, when error is not none
  bool ok() const { return error == ik_error::none; }
};

/// What an inverse must give: every joint (the tip checked by the forward transform too), or
/// the rotary angles alone (tool-tip control: the control places the tip; the axis checked).
enum class ik_need { joints, angles };

/// The joint values that put the tool of `tool_length` at `pose`, chosen as
/// docs/kinematics.md says from every solution within the limits, nearest to `previous`.
/// With ik_need::angles, `joints.linear` is left at 0 and `tip_error` is 0.
ik_result inverse(const kinematic_chain& c, const tool_pose& pose, double tool_length,
                  const joint_values& previous, ik_need need = ik_need::joints);
/// The same with the chain's plan made once by the caller (a post solves every CL point).
ik_result inverse(const chain_plan& p, const tool_pose& pose, double tool_length,
                  const joint_values& previous, ik_need need = ik_need::joints);

}  // namespace twinpost::kin
