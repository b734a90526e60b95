#pragma once
// The reading's one modal state of each channel's G codes (issue 37, "one owner of the NC
// words and the modal state"): the motion, the canned cycle in force, absolute or incremental,
// the unit, the plane, the feed mode and polar interpolation, as the channel's control reads
// them (the machine's codes: analysis/nc_codes, analysis/program_units), and what the block's
// own G words did. The reading applies each block once, before the rules read it, as it does
// the spindle state (analysis/spindle_state): the control emulator, the interference rule, the
// timer, the rotary sweep and (in post's self-check) the comparison with the CL read it, where
// each kept a modal motion, cycle, unit or G90/G91 of its own by rules of its own (a G80 ended a
// lathe's single cycle for one and not for another; the interference rule read no G91, the
// timer no G70/G71). Docs: docs/emulator.md, "One owner".
#include <cstdint>
#include <vector>

#include "analysis/nc_codes.hpp"
#include "analysis/program_units.hpp"
#include "machines/machine.hpp"
#include "nc/nc_words.hpp"

namespace twinpost {

/// What one block's G words did (analysis/nc_codes' roles).
struct block_g_codes {
  bool any = false;                 ///< the block has a G word
  bool motion = false;              ///< G0, G1, G2 or G3
  bool cycle = false;               ///< a drilling cycle or a lathe's single cycle (modal)
  bool once = false;                ///< a lathe's repetitive cycle (G70-G76): its own moves, once
  bool feed_move = false;           ///< a feed move of its own (threading G32, the sync feed)
  bool no_move = false;             ///< a dwell, data or coordinate setting, macro call, frame
  bool reference = false;           ///< G27-G30: to or from a reference point
  bool machine = false;             ///< G53: machine coordinates
  bool coordinate_setting = false;  ///< G92 or G50 that sets coordinates (not a cycle or a clamp's)
  bool work_offset = false;         ///< G54-G59 or G54.1
  bool data = false;                ///< G10, G65, G66 or G66.1: the block's words are data or arguments
  bool units = false;               ///< a unit code (G20/G21, system C's G70/G71)
  bool polar = false;               ///< G12.1/G112 or G13.1/G113
};

/// One channel's modal G state after the block last applied.
struct channel_modes {
  int motion = -1;             ///< the modal motion: 0, 1, 2, 3 (G0-G3), 32 (threading); -1: none yet
  bool hole_cycle = false;     ///< a drilling cycle is modal (until G80 or a motion code)
  bool turning_cycle = false;  ///< a lathe's single cycle is modal (until a motion code)
  bool incremental = false;    ///< G91 until G90 (system A's G90 is a cycle; its G91, an alarm, read as B's)
  bool inch = false;           ///< the program's unit is the inch (G20, system C's G70)
  int plane = 0;               ///< 17, 18, 19; 0: none given
  feed_kind feed = feed_kind::none;  ///< the feed mode a code selected; none: none given
  bool polar = false;                ///< polar interpolation (G12.1/G112 until G13.1/G113)
  /// G99 where G98 and G99 are the drilling cycles' return levels (no feed modes): back to R;
  /// G98 (and before either): to the initial level.
  bool return_to_r = false;
  block_g_codes now;  ///< the last block's G words

  /// A canned cycle is modal: the block's axis words place a hole or a cycle's end point.
  bool in_cycle() const { return hole_cycle || turning_cycle; }
};

class modal_states {
 public:
  explicit modal_states(const machine& m);

  /// Applies one block (every block of every channel, in program order; before the rules).
  void block(const nc_block& b) {
    if (b.channel < 1 || static_cast<std::size_t>(b.channel) > channels_.size()) [[unlikely]]
      return;
    slot& s = channels_[static_cast<std::size_t>(b.channel - 1)];
    if (s.modes.now.any) s.modes.now = {};
    if (b.may_have(nc_letter('G'))) apply(s, b.words());
  }
  /// The same for a block of channel `channel` already split into `words` (with their exact
  /// `letters`): a timer that reads one channel on its own (analysis/block_timer).
  void block(int channel, const std::vector<nc_word>& words, std::uint32_t letters) {
    slot& s = channels_[static_cast<std::size_t>(channel - 1)];
    if (s.modes.now.any) s.modes.now = {};
    if (letters & nc_letter('G')) apply(s, words);
  }
  /// Channel `number`'s state (1-based), with the last block applied.
  const channel_modes& channel(int number) const {
    return channels_[static_cast<std::size_t>(number - 1)].modes;
  }
  /// Its G codes (analysis/nc_codes).
  const nc_codes& codes(int number) const { return channels_[static_cast<std::size_t>(number - 1)].codes; }

 private:
  struct slot {
    slot(const machine& m, const channel_def& ch) : codes(m, ch) {}
    nc_codes codes;
    channel_modes modes;
  };
  void apply(slot& s, const std::vector<nc_word>& words) const;
  program_units units_;
  std::vector<slot> channels_;
};

}  // namespace twinpost
