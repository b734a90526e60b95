#pragma once
// Cycle time and the timeline of a multi-channel job, read from its NC programs: every
// block of every channel timed (analysis/block_timer.hpp), then the channels run together:
// at each wait a channel idles until its partners arrive (the checker's pairing: the k-th
// wait of a channel meets the k-th of its partners), which gives the idle per wait and per
// channel, the cycle time and the critical path. Only programs that check sound are timed:
// otherwise the checker's findings are the answer. docs/timeline.md.
//
// Memory: without keep_blocks, a channel keeps one record per operation (a run of blocks
// with one tool between two waits), per wait and per kind of untimed block, never one per
// block: a program of 10^7 blocks is timed in memory that does not grow with its blocks.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "analysis/interference.hpp"
#include "check/nc_program.hpp"
#include "machines/machine.hpp"
#include "support/diagnostics.hpp"

namespace twinpost {

/// The most blocks a channel keeps for the page (timeline_options::keep_blocks); past it the
/// page draws the channel's operations and no block is kept.
constexpr std::size_t timeline_max_kept_blocks = 20000;

struct timeline_options {
  bool keep_blocks =
      false;  ///< keep each block (the page's hover), up to timeline_max_kept_blocks per channel
};

/// One block, kept for the page.
struct timed_block {
  int line = 0;
  double start = 0;     ///< seconds from the start of the cycle
  double seconds = 0;   ///< its own time
  std::string text;     ///< the physical line
  std::string untimed;  ///< why it is not timed; empty: timed
  bool wait = false;
};

/// A run of blocks with one tool between two waits of a channel.
struct tool_operation {
  std::string tool;    ///< "T03"; empty before the first tool call
  double start = 0;    ///< seconds from the start of the cycle
  double seconds = 0;  ///< the sum of its blocks' times
  long blocks = 0;
  int segment = 0;     ///< wait segment: 0 before the first wait, k after the k-th
  int first_line = 0;  ///< its first block
  std::string first_text;
  bool critical = false;  ///< on the critical path
};

/// A channel at one of its waits.
struct wait_stop {
  std::string code;  ///< as written: "M101", "M100 P12", "!2L1"
  nc_place where;
  double arrive = 0;        ///< seconds from the start of the cycle
  double release = 0;       ///< when the last partner arrived
  int waited_for = 0;       ///< the partner that arrived last; 0: this channel was the last
  int waited_for_wait = 0;  ///< that partner's wait (0-based index in its waits)
  double idle() const { return release - arrive; }
};

/// Blocks of one kind that could not be timed.
struct untimed_group {
  std::string why;  ///< "G83", "G28", "G0 from an unknown position"
  long count = 0;
  nc_place first;
};

/// One channel's times.
struct channel_times {
  int channel = 0;
  std::string file;
  double busy = 0;  ///< the sum of its blocks' times
  double idle = 0;  ///< the sum of its idle at waits
  double end = 0;   ///< busy + idle: when it reaches its end
  long blocks = 0;
  long untimed = 0;
  /// Feed blocks shorter than the control reads them (limits.blocks_per_second), and the
  /// shortest of them.
  long short_blocks = 0;
  double shortest = 0;
  nc_place shortest_at;
  std::vector<tool_operation> operations;
  std::vector<wait_stop> waits;
  std::vector<timed_block> kept;  ///< with timeline_options::keep_blocks (none past the cap)
};

/// One wait at which a channel idles, for the balance advice.
struct idle_note {
  int channel = 0;
  double seconds = 0;
  std::string code;
  nc_place where;
  int waited_for = 0;
};

/// A stretch of the critical path: channel `channel` from `start` to `end`.
struct critical_stretch {
  int channel = 0;
  double start = 0, end = 0;
};

struct timeline {
  bool ok = false;
  std::vector<diagnostic> diagnostics;  ///< why there is no timeline (the check's findings)
  std::string machine;
  std::vector<channel_times> channels;
  double cycle = 0;                          ///< the end of the last channel
  int last_channel = 0;                      ///< the channel that ends last (the critical path's end)
  std::vector<critical_stretch> critical;    ///< in time order
  long untimed = 0;                          ///< blocks of all channels not timed
  std::vector<untimed_group> untimed_kinds;  ///< per kind, in channel then program order
  std::vector<idle_note> advice;             ///< the longest idles, longest first (at most 3)
  /// The turret interference rule's findings (analysis/interference.hpp), each error with its
  /// note at the other channel's block; the programs are timed all the same (make_timeline).
  std::vector<diagnostic> conflicts;
  std::vector<interference_meeting> meetings;  ///< the same conflicts' envelopes (the page's pictures)
};

/// Every block of channel `channel` of a timeline `t` made from `files`, timed and placed in
/// time as keep_blocks would keep it, handed to `f` one at a time by a reading of its own:
/// memory does not grow with the blocks (`timeline --json`).
void for_each_timed_block(const timeline& t, const std::vector<nc_source>& files, const machine& m,
                          int channel, const std::function<void(const timed_block&)>& f);

/// Checks `files` (check_nc_files) and, when they are sound, times them for machine `m`.
/// A machine without [timing] has no timeline (an error diagnostic says so).
timeline make_timeline(const std::vector<nc_source>& files, const machine& m, const timeline_options& o = {});

/// The same fed by a read that is made anyway (the post's self-check): hand it every block
/// and wait of programs that check sound, in the reader's order, then take the timeline with
/// that check's rendezvous (sync_result::rendezvous): who meets whom is the checker's word.
/// `m` must have timing (has_timing) and at most 64 channels.
class spindle_states;
class modal_states;

class timeline_feed {
 public:
  timeline_feed(const machine& m, const timeline_options& o);
  ~timeline_feed();
  timeline_feed(const timeline_feed&) = delete;
  timeline_feed& operator=(const timeline_feed&) = delete;
  /// Callbacks for nc_read_options (on_block, on_wait) that feed this timeline. `spindles`,
  /// `modes`, when given: the reading's one spindle state and modal state, with `b` applied
  /// already (the resource check's, check_nc_resources); else the timer keeps its own.
  void block(const nc_block& b, const spindle_states* spindles = nullptr,
             const modal_states* modes = nullptr);
  void wait(const nc_wait& w);
  timeline finish(const std::vector<std::uint64_t>& rendezvous);

 private:
  // The builder is made by the first call, on the thread that feeds it: a self-check's thread
  // then has it in its own memory, not in cache lines shared with the writer's (docs/design.md,
  // "Two cores").
  struct impl;
  void make();
  const machine& m_;
  timeline_options o_;
  std::unique_ptr<impl> p_;
};

/// True when every channel of `m` has timing figures.
bool has_timing(const machine& m);

}  // namespace twinpost
