#pragma once
// What a G code of a channel's program does with its block's axis words, read from the machine
// file once (issue 37, "one owner of the NC words": the spindle rules, the interference rule,
// the control emulator and the rotary sweep each kept a list of the codes whose axis words are
// no move, and the first two read a Fanuc lathe's G92 threading and G90 turning cycles of
// G-code system A as a coordinate setting and a rapid: a thread cut on a stopped spindle, or
// beside the other turret, passed `check`). Every rule that asks what a G code makes of a
// block's X, Y, Z, U, W asks here.
#include <cstdint>
#include <vector>

#include "machines/machine.hpp"

namespace twinpost {

/// Which Fanuc G-code system a channel's program is in, read from the machine file as the
/// control's parameter would say: a channel whose X is no diameter is a machining centre's;
/// a lathe channel is in system C when the header selects the unit with G70 or G71 (and
/// neither G20 nor G21), in system B when the header gives G90 or G91 (the absolute and
/// incremental modes), else in system A (G90 and G91 are no modes there; U, W the increments).
enum class gcode_system : unsigned char { mill, a, b, c };

gcode_system gcode_system_of(const machine& m, const channel_def& ch);

/// What a G code makes of the axis words of its block.
enum class axis_words : unsigned char {
  modal,          ///< they move as the modal motion says (G17, G40, G54, G97 and every code not below)
  motion,         ///< G0, G1, G2, G3: the code sets the modal motion
  feed_move,      ///< a feed move of its own, once: threading (G32, G33, G34) and the machine's sync_feed
  hole_cycle,     ///< a drilling cycle: X, Y (or Z across the part) the hole, the tool returns to R or the
                  ///< initial level
  turning_cycle,  ///< a lathe's single cycle, modal as G1 is (A: G90 G92 G94; B: G77 G78 G79; C: G20 G21
                  ///< G24; the machine's own box thread, Mazak G292): to its end point and back to its start
  repetitive_cycle,  ///< a lathe's multiple repetitive cycle, once (G70-G76; in C G72-G78): its X, Z (or U,
                     ///< W) the end point, and back to its start; a roughing cycle's U and W are allowances
  none,       ///< no move: a dwell, data or coordinate setting, a macro call, a frame, scaling, a radius
  reference,  ///< G27, G28, G29, G30: the axes named go to (or come from) a reference point
  machine,    ///< G53: machine coordinates
};

/// The feed mode a G code selects.
enum class feed_kind : unsigned char { none, per_minute, per_rev, inverse_time };

/// The G codes of one channel, as its control reads them.
class nc_codes {
 public:
  nc_codes(const machine& m, const channel_def& ch);

  gcode_system system() const { return system_; }
  /// What G`g` does with its block's axis words.
  axis_words role(double g) const;
  /// G`g` cuts a thread (its F is the lead: it follows the spindle whatever the feed mode).
  bool threads(double g) const;
  /// The feed mode G`g` selects: the machine's codes.feed_per_min and feed_per_rev (every G
  /// word of them), the channel's chain's inverse_time; none for any other code.
  feed_kind feed_mode(double g) const;

 private:
  gcode_system system_ = gcode_system::mill;
  std::vector<int> holes_;    // the machine's own drilling cycle codes, ten times the G number
  std::vector<int> boxes_;    // its single lathe cycles (the thread's g92, g292)
  std::vector<int> cycles_;   // its repetitive ones (the thread's g76, g276; the groove's g75)
  std::vector<int> threads_;  // its threading codes: sync_feed and the thread cycle
  std::vector<int> per_min_, per_rev_, inverse_;  // its feed mode codes
};

}  // namespace twinpost
