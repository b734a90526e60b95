#include "analysis/control_emulator.hpp"

#include <fmt/format.h>

#include <optional>
#include <string>

#include "analysis/modal_state.hpp"
#include "analysis/nc_codes.hpp"
#include "analysis/rotary_sweep.hpp"
#include "analysis/spindle_state.hpp"
#include "machines/macro_variables.hpp"

namespace twinpost {

namespace {

// A fixed code of the machine file ("M206", "G54.1 P1"), split once: a block gives it when it
// has every one of its words.
struct code {
  std::string text;
  std::vector<nc_word> words;
  explicit code(const std::string& t) : text(t), words(split_nc_words(text)) {
    for (nc_word& w : words) w.value = {};  // the views would die with a moved copy: numbers only
  }
  bool empty() const { return words.empty(); }
  bool in(const std::vector<nc_word>& block) const {
    if (words.empty()) return false;
    for (const nc_word& w : words) {
      bool found = false;
      for (const nc_word& b : block)
        if (b.address == w.address && b.numeric == w.numeric && b.number == w.number) {
          found = true;
          break;
        }
      if (!found) return false;
    }
    return true;
  }
};

struct chuck_codes {
  code open, close;
};

struct chuck_state {
  bool open = false;
  int line = 0;  // the block that opened it
};

struct channel_state {
  channel_state(const channel_spindles& spindles, const channel_modes& modes)
      : spindles(spindles), modes(modes) {}
  const channel_spindles& spindles;  // the reading's (spindle_states), this block applied
  const channel_modes& modes;        // the reading's (modal_states): the motion, the cycle in force
  bool offset = false;               // a work offset in force
  bool sync = false;                 // spindle synchronisation on
  std::vector<int> start_line;       // per spindle: the block that started it
  std::vector<chuck_state> chucks;   // per spindle, as this channel's blocks left it
  int holder = -1;                   // the spindle that closed its chuck on the part while synchronised
  std::optional<double> x_now;       // while `holder` holds the part: where X stands (none: not known)
  bool u_is_x = false;               // U is X's increment (a lathe's X in diameter, no U axis)
  int cutoff_line = 0;               // a part-off while `holder` held the part
  char head = 0;                     // the address of the channel's indexing head (B); 0: none
  int change_m = -1;                 // the M code of its tool change (M6 of "T{tool:02} M6"); -1: a T word
  int head_unknown = 0;              // the tool call since which the head has not been indexed; 0: known
  bool said_offset = false, said_chuck = false, said_start = false, said_cutoff = false, said_head = false,
       said_released = false, said_coolant = false;
  // The coolant before an index: said once, at the first; the later ones counted into its message
  // (review 40 L4: a program that did it at every tool change had one warning, for the first).
  std::size_t coolant_said = 0;    // its index in `found`
  long coolant_more = 0;           // the later blocks that did it too
  std::vector<int> coolant_lines;  // the first of them
  // A channel with a kinematic chain that has a rotary axis: its rapids' tip paths.
  std::optional<rotary_sweep> sweep;
};

constexpr std::uint32_t linear_axes =
    nc_letter('X') | nc_letter('Y') | nc_letter('Z') | nc_letter('U') | nc_letter('V') | nc_letter('W');

// The M code a tool call template writes ("T{tool:02} M6", "M6 T{tool:02}00"): the tool change
// proper; a T word alone is then an offset call (the 31i's T0707 after M6 T0700). -1: none.
int tool_change_code(const std::string& tool_call) {
  for (std::size_t i = 0; i + 1 < tool_call.size(); ++i) {
    if (tool_call[i] == '{') {
      i = tool_call.find('}', i);
      if (i == std::string::npos) break;
      continue;
    }
    if (tool_call[i] != 'M' || tool_call[i + 1] < '0' || tool_call[i + 1] > '9') continue;
    int code = 0;
    for (std::size_t k = i + 1; k < tool_call.size() && tool_call[k] >= '0' && tool_call[k] <= '9'; ++k)
      code = code * 10 + (tool_call[k] - '0');
    return code;
  }
  return -1;
}

}  // namespace

bool sweeps_chain(const machine& m, int channel) {
  // A mill's chain (a lathe's B head indexes at home, its X a diameter: not followed here).
  const channel_def& c = m.channels[static_cast<std::size_t>(channel - 1)];
  const axis_def* x = c.axis('X');
  const kinematic_chain* k = m.chain(channel);
  bool head = false;  // only a head swings the tip (a table turns the part: not held)
  for (const rotary_axis_def& r : k ? k->rotaries : std::vector<rotary_axis_def>{})
    head = head || r.kind == rotary_kind::head;
  return head && !c.head_index.present() && !(x && x->diameter);
}

struct control_emulator::impl {
  impl(const machine& m, const spindle_states& spindles, const modal_states& modes)
      : m(m), sync_on(m.codes.spindle_sync_on), sync_off(m.codes.spindle_sync_off) {
    for (std::size_t i = 0; i < m.channels.size(); ++i) {
      channels.emplace_back(spindles.channel(static_cast<int>(i) + 1),
                            modes.channel(static_cast<int>(i) + 1));
      channels.back().start_line.assign(m.spindles.size(), 0);
      channels.back().chucks.assign(m.spindles.size(), {});
      if (sweeps_chain(m, static_cast<int>(i) + 1))
        channels.back().sweep.emplace(m, *m.chain(static_cast<int>(i) + 1), static_cast<int>(i) + 1,
                                      tool_change_code(m.channels[i].tool_call));
      const axis_def* x = m.channels[i].axis('X');
      channels.back().u_is_x = x && x->diameter && !m.channels[i].axis('U');
      if (m.channels[i].head_index.present()) {
        channels.back().head = m.channels[i].head_index.address;
        channels.back().change_m = tool_change_code(m.channels[i].tool_call);
      }
    }
    for (const std::string& b : m.codes.coolant_on) coolant_on.emplace_back(b);
    for (const auto* pair : {&m.codes.coolant_mist, &m.codes.coolant_through, &m.codes.coolant_air})
      if (!pair->empty()) coolant_on.emplace_back(pair->front());
    for (const spindle_def& s : m.spindles) chucks.push_back({code(s.chuck_open), code(s.chuck_close)});
    for (const spindle_def& s : m.spindles)
      if (!s.work_offset.empty()) offset_codes.emplace_back(s.work_offset);
    reserved = reserved_variables(m);
    for (const chuck_codes& c : chucks) has_chucks = has_chucks || !c.open.empty();
    // Work offsets are the machine file's word: a machine whose spindles name none (a Swiss-type
    // whose tool geometry sets the frame) is not held to them.
    for (const spindle_def& s : m.spindles) offsets_used = offsets_used || !s.work_offset.empty();
    if (!offsets_used)
      for (channel_state& c : channels) c.offset = true;
  }
  const machine& m;
  code sync_on, sync_off;
  std::vector<channel_state> channels;
  // Per spindle. Each channel is followed on its own (its chucks as its own blocks left them), so
  // the findings do not depend on how the channels' blocks interleave in the reading.
  std::vector<chuck_codes> chucks;
  std::vector<code> offset_codes;  // each spindle's work offset ([[spindle]] work_offset)
  std::vector<code> coolant_on;    // each kind's code that turns it on
  std::vector<reserved_variable> reserved;
  bool has_chucks = false;
  bool offsets_used = false;
  std::vector<diagnostic> found;

