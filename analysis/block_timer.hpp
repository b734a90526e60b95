#pragma once
// The time of each block of one channel's program, read modally as the control reads it:
// G0/G1/G2/G3 and G32 threads, absolute/incremental (G90/G91, and U/W on a Fanuc-style
// lathe), X as a diameter where the channel's axis says so, G20/G21, feed per minute or per
// revolution (the machine's codes; the rpm from analysis/spindle_state, CSS at the tool's
// diameter), dwells (codes.dwell tells the address and unit), tool calls, M codes and waits
// (machine [timing]). docs/timeline.md has the rules and what is not timed.
//
// Canned cycles are timed from their words as the moves the control makes of them
// (analysis/block_cycles.cpp: drilling, pecking, tapping and boring along the hole's axis,
// the lathe's thread and grooving cycles).
//
// A block it cannot time honestly (a cycle it does not know, a reference return, a move from
// an unknown position, a feed per revolution on a stopped spindle ...) is timed 0 and named in
// block_timing::untimed: the caller counts and reports it, never silently.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/modal_state.hpp"
#include "analysis/nc_codes.hpp"
#include "analysis/spindle_state.hpp"
#include "machines/machine.hpp"
#include "nc/nc_words.hpp"

namespace twinpost {

/// What one block costs.
/// A G code as an integer in tenths, G1 as 10 and G84.2 as 842, so that a block's codes are
/// compared as numbers (no control has a code of two decimals).
consteval int g_code(std::string_view code) {
  int v = 0, decimals = -1;
  for (const char c : code) {
    if (c == '.') {
      decimals = 0;
      continue;
    }
    v = v * 10 + (c - '0');
    if (decimals >= 0) ++decimals;
  }
  return decimals <= 0 ? v * 10 : v;
}

/// The code as the program writes it after `prefix`: 10 "1", 842 "84.2" (with "G": "G84.2").
inline std::string g_code_text(int g, std::string_view prefix = {}) {
  const int a = g < 0 ? -g : g;
  std::string s(prefix);
  if (g < 0) s += '-';
  s += std::to_string(a / 10);
  if (a % 10 != 0) {
    s += '.';
    s += static_cast<char>('0' + a % 10);
  }
  return s;
}

struct block_timing {
  double seconds = 0;      ///< time of the block (0 when untimed)
  double motion = 0;       ///< of which moving (rapid, feed, thread)
  bool rapid = false;      ///< the motion was a rapid
  std::string untimed;     ///< why the block (or its motion) is not timed: "G83", "G28", ...; empty: timed
  bool tool_call = false;  ///< the block calls a new tool
};

/// One channel's blocks, fed in program order.
class block_timer {
 public:
  block_timer(const machine& m, int channel);

  /// Applies one block (the physical line) and returns its time.
  block_timing time(std::string_view text);
  /// The same for a block already split (the reader's nc_block: words and their letters, which
  /// must be exact: split_nc_words' own, not nc_block::letters() before the split).
  /// `spindles`, when given: the channel's spindles with this block applied already (the
  /// reading's spindle_states); the timer then keeps no spindle state of its own. `modes`, when
  /// given: the same for the modal state (the reading's modal_states), which gives the unit,
  /// absolute or incremental, the plane and the feed mode; else the timer keeps its own.
  block_timing time(const std::vector<nc_word>& words, std::uint32_t letters,
                    const channel_spindles* spindles = nullptr, const channel_modes* modes = nullptr);
  /// The seconds a wait code costs (machine [timing] wait).
  double wait_seconds() const { return ch_->timing.wait; }
  /// The tool in force, as the program calls it ("T03"); empty before the first call.
  const std::string& tool() const { return tool_; }

