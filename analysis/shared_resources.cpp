#include "analysis/shared_resources.hpp"

#include "analysis/nc_codes.hpp"

#include "analysis/control_emulator.hpp"
#include "analysis/cycle_time.hpp"
#include "analysis/length_offset.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <optional>

#include "analysis/interference.hpp"
#include "analysis/modal_state.hpp"
#include "analysis/spindle_state.hpp"

namespace twinpost {

namespace {

struct place_ref {
  std::string file;
  int line = 0;
  int column = 0;
  std::string source;
};

std::string at_text(const place_ref& p) { return fmt::format("{}:{}", p.file, p.line); }

// A command of a shared spindle (the conflict, hold and change rules).
struct command_rec {
  int seg = 0;
  spindle_command cmd;
  place_ref at;
  std::size_t own_turns = 0;  // how many starts and stops of that spindle the channel gave before it
  bool balance = false;       // given in a balance cut (codes.balance_on .. balance_off)
};

// A start or stop of a spindle (the feed and hold rules, the setting a cut relies on).
struct turn_rec {
  int seg = 0;
  bool start = false;
  int stop_code = 0;
  spindle_setting setting;  // the spindle as the channel set it with this block
  place_ref at;
};

// The first cut with feed per revolution of a stretch the feed rule treats alike: one
// segment, one spindle, the same own start or stop before it.
struct cut_rec {
  int seg = 0;
  int spindle = 0;
  std::size_t own_turns = 0;  // how many starts and stops of that spindle the channel gave before it
  place_ref at;
};

// The first cut (any feed mode) on a shared spindle of a stretch the change rule treats alike:
// one segment, one spindle, the same commands of it by the channel before it.
struct use_rec {
  int seg = 0;
  int spindle = 0;
  std::size_t own_turns = 0;
  spindle_setting own;  // the spindle as the channel itself set it (turn unknown: never)
  place_ref at;
  bool balance = false;  // cut in a balance cut
};

struct channel_data {
  channel_data(const machine& m, const channel_spindles& spindles, int number)
      : spindles(spindles), codes(m, m.channels[static_cast<std::size_t>(number - 1)]),
        quiet_without_gms(spindles.needs_gms()) {}
  const channel_spindles& spindles;  // the reading's (spindle_states), this block applied
  nc_codes codes;                    // what its G codes make of a block's axis words
  bool quiet_without_gms;            // a block without G, M or S cannot command a spindle
  int seg = 0;
  bool per_rev = false;
  int motion = -1;
  double turning_g = -1;  // a lathe's single cycle in force (G90, G92, G94 in system A), modal as G1
  std::vector<std::vector<command_rec>> commands;  // per spindle
  std::vector<std::vector<turn_rec>> turns;        // per spindle
  std::vector<cut_rec> cuts;
  std::vector<use_rec> uses;
  std::vector<std::size_t> own_commands;  // per spindle: how many commands the channel gave
  std::vector<bool> refused;              // per spindle: the "may not command" error is given
  bool has_cut_key = false;
  int last_seg = 0, last_spindle = 0;
  std::size_t last_turns = 0;
  bool balance = false;      // between the machine's balance_on and balance_off
  bool has_use_key = false;  // the same for uses: segment, spindle, own commands
  int use_seg = 0, use_spindle = 0;
  std::size_t use_commands = 0;

  // The per-revolution cut of this stretch is noted (or none can be: feed per minute).
  bool cut_noted() const {
    return !per_rev || (has_cut_key && last_seg == seg && last_spindle == spindles.current() &&
                        last_turns == turns[static_cast<std::size_t>(last_spindle)].size());
  }
  // The use of this stretch is noted (or the spindle is not shared: `shared` tells).
  bool use_noted(const std::vector<bool>& shared) const {
    const int s = spindles.current();
    return s < 0 || !shared[static_cast<std::size_t>(s)] ||
           (has_use_key && use_seg == seg && use_spindle == s &&
            use_commands == own_commands[static_cast<std::size_t>(s)]);
  }
};

// A start or stop that the feed rule weighs: which channel, which of its turns.
struct turn_ref {
  int channel = 0;
  std::size_t index = 0;
  const turn_rec* rec = nullptr;
};

}  // namespace

struct shared_resources::impl {
  impl(const machine& mm, const spindle_states& spindles) : m(mm) {
    for (const channel_def& c : m.channels) {
      channels.emplace_back(m, spindles.channel(c.number), c.number);
      channels.back().commands.resize(m.spindles.size());
      channels.back().turns.resize(m.spindles.size());
      channels.back().refused.assign(m.spindles.size(), false);
      channels.back().own_commands.assign(m.spindles.size(), 0);
    }
    for (std::size_t i = 0; i < m.spindles.size(); ++i)
      shared.push_back(m.shared_spindle(static_cast<int>(i)));
    for (auto [code, into] :
         {std::pair{&m.codes.balance_on, &balance_on}, {&m.codes.balance_off, &balance_off}})
      if (const std::vector<nc_word> w = split_nc_words(*code); !w.empty() && !w[0].expression) *into = w[0];
  }

