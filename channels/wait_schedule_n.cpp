#include "channels/wait_schedule_n.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <functional>
#include <limits>
#include <string>
#include <unordered_map>

namespace twinpost {

namespace {

constexpr int K = schedule_max_channels;

/// A pair as one of its operations sees it: the other channel's operation, and which may go first.
struct pair_ref {
  int q = 0, k = 0;
  int rule = 0;  ///< 0: either, 1: this one first, 2: the other first
};

struct problem {
  int channels = 0;
  std::array<int, K> n{};
  std::vector<std::vector<std::int64_t>> prefix;         ///< [c][j]: the time of c's first j operations
  std::vector<std::vector<std::vector<pair_ref>>> refs;  ///< [c][j]
  /// The positions a meeting may name in each channel: 0, the end, and the boundaries on each
  /// side of an operation in a pair (between them the channel's work only shifts times, and a
  /// meeting as far on as it may go, or as early as its news allows, is never worse).
  std::vector<std::vector<int>> cand;
  std::int64_t h = 0;
  std::int64_t work(int c, int from, int to) const {
    return prefix[static_cast<std::size_t>(c)][static_cast<std::size_t>(to)] -
           prefix[static_cast<std::size_t>(c)][static_cast<std::size_t>(from)];
  }
};

struct node {
  std::array<int, K> pos{};                   ///< operations each channel has committed to run
  std::array<std::array<int, K>, K> clock{};  ///< [c][r]: r's operations c knows are done
  std::array<std::int64_t, K> release{};      ///< when each channel left its last meeting
  int waits = 0;
};

// Whether channel c may run its operation j now, knowing what it knows: every pair of it with an
// operation another channel has already committed needs that operation known done (and the
// pair must let the other go first); one with an operation not yet committed goes first (and
// the pair must let it).
bool op_ok(const problem& p, const node& s, int c, int j) {
  for (const pair_ref& r : p.refs[static_cast<std::size_t>(c)][static_cast<std::size_t>(j)]) {
    if (r.k < s.pos[static_cast<std::size_t>(r.q)]) {
      if (r.rule == 1 || s.clock[static_cast<std::size_t>(c)][static_cast<std::size_t>(r.q)] < r.k + 1)
        return false;
    } else if (r.rule == 2) {
      return false;
    }
  }
  return true;
}

// The first operation from its position that channel c may not run before it learns more.
int block_of(const problem& p, const node& s, int c) {
  const auto cu = static_cast<std::size_t>(c);
  for (int j = s.pos[cu]; j < p.n[cu]; ++j)
    if (!op_ok(p, s, c, j)) return j;
  return p.n[cu];
}

// Whether the segments [pos, to) of the channels in `mask`, run at the same time, hold no pair.
bool segments_apart(const problem& p, const node& s, unsigned mask, const std::array<int, K>& to) {
  for (int c = 0; c < p.channels; ++c) {
    if (!(mask >> c & 1u)) continue;
    const auto cu = static_cast<std::size_t>(c);
    for (int j = s.pos[cu]; j < to[cu]; ++j)
      for (const pair_ref& r : p.refs[cu][static_cast<std::size_t>(j)])
        if (r.q > c && (mask >> r.q & 1u) && r.k >= s.pos[static_cast<std::size_t>(r.q)] &&
            r.k < to[static_cast<std::size_t>(r.q)])
          return false;
  }
  return true;
}

std::int64_t bound_of(const problem& p, const node& s, const std::array<int, K>& block) {
  std::int64_t lb = 0;
  for (int c = 0; c < p.channels; ++c) {
    const auto cu = static_cast<std::size_t>(c);
    std::int64_t v = s.release[cu] + p.work(c, s.pos[cu], p.n[cu]);
    if (block[cu] < p.n[cu]) v += p.h;  // it has to meet someone again
    lb = std::max(lb, v);
  }
  return lb;
}

struct child {
  node s;
  meeting m;
  std::int64_t lb = 0;
};

struct search {
  search(const problem& pr, const schedule_budget& b) : p(pr), budget(b) {}
  const problem& p;
  const schedule_budget& budget;
  std::int64_t best = -1;
  int best_waits = 0;
  std::vector<meeting> best_path;
  long nodes = 0;
  long limit = 0;  ///< the node count at which the search stops
  bool stopped = false;
  std::unordered_map<std::string, std::vector<std::pair<std::array<std::int64_t, K>, int>>> seen;

