#pragma once
// Shared resources: what the channels may command of the machine's spindles, and whether two
// channels that may run at the same time command one spindle differently (docs/shared-resources.md).
//
// The model is happens-before: a block of channel a and a block of channel b are ordered only
// when a chain of waits orders them (a's block comes before a wait that a meets, directly or
// through other channels, before b reaches its block). Vector clocks over the rendezvous of
// the wait simulation (check/sync_check: the same pairing as the checker) give each stretch of
// a channel's program between two of its waits (a segment) the set of segments of the other
// channels known to be over; two blocks are concurrent when neither is known to be over
// before the other begins.
//
// Rules:
// - a channel commands only the spindles machine.channels[].spindles gives it;
// - two channels command one shared spindle (machine::shared_spindle) with a different
//   direction, speed mode (CSS / rpm) or speed in blocks that may run at the same time: error
//   at one block, note at the other;
// - a channel cuts with feed per revolution (codes.feed_per_rev) on a spindle that no start
//   happens before, or that a stop ordered after every such start has stopped: error at the cut.
//
// Streaming: of the blocks only the spindle commands and, per stretch of a channel that the
// rule treats alike, its first cut with feed per revolution are kept.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "check/sync_check.hpp"
#include "machines/machine.hpp"
#include "support/diagnostics.hpp"

namespace twinpost {

class timeline_feed;

/// The vector clocks of the rendezvous (sync_result::rendezvous) for `channels` channels:
/// [channel-1][segment][other-1] = how many segments of channel `other` are over before that
/// segment of `channel` begins (docs/shared-resources.md, "The model"). Shared by the spindle
/// rules and the interference rule (analysis/interference).
std::vector<std::vector<std::vector<int>>> segment_clocks(const std::vector<std::uint64_t>& rendezvous,
                                                          std::size_t channels);

class spindle_states;
class modal_states;

class shared_resources {
 public:
  /// `spindles`: the reading's one spindle state, which must have applied each block before
  /// block() is given it; it must outlive the rules.
  shared_resources(const machine& m, const spindle_states& spindles);
  ~shared_resources();
  shared_resources(const shared_resources&) = delete;
  shared_resources& operator=(const shared_resources&) = delete;

  /// Every block of every channel, in program order (nc_read_options::on_block).
  void block(const nc_block& b);
  /// The channel passed a wait: its next block belongs to its next segment (on_wait).
  void wait(int channel);
  /// The rules, given the rendezvous of a check in which every channel reached its end
  /// (sync_result::rendezvous). The commands a channel may not give are reported however the
  /// waits paired; the others need the pairing.
  std::vector<diagnostic> finish(const std::vector<std::uint64_t>& rendezvous, bool waits_sound);

 private:
  struct impl;
  std::unique_ptr<impl> p_;
};

/// check_nc_files and the shared-resource rules on the same reading: what `twinpost check`
/// and post's self-check run. The rules' findings follow the checker's, and count in the result.
/// `more` gets every block and wait of the same reading, once each; `feed`, when given, too
/// (the post's cycle time), with the spindle state the rules read (spindle_states: one owner).
sync_result check_nc_resources(const std::vector<nc_source>& files, const machine& m,
                               const nc_read_options& more = {}, timeline_feed* feed = nullptr);

/// check_nc_resources for a caller that reads the programs itself (post reads its programs
/// while they are written: nc_stream_reader): read with options(), then result().
class compact_resource_check {
 public:
  explicit compact_resource_check(const machine& m, const nc_read_options& more = {},
                                  timeline_feed* feed = nullptr);
  ~compact_resource_check();
  compact_resource_check(const compact_resource_check&) = delete;
  compact_resource_check& operator=(const compact_resource_check&) = delete;
  /// What to read with: the check's and the rules' callbacks, and `more`'s.
  const nc_read_options& options() const;
  /// The reading's spindle state and modal state (each block applied before `more`'s
  /// on_block is given it): for a consumer of `more` that reads them.
  const spindle_states& spindles() const;
  const modal_states& modes() const;
  /// What check_nc_resources returns for the same programs, when the reading found nothing to
  /// say (compact_sync_check::result); nullopt: read them with check_nc_resources instead.
  std::optional<sync_result> result(const nc_programs& programs, const diagnostic_list& read);

 private:
  struct impl;
  std::unique_ptr<impl> p_;
};

}  // namespace twinpost