  const machine& m;
  std::vector<channel_data> channels;
  std::vector<bool> shared;  // per spindle: machine::shared_spindle
  // The first word of the balance-cut codes (Fanuc G68/G69, Mazak M562/M563): in a balance cut
  // the paths move together block by block, so a spindle command of one is where the other is.
  std::optional<nc_word> balance_on, balance_off;
  bool is_word(const nc_word& w, const std::optional<nc_word>& code) const {
    return code && w.address == code->address && w.numeric && code->numeric && w.number == code->number;
  }
  std::vector<diagnostic> refusals;
  std::vector<std::vector<std::vector<int>>> clocks;  // [channel][segment][channel]

  const channel_def& def(int channel) const { return m.channels[static_cast<std::size_t>(channel - 1)]; }
  const spindle_def& spindle(int index) const { return m.spindles[static_cast<std::size_t>(index)]; }

  std::string allowed(int channel) const {
    std::string out;
    for (std::size_t i = 0; i < m.spindles.size(); ++i)
      if (m.may_command(channel, static_cast<int>(i))) out += (out.empty() ? "" : ", ") + m.spindles[i].name;
    return out.empty() ? "none" : out;
  }

  // The command in the machine's words: "G96 S200 M3", "M5", "G97".
  std::string command_text(const spindle_command& c) const {
    const spindle_def& s = spindle(c.spindle);
    std::string out;
    auto add = [&](const std::string& w) {
      if (w.empty()) return;
      out += (out.empty() ? "" : " ") + w;
    };
    const std::string& mode_code = c.setting.mode == speed_mode::css   ? m.codes.css
                                   : c.setting.mode == speed_mode::rpm ? m.codes.rpm
                                                                       : std::string();
    if (c.speed || c.mode) add(mode_code);
    if (c.speed) add(fmt::format("S{}", c.setting.speed));
    if (c.turn && c.setting.turn == spindle_turn::held) {
      add(fmt::format("M{}", c_axis_code(s.c_axis.on)));
    } else if (c.turn && c.release) {
      add(fmt::format("M{}", c_axis_code(s.c_axis.off)));
    } else if (c.turn) {
      const int code = c.setting.turn == spindle_turn::cw    ? s.cw
                       : c.setting.turn == spindle_turn::ccw ? s.ccw
                                                             : s.stop;
      add(fmt::format("M{}", code));
    }
    return out;
  }

  // A setting in the machine's words, as a command that gives all of it: "G96 S200 M3".
  std::string setting_text(int spindle, const spindle_setting& st) const {
    spindle_command c{spindle, st};
    c.turn = st.turn != spindle_turn::unknown;
    c.speed = st.mode != speed_mode::unknown && st.speed > 0;
    c.mode = st.mode != speed_mode::unknown;
    return command_text(c);
  }