  std::array<int, K> blocks(const node& s) const {
    std::array<int, K> b{};
    for (int c = 0; c < p.channels; ++c) b[static_cast<std::size_t>(c)] = block_of(p, s, c);
    return b;
  }

  // A finished schedule from `s` (every channel runs to its end), if it holds every pair.
  void try_end(const node& s, const std::array<int, K>& block, const std::vector<meeting>& path) {
    for (int c = 0; c < p.channels; ++c)
      if (block[static_cast<std::size_t>(c)] < p.n[static_cast<std::size_t>(c)]) return;
    if (!segments_apart(p, s, (1u << p.channels) - 1, p.n)) return;
    std::int64_t mk = 0;
    for (int c = 0; c < p.channels; ++c) {
      const auto cu = static_cast<std::size_t>(c);
      mk = std::max(mk, s.release[cu] + p.work(c, s.pos[cu], p.n[cu]));
    }
    if (best < 0 || mk < best || (mk == best && s.waits < best_waits)) {
      best = mk;
      best_waits = s.waits;
      best_path = path;
    }
  }

  // Every useful next meeting from `s`: two or more channels, each at a candidate position it may
  // reach, running nothing at the same time that a pair keeps apart, and one that has work left
  // learning something. `wide`: at most that many positions per channel (the beam), else all.
  std::vector<child> children(const node& s, const std::array<int, K>& block, std::size_t wide) {
    std::vector<child> out;
    std::array<std::vector<int>, K> at;
    for (int c = 0; c < p.channels; ++c) {
      const auto cu = static_cast<std::size_t>(c);
      for (int x : p.cand[cu])
        if (x >= s.pos[cu] && x <= block[cu]) at[cu].push_back(x);
      if (at[cu].empty() || at[cu].front() != s.pos[cu]) at[cu].insert(at[cu].begin(), s.pos[cu]);
      if (at[cu].size() > wide) {  // where it is, and the farthest it may go
        std::vector<int> keep{at[cu].front()};
        keep.insert(keep.end(), at[cu].end() - static_cast<std::ptrdiff_t>(wide - 1), at[cu].end());
        at[cu] = keep;
      }
    }
    for (unsigned mask = 3; mask < (1u << p.channels); ++mask) {
      if (std::popcount(mask) < 2) continue;
      std::array<int, K> to = s.pos;
      std::array<std::size_t, K> idx{};
      std::vector<int> members;
      for (int c = 0; c < p.channels; ++c)
        if (mask >> c & 1u) members.push_back(c);
      while (true) {
        for (int c : members)
          to[static_cast<std::size_t>(c)] = at[static_cast<std::size_t>(c)][idx[static_cast<std::size_t>(c)]];
        add_child(s, mask, members, to, out);
        if (stopped) return out;
        std::size_t m = 0;
        for (; m < members.size(); ++m) {
          const auto cu = static_cast<std::size_t>(members[m]);
          if (++idx[cu] < at[cu].size()) break;
          idx[cu] = 0;
        }
        if (m == members.size()) break;
      }
    }
    return out;
  }

