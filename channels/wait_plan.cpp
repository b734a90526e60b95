#include "channels/wait_plan.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace twinpost {

void time_operations(job_operations& ops, const std::function<double(int side, int segment)>& seconds) {
  for (int side = 0; side < 2; ++side) {
    // The last operation of each segment takes its time.
    std::map<int, channel_op*> last;
    for (plan_section& s : ops.sections)
      for (channel_op& op : s.ops[side]) {
        op.us = 0;
        last[op.segment] = &op;
      }
    for (auto& [segment, op] : last)
      op->us = static_cast<std::int64_t>(std::llround(std::max(0.0, seconds(side, segment)) * 1e6));
  }
}

std::optional<std::int64_t> plan_waits(job_operations& ops, const std::vector<plan_pair>& pairs,
                                       std::int64_t handshake_us) {
  std::int64_t cycle = 0;
  for (std::size_t i = 0; i < ops.sections.size(); ++i) {
    plan_section& s = ops.sections[i];
    std::vector<std::int64_t> a, b;
    for (const channel_op& op : s.ops[0]) a.push_back(op.us);
    for (const channel_op& op : s.ops[1]) b.push_back(op.us);
    std::vector<op_pair> here;
    for (const plan_pair& p : pairs)
      if (p.section == i) here.push_back(p.pair);
    const std::optional<two_channel_schedule> best = schedule_two_channels(a, b, here, handshake_us);
    if (!best) return std::nullopt;
    s.waits = best->waits;
    cycle += best->makespan_us + (i > 0 ? handshake_us : 0);
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
      for (int side = 0; side < 2; ++side) {
        const std::vector<channel_op>& v = ops.sections[s].ops[side];
        for (std::size_t k = 0; k < v.size(); ++k)
          if (v[k].first_line <= line && line <= v[k].last_line)
            found.push_back({s, side, static_cast<int>(k)});
      }
  auto ordered = [&](std::size_t s, int a, int b) {
    const plan_section& sec = ops.sections[s];
    const bool a_first = sec.ops[0][static_cast<std::size_t>(a)].first_line <
                         sec.ops[1][static_cast<std::size_t>(b)].first_line;
    return plan_pair{s, op_pair{a, b, a_first ? pair_rule::a_first : pair_rule::b_first}};
  };
  std::vector<plan_pair> out;
  auto add = [&](const plan_pair& p) {
    if (std::find(out.begin(), out.end(), p) == out.end()) out.push_back(p);
  };
  for (std::size_t i = 0; i < found.size(); ++i)
    for (std::size_t j = i + 1; j < found.size(); ++j)
      if (found[i].section == found[j].section && found[i].side != found[j].side) {
        const place& a = found[i].side == 0 ? found[i] : found[j];
        const place& b = found[i].side == 0 ? found[j] : found[i];
        add(ordered(a.section, a.index, b.index));
      }
  if (!out.empty()) return out;
  // No partner: each operation found keeps the CL's order with the other channel's whole section.
  for (const place& p : found) {
    const std::size_t others = ops.sections[p.section].ops[1 - p.side].size();
    for (std::size_t k = 0; k < others; ++k)
      add(p.side == 0 ? ordered(p.section, p.index, static_cast<int>(k))
                      : ordered(p.section, static_cast<int>(k), p.index));
  }
  return out;
}

}  // namespace twinpost
