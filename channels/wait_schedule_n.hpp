#pragma once
// The shortest cycle of three (or four) channels that meet only at waits (issue 39, item 3;
// docs/wait-placement.md, "Three channels"). Each channel runs its operations in its own order;
// some pairs of operations of two channels must not run at the same time (either order), and
// some must keep the CL's order. A meeting is a wait code that names two or more channels
// (Fanuc 3-path `M200 P12`, `P123`): each stops at its position until all have arrived, and
// all go on after the handshake.
//
// Unlike the two-channel plane (wait_schedule.hpp), a pair here is kept by the meetings alone,
// never by the operations' times: channel q's operation k comes after channel p's operation i
// only when a chain of meetings says so (p meets someone after i, ..., someone meets q before
// k), which is what the control guarantees whatever the times turn out to be.
//
// The problem is NP-hard (Sotskov & Shakhlevich 1995). The search is a depth-first branch and
// bound over the sequence of meetings (each channel's knowledge of the others a vector clock),
// with a lower bound of each channel's release plus its remaining work, exact when it ends
// within its budget of nodes; beyond it, the best schedule found (a beam search seeds it) and
// the gap to the lower bound are returned.
#include <cstdint>
#include <optional>
#include <vector>

namespace twinpost {

/// Two operations of two channels kept apart: `p`'s operation `i` and `q`'s operation `j`.
struct channel_pair {
  int p = 0, i = 0, q = 0, j = 0;
  bool ordered = false;  ///< p's operation ends before q's starts; else either order, never together
};

/// One wait: each channel named (channel, operations done before it) stops until all arrive.
struct meeting {
  struct at {
    int channel = 0, position = 0;
    bool operator==(const at&) const = default;
  };
  std::vector<at> channels;  ///< by channel number, two or more
  bool operator==(const meeting&) const = default;
};

struct channels_schedule {
  std::int64_t makespan_us = 0;
  std::vector<meeting> waits;       ///< in an order every channel meets them in
  bool exact = false;               ///< the search ended within its budget: no schedule is shorter
  std::int64_t lower_bound_us = 0;  ///< no schedule is shorter than this (the makespan when exact)
  long nodes = 0;                   ///< the search's nodes
};

struct schedule_budget {
  long nodes = 2'000'000;  ///< the exact search's nodes before it stops (about a second)
  int max_waits = -1;      ///< the most meetings a schedule may have (-1: no limit; for tests)
  int beam = 64;           ///< the beam search's width (the first schedule)
};

/// The most channels the search takes.
constexpr int schedule_max_channels = 4;

/// The shortest schedule that keeps every pair by its meetings, then the fewest meetings; none
/// when there is none (contradicting orders) or the budget found none. `us[c]`: channel c's
/// operations' times (an operation shorter than 1 us is taken as 1 us); pairs name channels by
/// index into `us`. `handshake_us`: what a meeting costs each channel it names.
std::optional<channels_schedule> schedule_channels(const std::vector<std::vector<std::int64_t>>& us,
                                                   const std::vector<channel_pair>& pairs,
                                                   std::int64_t handshake_us,
                                                   const schedule_budget& budget = {});

}  // namespace twinpost
