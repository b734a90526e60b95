// analysis/nc_codes.hpp: what a G code does with its block's axis words.
#include "analysis/nc_codes.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/program_units.hpp"
#include "nc/nc_words.hpp"

namespace twinpost {

namespace {

// A G code as ten times its number: G84.2 is 842.
int g10(double g) { return static_cast<int>(std::lround(g * 10)); }

// The G number of a one-G-word code ("G81"; "G98 G81" is not one), ten times; -1 none.
int code_g10(const std::string& code) {
  const std::vector<nc_word> w = split_nc_words(code);
  return w.size() == 1 && w[0].address == 'G' && w[0].numeric ? g10(w[0].number) : -1;
}

}  // namespace

gcode_system gcode_system_of(const machine& m, const channel_def& ch) {
  const axis_def* x = ch.axis('X');
  if (x && !x->diameter) return gcode_system::mill;
  if (units_of(m).system_c) return gcode_system::c;
  for (const std::string& b : m.program.header)
    for (const nc_word& w : split_nc_words(b))
      if (w.address == 'G' && w.numeric && (g10(w.number) == 900 || g10(w.number) == 910))
        return gcode_system::b;
  return gcode_system::a;
}

nc_codes::nc_codes(const machine& m, const channel_def& ch) : system_(gcode_system_of(m, ch)) {
  const auto g_words = [](std::vector<int>& out, const std::string& code) {
    for (const nc_word& w : split_nc_words(code))
      if (w.address == 'G' && w.numeric) out.push_back(g10(w.number));
  };
  g_words(per_min_, m.codes.feed_per_min);
  g_words(per_rev_, m.codes.feed_per_rev);
  if (const kinematic_chain* k = m.chain(ch.number)) g_words(inverse_, k->inverse_time);
  const cycle_rules& cy = m.cycles;
  for (const std::string* code :
       {&cy.drill_code, &cy.dwell_code, &cy.peck_code, &cy.chip_break_code, &cy.tap_code, &cy.tap_left_code,
        &cy.side_drill_code, &cy.side_dwell_code, &cy.side_peck_code, &cy.side_tap_code})
    if (const int g = code_g10(*code); g >= 0) holes_.push_back(g);
  if (const int g = code_g10(cy.sync_feed); g >= 0) threads_.push_back(g);
  // The thread and groove cycles the machine writes: a box per pass ("g92", Mazak "g292") is a
  // single cycle, the two-block ones ("g76", "g276", the groove's "g75") repetitive.
  for (const std::string* kind : {&cy.thread, &cy.groove})
    if (kind->size() > 1 && (*kind)[0] == 'g') {
      double v = 0;
      if (!nc_number(std::string_view(*kind).substr(1), v)) continue;
      const int g = g10(v);
      (*kind == "g92" || *kind == "g292" ? boxes_ : cycles_).push_back(g);
      if (kind == &cy.thread) threads_.push_back(g);
    }
}

axis_words nc_codes::role(double number) const {
  const int g = g10(number);
  const bool lathe = system_ != gcode_system::mill;
  switch (g) {
    case 0:
    case 10:
    case 20:
    case 30: return axis_words::motion;
    case 320:
    case 330:
    case 340: return axis_words::feed_move;
    case 270:
    case 280:
    case 290:
    case 300: return axis_words::reference;
    case 530: return axis_words::machine;
    // A dwell (X is its time), data setting (G10, its mode's end G11, Mazak's radius and
    // diameter input G10.9), a coordinate setting or the speed clamp (G50, G52), a macro call
    // (its words are arguments), a rotated or tilted frame (G68, G68.1, G68.2, G68.3, G68.4),
    // scaling and mirror image, the radius of cylindrical interpolation, the stored stroke
    // check's limits (G22 X Z I K: attack 63 M5, read as a move to X0 Z-10).
    case 40:
    case 100:
    case 109:
    case 110:
    case 500:
    case 501:
    case 520:
    case 921:
    case 650:
    case 660:
    case 661:
    case 220:
    case 680:
    case 681:
    case 682:
    case 683:
    case 684:
    case 510:
    case 511:
    case 71:
    case 1070: return axis_words::none;
    default: break;
  }
  if (std::find(boxes_.begin(), boxes_.end(), g) != boxes_.end()) return axis_words::turning_cycle;
  if (std::find(cycles_.begin(), cycles_.end(), g) != cycles_.end()) return axis_words::repetitive_cycle;
  if (std::find(threads_.begin(), threads_.end(), g) != threads_.end()) return axis_words::feed_move;
  if (std::find(holes_.begin(), holes_.end(), g) != holes_.end()) return axis_words::hole_cycle;
  switch (system_) {
    case gcode_system::a:
      if (g == 900 || g == 920 || g == 940) return axis_words::turning_cycle;
      break;
    case gcode_system::b:
      if (g == 770 || g == 780 || g == 790) return axis_words::turning_cycle;
      break;
    case gcode_system::c:
      if (g == 200 || g == 210 || g == 240) return axis_words::turning_cycle;
      break;
    case gcode_system::mill: break;
  }
  // G92 sets the coordinates where it is no cycle (a machining centre, systems B and C).
  if (g == 920) return axis_words::none;
  // The multiple repetitive cycles: G70-G76 (finishing, roughing, pattern, face peck, groove,
  // thread), in system C G72-G78 (its G70 and G71 are the units).
  if (lathe && g % 10 == 0 && g >= (system_ == gcode_system::c ? 720 : 700) &&
      g <= (system_ == gcode_system::c ? 780 : 760))
    return axis_words::repetitive_cycle;
  // The drilling cycles of both: G73, G74, G76 on a machining centre (chip break, left tap,
  // fine boring), G81-G89, Fanuc's rigid taps G84.2, G84.3.
  if (g == 730 || g == 740 || g == 760 || (g >= 810 && g <= 890 && g % 10 == 0) || g == 842 || g == 843)
    return axis_words::hole_cycle;
  return axis_words::modal;
}

feed_kind nc_codes::feed_mode(double number) const {
  const int g = g10(number);
  const auto among = [g](const std::vector<int>& v) { return std::find(v.begin(), v.end(), g) != v.end(); };
  return among(per_rev_)   ? feed_kind::per_rev
         : among(per_min_) ? feed_kind::per_minute
         : among(inverse_) ? feed_kind::inverse_time
                           : feed_kind::none;
}

bool nc_codes::threads(double number) const {
  const int g = g10(number);
  if (g == 320 || g == 330 || g == 340) return true;
  if (std::find(threads_.begin(), threads_.end(), g) != threads_.end()) return true;
  switch (system_) {
    case gcode_system::a: return g == 920 || g == 760;
    case gcode_system::b: return g == 780 || g == 760;
    case gcode_system::c: return g == 210 || g == 780;
    case gcode_system::mill: return false;
  }
  return false;
}

}  // namespace twinpost
