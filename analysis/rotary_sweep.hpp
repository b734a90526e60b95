#pragma once
// A rotary move's tool-tip path (issue 37: "a rotary move whose tool-tip path (the forward
// transform between its end points) passes below the channel's last safe height"; item 7:
// head/head unwinds at the CAM's clearance). One channel with a kinematic chain, followed from
// its program text and the machine file alone: the linear and rotary axes (G90/G91, G20/G21,
// G28/G30 and G53 homes), the tool and its length offset, tool-tip control, the tilted plane
// (G68.2, G53.1, G69). A rapid that turns a head with tool-tip control off swings the tip: it
// is followed through the forward transform with every axis moving linearly from its start to
// its end, and it may not pass below the work's top (the channel's last safe height read from
// the program alone: the highest the program has fed a tool from or to), less a link's sag.
// With Z at home the tool is clear; under tool-tip control the control keeps the tip where it
// is; a table turns the part, whose size no program says: not held.
//
// The tool's length is the H register's, which the program does not say: the machine file's
// [[tool]] length of the T word's tool, else 0: the gauge point's path (a head's swing is then
// its pivot's alone, smaller than the tip's). Post and check find the same.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "machines/machine.hpp"
#include "nc/nc_words.hpp"

namespace twinpost {

struct channel_modes;

class rotary_sweep {
 public:
  /// `chain` is the channel's (machine::chain), with at least one rotary axis.
  /// `change_m`: the M code of the channel's tool change (M6), -1 where a T word changes it.
  /// `follow_only`: follow the axes for where() alone (the comparison with the CL), neither
  /// the swings nor the work's top (block() then finds nothing).
  rotary_sweep(const machine& m, const kinematic_chain& chain, int channel, int change_m,
               bool follow_only = false);
  ~rotary_sweep();
  rotary_sweep(rotary_sweep&&) noexcept;
  rotary_sweep& operator=(rotary_sweep&&) noexcept;

  /// The channel's next block; a finding's message (without "channel n: ") and the column of
  /// the word it is at, when this block's rapid swings the tip into the work. `modes`: the
  /// channel's modal state with the block applied (analysis/modal_state), whose G90/G91, unit
  /// and drilling return level the sweep reads.
  std::optional<std::pair<int, std::string>> block(const std::vector<nc_word>& words,
                                                   const channel_modes& modes);

  /// The tool tip and the tool's axis (tip to holder), in the part frame (mm).
  struct pose {
    vec3 tip, axis;
  };
  /// Where the blocks so far have put the tip of a tool `length` mm long and which way it
  /// points, as the control reads them: the linear words under the length offset (G43) through
  /// the forward transform with the rotary words, under tool-tip control (G43.4) the words
  /// themselves, in a tilted plane (G68.2, G53.1) its coordinates turned into the part frame.
  /// None where a word it needs is not known, in a drilling cycle, under G43.5 (its I J K are
  /// not followed), or with no length offset in force.
  std::optional<pose> where(double length) const;
  /// In follow-only mode: where the tip is a fraction `t` (0..1) along the last block, every
  /// axis moving linearly from where the block started, as a control interpolates the joints;
  /// none under tool-tip control, I J K or a tilted plane, where an end is not known, or when
  /// the block turned no rotary axis (the tip then runs straight between its ends).
  std::optional<pose> where_along(double length, double t) const;
  /// Every rotary axis at 0 and no tilted plane: the linear words are the tip, as on a
  /// three-axis machine.
  bool upright() const;
  /// The tool's axis the rotary words give (a drilling cycle's too); none where one is not
  /// known, or under G43.5.
  std::optional<vec3> axis_now() const;
  /// A tool length offset in force: the chain's length or tool-tip code, or the tool call of a
  /// control that gives it there (joints output with no `length_on`).
  bool length_on() const;
  /// Tool-tip control in force (the chain's code, G43.4 or G43.5).
  bool tool_tip_on() const;

 private:
  struct impl;
  std::unique_ptr<impl> p_;
};

}  // namespace twinpost
