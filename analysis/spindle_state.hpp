#pragma once
// What one channel's blocks have commanded of the machine's spindles, block by block: which
// spindle an S word goes to, each spindle's direction, speed mode (CSS or rpm), speed and
// clamp. Read from NC words with the machine's own codes ([[spindle]] cw/ccw/stop/select and
// clamp, [codes] css/rpm), so it reads any program of the machine, not only twinpost's.
// The input of the shared-spindle rules (analysis/shared_resources), the cycle time (feeds per
// revolution need the speed in rpm), the interference rule and the control emulator: on a
// reading they all read one `spindle_states`, applied once per block (issue 37, "one owner").
#include <algorithm>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include "machines/machine.hpp"
#include "nc/nc_words.hpp"

namespace twinpost {

/// `held`: the spindle is held as a C axis (spindle.c_on, Mazak M200) for live-tool work, so no
/// channel may turn it until c_off (M202) lets it go.
enum class spindle_turn : unsigned char { unknown, stopped, cw, ccw, held };
enum class speed_mode : unsigned char { unknown, css, rpm };

/// The M code of a spindle's c_on or c_off blocks (spindle.c_axis): the first block that is one
/// M word; -1 when none is. The 31i's c_on is `M35` then `G0 G28 H0.` (C to its reference):
/// M35 connects the C axis, so it is the hold.
int c_axis_code(const std::vector<std::string>& blocks);

/// One spindle as a channel's blocks have set it so far.
struct spindle_setting {
  spindle_turn turn = spindle_turn::unknown;  ///< unknown: not commanded by this channel yet
  speed_mode mode = speed_mode::unknown;      ///< the mode its speed was given in
  double speed = 0;                           ///< last S: rpm, or m/min (ft/min in G20) under CSS
  double clamp = 0;                           ///< highest rpm from the clamp block; 0: none given
  bool started() const { return turn == spindle_turn::cw || turn == spindle_turn::ccw; }
  bool operator==(const spindle_setting&) const = default;
};

/// What one block changed of one spindle.
struct spindle_change {
  int spindle = 0;  ///< index into machine::spindles
  spindle_setting before, after;
  int column = 0;  ///< column of the word that made the change (S, M or the mode G code)
};

/// What one block commands of one spindle, whether it changes the setting or repeats it (a
/// channel that writes `G97 S1200 M3` again still commands the spindle): the input of the
/// shared-spindle rules (analysis/shared_resources).
struct spindle_command {
  int spindle = 0;          ///< index into machine::spindles
  spindle_setting setting;  ///< the spindle as this channel has set it with the block
  bool turn = false;        ///< the block gives the direction or stops it (M3, M4, M5)
  bool speed = false;       ///< the block gives a speed (S) in the channel's speed mode
  bool mode = false;        ///< the block changes the speed mode only (G96 or G97 without S)
  bool clamp = false;       ///< the block sets the clamp (G50 S..)
  bool release = false;     ///< the stop is the spindle's c_off (the C axis let go: Mazak M202)
  int column = 0;           ///< column of the first word of the command
};

/// One channel's spindles, fed one block at a time.
class channel_spindles {
 public:
  channel_spindles(const machine& m, int channel);

  /// Applies one block's words; returns what it changed (empty for most blocks). The block
  /// order within a channel is program order.
  const std::vector<spindle_change>& apply(const std::vector<nc_word>& words);
  /// What the last block given to apply() commanded, changed or not.
  const std::vector<spindle_command>& commands() const { return commands_; }
  /// What the last block given to apply() changed.
  const std::vector<spindle_change>& changes() const { return changes_; }
  /// A block that cannot command a spindle (no G, M or S word where needs_gms()): it commanded
  /// and changed nothing, and apply() need not read it.
  void nothing_commanded() {
    changes_.clear();
    commands_.clear();
  }

  /// The spindle (index into machine::spindles) an S word without a spindle M-code goes to,
  /// and whose speed a feed per revolution follows: the last one this channel selected (its
  /// select code or its work offset, G54/G55) or turned, at first the channel's `spindle`. -1 when the
  /// machine has no spindles.
  int current() const { return current_; }
  const spindle_setting& setting(int spindle) const { return settings_[static_cast<std::size_t>(spindle)]; }
  /// The channel's speed mode (G96/G97 are modal per channel).
  speed_mode mode() const { return mode_; }
  /// True when every code apply() reads is a G, M or S word (the work offsets and the speed
  /// modes; the spindle codes are M and S anyway): a block without those letters changes
  /// nothing here.
  bool needs_gms() const;
  /// The rpm of the current spindle with the tool at `diameter` (in the program's unit; `inch`:
  /// G20, CSS in ft/min). CSS is turned into rpm at that diameter and held to the clamp and
  /// the spindle's max_rpm; 0 when the spindle is not turning or its speed is unknown.
  double rpm(double diameter, bool inch) const;
  /// Under CSS, the law rpm(d) = min(limit, k / d) of the current spindle (d in the program's
  /// unit; limit 0: none): false when it is not turning under CSS at a known speed.
  /// Inline: the timer asks it at every feed move under CSS.
  bool css_law(bool inch, double& k, double& limit) const {
    if (current_ < 0) return false;
    const spindle_setting& s = setting(current_);
    if (!s.started() || s.speed <= 0 || s.mode != speed_mode::css) return false;
    k = s.speed * (inch ? 12.0 : 1000.0) / std::numbers::pi;
    limit = cap();
    return true;
  }

