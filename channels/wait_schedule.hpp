#pragma once
// The shortest cycle of two channels that meet only at rendezvous waits (issue 39;
// docs/wait-placement.md). Each channel runs its operations in its own order; some pairs of
// operations of the two channels must not run at the same time (a spindle both need
// differently: either order), and some must keep the CL's order (envelopes that come closer
// than the clearance: the one the CL gives first runs first). A wait pair (M100 in both) holds
// the channel that arrives first until the other arrives, plus the handshake.
//
// Exact: Akers' shortest path in the plane of the two channels' times (Akers 1956; Brucker,
// Scheduling Algorithms, "two jobs"), each conflicting pair a rectangle the path may not cross,
// a pair with a fixed order a rectangle stretched to the plane's edge on the side it may not
// pass. The path runs diagonally (both channels cut) and turns only at a rectangle's corner,
// where one channel waits at the end of one of its operations for the other: each corner is
// one rendezvous, and every rendezvous schedule is such a path. Times are whole microseconds.
#include <cstdint>
#include <optional>
#include <vector>

namespace twinpost {

/// How a pair of operations (one of each channel) is kept apart.
enum class pair_rule {
  apart,    ///< never at the same time, either may go first (a spindle demand)
  a_first,  ///< A's operation ends before B's starts (the CL's order; envelopes)
  b_first,  ///< B's operation ends before A's starts
};

struct op_pair {
  int a = 0, b = 0;  ///< operation indices in channel A and B
  pair_rule rule = pair_rule::apart;
};

/// A rendezvous: A waits after its first `a` operations, B after its first `b`.
struct rendezvous {
  int a = 0, b = 0;
  bool operator==(const rendezvous&) const = default;
};

struct two_channel_schedule {
  std::int64_t makespan_us = 0;
  std::vector<rendezvous> waits;               ///< in order; none at the start or the end
  std::vector<std::int64_t> a_start, b_start;  ///< each operation's start (us)
};

/// The shortest schedule, then the one with the fewest waits among the shortest; none when the
/// pairs' orders contradict each other. `handshake_us`: the time a rendezvous costs both. An
/// operation shorter than 1 us is taken as 1 us long (its starts in the result too).
std::optional<two_channel_schedule> schedule_two_channels(const std::vector<std::int64_t>& a_us,
                                                          const std::vector<std::int64_t>& b_us,
                                                          const std::vector<op_pair>& pairs,
                                                          std::int64_t handshake_us);

/// What the waits `w` make of the two channels: each operation's start and the end of both (the
/// control's reading of a rendezvous schedule, independent of the search).
two_channel_schedule run_with_waits(const std::vector<std::int64_t>& a_us,
                                    const std::vector<std::int64_t>& b_us, const std::vector<rendezvous>& w,
                                    std::int64_t handshake_us);

/// Whether schedule `s` keeps every pair (no overlap of an `apart` pair, the order of the others).
bool keeps_pairs(const two_channel_schedule& s, const std::vector<std::int64_t>& a_us,
                 const std::vector<std::int64_t>& b_us, const std::vector<op_pair>& pairs);

}  // namespace twinpost