  void block(const nc_block& b) {
    const int channel = b.channel;
    const std::string& file = b.file;
    const int line = b.line;
    const std::string_view text = b.text;
    if (channel < 1 || static_cast<std::size_t>(channel) > channels.size()) return;
    channel_data& c = channels[static_cast<std::size_t>(channel - 1)];
    // Most blocks are moves with no G, M or S word: they change nothing here (the motion is
    // modal: only a G word changes it), and a cut among them counts only when it is the first
    // of its stretch (already noted otherwise).
    constexpr std::uint32_t gms = nc_letter('G') | nc_letter('M') | nc_letter('S');
    if (c.quiet_without_gms && !b.may_have(gms) &&
        (((c.motion < 1 || c.motion > 3) && c.turning_g < 0) || (c.cut_noted() && c.use_noted(shared))))
      return;
    const std::vector<nc_word>& words = b.words();
    bool cycle = false, thread = false, no_move = false;
    int axis_column = 0, cut_column = 0;
    for (const nc_word& w : words) {
      if (!w.numeric) continue;
      const double v = w.number;
      if (w.address == 'G') {
        if (v == 0 || v == 1 || v == 2 || v == 3) {
          c.motion = static_cast<int>(v);
          c.turning_g = -1;
          if (v != 0) cut_column = w.column;
        }
        if (const feed_kind f = c.codes.feed_mode(v); f != feed_kind::none)
          c.per_rev = f == feed_kind::per_rev;
        if (is_word(w, balance_on) || is_word(w, balance_off)) {
          c.balance = is_word(w, balance_on);
          c.has_use_key = false;
        }
        // A cycle cuts, and a thread follows the spindle whatever the feed mode; the axis words
        // of a dwell, a data or coordinate setting, a reference return or machine coordinates
        // are no cut (analysis/nc_codes: a system-A lathe's G92 is its threading cycle).
        switch (c.codes.role(v)) {
          case axis_words::turning_cycle:
            c.turning_g = v;  // its next blocks with axis words are passes of it (attack 63 M6)
            [[fallthrough]];
          case axis_words::feed_move:
          case axis_words::hole_cycle:
          case axis_words::repetitive_cycle:
            (c.codes.threads(v) ? thread : cycle) = true;
            cut_column = w.column;
            break;
          case axis_words::none:
          case axis_words::reference:
          case axis_words::machine: no_move = true; break;
          default: break;
        }
      } else if (w.address == 'M' && (is_word(w, balance_on) || is_word(w, balance_off))) {
        c.balance = is_word(w, balance_on);
        c.has_use_key = false;
      } else if (std::string_view("XYZUW").find(w.address) != std::string_view::npos && !axis_column) {
        axis_column = w.column;
      }
    }
    // A place (its file name a copy) is made only for a block that is noted: most blocks with
    // a G word command nothing and cut in a stretch already noted.
    const std::vector<spindle_command>& commands = c.spindles.commands();
    if (!commands.empty()) {
      place_ref at{file, line, 0, std::string(text)};
      for (const spindle_command& cmd : commands) {
        const auto s = static_cast<std::size_t>(cmd.spindle);
        at.column = cmd.column;
        if (!m.may_command(channel, cmd.spindle)) {
          if (!c.refused[s]) {
            c.refused[s] = true;
            refusals.push_back(
                {severity::error, file, line, cmd.column,
                 fmt::format("channel {} commands the {} spindle ({}), which machine '{}' does not "
                             "give it: channel {} may command {} (channel.spindles)",
                             channel, spindle(cmd.spindle).name, command_text(cmd), m.name, channel,
                             allowed(channel)),
                 at.source});
          }
          continue;
        }
        const std::size_t own_turns = c.turns[s].size();
        if (cmd.turn)
          c.turns[s].push_back({c.seg, cmd.setting.started(), spindle(cmd.spindle).stop, cmd.setting, at});
        if ((cmd.turn || cmd.speed || cmd.mode) && shared[s]) {
          c.commands[s].push_back({c.seg, cmd, at, own_turns, c.balance});
          ++c.own_commands[s];
        }
      }
    }
    // A block of axis words under a lathe's single cycle is another pass of it.
    if (c.turning_g >= 0 && axis_column > 0 && !no_move && !cycle && !thread)
      (c.codes.threads(c.turning_g) ? thread : cycle) = true;
    const bool feeding = c.motion >= 1 && c.motion <= 3 && axis_column > 0 && !no_move;
    const int s = c.spindles.current();
    if (s < 0 || !(thread || cycle || feeding)) return;
    const auto si = static_cast<std::size_t>(s);
    const bool new_use = !c.use_noted(shared);
    const std::size_t own = c.turns[si].size();
    const bool new_cut = (thread || c.per_rev) && !(c.has_cut_key && c.last_seg == c.seg &&
                                                    c.last_spindle == s && c.last_turns == own);
    if (!new_use && !new_cut) return;
    place_ref at{file, line, cut_column ? cut_column : axis_column, std::string(text)};
    if (new_use) {
      c.has_use_key = true;
      c.use_seg = c.seg;
      c.use_spindle = s;
      c.use_commands = c.own_commands[si];
      c.uses.push_back({c.seg, s, own, c.spindles.setting(s), at, c.balance});
    }
    if (!new_cut) return;
    c.has_cut_key = true;
    c.last_seg = c.seg;
    c.last_spindle = s;
    c.last_turns = own;
    c.cuts.push_back({c.seg, s, own, std::move(at)});
  }

