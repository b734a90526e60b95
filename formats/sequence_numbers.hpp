#pragma once
// The N numbers of one channel's section, counted in the order its blocks are written:
// header blocks, body, footer blocks and the end code, from program.sequence_start by
// sequence_step. Past the largest number the control's N format reads (N5: 99999) they
// start again at sequence_start, as the public Fanuc-family posts do (Autodesk Fusion
// "Doosan Mill/Turn" and "Mazak Integrex i": `if (sequenceNumber > 99999)` restarts the
// count); a number is a search target for a restart, and a control finds the first match.
// With program.sequence_numbers = "tool_change" only tool calls, the restart points, are
// numbered (the Fusion posts' "Only on tool change").
#include <string>

#include "machines/machine.hpp"

namespace twinpost {

class sequence_numbers {
 public:
  sequence_numbers(const program_format& p, const word_format& n);
  /// "N10 " for the next block (and counts it), or "" when such a block is not numbered.
  /// `restart`: the block is a restart point (a tool call).
  std::string next(bool restart = false);

 private:
  long start_, step_, max_, next_;
  bool on_ = false;           // numbering at all
  bool every_block_ = false;  // all blocks, not only restart points
};

}  // namespace twinpost
