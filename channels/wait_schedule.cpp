// channels/wait_schedule.hpp: Akers' shortest path for two channels that meet at rendezvous.
#include "channels/wait_schedule.hpp"

#include <algorithm>
#include <limits>
#include <queue>
#include <tuple>
#include <unordered_map>

namespace twinpost {

namespace {

constexpr std::int64_t far = std::int64_t{1} << 60;  // the plane's edge, past any cycle

// A pair as the region of the plane the path may not enter (open: touching is no overlap).
// The corners the path may turn at: its top-left (A waits at the start of its operation for B
// to end its one) and its bottom-right (B waits for A). A corner is named by the operations
// each channel has done there.
struct obstacle {
  std::int64_t x1, x2, y1, y2;
  bool nw, se;
  int nw_a, nw_b, se_a, se_b;
};

struct node {
  int a = 0, b = 0;  // operations done by each channel
};

std::vector<std::int64_t> starts(const std::vector<std::int64_t>& d) {
  std::vector<std::int64_t> s(d.size() + 1, 0);
  for (std::size_t i = 0; i < d.size(); ++i) s[i + 1] = s[i] + d[i];
  return s;
}

// Whether the open rectangle `o` meets the diagonal from (x, y) of length `t`, then the
// straight run to (cx, cy).
bool crosses(const obstacle& o, std::int64_t x, std::int64_t y, std::int64_t t, std::int64_t cx,
             std::int64_t cy) {
  // The diagonal: x + s, y + s for s in [0, t].
  const std::int64_t lo = std::max({o.x1 - x, o.y1 - y, std::int64_t{0}});
  const std::int64_t hi = std::min({o.x2 - x, o.y2 - y, t});
  if (lo < hi) return true;
  const std::int64_t mx = x + t, my = y + t;
  if (my == cy)  // then along X at y = cy, from mx to cx
    return o.y1 < cy && cy < o.y2 && std::max(mx, o.x1) < std::min(cx, o.x2);
  return o.x1 < cx && cx < o.x2 && std::max(my, o.y1) < std::min(cy, o.y2);  // along Y
}

// How the path came to a node: from the start, along X (B waited at its operation's start
// for A: a bottom-right corner) or along Y (A waited for B: a top-left corner).
enum class arrival : int { start = 0, along_x = 1, along_y = 2 };

struct label {
  std::int64_t time = std::numeric_limits<std::int64_t>::max();
  int waits = 0;
  std::int64_t from = -1;  // the node before (its key), -1 for the start
  // This node's rendezvous takes the place of the one before: the same channel kept waiting at
  // the same operation while the other went on past another region (one wait, one handshake).
  bool replaces = false;
  bool better_than(std::int64_t t, int w) const { return time < t || (time == t && waits <= w); }
};

}  // namespace

two_channel_schedule run_with_waits(const std::vector<std::int64_t>& a_us,
                                    const std::vector<std::int64_t>& b_us, const std::vector<rendezvous>& w,
                                    std::int64_t handshake_us) {
  two_channel_schedule s;
  s.waits = w;
  s.a_start.resize(a_us.size());
  s.b_start.resize(b_us.size());
  std::int64_t ta = 0, tb = 0;
  std::size_t ia = 0, ib = 0;
  const auto run = [](const std::vector<std::int64_t>& d, std::vector<std::int64_t>& start, std::size_t& i,
                      std::size_t to, std::int64_t& t) {
    for (; i < to && i < d.size(); ++i) {
      start[i] = t;
      t += d[i];
    }
  };
  for (const rendezvous& r : w) {
    run(a_us, s.a_start, ia, static_cast<std::size_t>(r.a), ta);
    run(b_us, s.b_start, ib, static_cast<std::size_t>(r.b), tb);
    ta = tb = std::max(ta, tb) + handshake_us;
  }
  run(a_us, s.a_start, ia, a_us.size(), ta);
  run(b_us, s.b_start, ib, b_us.size(), tb);
  s.makespan_us = std::max(ta, tb);
  return s;
}

bool keeps_pairs(const two_channel_schedule& s, const std::vector<std::int64_t>& a_us,
                 const std::vector<std::int64_t>& b_us, const std::vector<op_pair>& pairs) {
  for (const op_pair& p : pairs) {
    const std::int64_t sa = s.a_start[static_cast<std::size_t>(p.a)],
                       ea = sa + a_us[static_cast<std::size_t>(p.a)];
    const std::int64_t sb = s.b_start[static_cast<std::size_t>(p.b)],
                       eb = sb + b_us[static_cast<std::size_t>(p.b)];
    const bool ok = p.rule == pair_rule::a_first   ? ea <= sb
                    : p.rule == pair_rule::b_first ? eb <= sa
                                                   : std::max(sa, sb) >= std::min(ea, eb);
    if (!ok) return false;
  }
  return true;
}

std::optional<two_channel_schedule> schedule_two_channels(const std::vector<std::int64_t>& a_given,
                                                          const std::vector<std::int64_t>& b_given,
                                                          const std::vector<op_pair>& pairs,
                                                          std::int64_t handshake_us) {
  // An operation lasts at least a microsecond: in the plane a zero-length one has no extent, and
  // whether the other channel may pass it would not be seen.
  std::vector<std::int64_t> a_us = a_given, b_us = b_given;
  for (std::int64_t& d : a_us) d = std::max<std::int64_t>(d, 1);
  for (std::int64_t& d : b_us) d = std::max<std::int64_t>(d, 1);
  const std::vector<std::int64_t> sa = starts(a_us), sb = starts(b_us);
  const int m = static_cast<int>(b_us.size());
  const std::int64_t ta = sa.back(), tb = sb.back();
  std::vector<obstacle> obs;
  obs.reserve(pairs.size());
  for (const op_pair& p : pairs) {
    const std::int64_t x1 = sa[static_cast<std::size_t>(p.a)], x2 = sa[static_cast<std::size_t>(p.a) + 1];
    const std::int64_t y1 = sb[static_cast<std::size_t>(p.b)], y2 = sb[static_cast<std::size_t>(p.b) + 1];
    switch (p.rule) {
      case pair_rule::apart:
        if (x1 < x2 && y1 < y2) obs.push_back({x1, x2, y1, y2, true, true, p.a, p.b + 1, p.a + 1, p.b});
        break;
      // B may not start its operation before A has ended its one: everything above the
      // operation's start and left of the other's end. Only the bottom-right corner.
      case pair_rule::a_first: obs.push_back({-far, x2, y1, far, false, true, 0, 0, p.a + 1, p.b}); break;
      case pair_rule::b_first: obs.push_back({x1, far, -far, y2, true, false, p.a, p.b + 1, 0, 0}); break;
    }
  }
  const auto key = [m](int a, int b, arrival d) {
    return (static_cast<std::int64_t>(a) * (m + 1) + b) * 3 + static_cast<int>(d);
  };
  std::unordered_map<std::int64_t, label> best;
  // Nodes by the sum of their coordinates: every turn moves the path on, so a node's
  // predecessors are all done when it is taken.
  using entry = std::tuple<std::int64_t, std::int64_t>;
  std::priority_queue<entry, std::vector<entry>, std::greater<>> open;
  const std::int64_t start = key(0, 0, arrival::start);
  best[start] = {0, 0, -1, false};
  open.emplace(0, start);
  label end;
  bool end_drops = false;  // the last node's rendezvous is no rendezvous: one channel had ended
  const auto relax = [&](int a, int b, arrival d, std::int64_t t, int w, std::int64_t from, bool replaces) {
    const std::int64_t k = key(a, b, d);
    const auto [it, fresh] = best.try_emplace(k);
    if (!fresh && it->second.better_than(t, w)) return;
    it->second = {t, w, from, replaces};
    if (fresh) open.emplace(sa[static_cast<std::size_t>(a)] + sb[static_cast<std::size_t>(b)], k);
  };
  while (!open.empty()) {
    const std::int64_t k = std::get<1>(open.top());
    open.pop();
    const label here = best[k];
    const auto came = static_cast<arrival>(k % 3);
    const int a = static_cast<int>(k / 3 / (m + 1)), b = static_cast<int>(k / 3 % (m + 1));
    const std::int64_t x = sa[static_cast<std::size_t>(a)], y = sb[static_cast<std::size_t>(b)];
    // Along the diagonal until the first region, or to the end.
    const std::int64_t reach = std::min(ta - x, tb - y);
    std::int64_t first = reach;
    for (const obstacle& o : obs) {
      const std::int64_t lo = std::max(o.x1 - x, o.y1 - y), hi = std::min(o.x2 - x, o.y2 - y);
      if (lo < 0 && hi > 0) {
        first = -1;  // the node lies inside a region: no path goes on from it
        break;
      }
      if (std::max(lo, std::int64_t{0}) < hi) first = std::min(first, std::max(lo, std::int64_t{0}));
    }
    if (first < 0) continue;
    // A straight run on from a node reached the same way is the same wait going on.
    const auto goes_on = [&](std::int64_t cx, std::int64_t cy) {
      return (came == arrival::along_x && cy == y) || (came == arrival::along_y && cx == x);
    };
    if (first == reach) {
      // Nothing in the way: both channels run out (the last straight run crosses nothing, or
      // the diagonal would have met it). A channel that waited at its end waits for nothing.
      const bool ok = std::none_of(obs.begin(), obs.end(),
                                   [&](const obstacle& o) { return crosses(o, x, y, reach, ta, tb); });
      const bool drops = goes_on(ta, tb);
      const std::int64_t t = here.time + std::max(ta - x, tb - y) - (drops ? handshake_us : 0);
      const int w = here.waits - (drops ? 1 : 0);
      if (ok && !end.better_than(t, w)) {
        end = {t, w, k, false};
        end_drops = drops;
      }
      continue;
    }
    // Early turns: at a boundary the diagonal crosses before the region (the node itself
    // included), one channel stops and waits until the other has gone past the region on the
    // side it may pass. With a handshake per wait, one early wait can be shorter in all than
    // two that wait as late as they may (the extension arcs then carry it past later regions).
    for (const obstacle& o : obs) {
      const std::int64_t lo = std::max({o.x1 - x, o.y1 - y, std::int64_t{0}}),
                         hi = std::min(o.x2 - x, o.y2 - y);
      if (!(lo < hi && lo == first)) continue;
      if (o.nw)  // over it: A stops at one of its boundaries, B goes on past the region's top
        for (int i = a; i < static_cast<int>(sa.size()) && sa[static_cast<std::size_t>(i)] - x <= first;
             ++i) {
          const std::int64_t t = sa[static_cast<std::size_t>(i)] - x, px = x + t, py = y + t;
          if (t == 0 && came == arrival::along_y) continue;  // the wait going on: an extension
          const auto at = std::lower_bound(sb.begin() + b, sb.end(), std::max(o.y2 - (o.x1 - px), py));
          if (at == sb.end() || (t == 0 && *at == y)) continue;
          if (std::any_of(obs.begin(), obs.end(),
                          [&](const obstacle& q) { return crosses(q, x, y, t, px, *at); }))
            continue;
          relax(i, static_cast<int>(at - sb.begin()), arrival::along_y,
                here.time + std::max(px - x, *at - y) + handshake_us, here.waits + 1, k, false);
        }
      if (o.se)  // under it: B stops, A goes on past the region's right side
        for (int j = b; j < static_cast<int>(sb.size()) && sb[static_cast<std::size_t>(j)] - y <= first;
             ++j) {
          const std::int64_t t = sb[static_cast<std::size_t>(j)] - y, px = x + t, py = y + t;
          if (t == 0 && came == arrival::along_x) continue;
          const auto at = std::lower_bound(sa.begin() + a, sa.end(), std::max(o.x2 - (o.y1 - py), px));
          if (at == sa.end() || (t == 0 && *at == x)) continue;
          if (std::any_of(obs.begin(), obs.end(),
                          [&](const obstacle& q) { return crosses(q, x, y, t, *at, py); }))
            continue;
          relax(static_cast<int>(at - sa.begin()), j, arrival::along_x,
                here.time + std::max(*at - x, py - y) + handshake_us, here.waits + 1, k, false);
        }
    }
    for (const obstacle& o : obs) {
      const std::int64_t lo = std::max({o.x1 - x, o.y1 - y, std::int64_t{0}}),
                         hi = std::min(o.x2 - x, o.y2 - y);
      if (!(lo < hi && lo == first)) continue;
      // The wait this node ends may go on instead, until the diagonal after it passes the region:
      // one handshake for what would otherwise be two turns (the channel that waits would wait
      // again at the same operation).
      if (came == arrival::along_x && o.x2 < far) {
        const std::int64_t clear = o.x2 - (o.y1 - y);  // A's progress that lets B pass under it
        const auto at = std::lower_bound(sa.begin() + a + 1, sa.end(), std::max(clear, x + 1));
        if (at != sa.end() && std::none_of(obs.begin(), obs.end(),
                                           [&](const obstacle& q) { return crosses(q, x, y, 0, *at, y); }))
          relax(static_cast<int>(at - sa.begin()), b, arrival::along_x, here.time + (*at - x), here.waits, k,
                true);
      }
      if (came == arrival::along_y && o.y2 < far) {
        const std::int64_t clear = o.y2 - (o.x1 - x);
        const auto at = std::lower_bound(sb.begin() + b + 1, sb.end(), std::max(clear, y + 1));
        if (at != sb.end() && std::none_of(obs.begin(), obs.end(),
                                           [&](const obstacle& q) { return crosses(q, x, y, 0, x, *at); }))
          relax(a, static_cast<int>(at - sb.begin()), arrival::along_y, here.time + (*at - y), here.waits, k,
                true);
      }
      for (const arrival d : {arrival::along_y, arrival::along_x}) {
        if (!(d == arrival::along_y ? o.nw : o.se)) continue;
        const int ca = d == arrival::along_y ? o.nw_a : o.se_a, cb = d == arrival::along_y ? o.nw_b : o.se_b;
        const std::int64_t cx = sa[static_cast<std::size_t>(ca)], cy = sb[static_cast<std::size_t>(cb)];
        if (cx < x || cy < y) continue;
        const std::int64_t diagonal = std::min(cx - x, cy - y);
        const bool ok = std::none_of(obs.begin(), obs.end(),
                                     [&](const obstacle& q) { return crosses(q, x, y, diagonal, cx, cy); });
        if (!ok) continue;
        const bool same = d == came && goes_on(cx, cy);
        relax(ca, cb, d, here.time + std::max(cx - x, cy - y) + (same ? 0 : handshake_us),
              here.waits + (same ? 0 : 1), k, same);
      }
    }
  }
  if (end.from < 0) return std::nullopt;
  std::vector<rendezvous> w;
  bool skip = end_drops;
  for (std::int64_t k = end.from; k != start; k = best[k].from) {
    if (!skip) w.push_back({static_cast<int>(k / 3 / (m + 1)), static_cast<int>(k / 3 % (m + 1))});
    skip = best[k].replaces;
  }
  std::reverse(w.begin(), w.end());
  two_channel_schedule s = run_with_waits(a_us, b_us, w, handshake_us);
  return s;
}

}  // namespace twinpost
