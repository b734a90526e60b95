#include "analysis/spindle_state.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

namespace twinpost {

namespace {

// Two words name the same code: same address, same number (G96 = G96. = G096).
bool same_word(const nc_word& a, const nc_word& b) {
  return a.address == b.address && a.numeric && b.numeric && a.number == b.number;
}

bool has_word(const std::vector<nc_word>& words, const nc_word& w, int& column) {
  for (const nc_word& v : words)
    if (same_word(v, w)) {
      column = v.column;
      return true;
    }
  return false;
}

}  // namespace

int c_axis_code(const std::vector<std::string>& blocks) {
  for (const std::string& b : blocks) {
    double v = -1;
    const std::vector<nc_word> w = split_nc_words(b);
    if (w.size() == 1 && w[0].address == 'M' && nc_number(w[0].value, v)) return static_cast<int>(v);
  }
  return -1;
}

channel_spindles::channel_spindles(const machine& m, int channel) : m_(m), settings_(m.spindles.size()) {
  for (const spindle_def& s : m.spindles) {
    clamp_block c;
    if (!s.clamp.empty()) {
      const std::string_view c_tpl = s.clamp;
      const std::size_t hole = c_tpl.find("{max}");
      const std::string tpl = hole == std::string_view::npos ? std::string(c_tpl)
                                                             : std::string(c_tpl.substr(0, hole)) + "0" +
                                                                   std::string(c_tpl.substr(hole + 5));
      for (nc_word& w : split_nc_words(tpl))
        if (w.address != 'S') {
          w.value = {};  // `tpl` dies here: the words are compared by their numbers (same_word)
          c.fixed.push_back(w);
        }
    }
    clamps_.push_back(std::move(c));
  }
  const channel_def* ch = nullptr;
  for (const channel_def& c : m.channels)
    if (c.number == channel) ch = &c;
  const std::string start = ch ? ch->spindle : std::string("main");
  for (std::size_t i = 0; i < m.spindles.size(); ++i)
    if (m.spindles[i].name == start) current_ = static_cast<int>(i);
  if (current_ < 0 && !m.spindles.empty()) current_ = 0;
  // A key that is no number matches no word (same_word).
  const auto key = [this](const std::vector<nc_word>& code) {  // (its first word: G54.1 of G54.1 P2)
    if (code.empty() || !code.front().numeric) return;
    keys_.emplace_back(code.front().address, code.front().number);
    key_letters_ |= nc_letter(code.front().address);
    keys_not_letters_ = keys_not_letters_ || nc_letter(code.front().address) == 0;
  };
  key(css_code_);
  key(rpm_code_);
  for (const std::vector<nc_word>& code : offset_codes_) key(code);
}

bool channel_spindles::may_command(const std::vector<nc_word>& words) const {
  for (const nc_word& w : words) {
    if (w.address == 'M' || w.address == 'S') return true;
    if (!w.numeric || (!(nc_letter(w.address) & key_letters_) && !keys_not_letters_))
      continue;  // X, Z, F ...: no key
    for (const auto& [address, number] : keys_)
      if (w.address == address && w.number == number) return true;
  }
  return false;
}

bool channel_spindles::is_code(const std::vector<nc_word>& words, const std::vector<nc_word>& code,
                               int& column) const {
  // Every word of the code (`G54.1 P2`, a Fanuc extended work offset: attack 67 H5), at the
  // column of its first.
  if (code.empty() || !has_word(words, code[0], column)) return false;
  int other = 0;
  for (std::size_t i = 1; i < code.size(); ++i)
    if (!has_word(words, code[i], other)) return false;
  return true;
}

bool channel_spindles::needs_gms() const {
  const auto gms = [](const std::vector<nc_word>& code) {
    for (const nc_word& w : code)
      if (w.address != 'G' && w.address != 'M' && w.address != 'S') return false;
    return true;
  };
  for (const std::vector<nc_word>& code : offset_codes_)
    if (!gms(code)) return false;
  return gms(css_code_) && gms(rpm_code_);
}

bool channel_spindles::is_clamp(const std::vector<nc_word>& words, int spindle) const {
  const clamp_block& c = clamps_[static_cast<std::size_t>(spindle)];
  if (c.fixed.empty()) return false;
  int column = 0;
  for (const nc_word& w : c.fixed)
    if (!has_word(words, w, column)) return false;
  return true;
}

void channel_spindles::set(int spindle, const spindle_setting& to, int column) {
  spindle_setting& s = settings_[static_cast<std::size_t>(spindle)];
  if (s == to) return;
  for (spindle_change& c : changes_)
    if (c.spindle == spindle) {
      c.after = to;
      s = to;
      return;
    }
  changes_.push_back({spindle, s, to, column});
  s = to;
}

const std::vector<spindle_change>& channel_spindles::apply(const std::vector<nc_word>& words) {
  changes_.clear();
  commands_.clear();
  // Only M and S words and the one-word codes (is_code) can change or command anything below.
  if (current_ < 0 || !may_command(words)) return changes_;
  // A macro call's words are its arguments (`G65 P9001 E2. M3`: attack 68 M4), no commands.
  for (const nc_word& w : words)
    if (w.address == 'G' && w.numeric && (w.number == 65 || w.number == 66 || w.number == 66.1))
      return changes_;
  // The spindle the block itself selects, by a select code (M902) or a work offset (G55),
  // wherever it stands in the block: a code several spindles share goes to it (attack 67 H4:
  // `G55 G97 S500 M4` reversed the main, and `M203 M902` read otherwise than `M902 M203`).
  int selected = current_;
  for (std::size_t i = 0; i < m_.spindles.size(); ++i) {
    int column = 0;
    if (is_code(words, offset_codes_[i], column)) selected = static_cast<int>(i);
  }
  for (const nc_word& w : words)
    if (w.address == 'M' && w.numeric)
      for (std::size_t i = 0; i < m_.spindles.size(); ++i)
        if (m_.spindles[i].select && *m_.spindles[i].select == w.number) selected = static_cast<int>(i);
  // The spindle M-codes of the block: a code several spindles share goes to the selected one.
  int turned = -1, turned_column = 0;
  spindle_turn turn = spindle_turn::unknown;
  struct stop_word {
    int spindle, column;
    bool release;  // c_off: the C axis let go, the spindle still stopped
  };
  std::vector<stop_word> stops;
  for (const nc_word& w : words) {
    const double v = w.number;
    if (w.address != 'M' || !w.numeric || v != std::floor(v)) continue;
    const int code = static_cast<int>(v);
    int hit = -1;
    spindle_turn what = spindle_turn::unknown;
    bool select = false;
    for (std::size_t i = 0; i < m_.spindles.size(); ++i) {
      const spindle_def& s = m_.spindles[i];
      spindle_turn t = code == s.cw                 ? spindle_turn::cw
                       : code == s.ccw              ? spindle_turn::ccw
                       : code == s.stop             ? spindle_turn::stopped
                       : code == c_codes_[i].first  ? spindle_turn::held
                       : code == c_codes_[i].second ? spindle_turn::stopped
                                                    : spindle_turn::unknown;
      const bool sel = s.select && *s.select == code;
      if (t == spindle_turn::unknown && !sel) continue;
      if (hit < 0 || static_cast<int>(i) == selected) {
        hit = static_cast<int>(i);
        what = t;
        select = sel;
      }
    }
    if (hit < 0) continue;
    if (select) {
      current_ = hit;
    } else if (what == spindle_turn::stopped) {
      stops.push_back({hit, w.column, code == c_codes_[static_cast<std::size_t>(hit)].second});
    } else {
      turned = hit;
      turn = what;
      turned_column = w.column;
    }
  }
  // A workpiece spindle's work offset (G54 main, G55 sub) says which part the channel works
  // on from now: its S words and feeds per revolution go to that spindle (a HEAD/BOTH copy
  // on the master's spindle selects it so, with no spindle code of its own).
  for (std::size_t i = 0; i < m_.spindles.size(); ++i) {
    int offset_column = 0;
    if (is_code(words, offset_codes_[i], offset_column) && turned < 0) current_ = static_cast<int>(i);
  }
  // The mode codes (modal per channel).
  int mode_column = 0;
  const speed_mode before_mode = mode_;
  if (is_code(words, css_code_, mode_column))
    mode_ = speed_mode::css;
  else if (is_code(words, rpm_code_, mode_column))
    mode_ = speed_mode::rpm;
  const nc_word* s_word = nullptr;
  for (const nc_word& w : words)
    if (w.address == 'S' && !w.expression) s_word = &w;
  const bool has_s = s_word && s_word->numeric;
  const double s_value = has_s ? s_word->number : 0;
  const int target = turned >= 0 ? turned : current_;
  // A clamp block (G50 S.., G92 S.. R1): S is the highest rpm, not a speed.
  if (has_s) {
    int clamp_of = -1;
    for (std::size_t i = 0; i < m_.spindles.size(); ++i)
      if (is_clamp(words, static_cast<int>(i)) && (clamp_of < 0 || static_cast<int>(i) == target))
        clamp_of = static_cast<int>(i);
    if (clamp_of >= 0) {
      spindle_setting to = setting(clamp_of);
      to.clamp = s_value;
      set(clamp_of, to, s_word->column);
      spindle_command c{clamp_of, to};
      c.clamp = true;
      c.column = s_word->column;
      commands_.push_back(c);
      return changes_;
    }
  }
  if (turned >= 0) current_ = turned;
  spindle_setting to = setting(target);
  int column = 0;
  spindle_command command{target, {}};
  if (has_s) {
    to.speed = s_value;
    to.mode = mode_;
    column = s_word->column;
    command.speed = true;
  } else if (mode_ != before_mode && to.mode != speed_mode::unknown) {
    to.mode = mode_;
    to.speed = 0;  // G97 after G96 without S keeps the rpm of the moment: not known here
    column = mode_column;
    command.mode = true;
  }
  if (turned >= 0) {
    to.turn = turn;
    if (to.mode == speed_mode::unknown) to.mode = mode_;
    column = column ? std::min(column, turned_column) : turned_column;
    command.turn = true;
  }
  if (column) {
    set(target, to, column);
    if (has_s && mode_column) column = std::min(column, mode_column);
    command.setting = to;
    command.column = column;
    commands_.push_back(command);
  }
  for (const auto& [spindle, col, release] : stops) {
    spindle_setting off = setting(spindle);
    off.turn = spindle_turn::stopped;
    set(spindle, off, col);
    spindle_command c{spindle, off};
    c.turn = true;
    c.release = release;
    c.column = col;
    commands_.push_back(c);
  }
  return changes_;
}

double channel_spindles::rpm(double diameter, bool inch) const {
  if (current_ < 0) return 0;
  const spindle_setting& s = setting(current_);
  if (!s.started() || s.speed <= 0) return 0;
  const double cap = this->cap();
  if (s.mode != speed_mode::css) return cap > 0 ? std::min(s.speed, cap) : s.speed;
  const double d = std::abs(diameter);
  const double per_rev = std::numbers::pi * d / (inch ? 12.0 : 1000.0);  // m (ft) per revolution
  if (per_rev <= 0) return cap;
  const double r = s.speed / per_rev;
  return cap > 0 ? std::min(r, cap) : r;
}

spindle_states::spindle_states(const machine& m) {
  channels_.reserve(m.channels.size());
  for (std::size_t i = 0; i < m.channels.size(); ++i) {
    channel_spindles c(m, static_cast<int>(i) + 1);
    const bool gms_only = c.needs_gms();
    channels_.push_back({std::move(c), gms_only});
  }
}

}  // namespace twinpost
