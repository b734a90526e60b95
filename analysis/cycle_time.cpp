#include "analysis/cycle_time.hpp"

#include <algorithm>
#include <cstdint>
#include <functional>

#include <fmt/format.h>

#include "analysis/block_timer.hpp"
#include "analysis/modal_state.hpp"
#include "check/nc_input.hpp"
#include "check/sync_check.hpp"

namespace twinpost {

namespace {

using channel_mask = std::uint64_t;
channel_mask bit_of(int channel) { return channel_mask{1} << (channel - 1); }

// A wait as the run needs it: when the channel reached it (its own working time), whom it meets.
struct run_wait {
  double work = 0;  // busy seconds of the channel when it arrives
};

// The text of a wait as written, as the checker's messages give it.
std::string wait_text(const machine& m, const nc_wait& w) {
  if (m.waits.syntax == wait_syntax::bang)
    return fmt::format("{}{}{}{}", m.waits.marker, w.partner_text, m.waits.address, w.code);
  if (!w.has_partner_list) return fmt::format("{}{}", m.waits.address, w.code);
  return fmt::format("{}{} {}{}", m.waits.address, w.code, m.waits.partner_address, w.partner_text);
}

// One channel as its blocks are read.
struct channel_run {
  block_timer timer;
  channel_times times;
  std::vector<run_wait> waits;
  int segment = 0;
  std::vector<int> kept_segment;  // the segment of each kept block
  bool kept_over = false;         // more blocks than timeline_max_kept_blocks: none kept
  // Untimed blocks per kind, in program order: kept per channel, so that the kinds come out
  // in channel then program order however the channels' blocks were interleaved.
  std::vector<untimed_group> untimed;
  channel_run(const machine& m, int ch) : timer(m, ch) {}
};

class timeline_builder {
 public:
  timeline_builder(const machine& m, const timeline_options& o) : m_(m), o_(o) {
    n_ = static_cast<int>(m.channels.size());
    for (const channel_def& c : m.channels) runs_.emplace_back(m, c.number);
    for (int i = 0; i < n_; ++i) runs_[static_cast<std::size_t>(i)].times.channel = i + 1;
  }

  void block(const nc_block& b, const spindle_states* spindles, const modal_states* modes) {
    const int channel = b.channel;
    const std::string& file = b.file;
    const int line = b.line;
    const std::string_view text = b.text;
    channel_run& r = runs_[static_cast<std::size_t>(channel - 1)];
    channel_times& c = r.times;
    if (c.file.empty()) c.file = file;
    const std::vector<nc_word>& words = b.words();  // first: split, the letters come exact
    const block_timing t = r.timer.time(words, b.letters(), spindles ? &spindles->channel(channel) : nullptr,
                                        modes ? &modes->channel(channel) : nullptr);
    ++c.blocks;
    if (m_.limits.blocks_per_second > 0 && !t.rapid && t.motion > 0 &&
        t.motion * m_.limits.blocks_per_second < 1) [[unlikely]] {
      if (c.short_blocks++ == 0 || t.motion < c.shortest) {
        c.shortest = t.motion;
        c.shortest_at = {file, line, 1, std::string(text)};
      }
    }
    if (!t.untimed.empty()) {
      ++c.untimed;
      note_untimed(r.untimed, t.untimed, file, line, text);
    }
    // A new operation at a tool call and after each wait.
    if (c.operations.empty() || t.tool_call || c.operations.back().segment != r.segment) {
      tool_operation op;
      op.tool = r.timer.tool();
      op.start = c.busy;
      op.segment = r.segment;
      op.first_line = line;
      op.first_text = std::string(text);
      c.operations.push_back(std::move(op));
    }
    tool_operation& op = c.operations.back();
    op.seconds += t.seconds;
    ++op.blocks;
    if (o_.keep_blocks && !r.kept_over) {
      if (c.kept.size() == timeline_max_kept_blocks) {
        // More than the page draws: it shows the operations, and memory stays bounded.
        r.kept_over = true;
        std::vector<timed_block>().swap(c.kept);
        std::vector<int>().swap(r.kept_segment);
      } else {
        c.kept.push_back(timed(r, line, text, t));
        r.kept_segment.push_back(r.segment);
      }
    }
    if (channel == stream_channel_) {
      flush_streamed();
      pending_ = timed(r, line, text, t);
      pending_.start += stream_shift_[static_cast<std::size_t>(r.segment)];
      has_pending_ = true;
    }
    c.busy += t.seconds;
  }

