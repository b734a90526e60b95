// The wait placement of three channels (channels/wait_schedule_n.hpp, issue 39): small schedules
// worked out by hand, and random small instances against a brute force over every sequence of
// meetings, each read another way: a graph of the channels' operations and meetings, whose
// longest path is the cycle and whose paths are the orders the control guarantees.
#include <catch2/catch.hpp>

#include <algorithm>
#include <functional>
#include <random>
#include <vector>

#include "channels/wait_schedule_n.hpp"

using namespace twinpost;

namespace {

using times = std::vector<std::vector<std::int64_t>>;

// The control's reading of a sequence of meetings as a graph: each channel's operations and
// meetings in its order, an edge from each to the next; a meeting ends its handshake after the
// last of its channels arrives. Returns the cycle, or -1 when the sequence takes a channel
// back or leaves a pair unordered.
std::int64_t read_as_graph(const times& d, const std::vector<meeting>& seq,
                           const std::vector<channel_pair>& pairs, std::int64_t h) {
  const std::size_t nc = d.size();
  std::vector<std::vector<int>> op_node(nc);
  std::vector<std::int64_t> weight;
  std::vector<std::vector<int>> next;
  auto add = [&](std::int64_t w) {
    weight.push_back(w);
    next.emplace_back();
    return static_cast<int>(weight.size() - 1);
  };
  std::vector<int> meet_node;
  for (std::size_t m = 0; m < seq.size(); ++m) meet_node.push_back(add(h));
  std::vector<int> last(nc, -1);
  auto link = [&](std::size_t c, int v) {
    if (last[c] >= 0) next[static_cast<std::size_t>(last[c])].push_back(v);
    last[c] = v;
  };
  std::vector<int> at(nc, 0);
  for (std::size_t c = 0; c < nc; ++c) {
    const int n = static_cast<int>(d[c].size());
    for (int x = 0; x <= n; ++x) {
      for (std::size_t m = 0; m < seq.size(); ++m)
        for (const meeting::at& a : seq[m].channels)
          if (static_cast<std::size_t>(a.channel) == c && a.position == x) link(c, meet_node[m]);
      if (x < n) {
        const int v = add(std::max<std::int64_t>(1, d[c][static_cast<std::size_t>(x)]));
        op_node[c].push_back(v);
        link(c, v);
      }
    }
  }
  // Each channel's meetings in the sequence's order (positions never going back).
  for (std::size_t m = 0; m < seq.size(); ++m)
    for (const meeting::at& a : seq[m].channels) {
      const auto c = static_cast<std::size_t>(a.channel);
      if (a.position < at[c]) return -1;
      at[c] = a.position;
    }
  // Longest path (Kahn's order); a cycle is a deadlock.
  const std::size_t nv = weight.size();
  std::vector<int> indeg(nv, 0);
  for (const auto& e : next)
    for (int v : e) ++indeg[static_cast<std::size_t>(v)];
  std::vector<std::int64_t> start(nv, 0);
  std::vector<int> ready;
  for (std::size_t v = 0; v < nv; ++v)
    if (indeg[v] == 0) ready.push_back(static_cast<int>(v));
  std::size_t done = 0;
  std::int64_t cycle = 0;
  while (!ready.empty()) {
    const auto v = static_cast<std::size_t>(ready.back());
    ready.pop_back();
    ++done;
    const std::int64_t end = start[v] + weight[v];
    cycle = std::max(cycle, end);
    for (int w : next[v]) {
      start[static_cast<std::size_t>(w)] = std::max(start[static_cast<std::size_t>(w)], end);
      if (--indeg[static_cast<std::size_t>(w)] == 0) ready.push_back(w);
    }
  }
  if (done != nv) return -1;
  auto reaches = [&](int from, int to) {
    std::vector<char> seen(nv, 0);
    std::vector<int> stack{from};
    while (!stack.empty()) {
      const auto v = static_cast<std::size_t>(stack.back());
      stack.pop_back();
      if (static_cast<int>(v) == to) return true;
      if (seen[v]) continue;
      seen[v] = 1;
      for (int w : next[v]) stack.push_back(w);
    }
    return false;
  };
  for (const channel_pair& p : pairs) {
    const int a = op_node[static_cast<std::size_t>(p.p)][static_cast<std::size_t>(p.i)];
    const int b = op_node[static_cast<std::size_t>(p.q)][static_cast<std::size_t>(p.j)];
    if (!(reaches(a, b) || (!p.ordered && reaches(b, a)))) return -1;
  }
  return cycle;
}

struct found {
  std::int64_t cycle = -1;
  std::size_t waits = 0;
};

// Every sequence of up to `most` meetings of two or three channels at any positions.
found brute_force(const times& d, const std::vector<channel_pair>& pairs, std::int64_t h, std::size_t most) {
  found best;
  std::vector<meeting> seq;
  const int nc = static_cast<int>(d.size());
  std::function<void()> grow = [&] {
    const std::int64_t c = read_as_graph(d, seq, pairs, h);
    if (c >= 0 && (best.cycle < 0 || c < best.cycle || (c == best.cycle && seq.size() < best.waits)))
      best = {c, seq.size()};
    if (seq.size() == most) return;
    for (unsigned mask = 3; mask < (1u << nc); ++mask) {
      std::vector<int> members;
      for (int c2 = 0; c2 < nc; ++c2)
        if (mask >> c2 & 1u) members.push_back(c2);
      if (members.size() < 2) continue;
      std::vector<int> pos(members.size(), 0);
      while (true) {
        meeting m;
        for (std::size_t k = 0; k < members.size(); ++k) m.channels.push_back({members[k], pos[k]});
        seq.push_back(m);
        grow();
        seq.pop_back();
        std::size_t k = 0;
        for (; k < members.size(); ++k) {
          if (++pos[k] <= static_cast<int>(d[static_cast<std::size_t>(members[k])].size())) break;
          pos[k] = 0;
        }
        if (k == members.size()) break;
      }
    }
  };
  grow();
  return best;
}

}  // namespace