  void say(const nc_block& b, int column, std::string message, severity level = severity::error) {
    found.push_back({level, b.file, b.line, column, std::move(message), std::string(b.text)});
  }

  void variables(const nc_block& b) {
    for (const macro_use& u : macro_uses(b.text)) {
      if (!u.write) continue;
      if (u.number < 0) {
        std::string names;
        for (const reserved_variable& r : reserved)
          names += fmt::format("{}#{}", names.empty() ? "" : ", ", r.number);
        say(b, u.column,
            fmt::format("channel {}: #[...] is written here, a variable known only when the block runs, and "
                        "machine '{}' reserves {}: write a numbered variable the machine file does not name",
                        b.channel, m.name, names));
        continue;
      }
      for (const reserved_variable& r : reserved)
        if (r.number == u.number)
          say(b, u.column,
              fmt::format("channel {}: #{} is written here, but machine '{}' reserves it ({}): the setup "
                          "owns its value; write a variable the machine file does not name",
                          b.channel, u.number, m.name, r.why));
    }
  }

  void block(const nc_block& b) {
    if (b.channel < 1 || static_cast<std::size_t>(b.channel) > channels.size()) return;
    channel_state& c = channels[static_cast<std::size_t>(b.channel - 1)];
    if (!reserved.empty() && (b.letters() & nc_variable_bit)) variables(b);
    if (c.sweep)
      if (auto f = c.sweep->block(b.words(), c.modes))
        say(b, f->first, fmt::format("channel {}: {}", b.channel, f->second));
    // Once an offset is in force, only the G, M and S words matter, except while a part is held
    // by two spindles (a part-off is a move).
    constexpr std::uint32_t gms = nc_letter('G') | nc_letter('M') | nc_letter('S');
    // A channel with an indexing head also reads its tool calls (T) and head moves (B).
    const std::uint32_t mask = c.head ? gms | nc_letter('T') | nc_letter(c.head) : gms;
    const bool moves_matter = !c.offset || c.holder >= 0 || c.head_unknown;
    if (!moves_matter && !b.may_have(mask)) return;
    const std::vector<nc_word>& words = b.words();
    // What the block's G codes did (analysis/modal_state): a cycle cuts; a dwell, data or
    // coordinate setting, reference return, machine coordinates, macro call or frame does not
    // (a system-A lathe's G92 is its threading cycle, no setting).
    const block_g_codes& g = c.modes.now;
    const bool feed_code = g.cycle || g.once || g.feed_move, no_cut = g.no_move || g.reference || g.machine;
    const bool coordinate_setting = g.coordinate_setting, head_data = g.data;
    bool sets_offset = g.work_offset, tool_call = false, head_move = false;
    int axis_column = 0, x_column = 0;
    const nc_word *xw = nullptr, *uw = nullptr;
    for (const nc_word& w : words) {
      if (w.address == 'T') {
        tool_call = tool_call || c.change_m < 0;
      } else if (w.address == 'M' && c.change_m >= 0 && w.numeric && w.number == c.change_m) {
        tool_call = true;
      } else if (c.head && w.address == c.head) {
        head_move = true;
      } else if ((nc_letter(w.address) & linear_axes) != 0) {
        if (!axis_column) axis_column = w.column;
        if ((w.address == 'X' || (w.address == 'U' && c.u_is_x)) && w.numeric) {
          x_column = w.column;
          (w.address == 'X' ? xw : uw) = &w;
        }
      }
    }
    if (coordinate_setting && axis_column) sets_offset = true;  // G92 X.. Z..: a frame, if not a clamp
    // The machine's own work offset codes too, whatever their address (`E1`: attack 67 H6).
    if (!c.offset && !sets_offset)
      for (const code& o : offset_codes) sets_offset = sets_offset || o.in(words);
    const int motion = c.modes.motion;
    const bool cut = axis_column && !no_cut &&
                     (feed_code || c.modes.in_cycle() || (motion >= 1 && motion <= 3) || motion == 32);
    if (cut && !c.offset && !sets_offset && !c.said_offset) {
      c.said_offset = true;
      say(b, axis_column,
          fmt::format("channel {}: a feed move with no work offset in force: the program would cut in "
                      "whatever offset the last program left; set one (G54-G59, G54.1 P..) before the "
                      "first cut",
                      b.channel));
    }
    if (sets_offset) c.offset = true;
    if (c.head) {
      if (tool_call) c.head_unknown = b.line;
      // The coolant before the index sprays while the head turns at the tool changer (the
      // issue's item 10: public Integrex posts turn it on after the index); in the index's own
      // block too, where a Fanuc gives the M code as the block starts (attack 71 F4).
      if (c.head_unknown && b.may_have(nc_letter('M')))
        for (const code& k : coolant_on)
          if (k.in(words)) {
            if (c.said_coolant) {
              if (c.coolant_more++ < 5) c.coolant_lines.push_back(b.line);
              break;
            }
            c.said_coolant = true;
            c.coolant_said = found.size();
            const head_index_rules& h = m.channels[static_cast<std::size_t>(b.channel - 1)].head_index;
            say(b, 1,
                fmt::format("channel {}: {} turns the coolant on before the {} head is indexed for the tool "
                            "called at line {}: it sprays while the head turns; index it ({} {}..) first",
                            b.channel, k.text, c.head, c.head_unknown, h.move, c.head),
                severity::warning);
            break;
          }
      // (A B word of a data setting or a macro call's argument turns no head: attack 71 F5.)
      if (head_move && !head_data) c.head_unknown = 0;
      if (cut && c.head_unknown && !c.said_head) {
        c.said_head = true;
        const head_index_rules& h = m.channels[static_cast<std::size_t>(b.channel - 1)].head_index;
        say(b, axis_column,
            fmt::format(
                "channel {}: a feed move with the {} head not indexed since the tool call at line {}: "
                "the tool changer may leave it anywhere; index it ({} {}..) before the cut",
                b.channel, c.head, c.head_unknown, h.move, c.head));
      }
    }
    if (c.holder >= 0) {
      // Where X stands while the part is held by both spindles: an X, or an increment (U, X under
      // G91) from where it stood (attack 72 F4: a part-off by U was missed, and `G91 G1 X-10.`
      // from X30. was taken for one).
      if (g.reference || g.machine)
        c.x_now.reset();
      else if (xw && (coordinate_setting || !c.modes.incremental))
        c.x_now = xw->number;
      else if (xw && c.x_now)
        *c.x_now += xw->number;
      if (uw && !g.reference && !g.machine && !coordinate_setting) {
        if (c.x_now) *c.x_now += uw->number;
      } else if (uw && coordinate_setting) {
        c.x_now.reset();
      }
    }
    if (cut && c.holder >= 0 && x_column && c.x_now && *c.x_now <= 0 && !c.cutoff_line)
      c.cutoff_line = b.line;
    // Starts, stops, chucks and synchronisation are M words (the spindles' changes were applied
    // to the reading's spindle_states before this block came here): a block without one changes
    // none of them, and most blocks have none.
    if (!b.may_have(nc_letter('M'))) return;
    spindles_and_chucks(b, c, words);
  }