  /// Instead of keeping them, hands each timed block of `channel` to `f`, placed in time by
  /// `shift` (the idle before each of its wait segments, from a first timing of the same
  /// programs): a second reading that streams what keep_blocks would hold.
  void stream_blocks(int channel, std::vector<double> shift, std::function<void(const timed_block&)> f) {
    stream_channel_ = channel;
    stream_shift_ = std::move(shift);
    emit_ = std::move(f);
  }
  void flush_streamed() {
    if (has_pending_) emit_(pending_);
    has_pending_ = false;
  }

  void wait(const nc_wait& w) {
    channel_run& r = runs_[static_cast<std::size_t>(w.channel - 1)];
    channel_times& c = r.times;
    const double s = r.timer.wait_seconds();
    c.busy += s;
    if (!c.operations.empty()) c.operations.back().seconds += s;
    if (o_.keep_blocks && !c.kept.empty()) {
      c.kept.back().seconds += s;
      c.kept.back().wait = true;
    }
    if (w.channel == stream_channel_ && has_pending_) {
      pending_.seconds += s;
      pending_.wait = true;
    }
    run_wait rw;
    rw.work = c.busy;
    r.waits.push_back(rw);
    wait_stop ws;
    ws.code = wait_text(m_, w);
    ws.where = w.where;
    c.waits.push_back(std::move(ws));
    ++r.segment;
  }

  timeline finish(const std::vector<std::uint64_t>& rendezvous) {
    timeline tl;
    tl.machine = m_.name;
    if (!run_together(tl, rendezvous)) return tl;
    place_in_time(tl);
    find_critical_path(tl);
    give_advice(tl);
    tl.untimed_kinds = untimed_kinds();
    for (channel_run& r : runs_) tl.channels.push_back(std::move(r.times));
    tl.ok = true;
    return tl;
  }

 private:
  static void note_untimed(std::vector<untimed_group>& groups, const std::string& why,
                           const std::string& file, int line, std::string_view text) {
    for (untimed_group& g : groups)
      if (g.why == why) {
        ++g.count;
        return;
      }
    untimed_group g;
    g.why = why;
    g.count = 1;
    g.first.file = file;
    g.first.line = line;
    g.first.source_line = std::string(text);
    groups.push_back(std::move(g));
  }

  // The channels' untimed kinds as one list: channel 1's, then each kind first seen later.
  std::vector<untimed_group> untimed_kinds() {
    std::vector<untimed_group> all;
    for (channel_run& r : runs_)
      for (untimed_group& g : r.untimed) {
        auto same =
            std::find_if(all.begin(), all.end(), [&](const untimed_group& a) { return a.why == g.why; });
        if (same != all.end())
          same->count += g.count;
        else
          all.push_back(std::move(g));
      }
    return all;
  }

