#pragma once
// The arc blocks of one CIRCLE record against the CL's circle (issue 37; docs/emulator.md, "The
// comparison with the CL"): analysis/cl_compare reads the blocks, this holds them to the arc.
// Every block turns about the CL's circle axis the CL's way, about the CL's centre (I, J, K) or
// on its radius (R, negative exactly over half a turn); every block's end lies on the CL's
// circle; the blocks together go as far round as the CL's arc (TIMES,n full turns and on to
// its end); and along the axis each block goes its share of the CL's travel: one pitch over
// the whole sweep, as docs/records.md reads CIRCLE TIMES.
#include <span>
#include <string>

#include "parser/events.hpp"

namespace twinpost {

/// One arc block (G2/G3) of the program as the control reads it, in the part frame, mm.
struct nc_arc_block {
  bool ccw = false;  ///< G3
  int plane = 18;    ///< 17, 18, 19; 0: not known
  bool centre_known = false;
  vec3 centre;   ///< from I, J, K (the plane's normal axis not used)
  double r = 0;  ///< the R word in program units; 0: I, J, K given
  bool ends_known = false;
  vec3 start, end;
  std::string text;  ///< the block, for the message
};

/// How the program's frame stands to the part frame, and the tolerances.
struct arc_frame {
  double sx = 1;       ///< -1 on a mirrored X
  double zs = 1;       ///< -1 on a spindle with a reversed Z (Y and Z turned)
  double out_mm = 1;   ///< mm per program unit
  double cl_mm = 1;    ///< mm per CL unit
  double tol = 0.002;  ///< mm: a point's (the tip's tolerance, or the written words' units)
};

/// What is wrong with the record's arc blocks (`blocks`, in the order written) against the CL's
/// arc `a`, or "" when they follow it.
std::string arc_blocks_fault(std::span<const nc_arc_block> blocks, const arc_event& a, const arc_frame& f);

}  // namespace twinpost
