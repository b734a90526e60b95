#pragma once
// The length offset's cancel away from home (docs/machines.md, "Length offset cancel").
//
// G49 cancels the tool length offset (G43, G43.4, G43.5, G44). A control that performs the
// cancel as a move then brings the tip to where the spindle nose was: Z moves towards the part
// by the tool's length. The cancel belongs after the home return (the Autodesk posts write
// G28 G91 Z0, G90, then G49). Per channel, a G49 while an offset is in force and the axes have
// moved since the last reference return (G28, G30) or machine-coordinate move of Z (G53 with Z
// or W) is a warning at the G49. A block that homes and cancels at once (G28 G91 Z0. G49) is
// at home. Streaming: a few flags per channel; while no channel has an offset in force only
// blocks with an H word are read (inline, no call), blocks without a G word only right after a
// home return.
#include <memory>
#include <vector>

#include "check/nc_program.hpp"
#include "support/diagnostics.hpp"

namespace twinpost {

class length_offset_rule {
 public:
  explicit length_offset_rule(std::size_t channels);
  ~length_offset_rule();
  length_offset_rule(const length_offset_rule&) = delete;
  length_offset_rule& operator=(const length_offset_rule&) = delete;

  /// Every block of every channel, in program order (nc_read_options::on_block).
  void block(const nc_block& b) {
    if (on_ == 0 && !b.may_have(nc_letter('H'))) return;  // most blocks of most programs
    read(b);
  }
  /// The warnings found, in the order of the blocks.
  std::vector<diagnostic> finish();

 private:
  void read(const nc_block& b);
  struct impl;
  std::unique_ptr<impl> p_;
  int on_ = 0;  // channels with a length offset in force
};

}  // namespace twinpost
