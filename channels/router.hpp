#pragma once
// Routes the CL event stream to the machine's channels and places the waits.
//
// - HEAD/n, HEAD/MAIN|SIDE select the channel that serves that head (machine map);
//   CHANNEL,n / CHANNL/n select channel n; events before the first selection go to head 1.
// - HEAD/BOTH: a wait in both channels, the following events go to both, and another wait
//   when a single head is selected again. Balance cutting turns one spindle with one master,
//   the channel of head 1: a SPINDL between HEAD/BOTH and the section's first other record
//   goes to the master alone, before the opening wait (so the spindle turns before either
//   channel cuts); a later one goes to both, and the copy writes no spindle code
//   (channel_writer::set_balance_master).
// - Waits come from explicit sync records (CATIA SYNC, ICAM SYNCTR, MANUSpost UDE), under
//   the sequential policy from every head switch, or under optimise from a plan
//   (channels/wait_plan.hpp): the router finds the job's operations and sections for a
//   two-channel job under any policy (operations()), and places a plan's waits between them. A wait's code
//   comes from the machine's range in turn; the k-th explicit sync of a channel gets the code of that sync
//   number. Under optimise the job's own sync records bind: each is a barrier of the two channels at its
//   place in each (a section ends there), and the plan's waits go between them.
// - Job-level events (PARTNO, UNITS, MACHIN) go to channel 0.
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "channels/sync_policy.hpp"
#include "channels/wait_allocator.hpp"
#include "channels/wait_plan.hpp"
#include "machines/machine.hpp"
#include "parser/events.hpp"
#include "support/diagnostics.hpp"

namespace twinpost {

/// A wait placed in a channel.
struct wait_mark {
  int code = 0;
  std::vector<int> partners;  ///< all channels taking part, ascending, own channel included
  std::string partner_text;   ///< the P value in the machine's style, "" when none
  int cl_line = 0;            ///< the CL record that caused it
  /// The wait opens or closes a HEAD/BOTH (balance cutting) section.
  enum class section { none, opens_both, closes_both } both = section::none;
  /// The last rendezvous, before the programs' footers: the CL's work is over.
  bool ends_job = false;
};

/// Receives the routed stream.
class channel_sink {
 public:
  virtual ~channel_sink() = default;
  /// An event for channel `ch` (0 = the job as a whole). `both`: a HEAD/BOTH copy.
  virtual void on_event(int ch, const event& e, bool both) = 0;
  /// A wait for channel `ch`.
  virtual void on_wait(int ch, const wait_mark& w) = 0;
};

class channel_router {
 public:
  /// `policy` must be explicit_marks, sequential or optimise here (automatic is resolved by the
  /// caller); optimise needs set_plan before the first event.
  /// `job_channels`: the channels the job uses (a sync naming no channels means these).
  channel_router(const machine& m, sync_policy policy, channel_sink& sink, diagnostic_sink& diags,
                 std::string file, std::vector<int> job_channels);

  /// Routes one event.
  void route(const event& e);
  /// Closes an open HEAD/BOTH section at the end of the job.
  void finish(int last_line);
  /// Waits placed, counted once per rendezvous.
  int rendezvous() const { return rendezvous_; }
  /// Explicit sync records seen.
  int explicit_marks() const { return explicit_; }
  /// The job's operations and sections as routed (a job of two channels; a = b = 0 otherwise),
  /// each operation with the channel's waits before it.
  const job_operations& operations() const { return ops_; }
  /// The waits to place under the optimise policy: a plan made from operations() of an earlier
  /// routing of the same job. One that does not fit the job is an error (an optimiser fault).
  void set_plan(const job_operations* plan) {
    plan_ = plan;
    track_ = track_ || plan;
  }
  /// A rendezvous at every operation boundary inside a head's stretch too (a tool change, a
  /// spindle stop): the sequential post that times each operation on its own.
  void set_operation_waits(bool on) {
    op_waits_ = on;
    track_ = track_ || on;
  }
  /// The job's sync records set aside, without a word: the posts that work out what the
  /// optimise policy would give a job that has its own (post --compare-optimum).
  void set_aside_sync(bool on) { aside_sync_ = on; }
  /// Whether operations() is kept (set_plan and set_operation_waits keep it): off, the router
  /// does no work per event for it.
  void track_operations(bool on) { track_ = on; }

