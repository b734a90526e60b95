// The time of a canned cycle block: the moves the control makes of its words, each timed like
// a programmed move (rapids per axis at [timing] rates, feeds at F, per revolution at the
// spindle's rpm, threads at the lead). docs/timeline.md, "Canned cycles", has the model and
// where each rule comes from; what it does not know stays untimed (block_timer.cpp).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "analysis/block_timer.hpp"

namespace twinpost {

namespace {

// How far above the last depth a full-retract peck (G83) comes back in at rapid, and how far a
// chip-breaking peck (G73) backs off, in mm: Fanuc parameters 5115 and 5114, set by the machine
// builder. 0.5 mm is what twinpost's own expanded pecks use (machining/channel_cycles.cpp); the
// time it stands for is a few milliseconds a peck. UNVERIFIED for any given machine.
constexpr double peck_clearance_mm = 0.5;

// More pecks or passes than any real cycle: a word that would make the loop run away.
constexpr int max_steps = 10000;

const nc_word* find(const std::vector<nc_word>& words, char address) {
  const nc_word* hit = nullptr;
  for (const nc_word& w : words)
    if (w.address == address && !w.expression) hit = &w;
  return hit;
}

bool value(const nc_word* w, double& v) {
  if (!w || !w->numeric) return false;
  v = w->number;  // decoded when the block was split
  return true;
}

// Depths along one axis, from 0 to `depth` (> 0) in steps of `step`, each step starting
// `back` above where the last one ended (a retract and a return, or a back-off): the feed and
// rapid lengths are the caller's legs.
int steps_of(double depth, double step) {
  if (!(step > 0) || step >= depth) return 1;
  const double n = std::ceil(depth / step - 1e-9);
  return n > max_steps ? -1 : static_cast<int>(n);
}

}  // namespace

double block_timer::increments(const nc_word& w, double v) const {
  if (w.value.find('.') != std::string_view::npos) return v;
  return v * (inch_ ? 0.0001 : 0.001);
}

bool block_timer::leg(leg_kind k, char a, double va, block_timing& t, const std::string& code, char b,
                      double vb) {
  leg_target_.resize(axes_.size());
  for (std::size_t i = 0; i < axes_.size(); ++i) {
    leg_target_[i] = axes_[i].value;
    if (axes_[i].address == a) leg_target_[i] = va;
    if (b && axes_[i].address == b) leg_target_[i] = vb;
  }
  return leg_to_target(k, t, code);
}

bool block_timer::leg_to_target(leg_kind k, block_timing& t, const std::string& code) {
  const double s = move_time(leg_target_, k == leg_kind::rapid, code, words_, t, k == leg_kind::sync);
  if (!t.untimed.empty()) return false;
  for (std::size_t i = 0; i < axes_.size(); ++i) axes_[i].value = leg_target_[i];
  t.motion += s;
  return true;
}

bool block_timer::time_cycle(int g, const std::vector<nc_word>& words,
                             const std::vector<std::optional<double>>& target, block_timing& t) {
  if ((lathe_a_ && (g == g_code("76") || g == g_code("92"))) || g == g_code("292"))
    return thread_cycle(g, words, t);
  if (lathe_a_ && (g == g_code("74") || g == g_code("75"))) return groove_cycle(g, words, t);
  return drill_cycle(g, words, target, t);  // false for any other code
}

// Drilling, pecking, tapping and boring along the hole's axis: Z (the plane's third axis on a
// mill; the face cycles G83-G85 on a Fanuc lathe), or X for the lathe's side cycles G87-G89.
bool block_timer::drill_cycle(int g, const std::vector<nc_word>& words,
                              const std::vector<std::optional<double>>& target, block_timing& t) {
  enum class kind { drill, peck, chip_break, tap, bore_feed_out, bore_rapid_out } what = kind::drill;
  const nc_word* q_word = find(words, 'Q');
  double q = 0;
  const bool pecks = value(q_word, q) && q > 0;
  if (lathe_a_) {
    if (g == g_code("83") || g == g_code("87"))
      what = pecks ? kind::peck : kind::drill;
    else if (g == g_code("84") || g == g_code("88"))
      what = kind::tap;
    else if (g == g_code("85") || g == g_code("89"))
      what = kind::bore_feed_out;
    else
      return false;
  } else if (g == g_code("81") || g == g_code("82")) {
    what = kind::drill;
  } else if (g == g_code("83")) {
    what = pecks ? kind::peck : kind::drill;
  } else if (g == g_code("73")) {
    what = pecks ? kind::chip_break : kind::drill;
  } else if (g == g_code("84") || g == g_code("74") || g == g_code("84.2") || g == g_code("84.3")) {
    what = kind::tap;
  } else if (g == g_code("85") || g == g_code("89")) {
    what = kind::bore_feed_out;
  } else if (g == g_code("86")) {
    what = kind::bore_rapid_out;
  } else {
    return false;
  }
  const std::string code = g_code_text(g, "G");
  const char hole = lathe_a_ ? (g == g_code("87") || g == g_code("88") || g == g_code("89") ? 'X' : 'Z')
                             : (plane_ == 17   ? 'Z'
                                : plane_ == 18 ? 'Y'
                                               : 'X');
  axis_pos* h = axis(hole);
  if (!h) return false;
  // A diameter axis moves by half its change; R, Q and the clearance are distances along it.
  const double scale = h->diameter && !radius_x_ ? 2.0 : 1.0;
  const char inc_alias = hole == 'X' ? 'U' : hole == 'Z' ? 'W' : 'V';
  const bool alias = lathe_a_ && !axis(inc_alias);
  if (!h->value) {
    t.untimed = code + " from an unknown position";
    return true;
  }
  if (!cyc_.initial) cyc_.initial = *h->value;
  const double initial = *cyc_.initial;
  // The R level: on a Fanuc lathe (and where the machine says so) the distance from the
  // initial level, in radius along X; elsewhere the R point itself (G90) or from the initial
  // level (G91).
  if (double r = 0; value(find(words, 'R'), r)) {
    const bool from_initial = lathe_a_ || m_.cycles.r_from_initial || incremental_;
    cyc_.r = from_initial ? initial + r * scale : r;
  }
  if (!cyc_.r) cyc_.r = initial;  // no R yet: the R point is the initial level
  const double r_level = *cyc_.r;
  // The bottom: the hole axis word, absolute, or from the R point (G91, Fanuc lathe W/U).
  double v = 0;
  if (value(find(words, hole), v))
    cyc_.bottom = incremental_ ? r_level + v : v;
  else if (alias && value(find(words, inc_alias), v))
    cyc_.bottom = r_level + v;
  if (!cyc_.bottom) {
    t.untimed = code + " without a bottom";
    return true;
  }
  const double bottom = *cyc_.bottom;
  const double ret = cyc_.return_r && !lathe_a_ ? r_level : initial;
  double dwell = 0;
  if (double p = 0; value(find(words, 'P'), p)) dwell = p / 1000;  // ms: Fanuc and Mazak alike
  if (double k = 1; value(find(words, 'K'), k) && k != 1) {
    t.untimed = code + " with K (repeats)";
    return true;
  }

  // To the hole at the level the tool is at (one rapid of all the axes the block names), then
  // to the R point.
  leg_target_.resize(axes_.size());
  for (std::size_t i = 0; i < axes_.size(); ++i)
    leg_target_[i] = axes_[i].address == hole || !target[i] ? axes_[i].value : target[i];
  if (!leg_to_target(leg_kind::rapid, t, code) || !leg(leg_kind::rapid, hole, r_level, t, code)) return true;
  const double depth = std::abs(bottom - r_level);
  const double into = bottom >= r_level ? 1.0 : -1.0;
  auto at = [&](double s) { return r_level + into * s; };
  const double clearance = (inch_ ? peck_clearance_mm / 25.4 : peck_clearance_mm) * scale;
  const double step = pecks ? (m_.cycles.q_increments || lathe_a_ ? increments(*q_word, q) : q) * scale : 0;
  switch (what) {
    case kind::drill:
    case kind::bore_feed_out:
    case kind::bore_rapid_out:
    case kind::tap:
      if (!leg(leg_kind::feed, hole, bottom, t, code)) return true;
      break;
    case kind::peck:
    case kind::chip_break: {
      const int n = steps_of(depth, step);
      if (n < 0) {
        t.untimed = code + " with more than 10000 pecks";
        return true;
      }
      double reached = 0;
      for (int k = 1; k <= n; ++k) {
        const double next = k == n ? depth : k * step;
        if (k > 1 && what == kind::peck && reached - clearance > 0 &&
            !leg(leg_kind::rapid, hole, at(reached - clearance), t, code))
          return true;
        if (!leg(leg_kind::feed, hole, at(next), t, code)) return true;
        reached = next;
        if (k == n) break;
        // G83 pulls out to the R point; G73 backs off by the clearance and feeds on from there.
        const double out = what == kind::peck ? 0 : std::max(reached - clearance, 0.0);
        if (!leg(leg_kind::rapid, hole, at(out), t, code)) return true;
      }
      break;
    }
  }
  t.seconds += dwell;
  // Out: a tap and a bore feed back to the R point (the tap with the spindle reversed); then to
  // the return level at rapid.
  if ((what == kind::tap || what == kind::bore_feed_out) && !leg(leg_kind::feed, hole, r_level, t, code))
    return true;
  leg(leg_kind::rapid, hole, ret, t, code);
  return true;
}

// Threading: Fanuc lathe G76 (two blocks: passes of the control's own depths) and G92, Mazak
// G292 (one pass a block). Each pass: in along X at rapid, the thread at the lead, out along X
// and back along Z at rapid, to the start point where the cycle ends.
bool block_timer::thread_cycle(int g, const std::vector<nc_word>& words, block_timing& t) {
  const std::string code = g_code_text(g, "G");
  axis_pos* x = axis('X');
  axis_pos* z = axis('Z');
  if (!x || !z) return false;
  const double dia = x->diameter && !radius_x_ ? 2.0 : 1.0;
  const bool u_alias = lathe_a_ && !axis('U'), w_alias = lathe_a_ && !axis('W');
  const nc_word* xw = find(words, 'X');
  const nc_word* zw = find(words, 'Z');
  const nc_word* uw = u_alias ? find(words, 'U') : nullptr;
  const nc_word* ww = w_alias ? find(words, 'W') : nullptr;
  if (g == g_code("76") && !xw && !zw && !uw && !ww) {
    // The first block: P(m finishing passes)(r pull-out)(a tool angle) Q(least cut) R(allowance).
    double p = 0, v = 0;
    if (value(find(words, 'P'), p)) {
      const long digits = std::lround(p);
      cyc_.finish_passes = static_cast<int>(digits / 10000);
      cyc_.tool_angle = static_cast<double>(digits % 100);
    }
    if (const nc_word* qw = find(words, 'Q'); value(qw, v)) cyc_.min_cut = increments(*qw, v);
    if (value(find(words, 'R'), v)) cyc_.allowance = v;
    cyc_.thread_set = true;
    return true;  // a setting: no move
  }
  if (!x->value || !z->value) {
    t.untimed = code + " from an unknown position";
    return true;
  }
  const double x0 = *x->value, z0 = *z->value;
  double v = 0;
  double x_end = 0, z_end = 0;
  if (value(xw, v))
    x_end = incremental_ ? x0 + v : v;
  else if (value(uw, v))
    x_end = x0 + v;
  else {
    t.untimed = code + " without X";
    return true;
  }
  if (value(zw, v))
    cyc_.box_z = incremental_ ? z0 + v : v;
  else if (value(ww, v))
    cyc_.box_z = z0 + v;
  if (!cyc_.box_z) {
    t.untimed = code + " without Z";
    return true;
  }
  z_end = *cyc_.box_z;
  if (value(find(words, 'R'), v)) cyc_.box_r = v;
  const double taper = cyc_.box_r.value_or(0) * dia;  // radius at the start minus at the end

  // One pass at the end diameter `xe`, its start shifted along Z by `shift` (flank infeed).
  auto pass = [&](double xe, double shift) {
    const double zs = z0 + (z_end >= z0 ? 1.0 : -1.0) * shift;
    return (shift == 0 || leg(leg_kind::rapid, 'Z', zs, t, code)) &&
           leg(leg_kind::rapid, 'X', xe + taper, t, code) &&
           leg(leg_kind::sync, 'X', xe, t, code, 'Z', z_end) && leg(leg_kind::rapid, 'X', x0, t, code) &&
           leg(leg_kind::rapid, 'Z', z0, t, code);
  };
  if (g != g_code("76")) {
    pass(x_end, 0);
    return true;
  }
  // G76: the second block X Z R(taper) P(height) Q(first cut) F(lead), the depths as the
  // Fanuc control cuts them: pass n at first * sqrt(n), no cut thinner than the least cut, to
  // the height less the allowance; then the finishing pass, repeated m times in all.
  if (!cyc_.thread_set) {
    t.untimed = "G76 without its first block";
    return true;
  }
  const nc_word* pw = find(words, 'P');
  const nc_word* qw = find(words, 'Q');
  double height = 0, first = 0;
  if (!value(pw, height) || !value(qw, first)) {
    t.untimed = "G76 without P or Q";
    return true;
  }
  height = increments(*pw, height);
  first = increments(*qw, first);
  const double rough = height - cyc_.allowance;
  if (!(first > 0) || !(height > 0)) {
    t.untimed = "G76 without a depth";
    return true;
  }
  const double out = x0 >= x_end ? 1.0 : -1.0;  // from the root toward the start: outward
  const double tan_half = std::tan(cyc_.tool_angle / 2 * std::numbers::pi / 180);
  double d = 0;
  int n = 0;
  auto at_depth = [&](double depth) { return x_end + out * (height - depth) * dia; };
  while (d < rough - 1e-9) {
    if (++n > max_steps) {
      t.untimed = "G76 with more than 10000 passes";
      return true;
    }
    d = std::min(std::max(first * std::sqrt(static_cast<double>(n)), d + cyc_.min_cut), rough);
    if (!pass(at_depth(d), (d - first) * tan_half)) return true;
  }
  for (int k = 0; k < std::max(cyc_.finish_passes, 1); ++k)
    if (!pass(x_end, (height - first) * tan_half)) return true;
  return true;
}

// Fanuc lathe G75 (grooving along X, stepping along Z) and G74 (the same along Z, stepping
// along X): the first block R(e) the back-off of each peck; the second X(U) Z(W) P(peck along
// X) Q(along Z) F. Each plunge pecks to the bottom, comes back to the start level at rapid,
// steps on at rapid; the cycle ends at its start point.
bool block_timer::groove_cycle(int g, const std::vector<nc_word>& words, block_timing& t) {
  const std::string code = g_code_text(g, "G");
  axis_pos* x = axis('X');
  axis_pos* z = axis('Z');
  if (!x || !z) return false;
  const double dia = x->diameter && !radius_x_ ? 2.0 : 1.0;
  const nc_word* xw = find(words, 'X');
  const nc_word* zw = find(words, 'Z');
  const nc_word* uw = axis('U') ? nullptr : find(words, 'U');
  const nc_word* ww = axis('W') ? nullptr : find(words, 'W');
  double v = 0;
  if (!xw && !zw && !uw && !ww) {
    if (value(find(words, 'R'), v)) cyc_.groove_return = v;
    return true;  // the first block: a setting
  }
  if (!x->value || !z->value) {
    t.untimed = code + " from an unknown position";
    return true;
  }
  const double x0 = *x->value, z0 = *z->value;
  double x1 = x0, z1 = z0;
  if (value(xw, v))
    x1 = incremental_ ? x0 + v : v;
  else if (value(uw, v))
    x1 = x0 + v;
  if (value(zw, v))
    z1 = incremental_ ? z0 + v : v;
  else if (value(ww, v))
    z1 = z0 + v;
  double p = 0, q = 0;
  const nc_word* pw = find(words, 'P');
  const nc_word* qw = find(words, 'Q');
  if (value(pw, p)) p = increments(*pw, p);
  if (value(qw, q)) q = increments(*qw, q);
  // G75 plunges along X (P the peck, radius) and steps along Z (Q); G74 the other way round.
  const bool along_x = g == g_code("75");
  const char plunge = along_x ? 'X' : 'Z', shift = along_x ? 'Z' : 'X';
  const double p0 = along_x ? x0 : z0, p1 = along_x ? x1 : z1;
  const double s0 = along_x ? z0 : x0, s1 = along_x ? z1 : x1;
  const double plunge_scale = along_x ? dia : 1.0, shift_scale = along_x ? 1.0 : dia;
  const double peck = (along_x ? p : q) * plunge_scale, step = (along_x ? q : p) * shift_scale;
  const double back = cyc_.groove_return * plunge_scale;
  const double depth = std::abs(p1 - p0), into = p1 >= p0 ? 1.0 : -1.0;
  const double width = std::abs(s1 - s0), across = s1 >= s0 ? 1.0 : -1.0;
  const int pecks = steps_of(depth, peck), plunges = width > 0 ? steps_of(width, step) : 0;
  if (pecks < 0 || plunges < 0 || (width > 0 && !(step > 0))) {
    t.untimed = code + (width > 0 && !(step > 0) ? " without its step" : " with more than 10000 pecks");
    return true;
  }
  for (int j = 0; j <= plunges; ++j) {
    const double s = j == plunges ? s1 : s0 + across * j * step;
    if (j > 0 && !leg(leg_kind::rapid, shift, s, t, code)) return true;
    for (int k = 1; k <= pecks; ++k) {
      const double reached = k == pecks ? depth : k * peck;
      if (!leg(leg_kind::feed, plunge, p0 + into * reached, t, code)) return true;
      if (k < pecks && back > 0 &&
          !leg(leg_kind::rapid, plunge, p0 + into * std::max(reached - back, 0.0), t, code))
        return true;
    }
    if (!leg(leg_kind::rapid, plunge, p0, t, code)) return true;
  }
  if (width > 0) leg(leg_kind::rapid, shift, s0, t, code);
  return true;
}

}  // namespace twinpost
