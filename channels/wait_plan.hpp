#pragma once
// The operations of a two-channel job as the router finds them, and the waits the schedule puts
// between them (`--sync optimise`, issue 39, docs/wait-placement.md).
//
// An operation is a stretch of the CL that one head works alone: from a head switch to the
// next. A section is the part of the job between two barriers, which every channel meets
// whatever the policy: a part transfer (its two rendezvous) and the frame of a HEAD/BOTH
// section. Inside a section each channel runs its operations in the CL's order, and the plan
// says where the two channels meet (channels/wait_schedule.hpp: after A's first `a`
// operations and B's first `b`).
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "channels/wait_schedule.hpp"

namespace twinpost {

/// One operation of one channel.
struct channel_op {
  int first_line = 0, last_line = 0;  ///< its CL records
  int segment = 0;                    ///< the channel's waits before it (as the pass wrote them)
  std::int64_t us = 0;                ///< its time (time_operations)
};

struct plan_section {
  /// [0]: channel A's operations, [1]: channel B's.
  std::vector<channel_op> ops[2];
  /// Where the two meet inside the section (none at its start or end).
  std::vector<rendezvous> waits;
};

/// The job's sections, in order, for channels `a` < `b`.
struct job_operations {
  int a = 0, b = 0;
  std::vector<plan_section> sections;
  int operation_waits = 0;  ///< rendezvous placed inside stretches (channel_router::set_operation_waits)
};

/// A pair of operations of one section kept apart (wait_schedule's op_pair, in a section).
struct plan_pair {
  std::size_t section = 0;
  op_pair pair;
  bool operator==(const plan_pair& o) const {
    return section == o.section && pair.a == o.pair.a && pair.b == o.pair.b && pair.rule == o.pair.rule;
  }
};

/// Each operation's time: `seconds(side, segment)` is the time of that segment of the
/// channel's program as a sequential pass wrote it (side 0: channel a). Operations that share
/// a segment (a stretch that wrote no block, with no wait after it) take nothing of it but the
/// last one.
void time_operations(job_operations& ops, const std::function<double(int side, int segment)>& seconds);

/// The waits of every section for the shortest cycle that keeps `pairs`
/// (schedule_two_channels), into `ops`. Returns the predicted cycle (the sections' makespans
/// and a handshake per barrier between them), or nullopt when the pairs contradict each other.
std::optional<std::int64_t> plan_waits(job_operations& ops, const std::vector<plan_pair>& pairs,
                                       std::int64_t handshake_us);

/// The pairs that keep the CL's order between the operations holding the CL lines `lines`
/// (a finding's error and notes): two operations of the two channels in one section give one
/// pair; an operation whose partner is not among them keeps the CL's order with every
/// operation of the other channel in its section. Empty when no line is in an operation.
std::vector<plan_pair> pairs_for_lines(const job_operations& ops, const std::vector<int>& lines);

}  // namespace twinpost
