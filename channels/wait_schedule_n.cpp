#include "channels/wait_schedule_n.hpp"

#include "channels/wait_schedule.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <functional>
#include <limits>
#include <optional>
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
  /// [c][j]: the first of c's operations from j on that is in a pair (n: none); the others may
  /// always run.
  std::vector<std::vector<int>> next_ref;
  /// The pairs, for the lower bound (when there are few enough to walk at every node).
  std::vector<channel_pair> pairs;
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
  const std::vector<int>& nr = p.next_ref[cu];
  for (int j = nr[static_cast<std::size_t>(s.pos[cu])]; j < p.n[cu]; j = nr[static_cast<std::size_t>(j) + 1])
    if (!op_ok(p, s, c, j)) return j;
  return p.n[cu];
}

// Whether the segments [pos, to) of the channels in `mask`, run at the same time, hold no pair.
bool segments_apart(const problem& p, const node& s, unsigned mask, const std::array<int, K>& to) {
  for (int c = 0; c < p.channels; ++c) {
    if (!(mask >> c & 1u)) continue;
    const auto cu = static_cast<std::size_t>(c);
    const std::vector<int>& nr = p.next_ref[cu];
    for (int j = nr[static_cast<std::size_t>(s.pos[cu])]; j < to[cu]; j = nr[static_cast<std::size_t>(j) + 1])
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
  // A pair neither of whose operations has run: the second starts a handshake (a meeting) after
  // the first ends at the earliest, and its channel's work from there follows.
  auto after = [&](int a, int i, int b, int j) {
    const auto au = static_cast<std::size_t>(a), bu = static_cast<std::size_t>(b);
    return s.release[au] + p.work(a, s.pos[au], i + 1) + p.h + p.work(b, j, p.n[bu]);
  };
  for (const channel_pair& x : p.pairs) {
    if (x.i < s.pos[static_cast<std::size_t>(x.p)] || x.j < s.pos[static_cast<std::size_t>(x.q)]) continue;
    const std::int64_t v = x.ordered ? after(x.p, x.i, x.q, x.j)
                                     : std::min(after(x.p, x.i, x.q, x.j), after(x.q, x.j, x.p, x.i));
    lb = std::max(lb, v);
  }
  return lb;
}

// The state after the channels `members` meet at `to` (each its segment from its position run
// first); false when it teaches no channel that has work left anything (a wait for nothing).
bool apply_meeting(const problem& p, const node& s, const std::vector<int>& members,
                   const std::array<int, K>& to, node& out, bool only_useful = true) {
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
  if (!useful && only_useful) return false;
  out = s;
  std::int64_t arrive = 0;
  for (int c : members) {
    const auto cu = static_cast<std::size_t>(c);
    arrive = std::max(arrive, s.release[cu] + p.work(c, s.pos[cu], to[cu]));
  }
  for (int c : members) {
    const auto cu = static_cast<std::size_t>(c);
    out.pos[cu] = to[cu];
    out.clock[cu] = merged;
    out.release[cu] = arrive + p.h;
  }
  out.waits = s.waits + 1;
  return true;
}

// The cycle of a sequence of meetings, or none when it leaves a pair unkept or takes a channel
// back (the same rules as the search, for the pass that drops waits).
std::optional<std::int64_t> evaluate(const problem& p, const std::vector<meeting>& seq) {
  node s;
  for (const meeting& m : seq) {
    unsigned mask = 0;
    std::array<int, K> to = s.pos;
    std::vector<int> members;
    for (const meeting::at& a : m.channels) {
      const auto cu = static_cast<std::size_t>(a.channel);
      if (a.position < s.pos[cu] || block_of(p, s, a.channel) < a.position) return std::nullopt;
      mask |= 1u << a.channel;
      to[cu] = a.position;
      members.push_back(a.channel);
    }
    if (!segments_apart(p, s, mask, to)) return std::nullopt;
    node next;
    apply_meeting(p, s, members, to, next, false);
    s = next;
  }
  std::int64_t mk = 0;
  for (int c = 0; c < p.channels; ++c) {
    const auto cu = static_cast<std::size_t>(c);
    if (block_of(p, s, c) < p.n[cu]) return std::nullopt;
    mk = std::max(mk, s.release[cu] + p.work(c, s.pos[cu], p.n[cu]));
  }
  if (!segments_apart(p, s, (1u << p.channels) - 1, p.n)) return std::nullopt;
  return mk;
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
  // Whether it is shorter (or as short with fewer waits) than the best so far, which it becomes;
  // the caller then keeps its meetings.
  bool try_end(const node& s, const std::array<int, K>& block) {
    for (int c = 0; c < p.channels; ++c)
      if (block[static_cast<std::size_t>(c)] < p.n[static_cast<std::size_t>(c)]) return false;
    if (!segments_apart(p, s, (1u << p.channels) - 1, p.n)) return false;
    std::int64_t mk = 0;
    for (int c = 0; c < p.channels; ++c) {
      const auto cu = static_cast<std::size_t>(c);
      mk = std::max(mk, s.release[cu] + p.work(c, s.pos[cu], p.n[cu]));
    }
    if (best >= 0 && !(mk < best || (mk == best && s.waits < best_waits))) return false;
    best = mk;
    best_waits = s.waits;
    return true;
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
    child ch;
    if (!apply_meeting(p, s, members, to, ch.s)) return;
    for (int c : members) ch.m.channels.push_back({c, to[static_cast<std::size_t>(c)]});
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
    if (try_end(s, block)) best_path = path;
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

  // A first schedule: level by level, the `beam` most promising states kept. The meetings are a
  // tree of (parent, meeting), each state its leaf, so no level copies a path.
  void beam(const node& root) {
    std::vector<std::pair<int, meeting>> tree;
    auto path_of = [&](int leaf) {
      std::vector<meeting> out;
      for (int at = leaf; at >= 0; at = tree[static_cast<std::size_t>(at)].first)
        out.push_back(tree[static_cast<std::size_t>(at)].second);
      std::reverse(out.begin(), out.end());
      return out;
    };
    std::vector<std::pair<node, int>> level{{root, -1}};
    int total = 0;
    for (int c = 0; c < p.channels; ++c) total += p.n[static_cast<std::size_t>(c)];
    const auto width = static_cast<std::size_t>(std::max(1, budget.beam));
    for (int depth = 0; !level.empty() && depth <= 2 * total + 2; ++depth) {
      struct entry {
        std::int64_t lb;
        node s;
        int parent;
        meeting m;
      };
      std::vector<entry> next;
      std::unordered_map<std::string, std::size_t> where;
      for (auto& [s, leaf] : level) {
        const std::array<int, K> block = blocks(s);
        if (try_end(s, block)) best_path = path_of(leaf);
        if (budget.max_waits >= 0 && s.waits >= budget.max_waits) continue;
        for (child& c : children(s, block, 4)) {
          if (pruned(c.lb, c.s.waits)) continue;
          const std::string k = key(c.s);
          if (auto it = where.find(k); it != where.end()) {
            if (c.lb < next[it->second].lb) next[it->second] = {c.lb, c.s, leaf, std::move(c.m)};
            continue;
          }
          where.emplace(k, next.size());
          next.push_back({c.lb, c.s, leaf, std::move(c.m)});
        }
      }
      // The lowest bound first; among equal bounds (the longest channel's end), the least time
      // all channels together still need (the idle time spread over the others), then the
      // fewest waits.
      auto total = [&](const node& x) {
        std::int64_t t = 0;
        for (int c = 0; c < p.channels; ++c)
          t += x.release[static_cast<std::size_t>(c)] +
               p.work(c, x.pos[static_cast<std::size_t>(c)], p.n[static_cast<std::size_t>(c)]);
        return t;
      };
      std::stable_sort(next.begin(), next.end(), [&](const entry& a, const entry& b) {
        if (a.lb != b.lb) return a.lb < b.lb;
        const std::int64_t ta = total(a.s), tb = total(b.s);
        return ta != tb ? ta < tb : a.s.waits < b.s.waits;
      });
      if (next.size() > width) next.resize(width);
      level.clear();
      for (entry& e : next) {
        tree.emplace_back(e.parent, std::move(e.m));
        level.emplace_back(e.s, static_cast<int>(tree.size() - 1));
      }
    }
  }

  // Drops each wait whose removal keeps every pair and makes the cycle no longer (the last
  // first): the beam's schedules carry meetings the search needed on its way.
  void drop_waits() {
    for (std::size_t i = best_path.size(); i-- > 0;) {
      std::vector<meeting> fewer = best_path;
      fewer.erase(fewer.begin() + static_cast<std::ptrdiff_t>(i));
      const std::optional<std::int64_t> mk = evaluate(p, fewer);
      if (mk && *mk <= best) {
        best = *mk;
        best_path = std::move(fewer);
        best_waits = static_cast<int>(best_path.size());
      }
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
  p.next_ref.resize(us.size());
  for (std::size_t c = 0; c < us.size(); ++c) {
    auto& nr = p.next_ref[c];
    nr.assign(static_cast<std::size_t>(p.n[c]) + 1, p.n[c]);
    for (int j = p.n[c] - 1; j >= 0; --j)
      nr[static_cast<std::size_t>(j)] =
          p.refs[c][static_cast<std::size_t>(j)].empty() ? nr[static_cast<std::size_t>(j) + 1] : j;
  }
  // Walking the pairs at every node pays where the search may prove the optimum.
  if (pairs.size() <= 256) p.pairs = pairs;
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
  if (s.stopped && s.best >= 0) s.drop_waits();
  if (s.best < 0) return std::nullopt;
  channels_schedule out;
  out.makespan_us = s.best;
  out.waits = s.best_path;
  out.exact = !s.stopped;
  out.nodes = s.nodes;
  // Not proved: the best of the root's bound (the longest channel's work, or a pair's two
  // operations and the handshake between them with their channels' work before and after) and,
  // for each two channels, the shortest cycle of their work alone with no handshake (Akers'
  // path, exact: any schedule of all the channels, seen from two, is such a path).
  out.lower_bound_us = s.best;
  if (!out.exact) {
    std::int64_t lb = bound_of(p, root, s.blocks(root));
    for (int a = 0; a < p.channels; ++a)
      for (int b = a + 1; b < p.channels; ++b) {
        std::vector<op_pair> two;
        for (const channel_pair& x : pairs) {
          if (x.p == a && x.q == b)
            two.push_back({x.i, x.j, x.ordered ? pair_rule::a_first : pair_rule::apart});
          else if (x.p == b && x.q == a)
            two.push_back({x.j, x.i, x.ordered ? pair_rule::b_first : pair_rule::apart});
        }
        if (const auto t = schedule_two_channels(us[static_cast<std::size_t>(a)],
                                                 us[static_cast<std::size_t>(b)], two, 0))
          lb = std::max(lb, t->makespan_us);
      }
    out.lower_bound_us = std::min(lb, s.best);
  }
  return out;
}

}  // namespace twinpost
