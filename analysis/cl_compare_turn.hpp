#pragma once
// The C-axis turns of one CL motion record against the CL's move (issue 37, "a rotary move
// whose tool-tip path passes below the channel's last safe height"; docs/emulator.md, "The
// comparison with the CL"): analysis/cl_compare reads the blocks, this follows the tip round
// the part's axis. A block that turns C turns the part under the tool: in the part frame the
// tip runs round the Z axis, not along the straight line the CL asked for. It may do so clear
// of the part, at or above the lower end of the CL's move (measured along the CL's tool axis:
// the height above the face for an axial tool, the distance from the axis for a radial one);
// and in a feed move it may not leave the CL's straight line at all.
#include <span>
#include <string>
#include <vector>

#include "parser/events.hpp"

namespace twinpost {

/// One block that turns C, as the control reads it: the tip before and after in the part frame
/// before the turn (the program's X, Y, Z in mm, the diameter and a reversed Z undone), and C
/// before and after, in degrees.
struct c_turn_block {
  vec3 start, end;
  double c0 = 0, c1 = 0;
  bool rapid = true;  ///< under G0 (else G1)
  std::string text;   ///< the block, for the message
};

/// The tip's path through `b` in the part frame: the axes and C moving together, linearly
/// (a rapid under Fanuc's linear-interpolation positioning; UNVERIFIED for a control whose
/// rapids move each axis at its own speed), one point a degree of C or closer.
void c_turn_path(const c_turn_block& b, std::vector<vec3>& out);

/// What is wrong with the record's C turns `blocks` against the CL's move from `from` (none
/// after a tool change: only `to` then) to `to` with the tool along `axis` (part frame, mm),
/// or "" when they keep to it. `feed`: the CL cuts from `from` to `to`, in a straight line;
/// `chord`: how far a fed tip may leave that line (mm); `tol`: the tip's tolerance.
std::string c_turn_fault(std::span<const c_turn_block> blocks, const vec3* from, const vec3& to,
                         const vec3& axis, bool feed, double chord, double tol);

}  // namespace twinpost
