#pragma once
// The comparison of a channel's program with its CL (issue 37; docs/emulator.md, "The
// comparison with the CL"). Fed the program's lines as they are written (the head's first)
// and each CL record of the channel once its blocks are written, it follows the program as
// the control reads it, from the text and the machine file alone (the G90/G91 mode, the
// incremental U/W of a lathe, the diameter X, a mirrored turret, the sub spindle's reversed Z
// read from its work offset or select code, G20/G21 and the output units, words without a
// decimal point in least increments, G28/G30/G53, a mill's length offset, the tool through the
// channel's tool-call template, the feed mode and F, the spindles), and at every CL motion
// record (GOTO, GODLTA, the end of a CIRCLE) holds what the machine would do to what the CL
// asked:
// - the tool tip in the part frame within 0.002 mm (or half the last written digit, when
//   coarser); an axis at its reference point since a G28/G30/G53 is a finding, and so is a
//   mill's Z with no length offset in force (the gauge line);
// - the tool the T word called and its offset (a mill's H);
// - a rapid among the blocks of a CL feed move (G0, or a G27-G30/G53 block);
// - at a cut, the spindle's direction, speed (rpm or CSS) and clamp, and the coolant;
// - a CIRCLE's arc blocks: each one's sense about the CL's axis, its centre or its R and its end
//   on the circle; together the CL's sweep (TIMES) at its one pitch (analysis/cl_compare_arc);
// - a G32 pass's lead against THREAD/TURN;
// - the feed: in the same mode, F within 0.5 % (or half the post's last digit); in the other
//   mode, F x rpm (or F / rpm) at the spindle's speed, CSS at the tip's diameter under its clamp;
// - S or F given as an expression, and a block under block delete, before a cut.
// - a CL cycle's hole: the canned cycle block's X, Y (turned by C), or a side cycle's Z;
// - an indexing head's tool axis for a live tool, against the CL's (analysis/cl_compare_axis);
// Records it cannot follow yet are passed over, not guessed: a HEAD/BOTH copy, a CL cycle's
// hole drilled with moves,
// and while the program has a canned cycle, polar or cylindrical interpolation, a rotated or
// tilted frame, polar coordinates, inverse-time feed, a threading cycle, a rotary-axis word
// since the last tool call that no indexing head or C axis explains, an indexing head's index until its
// length offset is given again, a C axis whose angle is not known, offsets written (G10, #5221=), a
// coordinate setting or a work offset no spindle names in force. A channel with a kinematic
// chain is followed through it (analysis/rotary_sweep's follower): the tip and the tool axis
// from its words by the forward transform; a mill/turn's indexing head: X Y Z are the tip at
// each index, in the frame C turned the part to, and the head's angle the tool's axis.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "machines/machine.hpp"
#include "nc/nc_words.hpp"
#include "parser/events.hpp"
#include "support/diagnostics.hpp"

namespace twinpost {

class channel_spindles;
struct channel_modes;

// (In a cache line of its own: the self-check's thread reads it at every block.)
class alignas(64) cl_comparison {
 public:
  /// Compares channel `ch` of `m`; findings go to `diags` at the CL record of `cl_file`.
  cl_comparison(const machine& m, const channel_def& ch, diagnostic_sink& diags, std::string cl_file);
  ~cl_comparison();
  cl_comparison(const cl_comparison&) = delete;
  cl_comparison& operator=(const cl_comparison&) = delete;

  /// Reads the channel's spindles and modal G state from the reading's (post's self-check:
  /// analysis/spindle_state, analysis/modal_state), which apply each block before block() is
  /// given it, instead of keeping its own; before the first line or block. They must outlive it.
  void follow(const channel_spindles* spindles, const channel_modes* modes) {
    spindles_ = spindles;
    modes_ = modes;
  }
  /// The next line of the channel's program as written (head, body), without its line end.
  void line(std::string_view text);
  /// The same, read already: line `line` (1-based) of the program, split into `words` with
  /// their `letters` (split_nc_words); lines without words may be left out, but not one that
  /// writes a variable (`#5221=-5.`: nc_read_options::on_macro, handed with no words).
  /// `text` may be quoted later: it must live until keep_texts() (the reader's bytes, kept
  /// until the piece they came in is read).
  void block(int line, std::string_view text, const std::vector<nc_word>& words, std::uint32_t letters);
  /// Copies what the comparison may still quote of the texts block() was given.
  void keep_texts();
  /// The job's units (UNITS record): the CL's lengths after it.
  void units(unit_system u);
  /// A record of the channel, after the blocks written for it. `both`: a HEAD/BOTH copy.
  void record(const event& e, bool both);
  /// Motion records compared, and those passed over (not followed yet).
  long compared() const;
  long passed_over() const;

 private:
  // Made by the first call, on the thread that feeds it (the self-check's, on two cores): its
  // state, written at every block, then comes from that thread's memory, never in a cache
  // line with the writer's (docs/design.md, "Two cores"); as the timeline's.
  struct impl;
  impl& made();
  void make();
  const machine& m_;
  const channel_def& ch_;
  diagnostic_sink& diags_;
  std::string cl_file_;
  const channel_spindles* spindles_ = nullptr;
  const channel_modes* modes_ = nullptr;
  std::unique_ptr<impl> p_;
};

}  // namespace twinpost
