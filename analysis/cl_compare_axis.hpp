#pragma once
// The tool axis an indexing head gives a live tool, against the CL's (issue 37: "the tool axis
// (0.001°)" at every CL motion record, and "a tool that cuts with its axis not where the B head
// was last indexed for it"; docs/emulator.md, "The comparison with the CL"). analysis/cl_compare
// follows the head's angle word and the C axis; this turns them into a direction in the part
// frame and measures it against the CL's.
#include <optional>
#include <string>
#include <string_view>

#include "machines/millturn_rules.hpp"
#include "support/vec3.hpp"

namespace twinpost {

/// How a head's angle word points the tool, read from [channel.head_index] alone: the head
/// turns about Y, the tool (tip to holder) along +Z at the `axial` angle and along +X (across
/// the spindle axis, from the head's side) at the `radial` one, a quarter turn apart: the
/// Integrex's B0 and B90, the 31i path 3's B-90 and B0. A file whose two angles are not a
/// quarter turn apart (or not both given) says nothing the comparison can read: `known()` false.
struct head_turn {
  double axial = 0, scale = 0;  // the turn from +Z towards +X: (angle - axial) x scale, degrees

  static head_turn of(const head_index_rules& h);
  bool known() const { return scale != 0; }
  /// The tool's direction (tip to holder) in the machine's frame with the head at `angle`.
  vec3 machine_axis(double angle) const;
};

/// The machine frame's direction `a` in the part frame: X's sign `sx` (-1 on a mirrored
/// turret), Y's and Z's `zs` (-1 on a spindle that faces the main one: a half turn about X),
/// then turned by the C angle `c_deg` (the part's x, y are the program's turned by +C about Z).
vec3 part_axis(const vec3& a, double sx, double zs, double c_deg);

/// What is wrong with the tool's direction `have` (part frame) against the CL's `want` (any
/// length), or none within `tolerance` degrees: "the program's <who> the tool along (...)"
/// (`who`: "head points", "rotary axes point") and how far off, for the comparison's message.
std::optional<std::string> axis_fault(const vec3& have, const vec3& want, double tolerance,
                                      std::string_view who);

}  // namespace twinpost