  // --- happens-before -------------------------------------------------------------------

  void make_clocks(const std::vector<std::uint64_t>& rendezvous) {
    clocks = segment_clocks(rendezvous, channels.size());
  }

  bool known(int channel, int seg) const {
    return seg >= 0 && static_cast<std::size_t>(seg) < clocks[static_cast<std::size_t>(channel - 1)].size();
  }
  /// How many segments of channel `of` are over before segment `seg` of `channel` begins.
  int over(int channel, int seg, int of) const {
    return clocks[static_cast<std::size_t>(channel - 1)][static_cast<std::size_t>(seg)]
                 [static_cast<std::size_t>(of - 1)];
  }
  /// Segment `a_seg` of channel a ends before segment `b_seg` of channel b begins.
  bool before(int a, int a_seg, int b, int b_seg) const { return a_seg < over(b, b_seg, a); }

  // --- the rules ------------------------------------------------------------------------

  static const char* difference(const spindle_command& x, const spindle_command& y) {
    // A hold as the C axis (or its release) against a start is the held rule's finding (held_rule).
    if (x.setting.turn == spindle_turn::held || y.setting.turn == spindle_turn::held || x.release ||
        y.release)
      return nullptr;
    if (x.turn && y.turn && x.setting.turn != y.setting.turn) return "different direction";
    const bool x_speed = x.speed || x.mode, y_speed = y.speed || y.mode;
    if (x_speed && y_speed && x.setting.mode != speed_mode::unknown &&
        y.setting.mode != speed_mode::unknown && x.setting.mode != y.setting.mode)
      return "different speed mode (CSS and rpm)";
    if (x.speed && y.speed && x.setting.mode == y.setting.mode && x.setting.speed != y.setting.speed)
      return "different speed";
    return nullptr;
  }

  void conflicts(std::vector<diagnostic>& out) const {
    const int n = static_cast<int>(channels.size());
    for (std::size_t s = 0; s < m.spindles.size(); ++s)
      for (int b = 2; b <= n; ++b)
        for (const command_rec& y : channels[static_cast<std::size_t>(b - 1)].commands[s]) {
          if (!known(b, y.seg)) continue;
          for (int a = 1; a < b; ++a) {
            const std::vector<command_rec>& xs = channels[static_cast<std::size_t>(a - 1)].commands[s];
            const int from = over(b, y.seg, a);  // segments of a over before y's begins
            auto it = std::lower_bound(xs.begin(), xs.end(), from,
                                       [](const command_rec& r, int seg) { return r.seg < seg; });
            const command_rec* hit = nullptr;
            const char* why = nullptr;
            for (; it != xs.end() && known(a, it->seg) && !before(b, y.seg, a, it->seg); ++it)
              if ((why = difference(it->cmd, y.cmd))) {
                hit = &*it;
                break;
              }
            if (!hit) continue;
            out.push_back(
                {severity::error, y.at.file, y.at.line, y.at.column,
                 fmt::format("channel {} sets the shared {} spindle to {} while channel {} may set it "
                             "to {} at the same time ({}): {}; no wait orders the two blocks",
                             b, spindle(static_cast<int>(s)).name, command_text(y.cmd), a,
                             command_text(hit->cmd), at_text(hit->at), why),
                 y.at.source});
            out.push_back({severity::note, hit->at.file, hit->at.line, hit->at.column,
                           fmt::format("channel {} sets the {} spindle to {} here", a,
                                       spindle(static_cast<int>(s)).name, command_text(hit->cmd)),
                           hit->at.source});
            break;  // one finding for each block
          }
        }
  }