  void add_child(const node& s, unsigned mask, const std::vector<int>& members, const std::array<int, K>& to,
                 std::vector<child>& out) {
    if (++nodes > limit) {
      stopped = true;
      return;
    }
    if (!segments_apart(p, s, mask, to)) return;
    std::array<int, K> merged{};
    for (int c : members)
      for (int r = 0; r < p.channels; ++r)
        merged[static_cast<std::size_t>(r)] =
            std::max(merged[static_cast<std::size_t>(r)],
                     r == c ? to[static_cast<std::size_t>(c)]
                            : s.clock[static_cast<std::size_t>(c)][static_cast<std::size_t>(r)]);
    bool useful = false;
    for (int c : members) {
      const auto cu = static_cast<std::size_t>(c);
      if (to[cu] == p.n[cu]) continue;
      for (int r = 0; r < p.channels; ++r)
        if (r != c && merged[static_cast<std::size_t>(r)] > s.clock[cu][static_cast<std::size_t>(r)])
          useful = true;
    }
    if (!useful) return;
    child ch;
    ch.s = s;
    std::int64_t arrive = 0;
    for (int c : members) {
      const auto cu = static_cast<std::size_t>(c);
      arrive = std::max(arrive, s.release[cu] + p.work(c, s.pos[cu], to[cu]));
      ch.m.channels.push_back({c, to[cu]});
    }
    for (int c : members) {
      const auto cu = static_cast<std::size_t>(c);
      ch.s.pos[cu] = to[cu];
      ch.s.clock[cu] = merged;
      ch.s.release[cu] = arrive + p.h;
    }
    ch.s.waits = s.waits + 1;
    ch.lb = bound_of(p, ch.s, blocks(ch.s));
    out.push_back(std::move(ch));
  }

  std::string key(const node& s) const {
    std::string k;
    for (int c = 0; c < p.channels; ++c) {
      k += std::to_string(s.pos[static_cast<std::size_t>(c)]) + ',';
      for (int r = 0; r < p.channels; ++r)
        k += std::to_string(s.clock[static_cast<std::size_t>(c)][static_cast<std::size_t>(r)]) + ',';
    }
    return k;
  }

  // Whether a state as far on with no later releases and no more waits was seen (and if not,
  // remembers this one).
  bool dominated(const node& s) {
    auto& list = seen[key(s)];
    for (const auto& [rel, w] : list) {
      bool all = w <= s.waits;
      for (int c = 0; c < p.channels && all; ++c)
        all = rel[static_cast<std::size_t>(c)] <= s.release[static_cast<std::size_t>(c)];
      if (all) return true;
    }
    std::erase_if(list, [&](const auto& e) {
      bool all = s.waits <= e.second;
      for (int c = 0; c < p.channels && all; ++c)
        all = s.release[static_cast<std::size_t>(c)] <= e.first[static_cast<std::size_t>(c)];
      return all;
    });
    list.emplace_back(s.release, s.waits);
    return false;
  }

  bool pruned(std::int64_t lb, int waits) const {
    return best >= 0 && (lb > best || (lb == best && waits >= best_waits));
  }

  void dfs(const node& s, std::vector<meeting>& path) {
    if (stopped) return;
    const std::array<int, K> block = blocks(s);
    try_end(s, block, path);
    if (budget.max_waits >= 0 && s.waits >= budget.max_waits) return;
    std::vector<child> next = children(s, block, SIZE_MAX);
    if (stopped) return;
    std::stable_sort(next.begin(), next.end(), [](const child& a, const child& b) { return a.lb < b.lb; });
    for (child& c : next) {
      if (pruned(c.lb, c.s.waits)) continue;
      if (dominated(c.s)) continue;
      path.push_back(c.m);
      dfs(c.s, path);
      path.pop_back();
      if (stopped) return;
    }
  }

