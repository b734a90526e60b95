#include "channels/router.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <limits>

#include "machines/partner_list.hpp"

namespace twinpost {

namespace {
// The reason of the last rendezvous (next_code's messages), which marks it (wait_mark::ends_job).
const std::string end_of_programs = "the end of the programs";
}  // namespace

channel_router::channel_router(const machine& m, sync_policy policy, channel_sink& sink,
                               diagnostic_sink& diags, std::string file, std::vector<int> job_channels)
    : m_(m), policy_(policy), sink_(sink), diags_(diags), file_(std::move(file)), codes_(m.waits),
      busy_(m.channels.size() + 1, false), worked_(m.channels.size() + 1, false),
      job_channels_(std::move(job_channels)), side_(m.channels.size() + 1, -1),
      started_(m.channels.size() + 1, false), op_wrote_(m.channels.size() + 1, false),
      tracks_(m.channels.size() + 1), waits_sent_(m.channels.size() + 1, 0) {
  for (const channel_def& c : m_.channels)
    if (c.number >= 1 && static_cast<std::size_t>(c.number) < tracks_.size())
      tracks_[static_cast<std::size_t>(c.number)].own_is_part = c.live_spindle.empty();
  const channel_def* first = m_.channel_for_head(1);
  active_ = {first ? first->number : 1};
  std::vector<int> chs = job_channels_;
  std::sort(chs.begin(), chs.end());
  chs.erase(std::unique(chs.begin(), chs.end()), chs.end());
  const bool valid = std::all_of(chs.begin(), chs.end(),
                                 [&](int c) { return c >= 1 && c < static_cast<int>(side_.size()); });
  if (valid && chs.size() >= 2 && chs.size() <= static_cast<std::size_t>(schedule_max_channels)) {
    ops_.channels = chs;
    for (std::size_t k = 0; k < chs.size(); ++k)
      side_[static_cast<std::size_t>(chs[k])] = static_cast<int>(k);
    plan_next_.assign(chs.size(), 0);
    sec_.assign(chs.size(), 0);
    bound_.assign(chs.size(), {});
    ops_.add_section();
  }
}

// A record that begins an operation inside a head's stretch: a tool change, a spindle stop.
static bool opens_operation(const event& e) {
  if (std::holds_alternative<tool_event>(e.data)) return true;
  const auto* s = std::get_if<spindle_event>(&e.data);
  return s && s->mode == spindle_mode::off;
}

void channel_router::deliver(int ch, const event& e, bool both, bool writes) {
  if (!track_) return sink_.on_event(ch, e, both);
  const auto c = static_cast<std::size_t>(ch);
  if (!started_[c]) [[unlikely]] {
    start_op(ch, e.line);
  } else if (op_wrote_[c] && !both && side_[c] >= 0 && !std::holds_alternative<motion_event>(e.data) &&
             opens_operation(e)) [[unlikely]] {
    if (op_waits_) {
      rendezvous(ops_.channels, e.line, "an operation", true);
      ++ops_.operation_waits;
    }
    start_op(ch, e.line);
  }
  if (writes) op_wrote_[c] = true;
  if (const int side = side_[c]; side >= 0) {
    channel_op& op = ops_.sections[sec_[side]].ops[side].back();
    op.last_line = e.line;
    note_operation_event(op, tracks_[c], e);
  }
  sink_.on_event(ch, e, both);
}

void channel_router::send_wait(int ch, const wait_mark& w) {
  ++waits_sent_[static_cast<std::size_t>(ch)];
  sink_.on_wait(ch, w);
}

void channel_router::start_op(int ch, int line) {
  const auto c = static_cast<std::size_t>(ch);
  started_[c] = true;
  op_wrote_[c] = false;
  const int side = side_[c];
  if (side < 0) return;
  std::vector<channel_op>& ops = ops_.sections[sec_[side]].ops[side];
  if (plan_) plan_waits_at(side, ops.size(), line);
  ops.push_back({line, line, waits_sent_[c]});
}

void channel_router::plan_fault(int line, const std::string& what) {
  if (plan_failed_) return;
  plan_failed_ = true;
  error(line, fmt::format("--sync optimise: the wait plan does not fit the job ({}): an optimiser fault, "
                          "nothing is written; post the job with --sync sequential",
                          what));
}

void channel_router::plan_waits_at(int side, std::size_t count, int line) {
  const std::size_t section = sec_[side];
  if (section >= plan_->sections.size())
    return plan_fault(line, fmt::format("section {} not planned", section + 1));
  const std::vector<meeting>& waits = plan_->sections[section].waits;
  const int ch = ops_.channels[static_cast<std::size_t>(side)];
  for (std::size_t& next = plan_next_[static_cast<std::size_t>(side)]; next < waits.size(); ++next) {
    // The meetings that do not name this side are passed over.
    const auto mine = std::find_if(waits[next].channels.begin(), waits[next].channels.end(),
                                   [&](const meeting::at& a) { return a.channel == side; });
    if (mine == waits[next].channels.end()) continue;
    const int at = mine->position;
    if (at < 0 || static_cast<std::size_t>(at) > count) return;
    if (static_cast<std::size_t>(at) < count)
      return plan_fault(
          line, fmt::format("section {}: channel {} passed the place of wait {}", section + 1, ch, next + 1));
    auto it = plan_codes_.find({section, next});
    if (it == plan_codes_.end()) {
      auto code = next_code(line, "a planned wait");
      if (!code) return;
      it = plan_codes_.emplace(std::make_pair(section, next), *code).first;
      ++rendezvous_;
    }
    wait_mark w;
    w.code = it->second;
    for (const meeting::at& a : waits[next].channels)
      if (a.channel >= 0 && static_cast<std::size_t>(a.channel) < ops_.channels.size())
        w.partners.push_back(ops_.channels[static_cast<std::size_t>(a.channel)]);
    std::sort(w.partners.begin(), w.partners.end());
    w.partner_text = partner_list(w.partners, m_.waits.partners);
    w.cl_line = line;
    send_wait(ch, w);
    last_partners_ = w.partners;
  }
}

void channel_router::side_break(int side, int line) {
  const auto s = static_cast<std::size_t>(side);
  const std::size_t section = sec_[s];
  const std::size_t count = ops_.sections[section].ops[s].size();
  const int ch = ops_.channels[s];
  if (plan_) {
    plan_waits_at(side, count, line);
    if (section < plan_->sections.size()) {
      const plan_section& p = plan_->sections[section];
      const std::size_t planned = s < p.ops.size() ? p.ops[s].size() : 0;
      if (plan_next_[s] != p.waits.size() || planned != count)
        plan_fault(line, fmt::format("section {}: channel {} has {} operations, the plan {}", section + 1, ch,
                                     count, planned));
    }
  }
  ++sec_[s];
  if (ops_.sections.size() <= sec_[s]) ops_.add_section();
  plan_next_[s] = 0;
  started_[static_cast<std::size_t>(ch)] = false;
}

bool channel_router::unmet_sync(int line, bool at_end) {
  if (bind_failed_ || bound_.empty()) return false;
  // A bound sync record one channel has passed and another has not: the barrier here would
  // meet the one while it waits for the other (a deadlock in the programs too).
  std::size_t ahead = 0, behind = 0;
  for (std::size_t k = 1; k < bound_.size(); ++k) {
    if (bound_[k].size() > bound_[ahead].size()) ahead = k;
    if (bound_[k].size() < bound_[behind].size()) behind = k;
  }
  if (bound_[ahead].size() == bound_[behind].size()) return false;
  const bound_record& r = bound_[ahead][bound_[behind].size()];
  bind_failed_ = true;  // said once
  // Where the programs meet: the record being routed (a transfer; the first record of a
  // balance cut, whose opening wait goes before it), or the job's last.
  error(at_end ? line : column_line_,
        fmt::format("sync {} of channel {} (line {}) is not met by channel {} {}: each sync record of the "
                    "one channel needs its partner in the other before the programs meet again",
                    r.key.first, ops_.channels[ahead], r.line, ops_.channels[behind],
                    at_end ? "by the end of the job" : "before the programs meet here"));
  return true;
}

void channel_router::section_break(int line) {
  if (ops_.channels.empty() || !track_) return;
  if (unmet_sync(line, false)) return;
  for (std::size_t side = 0; side < ops_.channels.size(); ++side) side_break(static_cast<int>(side), line);
  std::fill(started_.begin(), started_.end(), false);
}

void channel_router::error(int line, std::string message) {
  diagnostic d;
  d.file = file_;
  d.line = line;
  d.column = line == column_line_ ? column_ : 0;
  d.message = std::move(message);
  diags_.report(std::move(d));
}

const channel_def* channel_router::head_channel(const head_event& h) const {
  switch (h.which) {
    case head_select::number: return m_.channel_for_head(h.number);
    case head_select::main: return m_.channel_for_head(std::string_view("MAIN"));
    case head_select::side: return m_.channel_for_head(std::string_view("SIDE"));
    case head_select::both: return nullptr;
  }
  return nullptr;
}

void channel_router::route(const event& e) {
  column_line_ = e.line;
  column_ = e.column;
  // Most events are moves: no head, channel, sync or job-level record, and a block to write.
  if (std::holds_alternative<motion_event>(e.data) && open_both_.empty()) [[likely]] {
    if (grip_line_ != 0) [[unlikely]]
      note_cutoff(e);
    for (int ch : active_) {
      busy_[static_cast<std::size_t>(ch)] = true;
      worked_[static_cast<std::size_t>(ch)] = true;
      if (track_) [[unlikely]]
        deliver(ch, e, both_, true);
      else
        sink_.on_event(ch, e, both_);
    }
    return;
  }
  if (const auto* h = std::get_if<head_event>(&e.data)) {
    if (h->which == head_select::both) {
      const channel_def* a = m_.channel_for_head(1);
      const channel_def* b = m_.channel_for_head(2);
      if (!a || !b || a == b)
        return error(e.line,
                     fmt::format("HEAD/BOTH: machine '{}' has no two channels for heads 1 and 2", m_.name));
      std::vector<int> both{a->number, b->number};
      std::sort(both.begin(), both.end());
      both_master_ = a->number;
      return select(both, e.line, true);
    }
    const channel_def* c = head_channel(*h);
    if (!c) {
      std::string what = h->which == head_select::number ? std::to_string(h->number)
                         : h->which == head_select::main ? "MAIN"
                                                         : "SIDE";
      return error(e.line, fmt::format("HEAD/{}: machine '{}' has no channel for this head", what, m_.name));
    }
    return select({c->number}, e.line, false);
  }
  if (const auto* c = std::get_if<channel_event>(&e.data)) {
    if (c->channel < 1 || c->channel > static_cast<int>(m_.channels.size()))
      return error(e.line, fmt::format("CHANNEL {}: machine '{}' has {} channels", c->channel, m_.name,
                                       m_.channels.size()));
    return select({c->channel}, e.line, false);
  }
  if (const auto* s = std::get_if<sync_event>(&e.data)) return explicit_sync(*s, e.line);
  if (const auto* t = std::get_if<transfer_event>(&e.data)) return transfer(e, *t);
  bool job_level = false;
  if (const auto* t = std::get_if<text_event>(&e.data)) job_level = t->kind == text_kind::partno;
  if (std::holds_alternative<units_event>(e.data) || std::holds_alternative<machin_event>(e.data))
    job_level = true;
  if (job_level) {
    if (const auto* u = std::get_if<units_event>(&e.data))
      for (channel_track& t : tracks_) t.mm = u->units == unit_system::inch ? 25.4 : 1;
    return sink_.on_event(0, e, false);
  }
  if (!open_both_.empty()) {
    // Before the balance cut's opening wait: the master sets the spindle (and comments go to
    // both); anything else opens the section.
    if (std::holds_alternative<spindle_event>(e.data)) {
      busy_[static_cast<std::size_t>(both_master_)] = true;
      worked_[static_cast<std::size_t>(both_master_)] = true;
      return deliver(both_master_, e, false, true);
    }
    if (!std::holds_alternative<comment_event>(e.data) && !std::holds_alternative<text_event>(e.data))
      open_both();
  }
  // Records that write no block (ends, comments, tool geometry, ...) do not make a channel
  // busy: a mark after them still collapses with the one before.
  bool writes = !(
      std::holds_alternative<end_event>(e.data) || std::holds_alternative<comment_event>(e.data) ||
      std::holds_alternative<passthrough_event>(e.data) || std::holds_alternative<tool_data_event>(e.data) ||
      std::holds_alternative<coordsys_event>(e.data) || std::holds_alternative<multax_event>(e.data));
  for (int ch : active_) {
    deliver(ch, e, both_, writes);
    if (writes) busy_[static_cast<std::size_t>(ch)] = worked_[static_cast<std::size_t>(ch)] = true;
  }
}

void channel_router::select(std::vector<int> channels, int line, bool both) {
  if (channels == active_ && both == both_) return;
  std::vector<int> all = active_;
  all.insert(all.end(), channels.begin(), channels.end());
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  // HEAD/BOTH is always framed by waits; plain switches wait only under the sequential policy.
  // (Forced: the balance-cut codes need their waits even where nothing was cut before.)
  if (both) {
    // The opening wait waits for the section's first record that is not a SPINDL (open_both).
    open_both_ = all;
    open_both_line_ = line;
  } else if (both_) {
    open_both();
    section_break(line);
    rendezvous(all, line, "the end of HEAD/BOTH", true, wait_mark::section::closes_both);
    barrier_beside(all, line, "the end of HEAD/BOTH");
  } else if (policy_ == sync_policy::sequential && all.size() > 1) {
    // On a job of three or four channels every channel of the job meets at a head switch: one
    // head works at a time, and a wait that left a path out could be pending, with a code given
    // again, while two others meet at the same code (attack 57).
    rendezvous(job_channels_.size() > 2 ? with_job_channels(all) : all, line, "a head switch");
  }
  for (int c : channels) started_[static_cast<std::size_t>(c)] = false;
  active_ = std::move(channels);
  both_ = both;
}

void channel_router::rendezvous(const std::vector<int>& channels, int line, const std::string& what,
                                bool force, wait_mark::section both) {
  // Consecutive marks with nothing between them collapse into one.
  // So does a mark before any channel has done anything: the programs start together.
  bool any_busy = std::any_of(channels.begin(), channels.end(),
                              [&](int c) { return busy_[static_cast<std::size_t>(c)]; });
  if (!any_busy && !force) return;
  auto code = next_code(line, what);
  if (!code) return;
  // Every channel of the job meets here: the waits before are all done.
  if (!live_codes_.empty() &&
      std::includes(channels.begin(), channels.end(), ops_.channels.begin(), ops_.channels.end()))
    live_codes_ = {*code};
  wait_mark w;
  w.code = *code;
  w.partners = channels;
  w.partner_text = partner_list(channels, m_.waits.partners);
  w.cl_line = line;
  w.both = both;
  w.ends_job = what == end_of_programs;
  for (int c : channels) {
    send_wait(c, w);
    busy_[static_cast<std::size_t>(c)] = false;
  }
  last_partners_ = channels;
  ++rendezvous_;
}

void channel_router::open_both() {
  if (open_both_.empty()) return;
  const std::vector<int> all = std::move(open_both_);
  open_both_.clear();
  section_break(open_both_line_);
  barrier_beside(all, open_both_line_, "HEAD/BOTH");
  if (!ops_.channels.empty() && track_) ops_.sections[sec_[0]].together = true;  // section_break made it
  rendezvous(all, open_both_line_, "HEAD/BOTH", true, wait_mark::section::opens_both);
}

void channel_router::barrier_beside(const std::vector<int>& pair, int line, const std::string& what) {
  const bool planned = !ops_.channels.empty() && track_ && (policy_ == sync_policy::optimise || op_waits_);
  // Sequential on three or four channels: every wait of a head switch names them all, and so
  // must the waits beside a balance cut, or a path left out of its P12 could sit at a code
  // given again (review 58).
  const bool sequential = policy_ == sync_policy::sequential && job_channels_.size() > 2;
  if (!planned && !sequential) return;
  const std::vector<int> all = with_job_channels(pair);
  if (all != pair) rendezvous(all, line, what, true);
}

std::vector<int> channel_router::with_job_channels(std::vector<int> channels) const {
  for (int c : job_channels_)
    if (c >= 1 && c <= static_cast<int>(m_.channels.size())) channels.push_back(c);
  std::sort(channels.begin(), channels.end());
  channels.erase(std::unique(channels.begin(), channels.end()), channels.end());
  return channels;
}

void channel_router::explicit_sync(const sync_event& s, int line) {
  open_both();
  if (aside_sync_) return;
  ++explicit_;
  ops_.has_sync_records = true;
  // optimise's posts (op_waits_: its timing post) keep the job's sync records and place the rest.
  const bool bind = policy_ == sync_policy::optimise || op_waits_;
  if (policy_ != sync_policy::explicit_marks && !bind) {
    if (!warned_ignored_) {
      diagnostic d;
      d.level = severity::warning;
      d.file = file_;
      d.line = line;
      d.column = line == column_line_ ? column_ : 0;
      d.message = "sync records ignored under --sync sequential";
      diags_.report(std::move(d));
      warned_ignored_ = true;
    }
    return;
  }
  // A record refused here is not bound: no later error about its partner (attack 49).
  const auto refuse = [&](std::string message) {
    bind_failed_ = bind_failed_ || bind;
    error(line, std::move(message));
  };
  // A balance cut keeps its two heads in step (G68, M562), framed by waits of its own: a wait
  // inside it would hold one head while the control waits for it to move.
  if (both_)
    return refuse(
        fmt::format("a sync record inside HEAD/BOTH (line {}): the balance cut is framed by waits "
                    "of its own, and one inside it would hold one head of the pair; give it before "
                    "HEAD/BOTH or after the HEAD that ends it",
                    open_both_line_));
  // No channel list: every channel the job uses (an idle third path is left out).
  std::vector<int> partners = s.channels.empty() ? job_channels_ : s.channels;
  for (int ch : active_) partners.push_back(ch);
  std::sort(partners.begin(), partners.end());
  partners.erase(std::unique(partners.begin(), partners.end()), partners.end());
  // Messages name the mark as the first active channel numbers it.
  const int shown = marker_of(s, active_.front());
  for (int p : partners)
    if (p < 1 || p > static_cast<int>(m_.channels.size()))
      return refuse(fmt::format("sync {} names channel {}, machine '{}' has {} channels", shown, p, m_.name,
                                m_.channels.size()));
  if (partners.size() < 2) return refuse(fmt::format("sync {} has no partner channel", shown));
  if (bind) return bound_sync(s, line, partners);
  for (int ch : active_) {
    const int index = marker_of(s, ch);
    if (s.source == sync_source::icam) auto_marker_[ch] = index;
    // The same sync record twice in a row in one channel is one wait.
    if (last_sync_line_ >= 0 && last_sync_index_ == index && last_sync_channel_ == ch &&
        !busy_[static_cast<std::size_t>(ch)])
      continue;
    if (!sync_wait(ch, {index, seen_[{ch, index}]++}, partners, line)) return;
    last_sync_channel_ = ch;
    last_sync_index_ = index;
  }
  last_sync_line_ = line;
  last_partners_ = partners;
}

void channel_router::bound_sync(const sync_event& s, int line, const std::vector<int>& partners) {
  // Not a job of two to four channels: the optimiser says so and falls back. After a refused
  // record, the rest are not bound (the post has failed).
  if (ops_.channels.empty() || bind_failed_) return;
  const int ch = active_.front();
  const int index = marker_of(s, ch);
  if (partners != ops_.channels) {
    bind_failed_ = true;
    return error(
        line, ops_.channels.size() == 2
                  ? fmt::format("sync {} names channels {}: under --sync optimise a sync record of "
                                "the job binds its two channels, {} and {}",
                                index, fmt::join(partners, ", "), ops_.channels[0], ops_.channels[1])
                  : fmt::format(
                        "sync {} names channels {}: under --sync optimise a sync record of "
                        "the job binds all its channels, {} (a sync record that names none, as SYNCTR/NEXT); "
                        "post it with --sync explicit",
                        index, fmt::join(partners, ", "), fmt::join(ops_.channels, ", ")));
  }
  if (s.source == sync_source::icam) auto_marker_[ch] = index;
  // The same sync record twice in a row in one channel is one wait: nothing worked between
  // (worked_, not busy_: the timing post's head-switch waits clear busy_, the planned post has
  // none, and both must bind the same records; attack 49).
  if (last_sync_line_ >= 0 && last_sync_index_ == index && last_sync_channel_ == ch &&
      !worked_[static_cast<std::size_t>(ch)])
    return;
  worked_[static_cast<std::size_t>(ch)] = false;
  last_sync_line_ = line;
  last_sync_channel_ = ch;
  last_sync_index_ = index;
  const int side = side_[static_cast<std::size_t>(ch)];
  const std::pair<int, int> key{index, seen_[{ch, index}]++};
  std::vector<bound_record>& mine = bound_[static_cast<std::size_t>(side)];
  const std::size_t k = mine.size();
  mine.push_back({key, line});
  // Each channel's k-th sync record meets the others' k-th: crossed (1, 3, 2 against 1, 2, 3)
  // or different (1 against 2), the programs would wait at different codes, each for the other.
  bool last = true;  // the last channel to reach its k-th: the record is kept
  for (std::size_t o = 0; o < bound_.size(); ++o) {
    if (o == static_cast<std::size_t>(side)) continue;
    const std::vector<bound_record>& theirs = bound_[o];
    if (k >= theirs.size()) {
      last = false;
      continue;
    }
    if (theirs[k].key != key) {
      bind_failed_ = true;
      return error(line,
                   fmt::format("sync {} is channel {}'s sync record number {}, where channel {}'s number {} "
                               "is sync {} (line {}): the two would wait at different codes, each for the "
                               "other; give {} channels the same sync records in the same order",
                               index, ch, k + 1, ops_.channels[o], k + 1, theirs[k].key.first, theirs[k].line,
                               bound_.size() == 2 ? "both" : "all"));
    }
  }
  if (last) ++ops_.kept_syncs;
  // The timing post: a rendezvous here too, so that each operation is timed on its own. Not
  // counted among its operation waits: one at a head switch stands for the sequential post's
  // own wait there (one in the middle of a head's work makes the sequential cycle a handshake
  // longer than it is).
  if (op_waits_) rendezvous(ops_.channels, line, "a sync record");
  side_break(side, line);
  if (plan_ && sync_wait(ch, key, partners, line)) last_partners_ = partners;
}

bool channel_router::sync_wait(int ch, std::pair<int, int> key, const std::vector<int>& partners, int line) {
  auto it = sync_codes_.find(key);
  if (it == sync_codes_.end()) {
    auto code = next_code(line, fmt::format("sync {}", key.first));
    if (!code) return false;
    it = sync_codes_.emplace(key, *code).first;
    ++rendezvous_;
  }
  wait_mark w;
  w.code = it->second;
  w.partners = partners;
  w.partner_text = partner_list(partners, m_.waits.partners);
  w.cl_line = line;
  send_wait(ch, w);
  busy_[static_cast<std::size_t>(ch)] = false;
  return true;
}

void channel_router::transfer(const event& e, const transfer_event& t) {
  const char* word = t.release ? "TRANSFER/RELEASE" : "TRANSFER/GRIP";
  if (!m_.spindle("sub"))
    return error(e.line, fmt::format("{}: machine '{}' has no sub spindle to take the part", word, m_.name));
  if (m_.transfer.channel == 0)
    return error(e.line, fmt::format("{}: machine '{}' gives no part transfer ([transfer] in its file)", word,
                                     m_.name));
  // GRIP and RELEASE come in pairs: a release with nothing gripped opens the main chuck under
  // a part the sub does not hold; a second grip would advance the sub into a held part.
  if (t.release && grip_line_ == 0)
    return error(e.line,
                 "TRANSFER/RELEASE with no TRANSFER/GRIP before it: the main chuck would open with "
                 "the sub spindle holding nothing");
  if (!t.release && grip_line_ != 0)
    return error(e.line, fmt::format("TRANSFER/GRIP while the TRANSFER/GRIP at line {} has not been released",
                                     grip_line_));
  grip_line_ = t.release ? 0 : e.line;
  grip_column_ = e.column;
  const int cutoff = t.release ? cutoff_line_ : 0;
  cutoff_line_ = 0;
  grip_has_x_ = false;
  if (both_) select({active_.front()}, e.line, false);
  // Every channel: both turrets (and an idle third path) leave the space between the spindles.
  std::vector<int> all;
  for (const channel_def& c : m_.channels) all.push_back(c.number);
  auto send = [&](int ch, transfer_event::phase step) {
    event copy = e;
    copy.data = transfer_event{step, t.release};
    sink_.on_event(ch, copy, false);
  };
  for (int ch : all) send(ch, transfer_event::phase::retract);
  const std::string what = fmt::format("{} at line {}", word, e.line);
  section_break(e.line);
  rendezvous(all, e.line, what, true);
  {
    event copy = e;
    copy.data = transfer_event{transfer_event::phase::blocks, t.release, cutoff};
    sink_.on_event(m_.transfer.channel, copy, false);
  }
  section_break(e.line);
  rendezvous(all, e.line, what, true);
  if (t.release)
    for (int ch : all) {
      send(ch, transfer_event::phase::on_sub);
      tracks_[static_cast<std::size_t>(ch)].part = 2;
    }
}

// A part-off while the sub holds the part: a feed move (no RAPID) whose end is on the centre
// line (CL x, a radius, within 0.001 mm of 0) or on its other side from the point before it.
void channel_router::note_cutoff(const event& e) {
  const auto& mv = std::get<motion_event>(e.data);
  if (mv.kind == motion_kind::from || mv.kind == motion_kind::home) return;
  const double x = mv.pos.x;
  const bool crossed = grip_has_x_ && ((grip_last_x_ > 0 && x < 0) || (grip_last_x_ < 0 && x > 0));
  if (!mv.rapid && cutoff_line_ == 0 && (std::abs(x) <= 0.001 || crossed)) cutoff_line_ = e.line;
  grip_last_x_ = x;
  grip_has_x_ = true;
}

int channel_router::marker_of(const sync_event& s, int ch) const {
  if (s.index) return *s.index;
  // ICAM: a SYNCTR/NEXT without a marker is the channel's previous marker plus one
  // (saturating: no overflow after a marker of INT_MAX).
  const auto it = auto_marker_.find(ch);
  const int last = it == auto_marker_.end() ? 0 : it->second;
  return last < std::numeric_limits<int>::max() ? last + 1 : last;
}

std::optional<int> channel_router::next_code(int line, const std::string& what) {
  if (m_.waits.syntax == wait_syntax::bang) {
    // Said once, at the first wait: the checker reads !2L1 waits, the post does not write them.
    if (!exhausted_)
      error(line,
            fmt::format("machine '{}' writes its waits as {}<partners>{}<number> (waits.syntax = bang), "
                        "which post cannot write yet: this machine is for check only",
                        m_.name, m_.waits.marker, m_.waits.address));
    exhausted_ = true;
    return std::nullopt;
  }
  auto code = codes_.next();
  if (code && plan_ && ops_.channels.size() > 2) {
    // Waits that name some of three or four channels may be pending at once: a code is given
    // again only after every channel of the job has met since its last use (attack 57: `M209 P12`
    // in paths 1 and 2 while path 3 waits at `M209 P13` for path 1).
    for (std::size_t tries = 0; code && live_codes_.count(*code) != 0 && tries <= live_codes_.size(); ++tries)
      code = codes_.next();
    if (code && live_codes_.count(*code) != 0) {
      if (!exhausted_)
        error(line,
              fmt::format("no wait code left for {}: the codes {}{}-{}{} are all held by waits of some of "
                          "the job's {} channels that may be pending at once (a code is given again only "
                          "after all of them have met)",
                          what, m_.waits.address, m_.waits.first, m_.waits.address, m_.waits.last,
                          ops_.channels.size()));
      exhausted_ = true;
      return std::nullopt;
    }
    if (code) live_codes_.insert(*code);
  }
  if (!code && !exhausted_) {
    // Said once: every later mark would repeat it.
    error(line,
          fmt::format("no wait code left for {}: {}{}-{}{} is used up and machine '{}' does not reuse codes",
                      what, m_.waits.address, m_.waits.first, m_.waits.address, m_.waits.last, m_.name));
    exhausted_ = true;
  }
  return code;
}

void channel_router::finish(int last_line) {
  if (grip_line_ != 0) {
    column_line_ = grip_line_;
    column_ = grip_column_;
    error(grip_line_,
          "TRANSFER/GRIP with no TRANSFER/RELEASE after it: the programs would end with the part "
          "held by both spindles");
  }
  if (both_) select({active_.front()}, last_line, false);
  if (!ops_.channels.empty() && track_ && unmet_sync(last_line, true)) return;
  if (plan_) {
    // The last section's waits, and a plan of no more sections than the job has.
    section_break(last_line);
    ops_.sections.pop_back();
    if (plan_->sections.size() != ops_.sections.size())
      plan_fault(last_line, fmt::format("the job has {} sections, the plan {}", ops_.sections.size(),
                                        plan_->sections.size()));
  }
  // A last rendezvous of every channel before the programs' footers: a channel that ends
  // first must not stop the spindle or the coolant another channel is still cutting with.
  std::vector<int> all;
  for (const channel_def& c : m_.channels) all.push_back(c.number);
  // Channels that took no part in the last mark (an idle third path) must wait too.
  if (all.size() > 1) rendezvous(all, last_line, end_of_programs, last_partners_ != all);
}

}  // namespace twinpost
