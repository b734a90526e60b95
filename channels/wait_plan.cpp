#include "channels/wait_plan.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <tuple>
#include <utility>

namespace twinpost {

namespace {

// Widens op's region by the |x| range of [xa, xb] and the z range of [za, zb] (CL units).
void sweep(channel_op& op, const channel_track& t, double xa, double xb, double za, double zb) {
  double lo = std::min(xa, xb), hi = std::max(xa, xb);
  double r0 = lo <= 0 && hi >= 0 ? 0 : std::min(std::abs(lo), std::abs(hi));
  double r1 = std::max(std::abs(lo), std::abs(hi));
  op.r0 = std::min(op.r0, r0 * t.mm);
  op.r1 = std::max(op.r1, r1 * t.mm);
  op.z0 = std::min(op.z0, std::min(za, zb) * t.mm);
  op.z1 = std::max(op.z1, std::max(za, zb) * t.mm);
  op.reach = std::max(op.reach, t.reach);
  op.parts |= t.part;
  const std::size_t k = t.part == 2 ? 1 : 0;
  if (t.rpm[k] != 0) {
    if (op.rpm[k] == 0) op.rpm[k] = t.rpm[k];
    if (op.rpm[k] != t.rpm[k]) op.rpm[k] = std::numeric_limits<double>::quiet_NaN();
  }
  if (t.css) op.css = true;
  if ((t.speed_parts & t.part) == 0) op.borrows_speed = true;
  if (!t.reach_known) op.unknown_tool = true;
}

// A TLDATA's reach past the tip: half the diameter of a drill or mill, the nose radius (the
// first value) of a turning tool; nothing known: -1.
double tool_reach(const tool_data_event& d) {
  if (d.values.empty()) return -1;
  bool diameter = d.major == "CUTTER";
  for (const std::string& w : d.words)
    if (w == "DRILL" || w == "MILL") diameter = true;
  return std::abs(d.values.front()) * (diameter ? 0.5 : 1.0);
}

}  // namespace

void note_operation_event(channel_op& op, channel_track& t, const event& e) {
  if (const auto* m = std::get_if<motion_event>(&e.data)) {
    if (m->kind == motion_kind::home) {
      t.has_last = false;
      return;
    }
    if (t.cycle >= 0 && m->kind != motion_kind::from) {
      const double d = t.cycle / t.mm;
      const vec3 from = t.has_last ? t.last : m->pos;
      if (t.cycle_kind == 1) {
        // A hole along the axis: its depth and retract within the cycle's largest distance.
        sweep(op, t, m->pos.x, m->pos.x, m->pos.z - d, m->pos.z + d);
      } else {
        // Grooving, threading and the rest: from where the tool stood to the point, down to
        // the centre line (a groove's or a thread's depth is not read: the whole radius counts),
        // and the cycle's largest distance along z.
        sweep(op, t, 0, std::max(std::abs(from.x), std::abs(m->pos.x)), std::min(from.z, m->pos.z) - d,
              std::max(from.z, m->pos.z) + d);
      }
    } else if (!m->rapid && m->kind != motion_kind::from) {
      const vec3 from = t.has_last ? t.last : m->pos;
      sweep(op, t, from.x, m->pos.x, from.z, m->pos.z);
      t.last_dr = (std::abs(m->pos.x) - std::abs(from.x)) * t.mm;
      t.fed = true;
    } else if (m->rapid) {
      op.rapid_r0 = std::min(op.rapid_r0, std::abs(m->pos.x) * t.mm);
      if (t.fed && t.last_dr < -0.5) op.retracts_inward = true;
      t.fed = false;
    }
    t.moved = true;
    t.last = m->pos;
    t.has_last = true;
    return;
  }
  if (const auto* a = std::get_if<arc_event>(&e.data)) {
    // The whole circle's box: conservative, and independent of the plane it is in.
    const double r = std::abs(a->radius);
    sweep(op, t, a->center.x - r, a->center.x + r, a->center.z - r, a->center.z + r);
    t.last = a->end;
    t.has_last = true;
    return;
  }
  if (const auto* s = std::get_if<spindle_event>(&e.data)) {
    if (s->spindle == "main") t.part = 1;
    if (s->spindle == "sub") t.part = 2;
    if (s->mode == spindle_mode::smm || s->mode == spindle_mode::sfm) t.css = true;
    if (s->mode == spindle_mode::rpm || s->mode == spindle_mode::off) t.css = false;
    if (s->mode == spindle_mode::rpm || s->mode == spindle_mode::smm || s->mode == spindle_mode::sfm)
      t.speed_parts |= t.part;
    // The part spindle's speed: a named main or sub, or the channel's own on a turret.
    const bool part_spindle =
        s->spindle == "main" || s->spindle == "sub" || (s->spindle.empty() && t.own_is_part);
    if (part_spindle) {
      const std::size_t k = t.part == 2 ? 1 : 0;
      t.rpm[k] = s->mode == spindle_mode::rpm ? (s->dir == rotation::ccw ? -s->speed : s->speed) : 0;
      if (s->mode != spindle_mode::off) t.turned = t.part;
    }
    if (s->mode == spindle_mode::off) {
      op.stops = true;
      op.parts |= t.part;
      // Unnamed, it stops the spindle the channel last turned (the writer's rule), which may
      // hold another part than the one the channel works on now: both count.
      if (s->spindle.empty()) op.parts |= t.turned;
    }
    return;
  }
  if (const auto* d = std::get_if<tool_data_event>(&e.data)) {
    // Before the tool call (NX, the samples) it is the next tool's; after it and before a move
    // (Creo, `$$-> CUTTER` after LOADTL), the tool's in use.
    const double reach = tool_reach(*d);
    if (reach < 0) return;
    if (t.called && !t.moved) {
      t.reach = reach * t.mm;
      t.reach_known = true;
    } else {
      t.pending = reach;
    }
    return;
  }
  if (const auto* tl = std::get_if<tool_event>(&e.data)) {
    if (tl->preselect) return;
    t.reach_known = t.pending >= 0;
    t.reach = t.reach_known ? t.pending * t.mm : 10;
    t.pending = -1;
    t.called = true;
    t.moved = false;
    return;
  }
  if (const auto* c = std::get_if<cycle_event>(&e.data)) {
    if (c->type == "OFF") {
      t.cycle = -1;
    } else {
      const bool axial = c->type == "DRILL" || c->type == "DEEP" || c->type == "DEEP2" || c->type == "TAP" ||
                         c->type == "BORE" || c->type == "BRKCHP" || c->type == "REAM";
      t.cycle_kind = axial ? 1 : 2;
      double d = 0;
      for (const auto& [name, value] : c->params) d = std::max(d, std::abs(value));
      for (double v : c->positional) d = std::max(d, std::abs(v));
      t.cycle = d * t.mm;
    }
    return;
  }
  if (std::holds_alternative<stop_event>(e.data) || std::holds_alternative<aux_event>(e.data) ||
      std::holds_alternative<passthrough_event>(e.data)) {
    op.exclusive = true;
    return;
  }
  if (const auto* x = std::get_if<text_event>(&e.data); x && x->kind == text_kind::insert)
    op.exclusive = true;
}

namespace {

enum class fixed_rule { none, alone, severs, stops, unknown, near, css, borrowed, speeds };

// Part `k`'s spindle at different speeds (or directions) in a and b: both known, and not the same.
bool speeds_differ(const channel_op& a, const channel_op& b, std::size_t k) {
  if (a.rpm[k] == 0 || b.rpm[k] == 0) return false;
  return std::isnan(a.rpm[k]) || std::isnan(b.rpm[k]) || a.rpm[k] != b.rpm[k];
}

fixed_rule fixed_between(const channel_op& a, const channel_op& b, double clearance_mm) {
  const unsigned shared = a.parts & b.parts;
  if (a.exclusive || b.exclusive) return fixed_rule::alone;
  if (shared == 0) return fixed_rule::none;
  if (severs_part(a) || severs_part(b)) return fixed_rule::severs;
  if (a.stops || b.stops) return fixed_rule::stops;
  if (a.unknown_tool || b.unknown_tool) return fixed_rule::unknown;
  const double near = a.reach + b.reach + clearance_mm;
  // A tool working inside fills the bore down to the centre line with its body.
  const double a0 = works_inside(a) ? 0 : a.r0, b0 = works_inside(b) ? 0 : b.r0;
  const double gap_r = std::max(a0 - b.r1, b0 - a.r1);
  const double gap_z = std::max(a.z0 - b.z1, b.z0 - a.z1);
  if (gap_r < near && gap_z < near) return fixed_rule::near;
  if (a.css && b.css) return fixed_rule::css;
  if ((a.css && b.borrows_speed) || (b.css && a.borrows_speed)) return fixed_rule::borrowed;
  if (((shared & 1) != 0 && speeds_differ(a, b, 0)) || ((shared & 2) != 0 && speeds_differ(a, b, 1)))
    return fixed_rule::speeds;
  return fixed_rule::none;
}

}  // namespace

bool severs_part(const channel_op& op) { return op.r0 <= 1 && op.r1 - op.r0 > 2; }

bool works_inside(const channel_op& op) {
  return op.retracts_inward && op.rapid_r0 <= op.r0 + 0.001 && op.rapid_r0 < op.r1 - 0.1;
}

std::vector<plan_pair> fixed_pairs(const job_operations& ops, double clearance_mm) {
  std::vector<plan_pair> out;
  for (std::size_t s = 0; s < ops.sections.size(); ++s) {
    const plan_section& sec = ops.sections[s];
    if (sec.together) continue;
    for (std::size_t p = 0; p < sec.ops.size(); ++p)
      for (std::size_t q = p + 1; q < sec.ops.size(); ++q)
        for (std::size_t i = 0; i < sec.ops[p].size(); ++i)
          for (std::size_t j = 0; j < sec.ops[q].size(); ++j) {
            const channel_op& a = sec.ops[p][i];
            const channel_op& b = sec.ops[q][j];
            if (fixed_between(a, b, clearance_mm) == fixed_rule::none) continue;
            const bool a_first = a.first_line < b.first_line;
            out.push_back(plan_pair{s,
                                    op_pair{static_cast<int>(i), static_cast<int>(j),
                                            a_first ? pair_rule::a_first : pair_rule::b_first},
                                    static_cast<int>(p), static_cast<int>(q)});
          }
  }
  return out;
}

std::string fixed_pair_reason(const job_operations& ops, const plan_pair& p, double clearance_mm) {
  const plan_section& sec = ops.sections[p.section];
  const channel_op& a = sec.ops[static_cast<std::size_t>(p.p)][static_cast<std::size_t>(p.pair.a)];
  const channel_op& b = sec.ops[static_cast<std::size_t>(p.q)][static_cast<std::size_t>(p.pair.b)];
  const char* part = (a.parts & b.parts & 1) != 0 ? "main" : "sub";
  switch (fixed_between(a, b, clearance_mm)) {
    case fixed_rule::none: return {};
    case fixed_rule::alone: return "a program stop, an M or G code or a record passed through runs alone";
    case fixed_rule::severs:
      return fmt::format(
          "one of them cuts to the centre line (a part-off or a face): nothing else cuts the part in the {} "
          "spindle meanwhile",
          part);
    case fixed_rule::stops:
      return fmt::format("one of them stops the {} spindle: nothing else cuts its part meanwhile", part);
    case fixed_rule::unknown:
      return fmt::format(
          "one of them cuts the part in the {} spindle with a tool of unknown size (no TLDATA or CUTTER): "
          "nothing else cuts the part meanwhile",
          part);
    case fixed_rule::near: {
      const bool inside = works_inside(a) || works_inside(b);
      return fmt::format(
          "they cut closer than {:.1f} mm to each other on the part in the {} spindle (radius {:.1f}-{:.1f}, "
          "z "
          "{:.1f}-{:.1f}; radius {:.1f}-{:.1f}, z {:.1f}-{:.1f}{}): the same material, or tools that meet",
          a.reach + b.reach + clearance_mm, part, works_inside(a) ? 0 : a.r0, a.r1, a.z0, a.z1,
          works_inside(b) ? 0 : b.r0, b.r1, b.z0, b.z1,
          inside ? "; a tool working inside fills its bore to the centre line" : "");
    }
    case fixed_rule::css:
      return fmt::format(
          "both cut under constant surface speed on the part in the {} spindle: each clamps the spindle's "
          "rpm",
          part);
    case fixed_rule::borrowed:
      return fmt::format(
          "one of them cuts the part in the {} spindle at a speed its CL never gives (no SPINDL of its own), "
          "the other under constant surface speed: its rpm would follow the other's diameter",
          part);
    case fixed_rule::speeds:
      return fmt::format(
          "they turn the {} spindle at different speeds or directions: each would change the other's", part);
  }
  return {};
}

void time_operations(job_operations& ops, const std::function<double(int side, int segment)>& seconds) {
  for (std::size_t side = 0; side < ops.channels.size(); ++side) {
    // The last operation of each segment takes its time.
    std::map<int, channel_op*> last;
    for (plan_section& s : ops.sections)
      for (channel_op& op : s.ops[side]) {
        op.us = 0;
        last[op.segment] = &op;
      }
    for (auto& [segment, op] : last)
      op->us = static_cast<std::int64_t>(
          std::llround(std::max(0.0, seconds(static_cast<int>(side), segment)) * 1e6));
  }
}

std::vector<std::size_t> minimal_pairs(const std::vector<plan_pair>& pairs) {
  // Per section, pair of sides and rule: p-first pairs by p's operation descending (q's
  // ascending), kept when q's operation is before every one kept so far; q-first the same with
  // the roles swapped.
  std::vector<std::size_t> order(pairs.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  auto key = [&](std::size_t i) {
    const plan_pair& p = pairs[i];
    const bool a_first = p.pair.rule == pair_rule::a_first;
    const int lead = a_first ? p.pair.a : p.pair.b, follow = a_first ? p.pair.b : p.pair.a;
    return std::make_tuple(p.section, p.p, p.q, static_cast<int>(p.pair.rule), -lead, follow);
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return key(x) < key(y); });
  std::vector<std::size_t> kept;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const plan_pair& p = pairs[order[k]];
    if (p.pair.rule == pair_rule::apart) {
      kept.push_back(order[k]);
      continue;
    }
    const bool a_first = p.pair.rule == pair_rule::a_first;
    const int follow = a_first ? p.pair.b : p.pair.a;
    // The kept pairs of this section, sides and rule all lead by as much or more, and each follows
    // earlier than the one kept before it: the last one kept follows earliest.
    bool implied = false;
    if (!kept.empty()) {
      const plan_pair& q = pairs[kept.back()];
      implied = q.section == p.section && q.p == p.p && q.q == p.q && q.pair.rule == p.pair.rule &&
                (a_first ? q.pair.b : q.pair.a) <= follow;
    }
    if (!implied) kept.push_back(order[k]);
  }
  std::sort(kept.begin(), kept.end());
  return kept;
}