  // A spindle held as a C axis (c_on) by one channel is held until that channel lets it go
  // (c_off, or any other turn command of its own): a start of it by another channel that no
  // wait orders before the hold or after the release turns the part under a live tool.
  void held_rule(std::vector<diagnostic>& out) const {
    const int n = static_cast<int>(channels.size());
    for (std::size_t s = 0; s < m.spindles.size(); ++s)
      for (int a = 1; a <= n; ++a) {
        const std::vector<command_rec>& xs = channels[static_cast<std::size_t>(a - 1)].commands[s];
        for (std::size_t i = 0; i < xs.size(); ++i) {
          const command_rec& hold = xs[i];
          if (!hold.cmd.turn || hold.cmd.setting.turn != spindle_turn::held || !known(a, hold.seg)) continue;
          const command_rec* release = nullptr;
          for (std::size_t j = i + 1; j < xs.size() && !release; ++j)
            if (xs[j].cmd.turn && xs[j].cmd.setting.turn != spindle_turn::held) release = &xs[j];
          for (int b = 1; b <= n; ++b) {
            if (b == a) continue;
            for (const command_rec& y : channels[static_cast<std::size_t>(b - 1)].commands[s]) {
              if (!y.cmd.turn || !y.cmd.setting.started() || !known(b, y.seg)) continue;
              if (before(b, y.seg, a, hold.seg)) continue;                 // turned before the hold
              if (release && before(a, release->seg, b, y.seg)) continue;  // after the release
              out.push_back(
                  {severity::error, y.at.file, y.at.line, y.at.column,
                   fmt::format("channel {} starts the shared {} spindle ({}) while channel {} may hold it as "
                               "the C axis ({}, {}); no wait orders the start before the hold or after "
                               "its release",
                               b, spindle(static_cast<int>(s)).name, command_text(y.cmd), a,
                               command_text(hold.cmd), at_text(hold.at)),
                   y.at.source});
              out.push_back({severity::note, hold.at.file, hold.at.line, hold.at.column,
                             fmt::format("channel {} holds the {} spindle as the C axis here", a,
                                         spindle(static_cast<int>(s)).name),
                             hold.at.source});
              break;  // one finding for each hold and channel
            }
          }
          still_turning(a, s, hold, out);
        }
      }
  }

  // A hold of spindle s by channel a while another channel's start of it may still be in force:
  // the last starts and stops known to come before the hold end in a start by another channel,
  // so the part may still turn when the C axis is connected. The hold is the error: stopping
  // the spindle there would change the other channel's turning behind its back.
  void still_turning(int a, std::size_t s, const command_rec& hold, std::vector<diagnostic>& out) const {
    for (const turn_ref& e : latest_turns(a, hold.seg, s, hold.own_turns)) {
      if (e.channel == a || !e.rec->start) continue;
      const std::string& name = spindle(static_cast<int>(s)).name;
      out.push_back(
          {severity::error, hold.at.file, hold.at.line, hold.at.column,
           fmt::format("channel {} holds the shared {} spindle as the C axis ({}) while channel {} may "
                       "still turn it ({}, {}); no wait orders a stop of it before the hold",
                       a, name, command_text(hold.cmd), e.channel,
                       setting_text(static_cast<int>(s), e.rec->setting), at_text(e.rec->at)),
           hold.at.source});
      out.push_back(
          {severity::note, e.rec->at.file, e.rec->at.line, e.rec->at.column,
           fmt::format("channel {} starts the {} spindle here; no stop of it is known to come before "
                       "the hold",
                       e.channel, name),
           e.rec->at.source});
      return;  // one finding for each hold
    }
  }

