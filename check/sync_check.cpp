#include "check/sync_check.hpp"

#include "check/nc_input.hpp"
#include "machines/code_overlap.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <map>
#include <tuple>

namespace twinpost {

namespace {

using channel_mask = std::uint64_t;
constexpr int max_channels = 64;  // partner sets are bit masks

channel_mask bit_of(int channel) { return channel_mask{1} << (channel - 1); }

/// A wait as the simulation sees it: what partners must agree on.
struct sim_wait {
  int code = 0;
  channel_mask partners = 0;  ///< always includes the wait's own channel
  bool plain = false;         ///< written without the partner list that was optional
  const nc_wait* src = nullptr;
  bool matches(const sim_wait& o) const {
    return code == o.code && partners == o.partners && plain == o.plain;
  }
};

/// "channel 2", "channels 2 and 3", "channels 1, 2 and 3".
std::string channel_list(const std::vector<int>& cs) {
  if (cs.size() == 1) return fmt::format("channel {}", cs[0]);
  std::string out = "channels ";
  for (std::size_t i = 0; i < cs.size(); ++i) {
    if (i > 0) out += i + 1 == cs.size() ? " and " : ", ";
    out += std::to_string(cs[i]);
  }
  return out;
}

std::string place(const nc_place& p) { return fmt::format("{}:{}", p.file, p.line); }

/// One check of one set of programs.
class checker {
 public:
  checker(const nc_programs& p, const machine& m)
      : progs_(p), m_(m), n_(static_cast<int>(p.channels.size())) {
    if (n_ <= max_channels) all_ = n_ == max_channels ? ~channel_mask{0} : bit_of(n_ + 1) - 1;
  }

  // The compact check (see check_nc_files): waits are taken one by one as they are read,
  // and only their simulation entries are kept.
  void begin_compact() { sims_.assign(static_cast<std::size_t>(n_), {}); }
  void take(const nc_wait& w) {
    sim_wait s = normalise(w);
    s.src = nullptr;  // the wait is gone after this call: a finding means a full check
    sims_[static_cast<std::size_t>(w.channel - 1)].push_back(s);
  }
  bool nothing_found() const { return result_.diagnostics.empty(); }
  std::vector<std::uint64_t> take_rendezvous() { return std::move(result_.rendezvous); }
  /// Simulates the channels together; true when every one reaches its end.
  bool all_paired() {
    pos_.assign(sims_.size(), 0);
    simulate();
    for (int c = 1; c <= n_; ++c)
      if (!finished(c)) return false;
    return true;
  }

  sync_result run() {
    if (n_ > max_channels) {
      // A machine file refuses this at load; a machine made in code is named by its source.
      nc_place at;
      at.file = !m_.source.empty() ? m_.source : !progs_.channels.empty() ? progs_.channels[0].file : m_.name;
      report(severity::error, at, 0,
             fmt::format("machine '{}' has {} channels: the checker handles at most {}", m_.name, n_,
                         max_channels));
    } else {
      for (const nc_channel_program& c : progs_.channels) {
        sims_.emplace_back();
        for (const nc_wait& w : c.waits) sims_.back().push_back(normalise(w));
        for (const nc_wait& w : c.near_waits) judge_near_wait(w);
      }
      sort_by_place();
      pos_.assign(sims_.size(), 0);
      simulate();
      explain_stuck();
    }
    for (std::size_t i = 0; i < progs_.channels.size(); ++i) {
      const nc_channel_program& c = progs_.channels[i];
      const int paired = i < pos_.size() ? static_cast<int>(pos_[i]) : 0;
      result_.channels.push_back({c.channel, c.file, static_cast<int>(c.waits.size()), paired});
      result_.paired += paired;
    }
    return std::move(result_);
  }

 private:
  void report(severity level, const nc_place& at, int column, std::string message) {
    result_.diagnostics.push_back({level, at.file, at.line, column, std::move(message), at.source_line});
  }

  std::string code_text(int code) const { return fmt::format("{}{}", m_.waits.address, code); }

  bool bang() const { return m_.waits.syntax == wait_syntax::bang; }

  // The alarm a partner list problem raises, where it is the control's own.
  const char* ps0161() const { return bang() ? "" : " (Fanuc PS0161)"; }

  std::string wait_text(const nc_wait& w) const {
    // Bang waits as written: !2L1, !2!3L5.
    if (bang()) return fmt::format("{}{}{}", m_.waits.marker, w.partner_text, code_text(w.code));
    if (!w.has_partner_list) return code_text(w.code);
    return fmt::format("{} {}{}", code_text(w.code), m_.waits.partner_address, w.partner_text);
  }

  std::string partner_text(const nc_wait& w) const {
    if (bang()) return fmt::format("partner list {} of wait {}", w.partner_text, wait_text(w));
    return fmt::format("partner list {}{} of wait {}", m_.waits.partner_address, w.partner_text,
                       code_text(w.code));
  }