namespace {

// Two channels: Akers' plane, and a rendezvous for every ordered pair.
std::optional<std::int64_t> plan_two(plan_section& s, std::size_t i, const std::vector<plan_pair>& pairs,
                                     std::int64_t handshake_us) {
  std::vector<std::int64_t> a, b;
  for (const channel_op& op : s.ops[0]) a.push_back(op.us);
  for (const channel_op& op : s.ops[1]) b.push_back(op.us);
  std::vector<op_pair> here;
  for (const plan_pair& p : pairs)
    if (p.section == i) here.push_back(p.pair);
  const std::optional<two_channel_schedule> best = schedule_two_channels(a, b, here, handshake_us);
  if (!best) return std::nullopt;
  std::vector<rendezvous> waits = best->waits;
  // Every ordered pair by a rendezvous: A has done its operation (x > a) while B has not
  // started its own (y <= b), or the other way round. In a schedule that keeps the pair, no
  // wait is on the wrong side of it, so the one added fits the chain of the others.
  for (const op_pair& p : here) {
    const rendezvous need =
        p.rule == pair_rule::a_first ? rendezvous{p.a + 1, p.b} : rendezvous{p.a, p.b + 1};
    const bool covered = std::any_of(waits.begin(), waits.end(), [&](const rendezvous& w) {
      return p.rule == pair_rule::a_first ? w.a >= need.a && w.b <= need.b : w.b >= need.b && w.a <= need.a;
    });
    if (covered || p.rule == pair_rule::apart) continue;
    waits.insert(std::upper_bound(waits.begin(), waits.end(), need,
                                  [](const rendezvous& x, const rendezvous& y) {
                                    return x.a < y.a || (x.a == y.a && x.b < y.b);
                                  }),
                 need);
  }
  s.waits.clear();
  for (const rendezvous& w : waits) s.waits.push_back(meeting{{{0, w.a}, {1, w.b}}});
  return run_with_waits(a, b, waits, handshake_us).makespan_us;
}

// Three or four: the meetings' search, which keeps each pair by its waits alone.
std::optional<std::int64_t> plan_many(plan_section& s, std::size_t i, const std::vector<plan_pair>& pairs,
                                      std::int64_t handshake_us, const schedule_budget& budget) {
  std::vector<std::vector<std::int64_t>> us(s.ops.size());
  for (std::size_t side = 0; side < s.ops.size(); ++side)
    for (const channel_op& op : s.ops[side]) us[side].push_back(op.us);
  std::vector<channel_pair> here;
  for (const plan_pair& p : pairs) {
    if (p.section != i) continue;
    if (p.pair.rule == pair_rule::b_first)
      here.push_back({p.q, p.pair.b, p.p, p.pair.a, true});
    else
      here.push_back({p.p, p.pair.a, p.q, p.pair.b, p.pair.rule == pair_rule::a_first});
  }
  const std::optional<channels_schedule> best = schedule_channels(us, here, handshake_us, budget);
  if (!best) return std::nullopt;
  s.waits = best->waits;
  return best->makespan_us;
}

}  // namespace