 private:
  struct axis_pos {
    char address = 0;
    bool diameter = false;
    bool rotary = false;
    double rate = 0;              // rapid, axis unit per minute (mm/min, deg/min)
    std::optional<double> value;  // as programmed (diameter for a diameter X), in program units
  };
  const machine& m_;
  const channel_def* ch_ = nullptr;
  channel_spindles own_spindles_;                      // applied by time() when it is not given a reading's
  const channel_spindles* spindles_ = &own_spindles_;  // the one the block being timed reads
  modal_states own_modes_;                             // the same for the modal state
  program_units units_;                                // the unit codes (no time of their own)
  int channel_ = 1;                                    // the channel timed (own_modes_'s)
  bool modes_read_ = false;                            // the modes were taken once (then at G words)
  std::string turning_text_;  // a single cycle of G-code system B or C in force ("G20"): not timed
  std::vector<axis_pos> axes_;
  bool lathe_a_ = false;  // Fanuc-style lathe: G90/G92/G94 are cycles, U/W incremental
  bool incremental_ = false;
  bool inch_ = false;
  bool per_rev_ = false;
  int plane_ = 18;                  // 17, 18, 19
  std::string motion_code_;         // the modal motion as a code, "G1" (made once, not at every move)
  bool plain_motion_codes_ = true;  // G0-G3 are only motions (no feed mode of the machine's)
  int motion_num_ = -1;             // the modal motion: 0, 1, 2, 3, 32 (G32/G33); -1: none yet
  void set_motion(int g) {
    motion_num_ = g / 10;
    // G0-G3 change at most blocks with a G word: their texts are made once.
    if (g >= 0 && g <= g_code("3") && g % 10 == 0)
      motion_code_ = plain_motion_texts_[static_cast<std::size_t>(g / 10)];
    else
      motion_code_ = g_code_text(g, "G");
  }
  const std::array<std::string, 4> plain_motion_texts_ = {
      g_code_text(g_code("0"), "G"), g_code_text(g_code("1"), "G"), g_code_text(g_code("2"), "G"),
      g_code_text(g_code("3"), "G")};
  int cycle_ = -1;  // a modal cycle in force (G83, or G90 on a Fanuc lathe, as g_code); -1: none
  double feed_ = 0;
  // The CSS law of the last feed move under CSS (feed_time): its k (rpm = k / d), clamp and F,
  // the diameter below which the clamp holds, and seconds per mm of path and mm of diameter.
  struct css_law_kept {
    double k = -1, limit = -1, feed = -1, clamped_below = 0, seconds_per = 0;
  } css_;
  std::string tool_;
  int tool_number_ = -1;
  char tool_address_ = 'T';
  long tool_divisor_ = 1;  // T0303 with {tool:02}{offset:02}: the tool is T / 100
  char dwell_address_ = 0;
  double dwell_unit_ = 1;      // seconds per unit of the dwell word
  nc_codes codes_;             // the channel's G codes (its feed modes), analysis/nc_codes
  bool inverse_time_ = false;  // G93: F is 1/min
  // Mill/turn modes ([milling]): X in radius while the spindle is a C axis, and C a linear
  // axis (the plane's second one, mm) in polar interpolation.
  bool radius_x_ = false, polar_ = false;
  std::vector<std::vector<nc_word>> radius_on_, radius_off_, polar_on_, polar_off_;
  // Cylindrical interpolation (milling.cylindrical_on, "G7.1 C{radius}"): the block's other
  // words, the address of the size and what it is per radius; C's degrees are then arc length
  // on a cylinder of cylinder_r_ (0: off, "G7.1 C0").
  std::vector<nc_word> cylinder_code_;
  char cylinder_address_ = 0;
  double cylinder_per_r_ = 1, cylinder_r_ = 0;
  /// True (and the mode set) when the block is one of the machine's mill/turn mode blocks.
  bool milling_mode(const std::vector<nc_word>& words);
  std::vector<nc_word> words_;                     // the block's words when given as text (reused)
  bool spindles_need_gms_ = false;                 // a block without G, M or S cannot change a spindle
  std::vector<std::optional<double>> target_;      // where the block sends each axis (reused)
  std::vector<std::optional<double>> leg_target_;  // where a cycle's move sends each axis (reused)