  /// Checks a wait's partner list (PS0161) and turns it into the set partners agree on.
  sim_wait normalise(const nc_wait& w) {
    sim_wait s{w.code, all_, false, &w};
    const nc_place& at = w.where;
    if (const wait_rules::fixed_wait* f = m_.waits.fixed_wait_of(w.code)) {
      s.partners = 0;
      for (int c : f->channels) s.partners |= bit_of(c);
      if (w.has_partner_list)
        report(severity::error, at, w.partner_column,
               fmt::format("wait {} is a wait of {} by its code and takes no partner list", wait_text(w),
                           channel_list(f->channels)));
      else if (!(s.partners & bit_of(w.channel)))
        report(severity::error, at, at.column,
               fmt::format("wait {} is a wait of {}: channel {} may not write it", wait_text(w),
                           channel_list(f->channels), w.channel));
      return s;
    }
    if (m_.waits.partners == partner_style::none) {
      if (w.has_partner_list)
        report(severity::error, at, w.partner_column,
               fmt::format("wait {} has a partner list, but this machine's waits take none", wait_text(w)));
    } else if (!w.has_partner_list) {
      if (n_ >= 3 && !m_.waits.partners_optional)
        report(severity::error, at, at.column,
               fmt::format("wait {} has no partner list: with {} channels every wait must "
                           "name its partners (Fanuc PS0161)",
                           code_text(w.code), n_));
      else
        s.plain = !m_.waits.partners_optional;  // optional: the same wait as one naming every channel
    } else if (bang() && w.partner_text.empty()) {
      report(severity::error, at, at.column,
             fmt::format("wait {} names no partner: write the channels it meets after {}, e.g. {}{}{}{}",
                         wait_text(w), m_.waits.marker, m_.waits.marker, w.channel == 1 ? 2 : 1,
                         m_.waits.address, w.code));
    } else if (!w.partners_readable) {
      report(severity::error, at, w.partner_column,
             fmt::format(
                 "{} is not {}{}", partner_text(w),
                 m_.waits.partners == partner_style::binary ? "a channel mask" : "a list of channel numbers",
                 ps0161()));
    } else {
      s.partners = partner_mask(w);
    }
    return s;
  }

  channel_mask partner_mask(const nc_wait& w) {
    channel_mask mask = 0;
    std::string problem;
    for (int p : w.partners) {
      if (p < 1 || p > n_) {
        if (problem.empty()) problem = fmt::format("names channel {}, which this machine does not have", p);
      } else if (mask & bit_of(p)) {
        if (problem.empty()) problem = fmt::format("names channel {} twice", p);
      } else {
        mask |= bit_of(p);
      }
    }
    const channel_mask own = bit_of(w.channel);
    if (m_.waits.partners == partner_style::others) {
      // The list names the other channels: the own one is implied, and wrong there.
      if (problem.empty() && (mask & own))
        problem = fmt::format("in channel {} names channel {}, its own: a wait names the channels it meets",
                              w.channel, w.channel);
    } else if (problem.empty() && !(mask & own))
      problem = fmt::format("in channel {} does not name channel {}", w.channel, w.channel);
    else if (problem.empty() && mask == own)
      problem = "names no channel but its own";
    if (!problem.empty())
      report(severity::error, w.where, w.partner_column,
             fmt::format("{} {}{}", partner_text(w), problem, ps0161()));
    return mask | own;
  }

  /// An M-code in the wait range but off its step, or one that carries a partner list.
  void judge_near_wait(const nc_wait& w) {
    const wait_rules& wr = m_.waits;
    const std::string range = fmt::format("{}-{}", code_text(wr.first), code_text(wr.last));
    if (w.code >= wr.first && w.code <= wr.last) {
      report(severity::warning, w.where, w.where.column,
             fmt::format("{} lies in the wait range {} but off its step of {}: it is not "
                         "checked as a wait",
                         code_text(w.code), range, wr.step));
      return;
    }
    if (bang()) {  // written as a wait, with a number the control does not take
      report(severity::error, w.where, w.where.column,
             fmt::format("{} looks like a wait, but {} is not a wait number of this machine ({})",
                         wait_text(w), code_text(w.code), range));
      return;
    }
    if (!w.has_partner_list || !w.partners_readable || w.partners.size() < 2) return;
    channel_mask seen = 0;
    for (int p : w.partners) {
      if (p < 1 || p > n_ || (seen & bit_of(p))) return;  // not a plausible partner list
      seen |= bit_of(p);
    }
    report(severity::error, w.where, w.where.column,
           fmt::format("{} looks like a wait, but {} is not a wait code of this machine ({})", wait_text(w),
                       code_text(w.code), range));
  }