  // The channels run together: a group of partners leaves a wait when the last one arrives.
  // The groups and their order are the checker's own (sync_result::rendezvous): who meets whom
  // is decided once, by the rules that proved the waits sound (partner lists, fixed waits).
  bool run_together(timeline& tl, const std::vector<std::uint64_t>& rendezvous) {
    std::vector<std::size_t> pos(runs_.size(), 0);
    std::vector<double> idle(runs_.size(), 0);  // idle so far, per channel
    auto finished = [&](int c) { return pos[c - 1] >= runs_[c - 1].waits.size(); };
    auto arrival = [&](int c) { return runs_[c - 1].waits[pos[c - 1]].work + idle[c - 1]; };
    for (const std::uint64_t group : rendezvous) {
      bool fits = group != 0;
      for (int p = 1; p <= n_; ++p)
        if ((group & bit_of(p)) && finished(p)) fits = false;
      if (!fits) break;  // not this reading's waits: said below
      double release = 0;
      int last = 0;
      for (int p = 1; p <= n_; ++p)
        if ((group & bit_of(p)) && arrival(p) > release + 1e-12) release = arrival(p), last = p;
      if (last == 0)  // everyone at 0 s: the lowest channel counts as the last
        for (int p = n_; p >= 1; --p)
          if (group & bit_of(p)) last = p;
      for (int p = 1; p <= n_; ++p) {
        if (!(group & bit_of(p))) continue;
        wait_stop& ws = runs_[p - 1].times.waits[pos[p - 1]];
        ws.arrive = arrival(p);
        ws.release = release;
        if (p != last) {
          ws.waited_for = last;
          ws.waited_for_wait = static_cast<int>(pos[last - 1]);
        }
        idle[p - 1] += release - ws.arrive;
      }
      for (int p = 1; p <= n_; ++p)
        if (group & bit_of(p)) ++pos[p - 1];
    }
    for (int c = 1; c <= n_; ++c)
      if (!finished(c)) {
        // The checker proved the waits sound; a run that stops here would be a bug.
        tl.diagnostics.push_back({severity::error,
                                  runs_[c - 1].times.file,
                                  0,
                                  0,
                                  fmt::format("channel {} does not reach its end in the timed run", c),
                                  {}});
        return false;
      }
    for (int c = 1; c <= n_; ++c) {
      channel_times& t = runs_[c - 1].times;
      t.idle = idle[c - 1];
      t.end = t.busy + t.idle;
    }
    return true;
  }

  // Working times become times from the start of the cycle: each segment is shifted by the
  // idle of the waits before it.
  void place_in_time(timeline& tl) {
    for (std::size_t i = 0; i < runs_.size(); ++i) {
      channel_times& t = runs_[i].times;
      std::vector<double> shift(t.waits.size() + 1, 0);
      for (std::size_t k = 0; k < t.waits.size(); ++k) shift[k + 1] = shift[k] + t.waits[k].idle();
      for (tool_operation& op : t.operations) op.start += shift[static_cast<std::size_t>(op.segment)];
      for (std::size_t b = 0; b < t.kept.size(); ++b)
        t.kept[b].start += shift[static_cast<std::size_t>(runs_[i].kept_segment[b])];
      if (t.end > tl.cycle + 1e-12 || tl.last_channel == 0) {
        tl.cycle = t.end;
        tl.last_channel = t.channel;
      }
      tl.untimed += t.untimed;
    }
  }

  // From the channel that ends last, back through each wait to the partner that arrived
  // last: the blocks whose time is the cycle time.
  void find_critical_path(timeline& tl) {
    int c = tl.last_channel;
    int segment = static_cast<int>(runs_[c - 1].times.waits.size());
    double until = tl.cycle;
    while (c > 0) {
      channel_times& t = runs_[c - 1].times;
      const double from = segment == 0 ? 0 : t.waits[static_cast<std::size_t>(segment - 1)].release;
      for (tool_operation& op : t.operations)
        if (op.segment == segment) op.critical = true;
      tl.critical.push_back({c, from, until});
      if (segment == 0) break;
      const wait_stop& w = t.waits[static_cast<std::size_t>(segment - 1)];
      until = w.release;
      if (w.waited_for != 0) {
        segment = w.waited_for_wait;  // the partner's segment before its wait
        c = w.waited_for;
      } else {
        --segment;
      }
    }
    std::reverse(tl.critical.begin(), tl.critical.end());
  }

  void give_advice(timeline& tl) {
    std::vector<idle_note> all;
    for (const channel_run& r : runs_)
      for (const wait_stop& w : r.times.waits)
        if (w.idle() >= 0.005) all.push_back({r.times.channel, w.idle(), w.code, w.where, w.waited_for});
    std::stable_sort(all.begin(), all.end(),
                     [](const idle_note& a, const idle_note& b) { return a.seconds > b.seconds; });
    if (all.size() > 3) all.resize(3);
    tl.advice = std::move(all);
  }

  const machine& m_;
  const timeline_options& o_;
  int n_ = 0;
  std::vector<channel_run> runs_;
  // stream_blocks: the channel streamed, its shifts, the block held until its wait is known.
  int stream_channel_ = 0;
  std::vector<double> stream_shift_;
  std::function<void(const timed_block&)> emit_;
  timed_block pending_;
  bool has_pending_ = false;