 private:
  struct clamp_block {
    std::vector<nc_word> fixed;  // the words of the clamp template besides S{max}
  };
  const machine& m_;
  std::vector<spindle_setting> settings_;
  std::vector<clamp_block> clamps_;
  std::vector<spindle_change> changes_;
  std::vector<spindle_command> commands_;
  int current_ = -1;
  speed_mode mode_ = speed_mode::unknown;
  std::vector<nc_word> css_code_ = split_nc_words(m_.codes.css);  // G96, split once
  std::vector<nc_word> rpm_code_ = split_nc_words(m_.codes.rpm);  // G97
  /// Each spindle's c_on and c_off M-code (c_axis_code), -1 where none.
  std::vector<std::pair<int, int>> c_codes_ = [this] {
    std::vector<std::pair<int, int>> out;
    const auto code = c_axis_code;
    for (const spindle_def& s : m_.spindles) out.emplace_back(code(s.c_axis.on), code(s.c_axis.off));
    return out;
  }();
  std::vector<std::vector<nc_word>> offset_codes_ = [this] {  // each spindle's work offset
    std::vector<std::vector<nc_word>> out;
    for (const spindle_def& s : m_.spindles) out.push_back(split_nc_words(s.work_offset));
    return out;
  }();
  // The one-word codes apply() looks for besides M and S words (work offsets, G96, G97): a
  // block with none of them and no M or S word commands nothing (most moves with a G0/G1).
  std::vector<std::pair<char, double>> keys_;  // address and number (same_word: numeric ones only)
  std::uint32_t key_letters_ = 0;              // their addresses (nc_letter bits)
  bool keys_not_letters_ = false;  // a key's address is no letter (no bit): every word is looked at
  bool may_command(const std::vector<nc_word>& words) const;
  bool is_code(const std::vector<nc_word>& words, const std::vector<nc_word>& code, int& column) const;
  bool is_clamp(const std::vector<nc_word>& words, int spindle) const;
  void set(int spindle, const spindle_setting& to, int column);
  double cap() const {  // the current spindle's highest rpm: clamp and max_rpm; 0 none
    const spindle_setting& s = setting(current_);
    const double max = m_.spindles[static_cast<std::size_t>(current_)].max_rpm;
    const double cap = s.clamp > 0 ? s.clamp : max;
    return max > 0 ? std::min(cap, max) : cap;
  }
};

/// The one owner of every channel's spindle state on a reading: each block applied once, before
/// the consumers that read it (the timer, the spindle rules, the interference rule, the control
/// emulator) see the block. Before, each of them applied the codes to a copy of its own, and the
/// emulator only the blocks with an M word: a `G55` that sends the next `M3` to the sub (a
/// machine whose spindles share their M-codes) was lost to it.
class spindle_states {
 public:
  explicit spindle_states(const machine& m);
  /// Applies block `b` to its channel's spindles (a channel the machine does not have: nothing).
  /// Inline: every block of every reading comes here, and most have no G, M or S word.
  void block(const nc_block& b) {
    if (b.channel < 1 || static_cast<std::size_t>(b.channel) > channels_.size()) [[unlikely]]
      return;
    slot& s = channels_[static_cast<std::size_t>(b.channel - 1)];
    constexpr std::uint32_t gms = nc_letter('G') | nc_letter('M') | nc_letter('S');
    if (s.gms_only && !b.may_have(gms))
      s.spindles.nothing_commanded();
    else
      s.spindles.apply(b.words());
  }
  /// Channel `number`'s spindles, the block given last included (1-based; in range).
  const channel_spindles& channel(int number) const {
    return channels_[static_cast<std::size_t>(number - 1)].spindles;
  }

 private:
  struct slot {
    channel_spindles spindles;
    bool gms_only;  // needs_gms(): a block without G, M or S commands nothing
  };
  std::vector<slot> channels_;
};

}  // namespace twinpost
