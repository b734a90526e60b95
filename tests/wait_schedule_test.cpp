// The two-channel wait placement (channels/wait_schedule.hpp, issue 39): small schedules worked
// out by hand, and random small instances against a brute force over every set of rendezvous
// (another formulation: the control's reading of each candidate, run_with_waits), never below
// the lower bound (the longer channel's work) nor above the sequential cycle.
#include <catch2/catch.hpp>

#include <algorithm>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "channels/wait_schedule.hpp"

using namespace twinpost;

namespace {

using us = std::vector<std::int64_t>;

struct best_found {
  std::int64_t makespan = -1;
  std::size_t waits = 0;
};

// Every chain of rendezvous (strictly increasing in both counts together, neither at the start
// nor at the end), each read as the control runs it.
best_found brute_force(const us& a, const us& b, const std::vector<op_pair>& pairs, std::int64_t h) {
  const int n = static_cast<int>(a.size()), m = static_cast<int>(b.size());
  best_found best;
  std::vector<rendezvous> chain;
  std::function<void(int, int)> grow = [&](int i, int j) {
    const two_channel_schedule s = run_with_waits(a, b, chain, h);
    if (keeps_pairs(s, a, b, pairs) && (best.makespan < 0 || s.makespan_us < best.makespan ||
                                        (s.makespan_us == best.makespan && chain.size() < best.waits)))
      best = {s.makespan_us, chain.size()};
    for (int x = i; x <= n; ++x)
      for (int y = j; y <= m; ++y) {
        if ((x == i && y == j && !chain.empty()) || (x == 0 && y == 0) || (x == n && y == m)) continue;
        chain.push_back({x, y});
        grow(x, y);
        chain.pop_back();
      }
  };
  grow(0, 0);
  return best;
}

}  // namespace

TEST_CASE("wait schedule: small cases worked out by hand", "[channels][schedule]") {
  // No pair kept apart: both run at once, no wait; the cycle is the longer channel's.
  auto s = schedule_two_channels({3, 2}, {4}, {}, 100);
  REQUIRE(s);
  CHECK(s->makespan_us == 5);
  CHECK(s->waits.empty());
  // One pair apart, either order: one after the other, one wait (and its handshake).
  s = schedule_two_channels({3}, {4}, {{0, 0, pair_rule::apart}}, 1);
  REQUIRE(s);
  CHECK(s->makespan_us == 8);
  CHECK(s->waits.size() == 1);
  // A: 2 then 5; B: 3 then 1; A's second may not overlap B's first. A waits after its first
  // for B's first (1 us idle), then both run on: 3 + 5 = 8, one wait at (1, 1). Letting B's
  // first wait for A's second instead would end at 7 + 3 + 1 = 11.
  s = schedule_two_channels({2, 5}, {3, 1}, {{1, 0, pair_rule::apart}}, 0);
  REQUIRE(s);
  CHECK(s->makespan_us == 8);
  CHECK(s->waits == std::vector<rendezvous>{{1, 1}});
  CHECK(s->a_start == us{0, 3});
  CHECK(s->b_start == us{0, 3});
  // The CL's order: B's operation after A's (B waits at its start), or A's after B's.
  s = schedule_two_channels({2}, {2}, {{0, 0, pair_rule::a_first}}, 0);
  REQUIRE(s);
  CHECK(s->makespan_us == 4);
  CHECK(s->waits == std::vector<rendezvous>{{1, 0}});
  s = schedule_two_channels({1, 4}, {3}, {{0, 0, pair_rule::b_first}}, 0);
  REQUIRE(s);
  CHECK(s->makespan_us == 8);
  CHECK(s->waits == std::vector<rendezvous>{{0, 1}});
  // Overlap allowed where the pairs leave room: A's long first operation beside B's two short
  // ones; only B's third must wait for A's first to end.
  s = schedule_two_channels({10, 1}, {2, 2, 3}, {{0, 2, pair_rule::a_first}}, 0);
  REQUIRE(s);
  CHECK(s->makespan_us == 13);
  CHECK(s->waits == std::vector<rendezvous>{{1, 2}});
  // Orders that contradict each other: no schedule.
  CHECK_FALSE(schedule_two_channels({1}, {1}, {{0, 0, pair_rule::a_first}, {0, 0, pair_rule::b_first}}, 0));
}

TEST_CASE("wait schedule: the optimum of a brute force, on random small instances", "[channels][schedule]") {
  std::mt19937 rng(39);
  int compared = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const int n = 1 + static_cast<int>(rng() % 4), m = 1 + static_cast<int>(rng() % 4);
    us a(static_cast<std::size_t>(n)), b(static_cast<std::size_t>(m));
    for (auto& d : a) d = 1 + static_cast<std::int64_t>(rng() % 6);
    for (auto& d : b) d = 1 + static_cast<std::int64_t>(rng() % 6);
    // A CL order of the operations (a random interleaving), so that ordered pairs agree with
    // one another as the CL's do.
    std::vector<int> order;  // 0: A's next, 1: B's next
    order.insert(order.end(), static_cast<std::size_t>(n), 0);
    order.insert(order.end(), static_cast<std::size_t>(m), 1);
    std::shuffle(order.begin(), order.end(), rng);
    std::vector<int> pos_a, pos_b;
    for (int k = 0; k < n + m; ++k) (order[static_cast<std::size_t>(k)] == 0 ? pos_a : pos_b).push_back(k);
    std::vector<op_pair> pairs;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < m; ++j) {
        const unsigned r = rng() % 6;
        if (r == 0) pairs.push_back({i, j, pair_rule::apart});
        if (r == 1)
          pairs.push_back({i, j,
                           pos_a[static_cast<std::size_t>(i)] < pos_b[static_cast<std::size_t>(j)]
                               ? pair_rule::a_first
                               : pair_rule::b_first});
      }
    const std::int64_t h = static_cast<std::int64_t>(rng() % 3);
    std::string shown;
    for (const op_pair& p : pairs) {
      shown += std::to_string(p.a);
      shown += p.rule == pair_rule::apart ? " apart " : p.rule == pair_rule::a_first ? " before " : " after ";
      shown += std::to_string(p.b);
      shown += "; ";
    }
    CAPTURE(trial, a, b, h, shown);
    const best_found want = brute_force(a, b, pairs, h);
    const auto got = schedule_two_channels(a, b, pairs, h);
    REQUIRE(want.makespan >= 0);  // the CL's order itself is one schedule
    REQUIRE(got);
    CHECK(got->makespan_us == want.makespan);
    CHECK(got->waits.size() == want.waits);
    CHECK(keeps_pairs(*got, a, b, pairs));
    CHECK(run_with_waits(a, b, got->waits, h).makespan_us == got->makespan_us);
    std::int64_t sa = 0, sb = 0;
    for (auto d : a) sa += d;
    for (auto d : b) sb += d;
    CHECK(got->makespan_us >= std::max(sa, sb));
    ++compared;
  }
  CHECK(compared == 2000);
}