  axis_pos* axis(char a) {
    const unsigned char u = static_cast<unsigned char>(a);
    return u < axis_at_.size() && axis_at_[u] >= 0 ? &axes_[static_cast<std::size_t>(axis_at_[u])] : nullptr;
  }
  // axes_'s index of each address, -1 where the channel has no such axis: one look-up per
  // word of every block, where a search of axes_ cost a loop.
  std::array<std::int8_t, 128> axis_at_{};
  // The axis a word's address moves (axis_at_, with a Fanuc lathe's U/W/V as X/Z/Y) and whether
  // it is incremental by its address alone.
  std::array<std::int8_t, 128> word_axis_{};
  std::array<bool, 128> word_incremental_{};
  int x_index_ = -1;        // axes_'s last X (the diameter of CSS), -1: none
  bool has_modes_ = false;  // the machine has mill/turn mode blocks (milling_mode has work)
  // Fixed by the channel's axes (set once): X in diameter, and whether U, W, V are axes of
  // their own or a Fanuc lathe's incremental X, Z, Y.
  bool lathe_x_ = false, has_u_ = false, has_w_ = false, has_v_ = false;
  double to_mm(double v) const { return inch_ ? v * 25.4 : v; }
  double move_time(const std::vector<std::optional<double>>& target, bool rapid, const std::string& code,
                   const std::vector<nc_word>& words, block_timing& t, bool sync = false);
  double feed_time(double length, double x0, double x1, block_timing& t, const std::string& code,
                   bool sync = false);

  // --- canned cycles (block_cycles.cpp) ---
  /// One move of a cycle: the axes it sends somewhere (program units, X as programmed).
  enum class leg_kind : unsigned char { rapid, feed, sync };
  struct cycle_state {
    std::optional<double> initial;    // the hole axis where the drilling cycle began
    std::optional<double> r, bottom;  // modal R level and bottom of the drilling cycle
    bool return_r = false;            // G99 where G98/G99 are return levels: back to R (the modal state's)
    // G76 (Fanuc lathe) first block: finishing passes, tool angle, least cut, allowance (mm)
    bool thread_set = false;
    int finish_passes = 1;
    double tool_angle = 60, min_cut = 0, allowance = 0;
    double groove_return = 0;            // G74/G75 first block R(e), mm
    std::optional<double> box_z, box_r;  // modal Z and R of G92/G292
  } cyc_;
  /// Times the cycle block `g` (g_code("83"), g_code("292")) from its words; false when it is not a cycle
  /// this knows (the caller names it untimed). `target`: where the block's axis words send each axis.
  bool time_cycle(int g, const std::vector<nc_word>& words, const std::vector<std::optional<double>>& target,
                  block_timing& t);
  bool drill_cycle(int g, const std::vector<nc_word>& words, const std::vector<std::optional<double>>& target,
                   block_timing& t);
  bool thread_cycle(int g, const std::vector<nc_word>& words, block_timing& t);
  bool groove_cycle(int g, const std::vector<nc_word>& words, block_timing& t);
  /// Moves axis `a` (and `b`, when given) to `va` (`vb`); adds its time to t.motion. False
  /// (and t.untimed set) when it cannot be timed.
  /// The modal cycle ends (G80, a motion code): its levels are forgotten.
  void end_cycle() {
    cycle_ = -1;
    cyc_.initial.reset();
    cyc_.r.reset();
    cyc_.bottom.reset();
    cyc_.box_z.reset();
    cyc_.box_r.reset();
  }
  bool leg(leg_kind k, char a, double va, block_timing& t, const std::string& code, char b = 0,
           double vb = 0);
  /// The same to leg_target_ (every axis where it says).
  bool leg_to_target(leg_kind k, block_timing& t, const std::string& code);
  /// mm (or inch) of a word the control reads in least increments when it has no point.
  double increments(const nc_word& w, double v) const;
  double arc_length(const std::vector<std::optional<double>>& target, const std::vector<nc_word>& words,
                    bool cw) const;
};

}  // namespace twinpost