std::optional<std::int64_t> plan_waits(job_operations& ops, const std::vector<plan_pair>& pairs,
                                       std::int64_t handshake_us, const schedule_budget& budget) {
  // The search's nodes shared by the sections of three or four channels (a job of many part
  // transfers would otherwise spend the whole budget on each; attack 57), each given at least
  // 50,000 (a few operations a channel are proved within that).
  std::size_t searched = 0;
  for (const plan_section& s : ops.sections) searched += s.ops.size() > 2 ? 1 : 0;
  schedule_budget each = budget;
  if (searched > 1) each.nodes = std::max<long>(50'000, budget.nodes / static_cast<long>(searched));
  std::int64_t cycle = 0;
  for (std::size_t i = 0; i < ops.sections.size(); ++i) {
    plan_section& s = ops.sections[i];
    const std::optional<std::int64_t> span =
        s.ops.size() == 2 ? plan_two(s, i, pairs, handshake_us) : plan_many(s, i, pairs, handshake_us, each);
    if (!span) return std::nullopt;
    cycle += *span + (i > 0 ? handshake_us : 0);
  }
  return cycle;
}

std::vector<plan_pair> pairs_for_lines(const job_operations& ops, const std::vector<int>& lines) {
  struct place {
    std::size_t section;
    int side, index;
  };
  std::vector<place> found;
  for (int line : lines)
    for (std::size_t s = 0; s < ops.sections.size(); ++s)
      for (int side = 0; side < static_cast<int>(ops.sections[s].ops.size()) && !ops.sections[s].together;
           ++side) {
        const std::vector<channel_op>& v = ops.sections[s].ops[static_cast<std::size_t>(side)];
        for (std::size_t k = 0; k < v.size(); ++k)
          if (v[k].first_line <= line && line <= v[k].last_line)
            found.push_back({s, side, static_cast<int>(k)});
      }
  // Side p's operation a and side q's b (p < q), in the CL's order.
  auto ordered = [&](std::size_t s, int p, int a, int q, int b) {
    const plan_section& sec = ops.sections[s];
    const bool a_first = sec.ops[static_cast<std::size_t>(p)][static_cast<std::size_t>(a)].first_line <
                         sec.ops[static_cast<std::size_t>(q)][static_cast<std::size_t>(b)].first_line;
    return plan_pair{s, op_pair{a, b, a_first ? pair_rule::a_first : pair_rule::b_first}, p, q};
  };
  std::vector<plan_pair> out;
  auto add = [&](const plan_pair& p) {
    if (std::find(out.begin(), out.end(), p) == out.end()) out.push_back(p);
  };
  for (std::size_t i = 0; i < found.size(); ++i)
    for (std::size_t j = i + 1; j < found.size(); ++j)
      if (found[i].section == found[j].section && found[i].side != found[j].side) {
        const place& a = found[i].side < found[j].side ? found[i] : found[j];
        const place& b = found[i].side < found[j].side ? found[j] : found[i];
        add(ordered(a.section, a.side, a.index, b.side, b.index));
      }
  if (!out.empty()) return out;
  // No partner: each operation found keeps the CL's order with the other channels' whole section.
  for (const place& p : found) {
    const plan_section& sec = ops.sections[p.section];
    for (int other = 0; other < static_cast<int>(sec.ops.size()); ++other) {
      if (other == p.side) continue;
      for (std::size_t k = 0; k < sec.ops[static_cast<std::size_t>(other)].size(); ++k)
        add(p.side < other ? ordered(p.section, p.side, p.index, other, static_cast<int>(k))
                           : ordered(p.section, other, static_cast<int>(k), p.side, p.index));
    }
  }
  return out;
}

}  // namespace twinpost
