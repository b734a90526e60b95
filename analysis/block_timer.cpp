#include "analysis/block_timer.hpp"

#include <tuple>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

namespace twinpost {

namespace {

constexpr double two_pi = 2 * std::numbers::pi;

// The mean over u in [0, 1] of max(d0 + (d1 - d0) u, c): a feed per revolution under CSS,
// where the minutes per unit of path are max(d(u), c) / (k f), the diameter d linear in u
// and c the diameter below which the clamp holds the rpm (0: none). A division only where the
// move crosses c (the divisions of the whole integral, one after another, were most of the
// timer's time).
double mean_of_max(double d0, double d1, double c) {
  if (d0 >= c && d1 >= c) return (d0 + d1) / 2;
  if (d0 <= c && d1 <= c) return c;
  const double u = (c - d0) / (d1 - d0);  // where it crosses c, inside (0, 1)
  return d0 < c ? c * u + (1 - u) * (c + d1) / 2 : u * (d0 + c) / 2 + (1 - u) * c;
}

// The code of a G word as compared (g_code): "01", "1." and "1.0" are G1, "84.2" is G84.2;
// -1 for a negative code or one of more than one decimal (no control has one: it is named as
// written, not timed).
int g_code_of(const nc_word& w) {
  if (std::signbit(w.number)) return -1;  // G-1, G-0: no code (named as written)
  const double tenths = w.number * 10;
  const double r = std::round(tenths);
  if (std::abs(tenths - r) > 1e-6 || std::abs(r) > 1e6) return -1;
  return static_cast<int>(r);
}

// G codes that set a mode or an offset and take no time of their own.
bool plain_g_code(int g) {
  static constexpr int codes[] = {
      g_code("10.1"), g_code("12.1"), g_code("13.1"), g_code("15"),  g_code("16"),   g_code("17"),
      g_code("18"),   g_code("19"),   g_code("20"),   g_code("21"),  g_code("40"),   g_code("41"),
      g_code("42"),   g_code("43"),   g_code("44"),   g_code("49"),  g_code("54"),   g_code("55"),
      g_code("56"),   g_code("57"),   g_code("58"),   g_code("59"),  g_code("54.1"), g_code("61"),
      g_code("64"),   g_code("67"),   g_code("68"),   g_code("69"),  g_code("69.1"), g_code("80"),
      g_code("90"),   g_code("91"),   g_code("94"),   g_code("95"),  g_code("96"),   g_code("97"),
      g_code("98"),   g_code("99"),   g_code("112"),  g_code("113"), g_code("0"),    g_code("1"),
      g_code("2"),    g_code("3"),    g_code("4"),    g_code("32"),  g_code("33")};
  return std::find(std::begin(codes), std::end(codes), g) != std::end(codes);
}

bool modal_drill_cycle(int g, bool lathe_a) {
  if (g >= g_code("81") && g < g_code("90")) return true;  // G81-G89 and G84.2/G84.3
  return !lathe_a && (g == g_code("73") || g == g_code("74") || g == g_code("76"));
}

bool one_shot_cycle(int g, bool lathe_a) {
  if (lathe_a && ((g >= g_code("70") && g <= g_code("76") && g % 10 == 0) || g == g_code("78"))) return true;
  return g == g_code("276") || g == g_code("290") || g == g_code("292") || g == g_code("294") ||
         g == g_code("270") || g == g_code("271") || g == g_code("272");
}

}  // namespace

namespace {

// Channel `number` of `m`, else its first (as the timer has always taken it).
const channel_def& channel_or_first(const machine& m, int number) {
  for (const channel_def& c : m.channels)
    if (c.number == number) return c;
  return m.channels.front();
}

}  // namespace

block_timer::block_timer(const machine& m, int channel)
    : m_(m), own_spindles_(m, channel), own_modes_(m), units_(units_of(m)),
      channel_(channel_or_first(m, channel).number), codes_(m, channel_or_first(m, channel)),
      spindles_need_gms_(own_spindles_.needs_gms()) {
  for (const channel_def& c : m.channels)
    if (c.number == channel) ch_ = &c;
  if (!ch_) ch_ = &m.channels.front();
  bool lathe = false;
  for (const axis_def& a : ch_->axes) {
    axis_pos p;
    p.address = a.address;
    p.diameter = a.diameter;
    p.rotary = a.address == 'A' || a.address == 'B' || a.address == 'C';
    p.rate = ch_->timing.rapid_of(a.address).value_or(0);
    axes_.push_back(p);
    if (a.address == 'X' && a.diameter) lathe = true;
  }
  axis_at_.fill(-1);
  for (std::size_t i = 0; i < axes_.size(); ++i)
    if (static_cast<unsigned char>(axes_[i].address) < axis_at_.size() && axis_at_[axes_[i].address] < 0)
      axis_at_[static_cast<unsigned char>(axes_[i].address)] = static_cast<std::int8_t>(i);
  lathe_x_ = axis('X') && axis('X')->diameter;
  has_u_ = axis('U') != nullptr, has_w_ = axis('W') != nullptr, has_v_ = axis('V') != nullptr;
  // Each word's axis once for all blocks: a Fanuc lathe's U, W, V (where no axis of their own)
  // are X, Z, Y incremental.
  word_axis_ = axis_at_;
  for (const auto& [alias, to, own] : {std::tuple{'U', 'X', has_u_}, {'W', 'Z', has_w_}, {'V', 'Y', has_v_}})
    if (lathe_x_ && !own) {
      word_axis_[static_cast<unsigned char>(alias)] = axis_at_[static_cast<unsigned char>(to)];
      word_incremental_[static_cast<unsigned char>(alias)] = true;
    }
  for (std::size_t i = 0; i < axes_.size(); ++i)
    if (axes_[i].address == 'X') x_index_ = static_cast<int>(i);  // the last X, as move_time took it
  // A lathe in G-code system A: G90/G92/G94 are turning, thread and facing cycles. The system
  // is read as every analysis reads it (analysis/nc_codes: a lathe whose header gives no G90
  // or G91); before, the timer alone took it from the control's name.
  lathe_a_ = lathe && gcode_system_of(m, *ch_) == gcode_system::a;
  for (const auto& [blocks, into] :
       {std::pair{&m.milling.radius_input, &radius_on_}, {&m.milling.diameter_input, &radius_off_}})
    for (const std::string& b : *blocks) into->push_back(split_nc_words(b));
  // Polar interpolation starts at the last block of polar_on (G12.1 after the plane) and ends
  // at the first of polar_off (G13.1 before it): the plane blocks alone are planes.
  if (!m.milling.polar_on.empty()) {
    polar_on_.push_back(split_nc_words(m.milling.polar_on.back()));
    polar_off_.push_back(split_nc_words(m.milling.polar_off.front()));
  }
  for (const std::string& b : m.milling.cylindrical_on)
    if (const std::size_t at = b.find('{'); at != std::string::npos && at > 0) {
      cylinder_address_ = b[at - 1];
      cylinder_per_r_ = b.compare(at, 10, "{diameter}") == 0 ? 2 : 1;
      cylinder_code_ = split_nc_words(std::string_view(b).substr(0, at - 1));  // in the machine's text
    }
  has_modes_ = cylinder_address_ || !radius_on_.empty() || !polar_on_.empty();
  target_.resize(axes_.size());
  // The feed modes (inverse time, G93, of a channel whose chain writes it: F is 1/min, the block
  // takes 1/F) are analysis/nc_codes' reading, shared with the spindle rules and the comparison.
  for (const int g : {g_code("0"), g_code("1"), g_code("2"), g_code("3")})
    plain_motion_codes_ = plain_motion_codes_ && codes_.feed_mode(g / 10.0) == feed_kind::none;
  // The tool call's address and how a number splits into tool and offset (T0303: tool 3).
  const std::string& call = ch_->tool_call;
  if (const std::size_t at = call.find("{tool"); at != std::string::npos && at > 0) {
    tool_address_ = call[at - 1];
    const std::size_t end = call.find('}', at);
    const std::size_t off = call.find("{offset", at);
    if (end != std::string::npos && off == end + 1) {
      const std::size_t close = call.find('}', off);
      const std::size_t colon = call.find(':', off);
      int width = 0;
      if (colon != std::string::npos && colon < close)
        std::from_chars(call.data() + colon + 1, call.data() + close, width);
      for (int i = 0; i < width; ++i) tool_divisor_ *= 10;
    }
  }
  // The dwell word: "G4 U{seconds}" (seconds) or "G4 P{ms}" (milliseconds).
  const std::string& dwell = m.codes.dwell;
  for (auto [hole, unit] : {std::pair<std::string_view, double>{"{seconds", 1.0}, {"{ms", 0.001}})
    if (const std::size_t at = dwell.find(hole); at != std::string::npos && at > 0) {
      dwell_address_ = dwell[at - 1];
      dwell_unit_ = unit;
    }
}

block_timing block_timer::time(std::string_view text) {
  const std::uint32_t letters = split_nc_words(text, words_);
  return time(words_, letters);
}

block_timing block_timer::time(const std::vector<nc_word>& words, std::uint32_t letters,
                               const channel_spindles* spindles, const channel_modes* modes) {
  // Each word's number was read once, when the block was split.
  auto num = [](const nc_word& w, double& v) {
    v = w.number;
    return w.numeric;
  };
  constexpr std::uint32_t gms = nc_letter('G') | nc_letter('M') | nc_letter('S');
  if (spindles) {
    spindles_ = spindles;
  } else {
    spindles_ = &own_spindles_;
    if (!spindles_need_gms_ || (letters & gms)) own_spindles_.apply(words);
  }
  // The modal state, this block applied (analysis/modal_state): one reading of the unit
  // (G20/G21, system C's G70/G71), G90/G91, the plane and the feed mode for every rule.
  // Only a G word changes them: most blocks read nothing here.
  if (!modes) {
    own_modes_.block(channel_, words, letters);
    modes = &own_modes_.channel(channel_);
  }
  if (modes->now.any || !modes_read_) {
    if (modes_read_ && modes->inch != inch_) {
      // The control keeps where the axes are: their values are said again in the new unit
      // (review 41 H5; the interference rule and the comparison did so, the timer kept the
      // numbers).
      const double to_new = inch_ ? 25.4 : 1 / 25.4;
      for (axis_pos& a : axes_)
        if (a.value && !a.rotary) *a.value *= to_new;
    }
    modes_read_ = true;
    inch_ = modes->inch;
    incremental_ = modes->incremental;
    if (modes->plane) plane_ = modes->plane;
    per_rev_ = modes->feed == feed_kind::per_rev;
    inverse_time_ = modes->feed == feed_kind::inverse_time;
    cyc_.return_r = modes->return_to_r;
    // The modal motion too (G0-G3, 32 for threading); its text made once per change.
    if (modes->motion >= 0 && modes->motion != motion_num_) set_motion(modes->motion * 10);
  }
  block_timing t;
  if (has_modes_ && milling_mode(words)) return t;  // a mode block: no time, no move (G10.9 X0 moves nothing)
  auto untimed = [&t](std::string why) {
    if (t.untimed.empty()) t.untimed = std::move(why);
  };

  bool dwell = false, reference = false, setting = false;
  int one_shot = -1;  // a one-shot cycle's code; -1: none
  // Most blocks of a program are moves without a G word, a tool, an M code or a feed: the
  // block's letters say so without a loop over its words.
  const bool has_g = (letters & nc_letter('G')) != 0;
  constexpr std::uint32_t tmf = nc_letter('T') | nc_letter('M') | nc_letter('F');
  for (const nc_word& w : words) {
    if (!has_g) break;
    if (w.address != 'G') continue;
    // A G code is a number (G84.2 is 842, see g_code): no text is built or compared per block.
    const int g = w.expression || !w.numeric ? -1 : g_code_of(w);
    if (g < 0) {
      untimed(fmt::format("G{}", w.value));
      continue;
    }
    // Most G words of a program are G0-G3: the motion (the modal state's, above) ends a cycle.
    if (plain_motion_codes_ && g <= g_code("3") && g % 10 == 0) {
      end_cycle();
      continue;
    }
    // (The unit, the plane, the feed mode, G90/G91, the drilling cycles' return level: the
    // modal state's, above.)
    // Box cycles: modal until another motion code, each later block with axis words another
    // pass (the Integrex's G292 too: attack 72 F6, its passes were timed as rapids).
    if ((lathe_a_ && (g == g_code("90") || g == g_code("92") || g == g_code("94"))) || g == g_code("292")) {
      if (cycle_ != g) end_cycle();
      cycle_ = g;
      continue;
    }
    // Another system's single cycle (B's G77-G79, C's G20 G21 G24): not timed, nor its passes
    // after it (below; review 41 H4: system C's G20 was timed as a rapid).
    if (!lathe_a_ && modes->turning_cycle && !one_shot_cycle(g, lathe_a_) &&
        codes_.role(g / 10.0) == axis_words::turning_cycle) {
      turning_text_ = g_code_text(g, "G");
      continue;
    }
    if (g == g_code("90") || g == g_code("91"))
      continue;
    else if (g <= g_code("3") && g % 10 == 0)
      end_cycle();
    else if (g == g_code("32") || g == g_code("33"))
      end_cycle();
    else if (g == g_code("80"))
      end_cycle();
    else if (g == g_code("4"))
      dwell = true;
    else if (g == g_code("28") || g == g_code("30") || g == g_code("53"))
      reference = true, untimed(g_code_text(g, "G"));
    else if (g == g_code("50") || g == g_code("92"))
      setting = true;  // speed clamp or coordinate setting
    else if (modal_drill_cycle(g, lathe_a_)) {
      if (cycle_ < 0) cyc_.initial.reset();  // a new cycle: its initial level is where it begins
      cycle_ = g;
    } else if (one_shot_cycle(g, lathe_a_)) {
      // Timed in its own block; a single cycle's passes after it (the Integrex's G292, modal)
      // are not (attack 72 F6: they were timed as rapids).
      one_shot = g;
      if (!lathe_a_ && modes->turning_cycle && codes_.role(g / 10.0) == axis_words::turning_cycle)
        turning_text_ = g_code_text(g, "G");
      else
        turning_text_.clear();
    } else if (!plain_g_code(g) && codes_.feed_mode(g / 10.0) == feed_kind::none &&
               !units_.selected_by(g / 10.0))
      untimed(
          g_code_text(g, "G"));  // (a feed mode of the machine's, G93, system C's G70/G71: the modal state's)
  }

  // Tool calls, M codes, the feed.
  for (const nc_word& w : words) {
    if (!(letters & tmf)) break;
    double v = 0;
    if (!num(w, v)) continue;
    if (w.address == tool_address_ && w.address == 'T') {
      const long n = static_cast<long>(v) / tool_divisor_;
      if (n != tool_number_ && n > 0) {
        tool_number_ = static_cast<int>(n);
        tool_ = fmt::format("T{:02}", n);
        t.tool_call = true;
        t.seconds += ch_->timing.tool_change;
      }
    } else if (w.address == 'M') {
      const int code = static_cast<int>(v);
      if (m_.waits.syntax == wait_syntax::m_code && m_.waits.address == 'M' && m_.waits.is_wait_code(code))
        continue;  // the wait's own time is added by the caller
      if (code == 98) untimed("M98");
      if (code == 30 || code == 2 || code == 99) continue;
      t.seconds += ch_->timing.m_code;
    } else if (w.address == 'F') {
      feed_ = v;
    }
  }

  if (dwell) {
    bool found = false;
    for (const nc_word& w : words) {
      double v = 0;
      if (w.address == dwell_address_ && num(w, v)) {
        t.seconds += v * dwell_unit_;
        found = true;
      }
    }
    if (!found) untimed("G4");
    return t;  // the dwell's U or X word is no move
  }

  // Where the block sends each axis (program units; X as programmed).
  std::vector<std::optional<double>>& target = target_;  // one per axis (sized once)
  bool moves = false;
  const std::size_t n_axes = axes_.size();  // (asked once: size() divides by an axis's size)
  for (std::size_t i = 0; i < n_axes; ++i) target[i] = axes_[i].value;
  const bool lathe = lathe_x_;
  for (const nc_word& w : words) {
    const auto u = static_cast<unsigned char>(w.address);
    if (u >= word_axis_.size() || word_axis_[u] < 0) continue;
    axis_pos* p = &axes_[static_cast<std::size_t>(word_axis_[u])];
    const bool inc = incremental_ || word_incremental_[u];
    if (w.address == 'B' && reference) continue;
    double v = 0;
    if (!num(w, v)) {
      untimed(fmt::format("{}{}", w.address, w.value));
      continue;
    }
    const std::size_t i = static_cast<std::size_t>(p - axes_.data());
    moves = true;
    if (inc)
      target[i] = p->value ? std::optional<double>(*p->value + v) : std::nullopt;
    else
      target[i] = v;
    if (inc && !p->value) target[i].reset();
    if (inc && !p->value && !setting)
      untimed(fmt::format("{} from an unknown position", motion_num_ < 0 ? "move" : motion_code_));
  }
  if (!turning_text_.empty() && !modes->turning_cycle) turning_text_.clear();
  if (moves && one_shot < 0 && !turning_text_.empty()) {
    // (Not timed; a single cycle returns to where it began: the axes stay.)
    untimed(turning_text_);
    t.seconds = 0;
    return t;
  }
  // `letters` are the block's exact addresses (it is split).
  const bool arc_words = (letters & (nc_letter('I') | nc_letter('J') | nc_letter('K') | nc_letter('R'))) != 0;

  if (setting) {
    for (std::size_t i = 0; i < n_axes; ++i) axes_[i].value = target[i];
    return t;
  }
  if (reference) {
    // G28/G30/G53: to a machine position this program does not know.
    for (const nc_word& w : words)
      if (axis_pos* p = axis(w.address == 'U' && lathe ? 'X' : w.address == 'W' && lathe ? 'Z' : w.address))
        p->value.reset();
    return t;
  }
  if (one_shot >= 0 || (cycle_ >= 0 && moves)) {
    // A cycle the control expands itself: timed from its words where this knows its moves
    // (block_cycles.cpp), else not timed. A drilling cycle leaves the tool over the hole at
    // its initial level; a lathe cycle returns to its start point.
    const int g = one_shot >= 0 ? one_shot : cycle_;
    if (t.untimed.empty() && time_cycle(g, words, target, t)) {
      if (!t.untimed.empty()) {
        t.seconds = 0;
        t.motion = 0;
        return t;
      }
      t.seconds += t.motion;
      return t;
    }
    untimed(g_code_text(g, "G"));
    if (one_shot < 0 && modal_drill_cycle(cycle_, lathe_a_))
      for (std::size_t i = 0; i < n_axes; ++i)
        if (axes_[i].address != 'Z') axes_[i].value = target[i];
    return t;
  }
  if (!moves && !(arc_words && (motion_num_ == 2 || motion_num_ == 3))) return t;
  if (!t.untimed.empty()) {
    for (std::size_t i = 0; i < n_axes; ++i) axes_[i].value = target[i];
    t.seconds = 0;
    return t;
  }
  if (motion_num_ < 0) {
    untimed("move without G0/G1");
    return t;
  }
  const double s = move_time(target, motion_num_ == 0, motion_code_, words, t);
  for (std::size_t i = 0; i < n_axes; ++i) axes_[i].value = target[i];
  if (!t.untimed.empty()) {
    t.seconds = 0;
    return t;
  }
  t.motion = s;
  t.rapid = motion_num_ == 0;
  t.seconds += s;
  return t;
}

bool block_timer::milling_mode(const std::vector<nc_word>& words) {
  if (cylinder_address_ && words.size() == cylinder_code_.size() + 1 &&
      words.back().address == cylinder_address_ &&
      std::equal(
          cylinder_code_.begin(), cylinder_code_.end(), words.begin(),
          [](const nc_word& a, const nc_word& b) { return a.address == b.address && a.value == b.value; })) {
    cylinder_r_ = std::abs(std::strtod(std::string(words.back().value).c_str(), nullptr)) / cylinder_per_r_;
    return true;
  }
  if (radius_on_.empty() && polar_on_.empty()) return false;
  auto same = [&](const std::vector<nc_word>& b) {
    if (b.size() != words.size()) return false;
    for (std::size_t i = 0; i < b.size(); ++i)
      if (b[i].address != words[i].address || b[i].value != words[i].value) return false;
    return true;
  };
  for (const auto& [list, flag, value] : {std::tuple{&radius_on_, &radius_x_, true},
                                          {&radius_off_, &radius_x_, false},
                                          {&polar_on_, &polar_, true},
                                          {&polar_off_, &polar_, false}})
    for (const std::vector<nc_word>& b : *list)
      if (same(b)) {
        if (flag == &radius_x_ && radius_x_ != value)  // X's value as now programmed
          for (axis_pos& p : axes_)
            if (p.address == 'X' && p.diameter && p.value) *p.value = value ? *p.value / 2 : *p.value * 2;
        if (flag == &polar_)  // C changes its unit, and X, C in the plane are not the slides' places
          for (axis_pos& p : axes_)
            if (p.address == 'C' || (p.address == 'X' && !value)) p.value.reset();
        *flag = value;
        return true;
      }
  return false;
}

double block_timer::move_time(const std::vector<std::optional<double>>& target, bool rapid,
                              const std::string& code, const std::vector<nc_word>& words, block_timing& t,
                              bool sync) {
  // Every axis that moves must start from a known place.
  double linear2 = 0, rotary = 0, slowest = 0;
  const std::size_t n_axes = axes_.size();
  for (std::size_t i = 0; i < n_axes; ++i) {
    const axis_pos& p = axes_[i];
    if (!target[i] || (p.value && *p.value == *target[i])) continue;
    if (!p.value) {
      t.untimed = code + " from an unknown position";
      return 0;
    }
    double d = std::abs(*target[i] - *p.value);
    if (p.diameter && !radius_x_) d /= 2;  // the slide moves the radius
    if (p.rotary && cylinder_r_ > 0 && p.address == 'C')
      linear2 += std::pow(d * std::numbers::pi / 180 * cylinder_r_, 2);  // on the cylinder
    else if (p.rotary && !(polar_ && p.address == 'C'))
      rotary = std::max(rotary, d);
    else
      linear2 += d * d;
    // Rapid: each axis at its own rate; the block lasts as long as the slowest axis.
    const double travel = p.rotary ? d : to_mm(d);
    if (rapid && p.rate > 0) slowest = std::max(slowest, travel / p.rate * 60);  // a feed needs none
  }
  if (rapid) return slowest;
  const axis_pos* x = x_index_ >= 0 ? &axes_[static_cast<std::size_t>(x_index_)] : nullptr;
  const std::size_t xi = x_index_ >= 0 ? static_cast<std::size_t>(x_index_) : 0;
  auto dia = [&](std::optional<double> v) {
    return !v ? -1.0 : x && x->diameter ? std::abs(*v) : 2 * std::abs(*v);
  };
  const double x0 = x ? dia(x->value) : -1, x1 = x ? dia(target[xi]) : -1;
  double length = std::sqrt(linear2);
  const std::string_view c = code;  // compared by length first: no strlen per block
  if (c == "G2" || c == "G3") {
    length = arc_length(target, words, c == "G2");
    if (length < 0) {
      t.untimed = code + " without I/J/K or R";
      return 0;
    }
  }
  if (length == 0) length = rotary;  // a rotary move alone: degrees at F degrees per minute
  if (length == 0) return 0;
  return feed_time(length, x0, x1, t, code, sync);
}

double block_timer::feed_time(double length, double x0, double x1, block_timing& t, const std::string& code,
                              bool sync) {
  if (!(feed_ > 0)) {
    t.untimed = code + " without F";
    return 0;
  }
  const bool thread = sync || std::string_view(code) == "G32";
  if (inverse_time_ && !thread) return 60 / feed_;  // F moves a block in 1/F minutes, whatever its length
  if (!per_rev_ && !thread) return length / feed_ * 60;
  // Per revolution: F units per turn at the spindle's rpm; under CSS the rpm follows the
  // diameter, so the move is summed in steps at each step's middle diameter.
  const bool css = spindles_->mode() == speed_mode::css;
  if (css && (x0 < 0 || x1 < 0)) {
    t.untimed = code + " under CSS at an unknown diameter";
    return 0;
  }
  double k = 0, limit = 0;
  if (css && x0 != x1 && spindles_->css_law(inch_, k, limit)) {
    // The rpm follows the diameter along the move: integrated exactly (rpm = min(limit, k/d)).
    // The law's divisions once per law and feed (most moves share both).
    if (k != css_.k || limit != css_.limit || feed_ != css_.feed) {
      css_.k = k, css_.limit = limit, css_.feed = feed_;
      css_.clamped_below = limit > 0 ? k / limit : 0;
      css_.seconds_per = 60 / (feed_ * k);
    }
    return length * mean_of_max(x0, x1, css_.clamped_below) * css_.seconds_per;
  }
  // rpm mode, or CSS along a constant diameter: one speed for the whole move.
  const double rpm = spindles_->rpm(std::max((x0 + x1) / 2, 0.0), inch_);
  if (!(rpm > 0)) {
    // A spindle this channel never commanded turns at another channel's speed, which this
    // channel's blocks do not tell (docs/timeline.md).
    const bool others =
        spindles_->current() >= 0 && spindles_->setting(spindles_->current()).turn == spindle_turn::unknown;
    t.untimed = code + (thread ? "" : " per revolution") +
                (others ? " on a spindle only another channel commands" : " on a stopped spindle");
    return 0;
  }
  return length / (feed_ * rpm) * 60;
}

double block_timer::arc_length(const std::vector<std::optional<double>>& target,
                               const std::vector<nc_word>& words, bool cw) const {
  // The plane's two axes (first, second) with CCW = G3 about the third: G17 XY, G18 ZX, G19 YZ.
  const char a1 = plane_ == 17 ? 'X' : plane_ == 18 ? 'Z' : 'Y';
  const char a2 = plane_ == 17 ? 'Y' : plane_ == 18 ? 'X' : 'Z';
  const char a3 = plane_ == 17 ? 'Z' : plane_ == 18 ? 'Y' : 'X';
  auto centre_word = [](char a) { return a == 'X' ? 'I' : a == 'Y' ? 'J' : 'K'; };
  auto get = [&](char a, bool end, double& out) {
    for (std::size_t i = 0; i < axes_.size(); ++i)
      if (axes_[i].address == a) {
        const std::optional<double> v = end ? target[i] : axes_[i].value;
        if (!v) return false;
        out = axes_[i].diameter ? *v / 2 : *v;
        return true;
      }
    out = 0;  // an axis the channel lacks stays at 0
    return true;
  };
  double s1, s2, e1, e2, h0 = 0, h1 = 0;
  if (!get(a1, false, s1) || !get(a2, false, s2) || !get(a1, true, e1) || !get(a2, true, e2)) return -1;
  get(a3, false, h0);
  get(a3, true, h1);
  std::optional<double> r, c1, c2;
  for (const nc_word& w : words) {
    if (!w.numeric) continue;
    const double v = w.number;
    if (w.address == 'R') r = v;
    if (w.address == centre_word(a1)) c1 = v;
    if (w.address == centre_word(a2)) c2 = v;
  }
  double radius = 0, sweep = 0;
  const double chord = std::hypot(e1 - s1, e2 - s2);
  if (c1 || c2) {
    const double k1 = s1 + c1.value_or(0), k2 = s2 + c2.value_or(0);
    radius = std::hypot(s1 - k1, s2 - k2);
    const double t0 = std::atan2(s2 - k2, s1 - k1), t1 = std::atan2(e2 - k2, e1 - k1);
    sweep = cw ? t0 - t1 : t1 - t0;
    while (sweep <= 1e-12) sweep += two_pi;
    while (sweep > two_pi) sweep -= two_pi;
    if (chord < 1e-9) sweep = two_pi;  // a full circle
  } else if (r) {
    radius = std::abs(*r);
    const double half = std::min(1.0, chord / (2 * radius));
    sweep = 2 * std::asin(half);
    if (*r < 0) sweep = two_pi - sweep;
  } else {
    return -1;
  }
  return std::hypot(radius * sweep, h1 - h0);
}

}  // namespace twinpost
