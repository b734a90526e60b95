// Solve times of the two-channel wait placement (channels/wait_schedule.hpp, issue 39) at 10,
// 100 and 1000 operations per channel: random operations of 1-60 s, each operation of A kept
// apart from `density` operations of B near it in the CL's order (a spindle both need, or
// envelopes that meet, as twin-turret work has them: among the neighbours), half of them in the
// CL's order. Prints the solve time (best of 3), the cycle against the lower bound (the longer
// channel's work) and against the sequential cycle (every operation after the other). Run:
//   build/wait_schedule_bench [density]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "channels/wait_schedule.hpp"

using namespace twinpost;

int main(int argc, char** argv) {
  const int density = argc > 1 ? std::atoi(argv[1]) : 2;
  std::printf("ops/channel  pairs  solve_ms  waits  cycle_s  bound_s  sequential_s\n");
  for (const int n : {10, 100, 1000}) {
    std::mt19937 rng(static_cast<unsigned>(n));
    std::vector<std::int64_t> a(static_cast<std::size_t>(n)), b(static_cast<std::size_t>(n));
    for (auto& d : a) d = 1'000'000 * (1 + static_cast<std::int64_t>(rng() % 60));
    for (auto& d : b) d = 1'000'000 * (1 + static_cast<std::int64_t>(rng() % 60));
    // The CL alternates A's and B's operations: A's i-th before B's i-th.
    std::vector<op_pair> pairs;
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < density; ++k) {
        const int j = std::clamp(i + static_cast<int>(rng() % 5) - 2, 0, n - 1);
        const pair_rule r = rng() % 2 ? pair_rule::apart : (i <= j ? pair_rule::a_first : pair_rule::b_first);
        pairs.push_back({i, j, r});
      }
    double best_ms = 1e300;
    std::optional<two_channel_schedule> s;
    for (int run = 0; run < 3; ++run) {
      const auto t0 = std::chrono::steady_clock::now();
      s = schedule_two_channels(a, b, pairs, 200'000);
      const auto t1 = std::chrono::steady_clock::now();
      best_ms = std::min(best_ms, std::chrono::duration<double, std::milli>(t1 - t0).count());
    }
    std::int64_t sa = 0, sb = 0;
    for (auto d : a) sa += d;
    for (auto d : b) sb += d;
    if (!s) {
      std::printf("%11d  %5zu  no schedule\n", n, pairs.size());
      continue;
    }
    std::printf("%11d  %5zu  %8.2f  %5zu  %7.1f  %7.1f  %12.1f\n", n, pairs.size(), best_ms, s->waits.size(),
                static_cast<double>(s->makespan_us) / 1e6, static_cast<double>(std::max(sa, sb)) / 1e6,
                static_cast<double>(sa + sb) / 1e6);
  }
  return 0;
}