  static timed_block timed(const channel_run& r, int line, std::string_view text, const block_timing& t) {
    timed_block b;
    b.line = line;
    b.start = r.times.busy;
    b.seconds = t.seconds;
    b.text = std::string(text);
    b.untimed = t.untimed;
    return b;
  }
};

}  // namespace

struct timeline_feed::impl {
  impl(const machine& m, const timeline_options& o) : b(m, o) {}
  timeline_builder b;
};

timeline_feed::timeline_feed(const machine& m, const timeline_options& o) : m_(m), o_(o) {}
timeline_feed::~timeline_feed() = default;
void timeline_feed::make() { p_ = std::make_unique<impl>(m_, o_); }
void timeline_feed::block(const nc_block& b, const spindle_states* spindles, const modal_states* modes) {
  if (!p_) [[unlikely]]
    make();
  p_->b.block(b, spindles, modes);
}
void timeline_feed::wait(const nc_wait& w) {
  if (!p_) make();
  p_->b.wait(w);
}
timeline timeline_feed::finish(const std::vector<std::uint64_t>& rendezvous) {
  if (!p_) make();
  return p_->b.finish(rendezvous);
}

void for_each_timed_block(const timeline& t, const std::vector<nc_source>& files, const machine& m,
                          int channel, const std::function<void(const timed_block&)>& f) {
  const channel_times& c = t.channels.at(static_cast<std::size_t>(channel - 1));
  std::vector<double> shift(c.waits.size() + 1, 0);
  for (std::size_t k = 0; k < c.waits.size(); ++k) shift[k + 1] = shift[k] + c.waits[k].idle();
  const timeline_options o;
  timeline_builder b(m, o);
  b.stream_blocks(channel, std::move(shift), f);
  nc_read_options read;
  // (The timers keep their own spindle and modal states, read by the rules the reading's keep.)
  read.on_block = [&](const nc_block& blk) { b.block(blk, nullptr, nullptr); };
  read.on_wait = [&](const nc_wait& w) { b.wait(w); };
  diagnostic_list ignored;  // the timeline was made from the same files: they read sound
  read_nc_programs(files, m, ignored, read);
  b.flush_streamed();
}

bool has_timing(const machine& m) {
  return !m.channels.empty() && std::all_of(m.channels.begin(), m.channels.end(),
                                            [](const channel_def& c) { return c.timing.given; });
}

timeline make_timeline(const std::vector<nc_source>& given, const machine& m, const timeline_options& o) {
  timeline tl;
  tl.machine = m.name;
  if (!has_timing(m)) {
    tl.diagnostics.push_back(
        {severity::error,
         m.source,
         0,
         0,
         fmt::format(
             "machine '{}' has no [timing] table: the cycle time needs its rapid rates and tool-change "
             "time (docs/machines.md, \"[timing]\")",
             m.name),
         {}});
    return tl;
  }
  if (m.channels.size() > 64) {
    tl.diagnostics.push_back(
        {severity::error, m.source, 0, 0, "the timeline handles at most 64 channels", {}});
    return tl;
  }
  const std::vector<nc_source> files = rereadable(given);
  // One reading: the check's first pass feeds the timeline too (what it built is dropped
  // when the check finds anything).
  timeline_builder b(m, o);
  spindle_states spindles(m);  // one state for the timer and the rule
  modal_states modes(m);
  interference_check meet(m, spindles,
                          modes);  // its findings are marked on the page, not a reason for no timeline
  nc_read_options read;
  read.on_block = [&](const nc_block& blk) {
    spindles.block(blk);
    modes.block(blk);
    b.block(blk, &spindles, &modes);
    if (meet.active()) meet.block(blk);
  };
  read.on_wait = [&](const nc_wait& w) {
    b.wait(w);
    meet.wait(w);
  };
  sync_result check = check_nc_files(files, m, read);
  if (!check.ok) {
    tl.diagnostics = std::move(check.diagnostics);
    return tl;
  }
  timeline out = b.finish(check.rendezvous);
  out.conflicts = meet.finish(check.rendezvous, true);
  out.meetings = meet.meetings();
  fill_source_lines(out.conflicts, files, m);
  out.diagnostics.insert(out.diagnostics.begin(), check.diagnostics.begin(), check.diagnostics.end());
  return out;
}

}  // namespace twinpost