  // A command of a shared spindle that changes it (a stop, a direction, speed mode or speed other
  // than the one a cut relies on) in a block that may run while another channel cuts on it: the
  // cut goes on at a speed its program did not ask for, or on a stopped spindle.
  void change_rule(std::vector<diagnostic>& out) const {
    const int n = static_cast<int>(channels.size());
    for (std::size_t s = 0; s < m.spindles.size(); ++s) {
      if (!shared[s]) continue;
      const std::string& name = spindle(static_cast<int>(s)).name;
      for (int b = 1; b <= n; ++b)
        for (const command_rec& y : channels[static_cast<std::size_t>(b - 1)].commands[s]) {
          if (!known(b, y.seg) || y.cmd.setting.turn == spindle_turn::held || y.cmd.release)
            continue;  // holds and releases are the hold rules' findings
          if (std::any_of(out.begin(), out.end(),
                          [&](const diagnostic& d) { return d.file == y.at.file && d.line == y.at.line; }))
            continue;  // rule 2 or the hold rule has named this block already
          for (int a = 1; a <= n; ++a) {
            if (a == b) continue;
            const std::vector<use_rec>& us = channels[static_cast<std::size_t>(a - 1)].uses;
            const int from = over(b, y.seg, a);  // segments of a over before y's begins
            auto it = std::lower_bound(us.begin(), us.end(), from,
                                       [](const use_rec& r, int seg) { return r.seg < seg; });
            const use_rec* hit = nullptr;
            spindle_setting expected;
            const char* why = nullptr;
            for (; it != us.end() && known(a, it->seg) && !before(b, y.seg, a, it->seg); ++it) {
              // Both in a balance cut: the paths move together, the change is where the cut is.
              if (it->spindle != static_cast<int>(s) || (it->balance && y.balance)) continue;
              expected = relied_on(a, *it);
              if (!expected.started()) continue;
              if (y.cmd.turn && y.cmd.setting.turn == spindle_turn::stopped) {
                hit = &*it;
                break;
              }
              spindle_command e{static_cast<int>(s), expected};
              e.turn = e.speed = e.mode = true;
              e.speed = expected.speed > 0;
              if ((why = difference(e, y.cmd))) {
                hit = &*it;
                break;
              }
            }
            if (!hit) continue;
            const std::string text =
                why ? fmt::format(
                          "channel {} sets the shared {} spindle to {} while channel {} may still cut on "
                          "it at {} ({}): {}; no wait orders the change after that cut",
                          b, name, command_text(y.cmd), a, setting_text(static_cast<int>(s), expected),
                          at_text(hit->at), why)
                    : fmt::format(
                          "channel {} stops the shared {} spindle ({}) while channel {} may still cut on "
                          "it ({}); no wait orders the stop after that cut",
                          b, name, command_text(y.cmd), a, at_text(hit->at));
            out.push_back({severity::error, y.at.file, y.at.line, y.at.column, text, y.at.source});
            out.push_back({severity::note, hit->at.file, hit->at.line, hit->at.column,
                           fmt::format("channel {} cuts on the {} spindle here", a, name), hit->at.source});
            break;  // one finding for each command
          }
        }
    }
  }

  // The setting a cut of channel a relies on: its own, or where it never commanded the spindle,
  // that of the start in force (turn unknown: none known).
  spindle_setting relied_on(int a, const use_rec& u) const {
    if (u.own.turn != spindle_turn::unknown) return u.own;
    for (const turn_ref& e : latest_turns(a, u.seg, static_cast<std::size_t>(u.spindle), u.own_turns))
      if (e.rec->start) return e.rec->setting;
    return {};
  }

  // turn `e` of channel `ec` happens before turn `f` of channel `fc`.
  bool turn_before(const turn_ref& e, const turn_ref& f) const {
    if (e.channel == f.channel) return e.index < f.index;
    return before(e.channel, e.rec->seg, f.channel, f.rec->seg);
  }

  // The starts and stops of spindle `s` in force at a block of channel `a` in segment `seg`,
  // after `own` turns of its own: of the last turn of each channel known to come before the
  // block (its own last one by program order), those that no other one is known to follow.
  std::vector<turn_ref> latest_turns(int a, int seg, std::size_t s, std::size_t own) const {
    const int n = static_cast<int>(channels.size());
    std::vector<turn_ref> last;
    if (own > 0) last.push_back({a, own - 1, &channels[static_cast<std::size_t>(a - 1)].turns[s][own - 1]});
    for (int b = 1; b <= n; ++b) {
      if (b == a) continue;
      const std::vector<turn_rec>& ts = channels[static_cast<std::size_t>(b - 1)].turns[s];
      const int done = over(a, seg, b);
      auto it =
          std::lower_bound(ts.begin(), ts.end(), done, [](const turn_rec& r, int sg) { return r.seg < sg; });
      if (it == ts.begin()) continue;
      --it;
      if (!known(b, it->seg)) continue;
      last.push_back({b, static_cast<std::size_t>(it - ts.begin()), &*it});
    }
    std::vector<turn_ref> latest;
    for (const turn_ref& e : last) {
      bool superseded = false;
      for (const turn_ref& f : last)
        if (&e != &f && turn_before(e, f)) superseded = true;
      if (!superseded) latest.push_back(e);
    }
    return latest;
  }