  // A first schedule: level by level, the `beam` most promising states kept.
  void beam(const node& root) {
    std::vector<std::pair<node, std::vector<meeting>>> level{{root, {}}};
    int total = 0;
    for (int c = 0; c < p.channels; ++c) total += p.n[static_cast<std::size_t>(c)];
    for (int depth = 0; !level.empty() && depth <= 2 * total + 2; ++depth) {
      std::vector<std::tuple<std::int64_t, node, std::vector<meeting>>> next;
      std::unordered_map<std::string, std::size_t> where;
      for (auto& [s, path] : level) {
        const std::array<int, K> block = blocks(s);
        try_end(s, block, path);
        if (budget.max_waits >= 0 && s.waits >= budget.max_waits) continue;
        for (child& c : children(s, block, 4)) {
          if (pruned(c.lb, c.s.waits)) continue;
          const std::string k = key(c.s);
          std::vector<meeting> np = path;
          np.push_back(c.m);
          if (auto it = where.find(k); it != where.end()) {
            auto& [lb, old, op] = next[it->second];
            if (c.lb < lb) next[it->second] = {c.lb, c.s, std::move(np)};
            continue;
          }
          where.emplace(k, next.size());
          next.emplace_back(c.lb, c.s, std::move(np));
        }
      }
      std::stable_sort(next.begin(), next.end(), [](const auto& a, const auto& b) {
        return std::get<0>(a) != std::get<0>(b) ? std::get<0>(a) < std::get<0>(b)
                                                : std::get<1>(a).waits < std::get<1>(b).waits;
      });
      if (next.size() > static_cast<std::size_t>(std::max(1, budget.beam)))
        next.resize(static_cast<std::size_t>(std::max(1, budget.beam)));
      level.clear();
      for (auto& [lb, s, path] : next) level.emplace_back(std::move(s), std::move(path));
    }
  }
};

}  // namespace

std::optional<channels_schedule> schedule_channels(const std::vector<std::vector<std::int64_t>>& us,
                                                   const std::vector<channel_pair>& pairs,
                                                   std::int64_t handshake_us, const schedule_budget& budget) {
  problem p;
  p.channels = static_cast<int>(us.size());
  if (p.channels < 2 || p.channels > K) return std::nullopt;
  p.h = std::max<std::int64_t>(0, handshake_us);
  p.prefix.resize(us.size());
  p.refs.resize(us.size());
  p.cand.resize(us.size());
  for (std::size_t c = 0; c < us.size(); ++c) {
    p.n[c] = static_cast<int>(us[c].size());
    p.prefix[c].push_back(0);
    for (std::int64_t d : us[c]) p.prefix[c].push_back(p.prefix[c].back() + std::max<std::int64_t>(1, d));
    p.refs[c].resize(us[c].size());
    p.cand[c] = {0, p.n[c]};
  }
  for (const channel_pair& x : pairs) {
    if (x.p < 0 || x.q < 0 || x.p >= p.channels || x.q >= p.channels || x.p == x.q || x.i < 0 || x.j < 0 ||
        x.i >= p.n[static_cast<std::size_t>(x.p)] || x.j >= p.n[static_cast<std::size_t>(x.q)])
      return std::nullopt;
    p.refs[static_cast<std::size_t>(x.p)][static_cast<std::size_t>(x.i)].push_back(
        {x.q, x.j, x.ordered ? 1 : 0});
    p.refs[static_cast<std::size_t>(x.q)][static_cast<std::size_t>(x.j)].push_back(
        {x.p, x.i, x.ordered ? 2 : 0});
    for (auto [c, o] : {std::pair{x.p, x.i}, {x.q, x.j}}) {
      p.cand[static_cast<std::size_t>(c)].push_back(o);
      p.cand[static_cast<std::size_t>(c)].push_back(o + 1);
    }
  }
  for (auto& v : p.cand) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }
  search s(p, budget);
  const node root;
  s.limit = std::numeric_limits<long>::max();
  s.beam(root);
  const long beam_nodes = s.nodes;
  s.nodes = 0;
  s.limit = budget.nodes;
  std::vector<meeting> path;
  s.dfs(root, path);
  s.nodes += beam_nodes;
  if (s.best < 0) return std::nullopt;
  channels_schedule out;
  out.makespan_us = s.best;
  out.waits = s.best_path;
  out.exact = !s.stopped;
  out.nodes = s.nodes;
  std::int64_t lb = 0;
  for (int c = 0; c < p.channels; ++c) lb = std::max(lb, p.work(c, 0, p.n[static_cast<std::size_t>(c)]));
  out.lower_bound_us = out.exact ? s.best : lb;
  return out;
}

}  // namespace twinpost