  void spindles_and_chucks(const nc_block& b, channel_state& c, const std::vector<nc_word>& words) {
    for (const spindle_change& ch : c.spindles.changes()) {
      const auto s = static_cast<std::size_t>(ch.spindle);
      if (!ch.after.started() || ch.before.started()) continue;
      c.start_line[s] = b.line;
      const chuck_codes& k = chucks[s];
      if (c.chucks[s].open && !c.said_start) {
        c.said_start = true;
        say(b, ch.column,
            fmt::format("channel {}: the {} spindle is started with its chuck open ({} at line {}): close "
                        "the chuck first{}",
                        b.channel, m.spindles[s].name, k.open.text, c.chucks[s].line,
                        k.close.empty() ? "" : fmt::format(" ({})", k.close.text)));
      }
    }
    if (!has_chucks && sync_on.empty()) return;
    if (sync_on.in(words)) c.sync = true;
    if (sync_off.in(words)) {
      c.sync = false;
      c.holder = -1;
      c.cutoff_line = 0;
    }
    for (std::size_t s = 0; s < chucks.size(); ++s) {
      const chuck_codes& k = chucks[s];
      if (k.close.in(words)) {
        c.chucks[s].open = false;
        if (c.sync) c.holder = static_cast<int>(s), c.x_now.reset();
      }
      if (!k.open.in(words)) continue;
      const spindle_setting& now = c.spindles.setting(static_cast<int>(s));
      if (now.started() && !c.sync && !c.said_chuck) {
        c.said_chuck = true;
        say(b, 1,
            fmt::format("channel {}: {} opens the {} spindle's chuck while the spindle turns (started at "
                        "line {}) and the spindles are not synchronised: stop it first{}",
                        b.channel, k.open.text, m.spindles[s].name, c.start_line[s],
                        sync_on.empty() ? "" : fmt::format(", or open it under {}", sync_on.text)));
      }
      if (c.cutoff_line && c.holder >= 0 && static_cast<int>(s) != c.holder && !c.said_cutoff) {
        c.said_cutoff = true;
        say(b, 1,
            fmt::format("channel {}: {} opens the {} spindle's chuck after the part-off at line {}: it "
                        "holds the bar, which would be released; after a part-off the {} spindle takes "
                        "the part away and the bar stays clamped ([transfer] release_after_cutoff)",
                        b.channel, k.open.text, m.spindles[s].name, c.cutoff_line,
                        m.spindles[static_cast<std::size_t>(c.holder)].name));
      }
      // In a transfer (the spindles synchronised) the part is in one chuck or both: the one that
      // opens must leave it in another, closed since this channel opened it (the sub's M168
      // dropped: M69 let the part go with the sub's chuck still open from M169).
      if (c.sync && !c.said_released)
        for (std::size_t t = 0; t < chucks.size(); ++t)
          if (t != s && !chucks[t].close.empty() && c.chucks[t].open) {
            c.said_released = true;
            say(b, 1,
                fmt::format("channel {}: {} opens the {} spindle's chuck in the transfer while the {} "
                            "spindle's is open ({} at line {}): the part would be held by neither; close "
                            "it first ({})",
                            b.channel, k.open.text, m.spindles[s].name, m.spindles[t].name,
                            chucks[t].open.text, c.chucks[t].line, chucks[t].close.text));
            break;
          }
      c.chucks[s] = {true, b.line};
      if (static_cast<int>(s) == c.holder || c.cutoff_line == 0) {
        c.holder = -1;
        c.cutoff_line = 0;
      }
    }
  }
};

control_emulator::control_emulator(const machine& m, const spindle_states& spindles,
                                   const modal_states& modes)
    : p_(std::make_unique<impl>(m, spindles, modes)) {}
control_emulator::~control_emulator() = default;

void control_emulator::block(const nc_block& b) { p_->block(b); }

std::vector<diagnostic> control_emulator::finish() {
  for (const channel_state& c : p_->channels)
    if (c.coolant_more > 0) {
      std::string lines;
      for (const int l : c.coolant_lines) lines += fmt::format("{}{}", lines.empty() ? "" : ", ", l);
      p_->found[c.coolant_said].message += fmt::format(
          "; the same at {} more block{} (line{} {}{})", c.coolant_more, c.coolant_more == 1 ? "" : "s",
          c.coolant_more == 1 ? "" : "s", lines, c.coolant_more > 5 ? ", ..." : "");
    }
  return std::move(p_->found);
}

}  // namespace twinpost