  void feed_rule(std::vector<diagnostic>& out) const {
    const int n = static_cast<int>(channels.size());
    for (int a = 1; a <= n; ++a) {
      const channel_data& c = channels[static_cast<std::size_t>(a - 1)];
      std::string last_cause;  // one report while the same cause holds
      int last_spindle = -1;
      for (const cut_rec& cut : c.cuts) {
        if (!known(a, cut.seg)) continue;
        const auto s = static_cast<std::size_t>(cut.spindle);
        const turn_ref* stop = nullptr;
        bool started = false;
        const std::vector<turn_ref> latest = latest_turns(a, cut.seg, s, cut.own_turns);
        for (const turn_ref& e : latest) {
          if (e.rec->start)
            started = true;
          else if (!stop)
            stop = &e;
        }
        if (started) {
          last_cause.clear();
          continue;
        }
        const std::string cause = stop ? at_text(stop->rec->at) : std::string("none");
        if (cause == last_cause && last_spindle == cut.spindle) continue;
        last_cause = cause;
        last_spindle = cut.spindle;
        const std::string& name = spindle(cut.spindle).name;
        std::string why =
            stop ? fmt::format("channel {} stops it at {} (M{}) and no start is known to come after that",
                               stop->channel, at_text(stop->rec->at), stop->rec->stop_code)
                 : std::string(
                       "no channel is known to have started it before this block (a start in another channel "
                       "counts only when a wait orders it before)");
        out.push_back({severity::error, cut.at.file, cut.at.line, cut.at.column,
                       fmt::format("channel {} cuts with feed per revolution ({}) on the {} spindle, but {}",
                                   a, m.codes.feed_per_rev, name, why),
                       cut.at.source});
      }
    }
  }
};

std::vector<std::vector<std::vector<int>>> segment_clocks(const std::vector<std::uint64_t>& rendezvous,
                                                          std::size_t n) {
  std::vector<std::vector<std::vector<int>>> clocks(n);
  std::vector<std::vector<int>> now(n, std::vector<int>(n, 0));
  for (std::size_t c = 0; c < n; ++c) clocks[c].push_back(now[c]);
  for (std::uint64_t members : rendezvous) {
    std::vector<int> merged(n, 0);
    for (std::uint64_t b = members; b; b &= b - 1) {
      const auto c = static_cast<std::size_t>(std::countr_zero(b));
      if (c >= n) continue;
      for (std::size_t k = 0; k < n; ++k) merged[k] = std::max(merged[k], now[c][k]);
    }
    for (std::uint64_t b = members; b; b &= b - 1) {
      const auto c = static_cast<std::size_t>(std::countr_zero(b));
      if (c < n) ++merged[c];
    }
    for (std::uint64_t b = members; b; b &= b - 1) {
      const auto c = static_cast<std::size_t>(std::countr_zero(b));
      if (c >= n) continue;
      now[c] = merged;
      clocks[c].push_back(merged);
    }
  }
  return clocks;
}

shared_resources::shared_resources(const machine& m, const spindle_states& spindles)
    : p_(std::make_unique<impl>(m, spindles)) {}
shared_resources::~shared_resources() = default;

void shared_resources::block(const nc_block& b) { p_->block(b); }

void shared_resources::wait(int channel) {
  if (channel >= 1 && static_cast<std::size_t>(channel) <= p_->channels.size())
    ++p_->channels[static_cast<std::size_t>(channel - 1)].seg;
}

std::vector<diagnostic> shared_resources::finish(const std::vector<std::uint64_t>& rendezvous,
                                                 bool waits_sound) {
  std::vector<diagnostic> out = p_->refusals;
  if (!waits_sound) return out;
  p_->make_clocks(rendezvous);
  p_->conflicts(out);
  p_->held_rule(out);
  p_->change_rule(out);
  p_->feed_rule(out);
  return out;
}

namespace {

// The rules' findings after the checker's, counted in the result; the interference rule's
// (analysis/interference) after the spindle rules', the length offset's (analysis/length_offset)
// last.
void add_findings(sync_result& r, shared_resources& rules, interference_check& meet, length_offset_rule& len,
                  control_emulator& control) {
  const bool sound = r.ok;
  std::vector<diagnostic> found = rules.finish(r.rendezvous, sound);
  std::vector<diagnostic> met = meet.finish(r.rendezvous, sound);
  found.insert(found.end(), met.begin(), met.end());
  std::vector<diagnostic> cancels = len.finish();
  found.insert(found.end(), cancels.begin(), cancels.end());
  std::vector<diagnostic> emulated = control.finish();
  found.insert(found.end(), emulated.begin(), emulated.end());
  if (found.empty()) return;
  r.diagnostics.insert(r.diagnostics.end(), found.begin(), found.end());
  diagnostic_counts n;
  for (const diagnostic& d : r.diagnostics) n.add(d);
  r.errors = n.errors;
  r.warnings = n.warnings;
  r.ok = r.errors == 0;
}

// The rules fed by a reading, and `feed` and `more` with them: the spindle state first, once
// for all who read it (the timer, the spindle rules, the interference rule, the emulator), and
// the modal state (the timer, the interference rule, the emulator, and `more`'s comparison).
nc_read_options feeding(spindle_states& spindles, modal_states& modes, shared_resources& rules,
                        interference_check& meet, length_offset_rule& len, control_emulator& control,
                        const nc_read_options& more, timeline_feed* feed) {
  nc_read_options also;
  // `more` settles what it owes the blocks before (before_block) with the states as they left
  // them, then the states apply the block once for all who read them, then `more` reads it.
  also.before_block = more.before_block;
  also.on_block = [&spindles, &modes, &rules, &meet, &len, &control, more, feed,
                   interfere = meet.active()](const nc_block& b) {
    // The timer splits every block: split first, and the spindle state finds its letters exact
    // (else it scans a block's text for them, which the split then reads again). `more` (the
    // comparison with the CL) splits it too.
    if (feed || more.on_block) (void)b.words();
    spindles.block(b);
    modes.block(b);
    if (more.on_block) more.on_block(b);
    if (feed) feed->block(b, &spindles, &modes);
    rules.block(b);
    if (interfere) meet.block(b);  // a machine without envelopes pays nothing per block for it
    len.block(b);
    control.block(b);
  };
  also.on_macro = [&modes, &control, more](const nc_block& b) {
    modes.block(b);  // (no words: the block's own G codes none)
    if (more.on_macro) more.on_macro(b);
    control.block(b);
  };
  also.on_wait = [&rules, &meet, more, feed](const nc_wait& w) {
    rules.wait(w.channel);
    meet.wait(w);
    if (feed) feed->wait(w);
    if (more.on_wait) more.on_wait(w);
  };
  return also;
}

}  // namespace

sync_result check_nc_resources(const std::vector<nc_source>& files, const machine& m,
                               const nc_read_options& more, timeline_feed* feed) {
  spindle_states spindles(m);
  modal_states modes(m);
  shared_resources rules(m, spindles);
  interference_check meet(m, spindles, modes);
  length_offset_rule len(m.channels.size());
  control_emulator control(m, spindles, modes);
  sync_result r = check_nc_files(files, m, feeding(spindles, modes, rules, meet, len, control, more, feed));
  add_findings(r, rules, meet, len, control);
  fill_source_lines(r.diagnostics, files, m);
  return r;
}

struct compact_resource_check::impl {
  impl(const machine& m, const nc_read_options& more, timeline_feed* feed)
      : spindles(m), modes(m), rules(m, spindles), meet(m, spindles, modes), len(m.channels.size()),
        control(m, spindles, modes),
        compact(m, feeding(spindles, modes, rules, meet, len, control, more, feed)) {}
  spindle_states spindles;
  modal_states modes;
  shared_resources rules;
  interference_check meet;
  length_offset_rule len;
  control_emulator control;
  compact_sync_check compact;
};

compact_resource_check::compact_resource_check(const machine& m, const nc_read_options& more,
                                               timeline_feed* feed)
    : p_(std::make_unique<impl>(m, more, feed)) {}

compact_resource_check::~compact_resource_check() = default;

const nc_read_options& compact_resource_check::options() const { return p_->compact.options(); }
const spindle_states& compact_resource_check::spindles() const { return p_->spindles; }
const modal_states& compact_resource_check::modes() const { return p_->modes; }

std::optional<sync_result> compact_resource_check::result(const nc_programs& programs,
                                                          const diagnostic_list& read) {
  std::optional<sync_result> r = p_->compact.result(programs, read);
  if (r) add_findings(*r, p_->rules, p_->meet, p_->len, p_->control);
  return r;
}

}  // namespace twinpost