 private:
  void select(std::vector<int> channels, int line, bool both);
  /// A wait in every channel of `channels`, unless none has worked since its last wait
  /// (consecutive marks collapse) and `force` is off.
  void rendezvous(const std::vector<int>& channels, int line, const std::string& what, bool force = false,
                  wait_mark::section both = wait_mark::section::none);
  void explicit_sync(const sync_event& s, int line);
  /// A sync record under --sync optimise (its timing post and its planned post): it binds, a
  /// barrier of the job's channels at its own place in each; the plan's waits go between.
  void bound_sync(const sync_event& s, int line, const std::vector<int>& partners);
  /// The wait of sync record `key` (sync number, occurrence) in channel `ch`: the code of that
  /// key, allocated at its first record; false when no code is left (said).
  bool sync_wait(int ch, std::pair<int, int> key, const std::vector<int>& partners, int line);
  /// The section of side `side` ends here (its remaining planned waits placed), its next begins.
  void side_break(int side, int line);
  /// A bound sync record one channel has passed and another not (said as an error): true.
  bool unmet_sync(int line, bool at_end);
  /// TRANSFER/GRIP or RELEASE: every channel retracts, a rendezvous of all, the machine's
  /// transfer channel writes its blocks, a rendezvous of all; after a release every channel
  /// works on the sub spindle.
  void transfer(const event& e, const transfer_event& t);
  /// The mark `s` in channel `ch`: its own number, or for an ICAM marker left out the
  /// channel's last marker plus one. The router is the one owner of this numbering.
  int marker_of(const sync_event& s, int ch) const;
  void error(int line, std::string message);
  /// An event for channel `ch`: the first of a stretch starts an operation, and so does a tool
  /// change or a spindle stop after a record that wrote (`writes`: this one writes a block).
  void deliver(int ch, const event& e, bool both, bool writes);
  void send_wait(int ch, const wait_mark& w);
  void start_op(int ch, int line);
  /// The plan's waits of side `side` placed after `count` operations of the section.
  void plan_waits_at(int side, std::size_t count, int line);
  /// A barrier: the section ends (its remaining planned waits placed), the next begins.
  void section_break(int line);
  void plan_fault(int line, const std::string& what);
  int column_line_ = 0, column_ = 0;  // the event being routed: where its errors point
  std::optional<int> next_code(int line, const std::string& what);
  const channel_def* head_channel(const head_event& h) const;

  const machine& m_;
  sync_policy policy_;
  channel_sink& sink_;
  diagnostic_sink& diags_;
  std::string file_;
  wait_allocator codes_;
  std::vector<int> active_;  // channels receiving events now
  bool both_ = false;        // inside HEAD/BOTH
  /// The channels of a HEAD/BOTH whose opening wait is not written yet (spindle records first).
  std::vector<int> open_both_;
  int open_both_line_ = 0;
  int both_master_ = 0;  // the channel of head 1 in HEAD/BOTH
  /// Writes the opening wait of HEAD/BOTH held back by select().
  void open_both();
  /// Under optimise (its posts) and under sequential on three or four channels, the job's
  /// channels outside a HEAD/BOTH `pair` meet the pair
  /// where its balance cut opens and closes: the cut is a section, a barrier that every
  /// channel's plan starts and ends at, and a channel not held there would run its work of
  /// the sections before or after beside the cut, ordered by nothing (attack 57).
  void barrier_beside(const std::vector<int>& pair, int line, const std::string& what);
  /// `channels` and every channel of the job, sorted, once each.
  std::vector<int> with_job_channels(std::vector<int> channels) const;
  int grip_line_ = 0;  // the TRANSFER/GRIP not yet released; 0: none
  int grip_column_ = 0;
  /// Between GRIP and RELEASE: the last point's x (CL radius) and the first feed move that
  /// reached or crossed the centre line (a part-off), 0: none.
  double grip_last_x_ = 0;
  bool grip_has_x_ = false;
  int cutoff_line_ = 0;
  void note_cutoff(const event& e);
  std::vector<bool> busy_;                         // per channel: events since its last wait
  std::vector<bool> worked_;                       // per channel: events since its last bound sync record
  std::vector<int> last_partners_;                 // the channels of the last mark
  std::vector<int> job_channels_;                  // the channels the job uses
  std::map<int, int> auto_marker_;                 // per channel: the last ICAM marker number
  std::map<std::pair<int, int>, int> sync_codes_;  // (sync number, occurrence) -> code
  std::map<std::pair<int, int>, int> seen_;        // (channel, sync number) -> occurrences
  int last_sync_line_ = -1, last_sync_index_ = -1, last_sync_channel_ = -1;
  int rendezvous_ = 0;
  int explicit_ = 0;
  bool warned_ignored_ = false;
  bool exhausted_ = false;
  // Operations (a job of two to four channels): side_[ch] its index in ops_.channels, -1 for any other.
  job_operations ops_;
  std::vector<int> side_;
  std::vector<bool> started_;          // per channel: its current stretch has started an operation
  std::vector<bool> op_wrote_;         // per channel: its current operation has a record that writes
  std::vector<channel_track> tracks_;  // per channel: what its operations are noted with
  bool op_waits_ = false;
  bool aside_sync_ = false;
  bool track_ = false;
  std::vector<int> waits_sent_;  // per channel: waits written so far
  const job_operations* plan_ = nullptr;
  std::vector<std::size_t> plan_next_;  // per side: the next planned wait to place
  std::vector<std::size_t> sec_;        // per side: its section (a bound sync record moves one side on)
  /// Per side: its bound sync records in order.
  struct bound_record {
    std::pair<int, int> key;  ///< (sync number, occurrence)
    int line = 0;
  };
  std::vector<std::vector<bound_record>> bound_;
  bool bind_failed_ = false;  // a sync record refused: the rest are not bound
  std::map<std::pair<std::size_t, std::size_t>, int> plan_codes_;  // (section, wait) -> code
  /// Under a plan of three or four channels: the codes given since all the job's channels
  /// last met, which may still be pending (next_code gives none of them again).
  std::set<int> live_codes_;
  bool plan_failed_ = false;
};

}  // namespace twinpost
