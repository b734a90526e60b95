#pragma once
// The operations of a job of two to four channels as the router finds them, and the waits the
// schedule puts between them (`--sync optimise`, issue 39, docs/wait-placement.md).
//
// An operation is a stretch of the CL that one head works alone: from a head switch to the
// next. A section is the part of the job between two barriers, which every channel meets
// whatever the policy: a part transfer (its two rendezvous) and the frame of a HEAD/BOTH
// section. Inside a section each channel runs its operations in the CL's order, and the plan
// says where the channels meet: each wait a meeting (channels/wait_schedule_n.hpp) of two or
// more of them, each after its first so many operations. Two channels meet at a rendezvous of
// both (channels/wait_schedule.hpp); three or four at waits that name the channels concerned
// (the 31i's `M200 P12`).
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "channels/wait_schedule.hpp"
#include "channels/wait_schedule_n.hpp"
#include "parser/events.hpp"

namespace twinpost {

/// One operation of one channel.
struct channel_op {
  int first_line = 0, last_line = 0;  ///< its CL records
  int segment = 0;                    ///< the channel's waits before it (as the pass wrote them)
  std::int64_t us = 0;                ///< its time (time_operations)
  // What it does to the part (note_operation_event), in mm in the part frame of its spindle:
  // the region its feed moves, arcs and cycle holes sweep (r: |CL x|, z), and the reach of the
  // tool that sweeps it.
  double r0 = std::numeric_limits<double>::infinity(), r1 = -std::numeric_limits<double>::infinity();
  double z0 = std::numeric_limits<double>::infinity(), z1 = -std::numeric_limits<double>::infinity();
  double reach = 0;
  unsigned parts = 0;  ///< bit 0: it cuts the part in the main spindle, bit 1: in the sub
  bool css = false;    ///< it cuts under constant surface speed
  /// It cuts on a spindle whose speed its channel never gave: at the other channel's setting
  /// (a drill without a SPINDL of its own beside a turning tool's G96).
  bool borrows_speed = false;
  bool unknown_tool = false;  ///< it cuts with a tool whose size no TLDATA or CUTTER gives
  /// The least radius a rapid took the tool to: a tool that comes to its cut from nearer the
  /// centre line works inside (a boring bar, whose shank lies across the bore: inside()).
  double rapid_r0 = std::numeric_limits<double>::infinity();
  bool retracts_inward = false;  ///< a cut that ends by feeding towards the centre line before a rapid
  bool stops = false;            ///< SPINDL/OFF: it stops the spindle of its part
  /// Per part (main, sub): the speed its channel set that spindle to where the operation cuts
  /// the part, in rpm, negative counter-clockwise; 0: none known (constant surface speed, or
  /// not set by its channel); NaN: more than one.
  double rpm[2] = {0, 0};
  bool exclusive = false;  ///< STOP, OPSTOP, AUXFUN, PREFUN, INSERT or a record passed through
};

/// What a channel's operations are noted with: where its tool is, which part it works on.
struct channel_track {
  double mm = 1;  ///< mm per CL unit
  vec3 last;
  bool has_last = false;
  unsigned part = 1;  ///< the part's spindle bit: 1 main, 2 sub
  bool css = false;   ///< the spindle in constant surface speed
  /// Per part (main, sub): the rpm this channel last set that spindle to (negative
  /// counter-clockwise), 0: none, or constant surface speed.
  double rpm[2] = {0, 0};
  /// An unnamed SPINDL sets the part's spindle: false on a channel with a live-tool spindle
  /// of its own (a mill head), where it may be the tool's.
  bool own_is_part = true;
  /// The part spindle (bit) this channel last turned: an unnamed SPINDL/OFF stops it, wherever
  /// the part has gone since (head 1's M5 after a transfer stops the bar's main spindle).
  unsigned turned = 0;
  unsigned speed_parts = 0;  ///< the parts' spindle bits whose speed (rpm or CSS) this channel gave
  double reach = 10;         ///< the tool's reach past its tip (mm): 10 until TLDATA says
  bool reach_known = false;  ///< a TLDATA or CUTTER gave the tool in use its size
  bool called = false;       ///< a tool call has been made
  bool moved = false;        ///< a move since the last tool call (a TLDATA then is the next tool's)
  double pending = -1;       ///< a TLDATA's reach for the next tool call
  double cycle = -1;         ///< a canned cycle's largest distance (mm) while one is on; -1: none
  /// 1: along the axis (drilling, tapping, boring); 2: grooving, threading and the rest
  int cycle_kind = 0;
  double last_dr = 0;  ///< the last feed move's change of radius (mm), until the next rapid
  bool fed = false;    ///< a feed move since the last rapid
};

/// Notes event `e` of channel track `t` in its operation `op`.
void note_operation_event(channel_op& op, channel_track& t, const event& e);

/// Whether an operation severs its part: its region reaches within 1 mm of the centre line
/// across more than 2 mm of radius (a part-off to the centre, slowing down or leaving a pip, a
/// groove cycle to the centre, an arc that ends there, a face). A drill on the axis does not.
bool severs_part(const channel_op& op);

/// Whether an operation works inside the part: a rapid took its tool no farther from the centre
/// line than its cuts begin, its cuts reach farther out, and a cut ends by
/// feeding back towards the centre line before the tool rapids away (a boring bar, an inside
/// chamfer; an outside finish with a lead-in retracts outwards). Its tool's body then fills
/// the bore down to the centre line (fixed_pairs counts its region from r = 0).
bool works_inside(const channel_op& op);

struct plan_section {
  /// Per side (job_operations::channels, in order): its operations.
  std::vector<std::vector<channel_op>> ops;
  /// Where the channels meet inside the section (none at its start or end), in an order each
  /// channel meets them in; a meeting names sides, not channel numbers.
  std::vector<meeting> waits;
  /// HEAD/BOTH's frame: one operation cut by both heads at once (a balance cut), which the
  /// control keeps in step. No pair of it is ever kept apart: waits inside it would stop one
  /// head of the pair.
  bool together = false;
};

/// The job's sections, in order, for its channels.
struct job_operations {
  /// The job's channels in order (two to schedule_max_channels); empty when it has no
  /// operations to plan (one channel, or more than the schedule takes). Its sides index this.
  std::vector<int> channels;
  std::vector<plan_section> sections;
  /// A new last section, with an empty list of operations per side.
  void add_section() {
    sections.emplace_back();
    sections.back().ops.resize(channels.size());
  }
  int operation_waits = 0;  ///< rendezvous placed inside stretches (channel_router::set_operation_waits)
  /// The job's own sync records kept (under optimise they bind: a section ends at each), counted
  /// once per pair.
  int kept_syncs = 0;
  /// The job has sync records of its own (any number of channels): a post that cannot place
  /// waits falls back to them (explicit), never to sequential, which would set them aside.
  bool has_sync_records = false;
};

/// A pair of operations of one section kept apart (wait_schedule's op_pair, in a section):
/// `pair.a` is side `p`'s operation, `pair.b` side `q`'s (p < q; a_first: p's first).
struct plan_pair {
  std::size_t section = 0;
  op_pair pair;
  int p = 0, q = 1;
  bool operator==(const plan_pair& o) const {
    return section == o.section && pair.a == o.pair.a && pair.b == o.pair.b && pair.rule == o.pair.rule &&
           p == o.p && q == o.q;
  }
};

/// Each operation's time: `seconds(side, segment)` is the time of that segment of the
/// channel's program as a sequential pass wrote it (side k: channels[k]). Operations that share
/// a segment (a stretch that wrote no block, with no wait after it) take nothing of it but the
/// last one.
void time_operations(job_operations& ops, const std::function<double(int side, int segment)>& seconds);

/// The pairs every schedule keeps in the CL's order, each with why (docs/wait-placement.md):
/// an operation that stops the program or writes codes the checks do not read runs alone;
/// an operation that cuts to the centre line from off it (a part-off, a face) is the only one
/// on its part, and so is one that stops the spindle or cuts with a tool of unknown size; two operations on
/// one part whose swept regions come within their tools' reach and `clearance_mm` of each other may cut the
/// same material (a finish after its rough, a part-off) or meet; two operations on one part under constant
/// surface speed each clamp the spindle's rpm; two on one part at different speeds (or
/// directions) that their channels set would each change the other's.
std::vector<plan_pair> fixed_pairs(const job_operations& ops, double clearance_mm);

/// Why fixed_pairs keeps pair `p` (a sentence; empty when it does not).
std::string fixed_pair_reason(const job_operations& ops, const plan_pair& p, double clearance_mm);

/// Of `pairs`, the indices of those no other implies (p's i before q's j is implied by p's i'
/// before q's j' with i' >= i and j' <= j: the channels keep their own order), in order.
std::vector<std::size_t> minimal_pairs(const std::vector<plan_pair>& pairs);

/// The waits of every section for the shortest cycle that keeps `pairs`, into `ops`. Two
/// channels: schedule_two_channels, with a rendezvous that orders every pair (a pair the
/// schedule keeps only by the operations' times gets one: the times are estimates, the order
/// must not depend on them). Three or four: schedule_channels, whose meetings keep every pair
/// whatever the times (`budget`: its search's). Returns the predicted cycle (the sections'
/// makespans and a handshake per barrier between them), or nullopt when the pairs contradict
/// each other or the search found no schedule.
std::optional<std::int64_t> plan_waits(job_operations& ops, const std::vector<plan_pair>& pairs,
                                       std::int64_t handshake_us, const schedule_budget& budget = {});

/// The pairs that keep the CL's order between the operations holding the CL lines `lines`
/// (a finding's error and notes): two operations of two channels in one section give one
/// pair; an operation whose partner is not among them keeps the CL's order with every
/// operation of the other channels in its section. Empty when no line is in an operation.
std::vector<plan_pair> pairs_for_lines(const job_operations& ops, const std::vector<int>& lines);

}  // namespace twinpost
