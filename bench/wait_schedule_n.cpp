// Solve times of the three-channel wait placement (channels/wait_schedule_n.hpp, issue 39) at 5,
// 10, 100 and 1000 operations per channel: random operations of 1-60 s, each operation of a
// channel kept apart from `density` operations of each other channel near it in the CL's order
// (a spindle two turrets need, or envelopes that meet), half of them in the CL's order (the
// channels' operations interleaved: channel 0's i-th, then 1's, then 2's). Prints the solve
// time (best of 3), whether the search proved the optimum within its budget, the cycle against
// the search's lower bound (the longest channel's work, or a pair's two operations with the
// handshake between them and their channels' work around them; the cycle itself when exact), the
// longest channel's work, and the sequential cycle. Run:
//   build/wait_schedule_n_bench [density] [nodes] [beam]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "channels/wait_schedule_n.hpp"

using namespace twinpost;

int main(int argc, char** argv) {
  const int density = argc > 1 ? std::atoi(argv[1]) : 1;
  schedule_budget budget;
  if (argc > 2) budget.nodes = std::atol(argv[2]);
  if (argc > 3) budget.beam = std::atoi(argv[3]);
  std::printf(
      "ops/channel  pairs  solve_ms  exact    nodes  waits  cycle_s  bound_s  gap_%%  longest_s  "
      "sequential_s\n");
  for (const int n : {5, 10, 100, 1000}) {
    std::mt19937 rng(static_cast<unsigned>(n));
    std::vector<std::vector<std::int64_t>> d(3, std::vector<std::int64_t>(static_cast<std::size_t>(n)));
    for (auto& ch : d)
      for (auto& x : ch) x = 1'000'000 * (1 + static_cast<std::int64_t>(rng() % 60));
    std::vector<channel_pair> pairs;
    for (int p = 0; p < 3; ++p)
      for (int q = p + 1; q < 3; ++q)
        for (int i = 0; i < n; ++i)
          for (int k = 0; k < density; ++k) {
            const int j = std::clamp(i + static_cast<int>(rng() % 5) - 2, 0, n - 1);
            const bool apart = rng() % 2;
            // The CL's order: index first, then channel.
            if (apart)
              pairs.push_back({p, i, q, j, false});
            else if (i <= j)
              pairs.push_back({p, i, q, j, true});
            else
              pairs.push_back({q, j, p, i, true});
          }
    double best_ms = 1e300;
    std::optional<channels_schedule> s;
    for (int run = 0; run < 3; ++run) {
      const auto t0 = std::chrono::steady_clock::now();
      s = schedule_channels(d, pairs, 200'000, budget);
      const auto t1 = std::chrono::steady_clock::now();
      best_ms = std::min(best_ms, std::chrono::duration<double, std::milli>(t1 - t0).count());
      if (best_ms > 20'000) break;
    }
    std::int64_t longest = 0, all = 0;
    for (const auto& ch : d) {
      std::int64_t w = 0;
      for (auto x : ch) w += x;
      longest = std::max(longest, w);
      all += w;
    }
    if (!s) {
      std::printf("%11d  %5zu  %8.1f  no schedule found\n", n, pairs.size(), best_ms);
      continue;
    }
    const double gap = 100.0 * static_cast<double>(s->makespan_us - s->lower_bound_us) /
                       static_cast<double>(s->lower_bound_us);
    std::printf("%11d  %5zu  %8.1f  %5s  %7ld  %5zu  %7.1f  %7.1f  %5.1f  %9.1f  %12.1f\n", n, pairs.size(),
                best_ms, s->exact ? "yes" : "no", s->nodes, s->waits.size(),
                static_cast<double>(s->makespan_us) / 1e6, static_cast<double>(s->lower_bound_us) / 1e6, gap,
                static_cast<double>(longest) / 1e6, static_cast<double>(all) / 1e6);
  }
  return 0;
}
