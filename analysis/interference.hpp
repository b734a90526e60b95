#pragma once
// Turret interference: no two tools in the same place at the same time (docs/interference.md).
//
// Each block of a channel that has an envelope ([[interference.channel]]) sweeps its tool tip
// over a box in the XZ plane of the workpiece spindle it works on, a live tool's too (its part
// is in that spindle): a line, the box of its ends; an arc, the box of the arc, its quadrant
// points included; a drilling cycle, from the start down to the hole's Z. Off the XZ plane
// (polar interpolation, Y) r is the tip's distance from the spindle axis. The channel's boxes (tool, turret
// or head body), fixed to the tip, ride along. Two blocks of two channels that may run at the same time
// (happens-before from the checker's rendezvous, as for the spindle rules: analysis/shared_resources) on the
// same spindle must keep the machine's clearance; every block must keep out of its spindle's static zones.
//
// Streaming: blocks are kept as swept tip boxes, consecutive ones merged while their union stays
// within a few millimetres, and each wait interval (segment) keeps at most a bounded number of
// boxes (neighbours are merged beyond it): memory is bounded by segments, not by blocks.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "check/nc_program.hpp"
#include "machines/machine.hpp"
#include "support/diagnostics.hpp"

namespace twinpost {

/// The box an arc of the tip sweeps, in (r, z): from (r_start, z_start) to (r_end, z_end) about
/// the centre (r_c, z_c); `cw`: clockwise seen with Z to the right and r up (G2 seen from +Y).
/// A full circle when start and end are one point.
xz_box arc_box(double r_start, double z_start, double r_end, double z_end, double r_c, double z_c, bool cw);

/// The box of an arc given by its radius (G2/G3 R): R > 0 the arc of at most 180 degrees, R < 0
/// the longer one; an R too short for the chord gives the box of the two ends.
xz_box arc_box_radius(double r_start, double z_start, double r_end, double z_end, double radius, bool cw);

/// The boxes of channel `e` around the swept tip box `tip` (r as programmed: X/2), in the frame
/// of the spindle: r mirrored for a lower turret (side -1).
std::vector<xz_box> envelope_boxes(const interference_channel& e, const xz_box& tip);

/// The distance between two boxes (0 when they touch or overlap).
double box_distance(const xz_box& a, const xz_box& b);

/// One finding of the rule, for a picture (the timeline page): the two blocks' envelopes in the
/// frame of their spindle, as the rule compared them.
struct interference_meeting {
  int channel_a = 0, channel_b = 0;
  std::string spindle;
  xz_box tip_a, tip_b;                         ///< the swept tip boxes, in the spindle's frame
  std::vector<xz_box> envelope_a, envelope_b;  ///< their envelopes' boxes
  double distance = 0;
  std::string file_a, file_b;
  int line_a = 0, line_b = 0;
};

/// Gives each diagnostic at a line of `files` that has no source line (the interference rule
/// keeps line numbers only) the line's text, reading the programs again when there is one.
void fill_source_lines(std::vector<diagnostic>& found, const std::vector<nc_source>& files, const machine& m);

/// Whether machine `m` has the interference rule on: two or more of its channels with an
/// envelope, or a static zone ([interference], docs/interference.md).
bool interference_checked(const machine& m);

/// The interference rule, fed block by block like analysis/shared_resources.
class spindle_states;
class modal_states;

class interference_check {
 public:
  /// `spindles`, `modes`: the reading's one spindle state and modal state
  /// (analysis/modal_state.hpp), which must have applied each block before block() is given it;
  /// they must outlive the rule.
  interference_check(const machine& m, const spindle_states& spindles, const modal_states& modes);
  ~interference_check();
  interference_check(const interference_check&) = delete;
  interference_check& operator=(const interference_check&) = delete;

  /// Whether the machine gives two or more channels an envelope (else the rule is off).
  bool active() const;
  /// Every block of every channel, in program order.
  void block(const nc_block& b);
  /// The channel passed wait `w`.
  void wait(const nc_wait& w);
  /// The findings, given the rendezvous of a sound check (sync_result::rendezvous); the static
  /// zones need no order and are checked however the waits paired.
  std::vector<diagnostic> finish(const std::vector<std::uint64_t>& rendezvous, bool waits_sound);
  /// The pairs of blocks finish() found, one per error of the pair rule, in the same order.
  const std::vector<interference_meeting>& meetings() const;

 private:
  struct impl;
  std::unique_ptr<impl> p_;
};

}  // namespace twinpost
