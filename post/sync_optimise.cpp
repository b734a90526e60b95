#include "post/sync_optimise.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "analysis/cycle_time.hpp"

namespace twinpost {

namespace {

void replay(const diagnostic_list& from, diagnostic_sink& to) {
  for (const diagnostic& d : from.all()) to.report(d);
}

void report(diagnostic_sink& to, severity level, const std::string& file, std::string message) {
  diagnostic d;
  d.level = level;
  d.file = file;
  d.message = std::move(message);
  to.report(std::move(d));
}

// The CL lines of each error and its notes, one list per error.
std::vector<std::vector<int>> finding_lines(const diagnostic_list& got, const std::string& cl_file) {
  std::vector<std::vector<int>> out;
  bool in_error = false;
  for (const diagnostic& d : got.all()) {
    if (d.level != severity::note) {
      in_error = d.level == severity::error;
      if (in_error) out.emplace_back();
    }
    if (in_error && d.file == cl_file && d.line > 0) out.back().push_back(d.line);
  }
  return out;
}

// The errors, one per finding_lines entry.
std::vector<std::string> finding_messages(const diagnostic_list& got) {
  std::vector<std::string> out;
  for (const diagnostic& d : got.all())
    if (d.level == severity::error) out.push_back(d.message);
  return out;
}

// "channel 1 (job.cls:12-20) before channel 2 (job.cls:21-30): why".
std::string pair_text(const job_operations& ops, const plan_pair& p, const std::string& file,
                      const std::string& why) {
  const plan_section& sec = ops.sections[p.section];
  const auto sp = static_cast<std::size_t>(p.p), sq = static_cast<std::size_t>(p.q);
  const channel_op& a = sec.ops[sp][static_cast<std::size_t>(p.pair.a)];
  const channel_op& b = sec.ops[sq][static_cast<std::size_t>(p.pair.b)];
  const std::string ta =
      fmt::format("channel {} ({}:{}-{})", ops.channels[sp], file, a.first_line, a.last_line);
  const std::string tb =
      fmt::format("channel {} ({}:{}-{})", ops.channels[sq], file, b.first_line, b.last_line);
  const bool a_first = p.pair.rule == pair_rule::a_first;
  return fmt::format("{} before {}: {}", a_first ? ta : tb, a_first ? tb : ta, why);
}

std::string first_error(const diagnostic_list& got) {
  for (const diagnostic& d : got.all())
    if (d.level == severity::error) return d.message;
  return "no error";
}

}  // namespace

post_summary post_optimised(const post_options& o, const machine& m, diagnostic_sink& diags,
                            const post_attempt& attempt, bool compare) {
  if (!has_timing(m)) {
    report(diags, severity::error, m.source,
           fmt::format("--sync optimise: machine '{}' has no [timing] table, and the waits are placed by "
                       "the operations' times (docs/wait-placement.md)",
                       m.name));
    return {};
  }
  // The sequential post: the operations and their times.
  diagnostic_list first;
  optimise_attempt seq = attempt(optimise_step::timing, nullptr, first);
  if (!seq.sum.ok) {
    if (compare) {
      post_summary none;
      none.optimum_unknown =
          fmt::format("the job does not post with a wait at every operation ({})", first_error(first));
      return none;
    }
    replay(first, diags);
    return seq.sum;
  }
  job_operations ops = seq.ops;
  auto fall_back = [&](const std::string& why) {
    if (compare) {
      post_summary none;
      none.optimum_unknown = why;
      return none;
    }
    // A job with sync records of its own keeps them: sequential would set them aside and run
    // the heads in an order they may forbid (attack 49).
    const bool own = seq.ops.has_sync_records;
    report(diags, severity::warning, o.cl_path,
           fmt::format("{}: {}; {}",
                       // The policy asked for: `auto` chose optimise for a job without sync records.
                       o.policy == sync_policy::automatic ? "--sync auto (optimise)" : "--sync optimise", why,
                       own ? "the channels wait at the job's sync records alone (explicit)"
                           : "the channels wait for each other at every head switch (sequential)"));
    diagnostic_list last;
    optimise_attempt r =
        attempt(own ? optimise_step::fallback_explicit : optimise_step::fallback, nullptr, last);
    replay(last, diags);
    return r.sum;
  };
  if (ops.channels.empty())
    return fall_back(
        fmt::format("it places waits between two to {0} channels, and this job does not use two to {0}",
                    schedule_max_channels));
  if (!seq.sum.timing || !seq.sum.timing->ok) return fall_back("the sequential programs could not be timed");
  for (const plan_section& s : ops.sections)
    for (std::size_t p = 0; p < s.ops.size(); ++p)
      for (std::size_t q = p + 1; q < s.ops.size(); ++q)
        if (s.ops[p].size() * s.ops[q].size() > optimise_max_section_pairs)
          return fall_back(
              fmt::format("channels {} and {} have {} and {} operations between two barriers, more than "
                          "the {} pairs of them it weighs",
                          ops.channels[p], ops.channels[q], s.ops[p].size(), s.ops[q].size(),
                          optimise_max_section_pairs));
  const timeline& t = *seq.sum.timing;
  time_operations(ops, [&](int side, int segment) {
    const int ch = ops.channels[static_cast<std::size_t>(side)];
    double s = 0;
    for (const channel_times& c : t.channels)
      if (c.channel == ch)
        for (const tool_operation& op : c.operations)
          if (op.segment == segment) s += op.seconds;
    return s;
  });
  double handshake = 0;
  for (int ch : ops.channels)
    handshake = std::max(handshake, m.channels[static_cast<std::size_t>(ch - 1)].timing.wait);
  const auto handshake_us = static_cast<std::int64_t>(std::llround(std::max(0.0, handshake) * 1e6));

  const double clearance = m.interference.clearance;
  std::vector<plan_pair> pairs = fixed_pairs(ops, clearance);
  std::vector<std::string> reasons(pairs.size());  // per pair; a fixed pair's made when shown
  std::string why;
  for (int post = 2; post <= optimise_max_posts; ++post) {
    // The pairs no other implies: the schedule's rectangles, and the summary's lines.
    const std::vector<std::size_t> needed = minimal_pairs(pairs);
    std::vector<plan_pair> kept;
    for (std::size_t i : needed) kept.push_back(pairs[i]);
    if (!plan_waits(ops, kept, handshake_us)) {
      why = "the operations the self-check kept apart cannot be ordered";
      break;
    }
    diagnostic_list got;
    optimise_attempt r = attempt(optimise_step::planned, &ops, got);
    if (r.sum.ok) {
      if (!compare) replay(got, diags);
      // The timing post's cycle less the waits it placed inside the heads' stretches: the
      // sequential post's (each of its waits is on the critical path).
      r.sum.sequential_cycle = t.cycle - seq.ops.operation_waits * handshake;
      r.sum.passes = post;
      r.sum.schedule = ops;
      for (std::size_t i : needed)
        r.sum.kept_apart.push_back(
            !reasons[i].empty()
                ? std::move(reasons[i])
                : pair_text(ops, pairs[i], o.cl_path, fixed_pair_reason(ops, pairs[i], clearance)));
      return r.sum;
    }
    const std::size_t known = pairs.size();
    const std::vector<std::vector<int>> lines = finding_lines(got, o.cl_path);
    const std::vector<std::string> messages = finding_messages(got);
    for (std::size_t f = 0; f < lines.size(); ++f)
      for (const plan_pair& p : pairs_for_lines(ops, lines[f]))
        if (std::find(pairs.begin(), pairs.end(), p) == pairs.end()) {
          pairs.push_back(p);
          reasons.push_back(pair_text(ops, p, o.cl_path, f < messages.size() ? messages[f] : ""));
        }
    if (pairs.size() == known) {
      why = fmt::format("the post's self-check refused a schedule at no pair of operations ({})",
                        first_error(got));
      break;
    }
    if (post == optimise_max_posts)
      why = fmt::format("no schedule the self-check passes after {} posts", optimise_max_posts);
  }
  return fall_back(why);
}

}  // namespace twinpost