TEST_CASE("three channels with nothing kept apart cut at once, with no wait", "[wait_schedule_n]") {
  const auto s = schedule_channels({{5, 5}, {3}, {4, 4, 4}}, {}, 2);
  REQUIRE(s);
  CHECK(s->makespan_us == 12);
  CHECK(s->waits.empty());
  CHECK(s->exact);
}

TEST_CASE("an order between two channels is one meeting of those two alone", "[wait_schedule_n]") {
  // Channel 0's 5 us before channel 1's 3 us; channel 2 cuts 20 us beside them.
  const auto s = schedule_channels({{5}, {3}, {20}}, {{0, 0, 1, 0, true}}, 1);
  REQUIRE(s);
  CHECK(s->makespan_us == 20);
  REQUIRE(s->waits.size() == 1);
  CHECK(s->waits[0] == meeting{{{0, 1}, {1, 0}}});
}

TEST_CASE("a chain of orders across three channels is a meeting per link", "[wait_schedule_n]") {
  // 0's first before 1's first before 2's first: 4 + 1 + 3 + 1 + 2 = 11, two meetings.
  const auto s = schedule_channels({{4}, {3}, {2}}, {{0, 0, 1, 0, true}, {1, 0, 2, 0, true}}, 1);
  REQUIRE(s);
  CHECK(s->makespan_us == 11);
  CHECK(s->waits == std::vector<meeting>{meeting{{{0, 1}, {1, 0}}}, meeting{{{1, 1}, {2, 0}}}});
}

TEST_CASE("a pair kept apart either way takes the shorter order", "[wait_schedule_n]") {
  // Channel 1 cuts 2 then 9, channel 2 cuts 6; 1's first and 2's first never together. 1's
  // first goes first: 2 + 1 + 6 = 9 for channel 2, 2 + 1 + 9 = 12 for channel 1 (it waits at
  // no more than the handshake, so it may meet channel 2 at its end of 2 us). 2 first: 6 + 1 +
  // 2 + 9 = 18.
  const auto s = schedule_channels({{1}, {2, 9}, {6}}, {{1, 0, 2, 0, false}}, 1);
  REQUIRE(s);
  CHECK(s->makespan_us == 12);
  CHECK(s->waits == std::vector<meeting>{meeting{{{1, 1}, {2, 0}}}});
}

TEST_CASE("orders that contradict each other have no schedule", "[wait_schedule_n]") {
  CHECK_FALSE(schedule_channels({{1}, {1}, {1}}, {{0, 0, 1, 0, true}, {1, 0, 0, 0, true}}, 0));
  CHECK_FALSE(
      schedule_channels({{1}, {1}, {1}}, {{0, 0, 1, 0, true}, {1, 0, 2, 0, true}, {2, 0, 0, 0, true}}, 0));
}

TEST_CASE("three channels' schedule equals a brute force over every sequence of meetings",
          "[wait_schedule_n][property]") {
  std::mt19937 rng(39);
  int compared = 0, with_waits = 0;
  for (int round = 0; round < 150; ++round) {
    times d(3);
    for (auto& ch : d) {
      ch.resize(1 + rng() % 2);
      for (auto& x : ch) x = 1 + static_cast<std::int64_t>(rng() % 6);
    }
    std::vector<channel_pair> pairs;
    for (int p = 0; p < 3; ++p)
      for (int q = p + 1; q < 3; ++q)
        for (int i = 0; i < static_cast<int>(d[static_cast<std::size_t>(p)].size()); ++i)
          for (int j = 0; j < static_cast<int>(d[static_cast<std::size_t>(q)].size()); ++j) {
            const unsigned r = rng() % 8;
            if (r == 0) pairs.push_back({p, i, q, j, false});
            if (r == 1) pairs.push_back({p, i, q, j, true});
            if (r == 2) pairs.push_back({q, j, p, i, true});
          }
    const std::int64_t h = rng() % 3;
    const found b = brute_force(d, pairs, h, 3);
    schedule_budget budget;
    budget.max_waits = 3;
    const auto s = schedule_channels(d, pairs, h, budget);
    INFO("round " << round);
    if (b.cycle < 0) {
      CHECK_FALSE(s);
      continue;
    }
    REQUIRE(s);
    CHECK(s->exact);
    CHECK(s->makespan_us == b.cycle);
    CHECK(s->waits.size() == b.waits);
    // The schedule's own meetings, read as the graph reads them, give its cycle.
    CHECK(read_as_graph(d, s->waits, pairs, h) == s->makespan_us);
    std::int64_t longest = 0;
    for (const auto& ch : d) {
      std::int64_t w = 0;
      for (auto x : ch) w += x;
      longest = std::max(longest, w);
    }
    CHECK(s->makespan_us >= longest);
    ++compared;
    if (!s->waits.empty()) ++with_waits;
  }
  CHECK(compared > 100);
  CHECK(with_waits > 40);
}