  /// Static problems in file order, as a compiler lists them.
  void sort_by_place() {
    std::map<std::string, std::size_t> file_order;
    for (const nc_channel_program& c : progs_.channels) file_order.emplace(c.file, file_order.size());
    auto key = [&](const diagnostic& d) {
      auto it = file_order.find(d.file);
      return std::tuple(it == file_order.end() ? file_order.size() : it->second, d.line, d.column);
    };
    std::stable_sort(result_.diagnostics.begin(), result_.diagnostics.end(),
                     [&](const diagnostic& a, const diagnostic& b) { return key(a) < key(b); });
  }

  bool finished(int c) const { return pos_[c - 1] >= sims_[c - 1].size(); }
  const sim_wait& current(int c) const { return sims_[c - 1][pos_[c - 1]]; }

  template <class F>
  static void for_each_channel(channel_mask mask, F&& f) {
    for (; mask != 0; mask &= mask - 1) f(std::countr_zero(mask) + 1);
  }

  /// Runs all channels together. A channel is looked at only when it reaches a new wait;
  /// the last partner to arrive releases the group, so the work is linear in the waits.
  void simulate() {
    std::vector<int> todo;
    for (int c = n_; c >= 1; --c) todo.push_back(c);
    while (!todo.empty()) {
      const int c = todo.back();
      todo.pop_back();
      if (finished(c)) continue;
      const sim_wait& w = current(c);
      bool ready = true;
      for_each_channel(w.partners,
                       [&](int p) { ready = ready && (p == c || (!finished(p) && current(p).matches(w))); });
      if (!ready) continue;
      result_.rendezvous.push_back(w.partners);
      for_each_channel(w.partners, [&](int p) {
        ++pos_[p - 1];
        todo.push_back(p);
      });
    }
  }

  /// Says why each channel that did not reach its end is stuck; names every one of them.
  void explain_stuck() {
    std::vector<bool> covered(static_cast<std::size_t>(n_) + 1, false);
    std::vector<std::vector<int>> blocked_by(static_cast<std::size_t>(n_) + 1);
    for (int a = 1; a <= n_; ++a) {
      if (finished(a)) continue;
      const sim_wait& w = current(a);
      std::vector<int> ended;
      for_each_channel(w.partners, [&](int b) {
        if (b == a) return;
        if (finished(b)) return ended.push_back(b);
        const sim_wait& o = current(b);
        if (o.matches(w)) return;
        if (!(o.partners & bit_of(a))) return blocked_by[a].push_back(b);
        // Both wait for each other on different waits: neither can ever go on.
        covered[a] = covered[b] = true;
        if (a < b) report_mismatch(w, o);
      });
      if (!ended.empty()) {
        covered[a] = true;
        report_unpaired(w, ended);
      }
    }
    std::string chain;
    const nc_place* first = nullptr;
    for (int a = 1; a <= n_; ++a) {
      if (finished(a) || covered[a]) continue;
      const nc_wait& w = *current(a).src;
      if (!first) first = &w.where;
      chain += fmt::format("{}channel {} waits at {} ({}) for {}", chain.empty() ? "" : "; ", a,
                           place(w.where), wait_text(w), channel_list(blocked_by[a]));
    }
    if (first) report(severity::error, *first, first->column, "deadlock: " + chain);
  }

  void report_unpaired(const sim_wait& w, const std::vector<int>& ended) {
    std::string how;
    for (int c : ended) {
      const nc_place& end = progs_.channels[static_cast<std::size_t>(c - 1)].end;
      how += how.empty() ? "" : "; ";
      how += end.line > 0 ? fmt::format("channel {} ends at {} without a matching wait", c, place(end))
                          : fmt::format("channel {} has no program", c);
    }
    report(severity::error, w.src->where, w.src->where.column,
           fmt::format("wait {} of channel {} is never met: {}", wait_text(*w.src), w.src->channel, how));
  }

  void report_mismatch(const sim_wait& a, const sim_wait& b) {
    const char* why = a.code != b.code     ? (bang() ? "different wait numbers" : "different codes")
                      : a.plain != b.plain ? "one with a partner list, one without"
                                           : "different partner lists";
    report(severity::error, a.src->where, a.src->where.column,
           fmt::format("deadlock: channel {} waits on {} at {} while channel {} waits on {} "
                       "at {} ({}{})",
                       a.src->channel, wait_text(*a.src), place(a.src->where), b.src->channel,
                       wait_text(*b.src), place(b.src->where), why,
                       // Name the alarm only where it is the control's own.
                       m_.control.find("fanuc") != std::string::npos ? ", Fanuc PS0160" : ""));
  }

