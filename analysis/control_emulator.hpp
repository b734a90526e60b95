#pragma once
// The control emulator (docs/emulator.md): each channel's modal state as the control would
// hold it, read from the program text and the machine file alone, and the invariants a
// program must keep whoever wrote it (twinpost, a user's [events] block or script, another
// post). It runs in `twinpost check` and in post's self-check, on the one block stream.
//
// State per channel: the work offset in force (G54-G59, G54.1 P.., a G92/G50 coordinate
// setting), the modal motion (G0-G3) and canned cycle, what the channel has commanded of each
// spindle (analysis/spindle_state: the reading's one spindle_states, which the timer, the
// spindle rules and the interference rule read too), each spindle's chuck (spindle.chuck_open/chuck_close),
// spindle synchronisation (codes.spindle_sync_on/off), and the part held by two spindles at
// once during a transfer.
//
// Invariants (each an error at the block, once per channel and kind):
// - a feed move (G1/G2/G3 or a drilling cycle with an axis word) with no work offset in force,
//   on a machine whose spindles name work offsets (spindle.work_offset);
// - a chuck opened while its spindle turns and the spindles are not synchronised;
// - a spindle started with its chuck open;
// - the chuck of the spindle a part was cut off from opened after the part-off (a feed to or
//   past the centre line, X <= 0, while the other spindle held the part): the bar would be
//   released;
// - a block that writes a variable the machine reserves (machines/macro_variables.hpp);
// - on a mill's kinematic chain, a rapid that turns a head with tool-tip control off and swings
//   the tip below the work's top (analysis/rotary_sweep.hpp).
//
// What it does not model yet (docs/emulator.md): the comparison with the CL; the order of
// blocks across channels (each channel is followed on its own: a chuck opened by one channel
// while another turns the spindle is the shared-spindle rules' matter); tool offsets and planes
// beyond the rotary sweep's.
#include <memory>
#include <vector>

#include "check/nc_program.hpp"
#include "machines/machine.hpp"
#include "support/diagnostics.hpp"

namespace twinpost {

/// Whether the emulator follows channel `channel`'s chain through every block (a mill's chain
/// with a head, analysis/rotary_sweep): it then reads the words of each of its blocks.
bool sweeps_chain(const machine& m, int channel);

class spindle_states;
class modal_states;

class control_emulator {
 public:
  /// `spindles`, `modes`: the reading's one spindle state (analysis/spindle_state.hpp) and modal
  /// state (analysis/modal_state.hpp), which must have applied each block before block() is
  /// given it; they must outlive the emulator.
  control_emulator(const machine& m, const spindle_states& spindles, const modal_states& modes);
  ~control_emulator();
  control_emulator(const control_emulator&) = delete;
  control_emulator& operator=(const control_emulator&) = delete;

  /// Every block of every channel, in program order (nc_read_options::on_block).
  void block(const nc_block& b);
  /// The findings, in the order of the blocks.
  std::vector<diagnostic> finish();

 private:
  struct impl;
  std::unique_ptr<impl> p_;
};

}  // namespace twinpost