  const nc_programs& progs_;
  const machine& m_;
  const int n_;
  channel_mask all_ = 0;
  std::vector<std::vector<sim_wait>> sims_;  ///< per channel, in program order
  std::vector<std::size_t> pos_;             ///< per channel: index of its current wait
  sync_result result_;
};

void count(sync_result& r) {
  diagnostic_counts n;
  for (const diagnostic& d : r.diagnostics) n.add(d);
  r.errors = n.errors;
  r.warnings = n.warnings;
  r.ok = r.errors == 0;
}

}  // namespace

namespace {

// A program of several channels in which no wait of the machine was found: nothing was
// checked, and the channels would run with no synchronisation at all; most likely the
// programs are for another machine (another wait syntax). Never a silent "sound".
void no_waits_found(sync_result& r, const machine& m) {
  if (r.channels.size() < 2 || r.errors > 0) return;
  for (const channel_sync_summary& c : r.channels)
    if (c.waits > 0) return;
  diagnostic d;
  d.file = r.channels.front().file;
  d.message = fmt::format(
      "no wait code of machine '{}' ({}) in any of the {} channels: nothing to check, and the channels would "
      "run with no synchronisation; is this the right machine?",
      m.name, wait_range_text(m.waits), r.channels.size());
  r.diagnostics.push_back(std::move(d));
  count(r);
}

}  // namespace

sync_result check_sync(const nc_programs& programs, const machine& m) {
  sync_result r = checker(programs, m).run();
  count(r);
  return r;
}

namespace {

// Reads the files keeping every wait, and checks them with all messages.
sync_result full_check(const std::vector<nc_source>& files, const machine& m) {
  diagnostic_list read;
  const nc_programs programs = read_nc_programs(files, m, read);
  sync_result r = checker(programs, m).run();
  r.diagnostics.insert(r.diagnostics.begin(), read.all().begin(), read.all().end());
  count(r);
  return r;
}

}  // namespace

struct compact_sync_check::impl {
  impl(const machine& m, const nc_read_options& also)
      : m(m), shape(one_per_channel(m)), compact(shape, m), waits(m.channels.size(), 0) {
    compact.begin_compact();
    options.on_wait = [this, also](const nc_wait& w) {
      compact.take(w);
      ++waits[static_cast<std::size_t>(w.channel - 1)];
      if (also.on_wait) also.on_wait(w);
    };
    options.on_block = also.on_block;
    options.on_macro = also.on_macro;
    options.before_block = also.before_block;
  }
  static nc_programs one_per_channel(const machine& m) {
    nc_programs p;
    p.channels.resize(m.channels.size());
    return p;
  }
  const machine& m;
  nc_programs shape;  // one program per machine channel, as read_nc_programs makes them
  checker compact;
  std::vector<int> waits;
  nc_read_options options;
};

compact_sync_check::compact_sync_check(const machine& m, const nc_read_options& also)
    : p_(std::make_unique<impl>(m, also)) {}

compact_sync_check::~compact_sync_check() = default;

const nc_read_options& compact_sync_check::options() const { return p_->options; }

std::optional<sync_result> compact_sync_check::result(const nc_programs& programs,
                                                      const diagnostic_list& read) {
  bool near_waits = false;
  for (const nc_channel_program& c : programs.channels) near_waits = near_waits || !c.near_waits.empty();
  if (!read.all().empty() || near_waits || !p_->compact.nothing_found() || !p_->compact.all_paired())
    return std::nullopt;
  sync_result r;
  for (std::size_t i = 0; i < programs.channels.size(); ++i) {
    const nc_channel_program& c = programs.channels[i];
    r.channels.push_back({c.channel, c.file, p_->waits[i], p_->waits[i]});
    r.paired += p_->waits[i];
  }
  r.rendezvous = p_->compact.take_rendezvous();
  count(r);
  no_waits_found(r, p_->m);
  return r;
}

sync_result check_nc_files(const std::vector<nc_source>& given, const machine& m,
                           const nc_read_options& also) {
  // Read twice below: a pipe or FIFO is copied once first (check/nc_input.hpp).
  const std::vector<nc_source> files = rereadable(given);
  // First the compact way: each wait is kept only as its 32-byte simulation entry, so a
  // sound program of any length is checked in memory that does not grow with its waits.
  // Anything at all to say (a reading problem, a wait that looks wrong, a channel that does
  // not reach its end) has the files read again the full way, which says it: the same
  // reader, the same rules and the same simulation, with every wait kept for the messages.
  if (m.channels.size() <= static_cast<std::size_t>(max_channels)) {
    compact_sync_check compact(m, also);
    diagnostic_list read;
    const nc_programs programs = read_nc_programs(files, m, read, compact.options());
    if (std::optional<sync_result> r = compact.result(programs, read)) return std::move(*r);
  }
  sync_result r = full_check(files, m);
  no_waits_found(r, m);
  return r;
}

}  // namespace twinpost
