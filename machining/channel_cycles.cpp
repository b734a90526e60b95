// channel_writer: drilling and tapping cycles along Z on the spindle centre line: the
// control's canned cycle where the machine's [cycles] gives one, plain moves otherwise.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "kinematics/vec3_ops.hpp"
#include "machining/channel_writer.hpp"
#include "parser/cycle_words.hpp"

namespace twinpost {

namespace {

bool has_word(const cycle_event& c, std::string_view word) {
  return std::find(c.words.begin(), c.words.end(), word) != c.words.end();
}

// A peck count past any real hole (a depth of 1e300 or a STEP of 1e-9) would write moves
// without end: refused before the first move.
constexpr double max_pecks = 10000;
// How far above the last depth an expanded peck comes back in, and how far a chip-breaking
// peck backs off (mm): what the canned cycles' parameters usually hold (Fanuc 5114/5115).
constexpr double peck_clearance = 0.5;

}  // namespace

/// One hole of a cycle, with the dialect's meaning of the words applied: Z values in CL
/// units along the spindle axis, `into` the direction of drilling.
struct channel_writer::hole {
  double x = 0, y = 0;
  double top = 0;           // the hole's point (the GOTO) along Z
  double into = -1;         // -1: drilling towards -Z
  double clear = 0;         // the R plane (RAPTO, CLEAR above the top)
  double initial = 0;       // the retract plane (RTRCTO above the top; else the R plane)
  double bottom = 0;        // FEDTO or DEPTH
  double first = 0;         // the first peck, 0 for none
  double later = 0;         // the pecks after it
  bool chip_break = false;  // short retracts (DEEP2) rather than out to the R plane (DEEP)
  double dwell = 0;         // seconds at the bottom
  double pitch = 0;         // a tap's lead (mm)
  bool left = false;        // a left-hand tap
};

bool channel_writer::cycle_supported(const cycle_event& c, int line) {
  // Only what the writer really does is taken; a bore, a ream or a thread written as a drill
  // would mark the bore or break the tool, so anything else stops the post at the record.
  const bool tap = c.type == "TAP";
  if (c.type != "DRILL" && c.type != "DEEP" && c.type != "DEEP2" && !tap) {
    error(line, fmt::format("CYCLE/{} is not supported by the post: only DRILL, DEEP, DEEP2 and TAP are "
                            "written; a boring or reaming cycle cannot be (THREAD and GROOVE go by [cycles])",
                            c.type));
    return false;
  }
  const cycle_word_meaning& mean = c.meaning;
  auto known = [&](std::string_view name) {
    if (name == "FEDTO" || name == "DEPTH" || name == "RAPTO" || name == "CLEAR") return true;
    if (name == "MMPR" || name == "IPR" || name == "MMPM" || name == "IPM") return true;
    if (name == "STEP") return c.type == "DEEP";  // only DEEP is written in pecks of STEP
    if (name == "RTRCTO") return mean.rtrcto_above_top;
    if (name == "DWELL") return mean.dwell_seconds && (!tap || *cycle_param(c, "DWELL") == 0);
    if (name == "1STPECK" || name == "SUBPECK") return mean.first_and_later_pecks && c.type == "DEEP2";
    if (name == "PITCH") return tap;
    return false;
  };
  const std::string_view knows = tap ? "it knows FEDTO, DEPTH, RAPTO, CLEAR, PITCH, LEFT and the feed"
                                     : "it knows FEDTO, DEPTH, RAPTO, CLEAR, STEP and the feed";
  for (const auto& [name, value] : c.params) {
    if (known(name)) continue;
    const bool dialect_word = (name == "RTRCTO" && !mean.rtrcto_above_top) ||
                              (name == "DWELL" && !mean.dwell_seconds) ||
                              ((name == "1STPECK" || name == "SUBPECK") && !mean.first_and_later_pecks);
    error(line, fmt::format("CYCLE/{}: {} is not carried out by the post ({}{})", c.type, name, knows,
                            !dialect_word      ? ""
                            : name == "RTRCTO" ? "; the meaning of this word is known only in the SolidWorks "
                                                 "and NX dialects"
                                               : "; the meaning of this word is known only in the SolidWorks "
                                                 "dialect"));
    return false;
  }
  for (const std::string& w : c.words) {
    if (tap && w == "LEFT") continue;
    error(line, fmt::format("CYCLE/{}: {} is not carried out by the post ({}, each with its value)", c.type,
                            w, knows));
    return false;
  }
  if (!c.positional.empty()) {
    // CATIA writes CYCLE/DRILL,d,f,... as its site's PP table says (the table names each value,
    // "PP Tables and PP Word Syntaxes" of the CATIA V5 manual); Creo's cycle_format = fixed and
    // the old ISO 4343:1978 form are positional too, and ICAM's CYCLE page calls that form
    // undocumented. No public definition says which value is the depth: none is guessed.
    std::string values;
    for (double v : c.positional) values += fmt::format("{}{}", values.empty() ? "" : ", ", v);
    error(line, fmt::format("CYCLE/{}: the values {} stand by position, whose meaning the CAM's post table "
                            "sets (CATIA's PP table) and no public definition fixes; twinpost does not "
                            "guess which is the depth ({}, each with its value)",
                            c.type, values, knows));
    return false;
  }
  if (c.type == "DEEP" && !(cycle_param(c, "STEP").value_or(0) > 0)) {
    // Without a peck depth the peck cycle would be drilled in one feed: a deep hole's chips
    // would jam the drill.
    error(line, "CYCLE/DEEP (NX: CYCLE/DRILL,DEEP) needs STEP, the depth of each peck");
    return false;
  }
  if (c.type == "DEEP2" && !(cycle_param(c, "SUBPECK").value_or(0) > 0)) {
    error(line, "CYCLE/DEEP2 needs SUBPECK, the depth of each peck after the first");
    return false;
  }
  if (tap) {
    if (m_.cycles.tap == "none") {
      error(line, fmt::format("CYCLE/TAP: machine '{}' has no tapping cycle ([cycles] tap = \"none\"); a "
                              "tap fed as a drill would break",
                              m_.name));
      return false;
    }
    if (!cycle_param(c, "PITCH") && !cycle_param(c, "MMPR") && !cycle_param(c, "IPR")) {
      error(line,
            "CYCLE/TAP needs the pitch: PITCH or a feed per revolution (MMPR, IPR); a feed per minute "
            "would tap in step with the spindle only at one speed");
      return false;
    }
  }
  return true;
}

vec3 channel_writer::cycle_approach(const vec3& p) const {
  // As cycle_point reads the planes: the tool looks down -Z (axis +Z) and drills towards -Z.
  const cycle_event& c = *cycle_;
  const double into = axis_.z < 0 ? 1.0 : -1.0;
  const std::optional<double> above =
      c.meaning.rtrcto_above_top && cycle_param(c, "RTRCTO")
          ? cycle_param(c, "RTRCTO")
          : cycle_param(c, "RAPTO").value_or(cycle_param(c, "CLEAR").value_or(0));
  if (std::abs(axis_.z) >= 0.9999) return {p.x, p.y, p.z - into * *above};
  // A tilted tool (a hole in a tilted working plane): up its axis.
  const double len = kin::norm(axis_);
  return {p.x + *above * axis_.x / len, p.y + *above * axis_.y / len, p.z + *above * axis_.z / len};
}

bool channel_writer::hole_from_cut(const vec3& p, int line) {
  // The control positions a hole's cycle across the tool at the level the tool stands at, then
  // goes to its R level: straight from a cut below that level (no retract in the CL) the
  // positioning runs through the part, and on a mill/turn C turns the part under the cutter
  // (review 38b P3: an end mill 3 mm deep, then `G0 C0.` and `X20. Y10. Z2.`).
  const vec3 r = cycle_approach(p);
  const double n = kin::norm(axis_);
  const double below = ((r.x - pos_.x) * axis_.x + (r.y - pos_.y) * axis_.y + (r.z - pos_.z) * axis_.z) / n;
  if (below <= 1e-6) return false;
  error(line, fmt::format("CYCLE/{}: the hole's cycle starts straight from a cut, {} below its R level: the "
                          "control would position it across the tool there, through the part; give the "
                          "retract before the cycle",
                          cycle_->type, kin::number_text(below * cl_mm_)));
  from_cut_ = false;
  return true;
}

void channel_writer::cycle_point(const vec3& p, int line) {
  const cycle_event& c = *cycle_;
  c_hole_deg_.reset();
  // Only along the spindle axis: a radial or tilted tool (cross drilling with a live tool)
  // would be fed along Z, through the side of the part.
  if (has_c_ && !index_head(line)) return;
  if (!spindle_turning(line)) return;  // a hole is a cut: the spindle must turn
  // A cross hole on a channel with a C axis: drilled in the turned frame (milling.radial_frame_on),
  // whose Z is the tool axis; its moves come in that frame (radial_ok_).
  // With milling.cross_holes = "side_cycle" (Fanuc) C turns to the hole and the side codes
  // drill along X; the hole's points take the turned frame's terms all the same (side_point).
  vec3 at = p;
  const bool cross = has_c_ && c_mode_ && std::abs(axis_.z) <= 1e-4;
  const bool side = cross && side_holes();
  if (cross && c.meaning.fedto_absolute() && cycle_param(c, "FEDTO"))
    return error(line, fmt::format("CYCLE/{} across the spindle axis with an absolute FEDTO: give the depth "
                                   "(DEPTH) of a cross hole",
                                   c.type));
  if (side ? !side_point(p, at, line) : cross && !radial_point(p, at, line)) return;
  if (cross) clamp_c();  // at the angle cylindrical interpolation left C at, C is still free
  // In a tilted working plane: the hole in the plane's frame, drilled down its Z (G17 there).
  const bool tilted = chain_ && plane_on_;
  if (tilted) {
    if (!plane_takes(line)) return;
    if (c.meaning.fedto_absolute() && cycle_param(c, "FEDTO"))
      return error(line, fmt::format("CYCLE/{} in a tilted working plane ({}) with an absolute FEDTO: a Z of "
                                     "the part frame is no depth along the tilted tool; give the depth "
                                     "(DEPTH)",
                                     c.type, chain_->plane));
    at = to_plane(p);
  }
  struct frame_points {
    bool& flag;
    bool& side;
    bool& plane;
    ~frame_points() { flag = side = plane = false; }
  } in_frame{radial_ok_, side_hole_, plane_hole_};
  radial_ok_ = cross;
  side_hole_ = side;
  plane_hole_ = tilted;
  if (cross || tilted) {
    // as an axial hole drilled towards -Z in the turned frame or the plane
  } else if (std::abs(axis_.z) < 0.9999)
    return error(line,
                 fmt::format("CYCLE/{} with the tool axis ({}, {}, {}): only drilling along Z is written; "
                             "cross and tilted drilling is not supported yet",
                             c.type, axis_.x, axis_.y, axis_.z));
  // On a lathe on the centre line only: an axial hole off centre needs a live tool and the C
  // axis; with the workpiece turning, the drill would cut a ring. On a machining centre the
  // part stands still: a hole anywhere.
  if (!cross && !part_stands_still() && std::hypot(p.x, p.y) * cl_mm_ > 1e-3 && !c_axis_hole(p) &&
      !(c_mode_ && has_y_))
    return error(line, fmt::format("CYCLE/{} at X {} Y {}: off the spindle centre line; {}", c.type, p.x, p.y,
                                   off_centre_hole_needs()));
  // A tool pointing -Z drills towards +Z: on a machining centre without rotary axes, on the
  // main spindle and on a spindle whose CL Z is its own (reverse_z) that is away from the part,
  // and the planes (R, retract) would lie inside it. Only a spindle the CL sees in the machine's
  // Z facing the other way (a sub spindle without reverse_z) is drilled so.
  if (axis_.z < 0 && !cross && !tilted &&
      ((!chain_ && part_stands_still()) ||
       (work_ && (work_->reverse_z || (!m_.spindles.empty() && work_ == &m_.spindles.front())))))
    return error(line,
                 fmt::format("CYCLE/{} with the tool axis ({:g},{:g},{:g}): the tool would drill towards +Z, "
                             "away from the {} spindle's part; a hole is drilled down the tool towards -Z",
                             c.type, axis_.x, axis_.y, axis_.z, work_ ? work_->name : "workpiece"));
  hole h;
  h.x = at.x;
  h.y = at.y;
  // The tool looks down -Z (axis +Z): it drills towards -Z (in a plane: its Z is the tool's).
  h.into = axis_.z < 0 && !cross && !tilted ? 1.0 : -1.0;
  const double top = at.z;
  h.top = top;
  const double rapto = cycle_param(c, "RAPTO").value_or(cycle_param(c, "CLEAR").value_or(0));
  // The R plane is where the rapid down ends: below the hole's top it is inside the part
  // (attack 45: RAPTO,-50 wrote G0 ... Z-50., a rapid 50 mm into the material).
  if (rapto < 0)
    return error(line, fmt::format("CYCLE/{}: {} {} puts the clearance plane {} mm below the hole's top: the "
                                   "tool would rapid into the part",
                                   c.type, cycle_param(c, "RAPTO") ? "RAPTO" : "CLEAR",
                                   kin::number_text(rapto), kin::number_text(-rapto * cl_mm_)));
  h.clear = top - h.into * rapto;
  const std::optional<double> fedto = cycle_param(c, "FEDTO");
  // FEDTO: a depth (SolidWorks), a distance along the tool axis, negative into the part (NX),
  // or a Z (the others).
  const std::optional<double> bottom = cycle_bottom(c, top, h.into);
  if (!bottom) return error(line, fmt::format("CYCLE/{} needs FEDTO or DEPTH", c.type));
  h.bottom = *bottom;
  // A hole deeper than the tool is long: the holder would drive into the part (a FEDTO read
  // in the wrong sense, or a CAM error). The length is TLDATA's or the tool table's, the shorter.
  if (const double deep = (h.bottom - top) * h.into * cl_mm_; reach_ && deep > *reach_ + 1e-6)
    return error(
        line,
        fmt::format("CYCLE/{}: the hole goes {} mm below its top (the GOTO point, Z {}) to Z {}, "
                    "but tool {} is {} mm long ({}): its holder would drive into the part",
                    c.type, kin::number_text(deep), kin::number_text(top), kin::number_text(h.bottom), tool_,
                    kin::number_text(*reach_), reach_from_table_ ? "[[tool]] length" : "TLDATA"));
  if ((h.bottom - h.clear) * h.into <= 0)
    return error(line,
                 fmt::format("CYCLE/{}: the bottom Z {} is not beyond the clearance plane Z {} in the "
                             "drilling direction: the tool would feed away from the part{}",
                             c.type, h.bottom, h.clear,
                             !c.meaning.fedto_absolute() || !fedto ? "" : " (is FEDTO a depth in this CL?)"));
  h.initial = h.clear;
  if (auto r = cycle_param(c, "RTRCTO")) {
    h.initial = top - h.into * *r;
    if ((h.initial - h.clear) * h.into > 0)
      return error(line, fmt::format("CYCLE/{}: RTRCTO {} lies below RAPTO: the tool would return to a plane "
                                     "nearer the part than the one it started from",
                                     c.type, *r));
  }
  h.dwell = cycle_param(c, "DWELL").value_or(0);
  if (h.dwell < 0) return error(line, fmt::format("CYCLE/{}: DWELL {} is negative", c.type, h.dwell));
  if (c.type == "TAP") {
    if (inch_thread_refused("CYCLE/TAP", line)) return;
    // The lead: PITCH, or the feed per revolution, which for a tap is the lead (mm output).
    double pitch = cycle_param(c, "PITCH").value_or(0) * cl_mm_;
    if (auto f = cycle_param(c, "MMPR"); f && pitch == 0) pitch = *f;
    if (auto f = cycle_param(c, "IPR"); f && pitch == 0) pitch = *f * 25.4;
    if (!(pitch > 0)) return error(line, fmt::format("CYCLE/TAP: the pitch {} is not a lead", pitch));
    // ISO 261's coarsest metric pitch is 6 mm (M64 and over); a lead past 10 mm is a unit or
    // value the CAM did not mean (attack 45: PITCH,500).
    if (pitch > 10)
      return error(line,
                   fmt::format("CYCLE/TAP: a lead of {} mm is no tap's (ISO 261's coarsest pitch is 6 mm)",
                               kin::number_text(pitch)));
    // The tap feeds its lead a turn: at the speed in force that is a feed per minute the machine
    // must make (attack 45: a 500 mm lead at 500 rpm was written, 250 m/min).
    if (const double max_feed = m_.limits.max_feed; max_feed > 0 && last_speed_ &&
                                                    last_speed_->mode == spindle_mode::rpm &&
                                                    pitch * last_speed_->speed > max_feed)
      return error(line,
                   fmt::format("CYCLE/TAP: a lead of {} mm at {} rpm feeds {} mm/min, over the machine's {} "
                               "mm/min (limits.max_feed)",
                               kin::number_text(pitch), kin::number_text(last_speed_->speed),
                               kin::number_text(pitch * last_speed_->speed), kin::number_text(max_feed)));
    if (!fits('F', pitch, 4)) return;
    h.pitch = pitch;
    h.left = has_word(c, "LEFT") || (last_speed_ && last_speed_->dir == rotation::ccw);
    return tap_hole(h, line);
  }
  for (const char* unit : {"MMPR", "IPR", "MMPM", "IPM"}) {
    if (auto f = cycle_param(c, unit)) {
      const bool per_rev = std::string_view(unit).back() == 'R';
      const double value = *f * ((unit[0] == 'I') ? 25.4 : 1.0) * out_per_mm_;
      if (!feed_writable(value, per_rev, "CYCLE", line)) return;
      // The cycle's own feed (docs/records.md, CYCLE): the FEDRAT it replaces is back at
      // CYCLE/OFF (review 55 L3: a polar cut after the holes ran at the drill's F150.).
      if (!fedrat_before_cycle_ && feed_value_ > 0) fedrat_before_cycle_ = std::pair{feed_value_, per_rev_};
      feed_value_ = value;
      feed_mode(per_rev);
    }
  }
  if (c.type == "DEEP") {
    h.first = h.later = cycle_param(c, "STEP").value_or(0);
  } else if (c.type == "DEEP2") {
    h.later = *cycle_param(c, "SUBPECK");
    h.first = cycle_param(c, "1STPECK").value_or(h.later);
    h.chip_break = true;
  }
  if (h.first < 0 || h.later < 0)
    return error(line, fmt::format("CYCLE/{}: a peck depth is negative", c.type));
  const double depth = std::abs(h.bottom - h.clear);
  if (h.first > 0 && !((depth - h.first) / h.later <= max_pecks))
    return error(line, fmt::format("CYCLE/{}: a depth of {} in pecks of {} makes more than {} pecks", c.type,
                                   depth, h.later, max_pecks));
  if (h.first >= depth) h.first = h.later = 0;  // one peck reaches the bottom: a plain drill
  const cycle_rules& k = m_.cycles;
  if (k.drill == "canned") {
    const bool pecks = h.first > 0;
    // Across the spindle axis with the side cycles: no chip-breaking side code is read.
    const std::string none;
    const std::string& code = side          ? (pecks         ? (h.chip_break ? none : k.side_peck_code)
                                               : h.dwell > 0 ? k.side_dwell_code
                                                             : k.side_drill_code)
                              : pecks       ? (h.chip_break ? k.chip_break_code : k.peck_code)
                              : h.dwell > 0 ? k.dwell_code
                                            : k.drill_code;
    // One Q for every peck and no dwell with pecks: what the control cannot do is written
    // as moves, never approximated.
    const bool fits_canned =
        !code.empty() && (!pecks || (std::abs(h.first - h.later) < 1e-9 && h.dwell == 0));
    if (fits_canned) return canned_hole(h, code, line);
  }
  expanded_hole(h, line);
}

void channel_writer::turn_c_to_hole(double degrees) {
  position_c(degrees);
  clamp_c();
}

void channel_writer::to_hole(const hole& h, int line) {
  // From the last hole's retract plane to this one's: a rapid that climbs or drops while it
  // travels cuts the corner of whatever stands between (a boss, a clamp, the step between two
  // holes' tops). Up first when this hole's plane lies further out, across at the higher of the
  // two, down last, as NX's and Fusion's posts move between G98 cycles. In a turned frame
  // (cross holes, tilted planes) the points are not the CL's: one move, as before.
  // Between two holes the tool stands on the last one's retract plane (the CL's position is
  // then that hole's point); after a GOTO or an arc at the CL's point. After a tool call the
  // tool call's approach brings it (the tool's position is not the CL's).
  const bool plain = !radial_ok_ && !side_hole_ && !plane_hole_;
  const bool after_hole = hole_exit_ && kin::distance(pos_, hole_point_) <= 1e-9;
  const vec3 from = after_hole ? *hole_exit_ : pos_;
  const std::optional<double> c_turn = std::exchange(c_hole_deg_, std::nullopt);
  if ((after_hole || at_pos_) && !homed_ && pending_offset_.empty() && plain &&
      (std::abs(from.x - h.x) > 1e-9 || std::abs(from.y - h.y) > 1e-9)) {
    const double out = (from.z - h.initial) * h.into;  // > 0: this hole's plane lies further out
    if (out > 1e-9) linear(true, from.x, from.y, h.initial, line);
    // A face hole at a C position: the part turns once the tool stands on the higher plane
    // (C at the last hole's angle until then), and C is clamped for the cycle.
    if (c_turn) turn_c_to_hole(*c_turn);
    if (out < -1e-9) linear(true, h.x, h.y, from.z, line);
  } else if (c_turn) {
    turn_c_to_hole(*c_turn);
  }
  linear(true, h.x, h.y, h.initial, line);
  // Every hole ends on its retract plane.
  if (plain) {
    hole_exit_ = vec3{h.x, h.y, h.initial};
    hole_point_ = {h.x, h.y, h.top};
  } else
    hole_exit_.reset();
}

void channel_writer::expanded_hole(const hole& h, int line) {
  // Rapid to the retract plane and the R plane, feed to depth (in pecks), rapid back out to
  // the retract plane: moves every control reads.
  to_hole(h, line);
  if (h.initial != h.clear) linear(true, h.x, h.y, h.clear, line);
  const double back = peck_clearance / cl_mm_;
  if (h.first > 0) {
    for (double z = h.clear + h.into * h.first; (h.bottom - z) * h.into > 0; z += h.into * h.later) {
      linear(false, h.x, h.y, z, line);
      if (!h.chip_break) linear(true, h.x, h.y, h.clear, line);
      linear(true, h.x, h.y, z - h.into * back, line);
    }
  }
  linear(false, h.x, h.y, h.bottom, line);
  if (h.dwell > 0) write_dwell(h.dwell);
  linear(true, h.x, h.y, h.initial, line);
}

void channel_writer::cycle_block(const hole& h, const std::string& code, double q, double pitch, int line) {
  // [G98] G8x X.. Z<bottom> R.. [Q..] [P..] F.., then the cancel code, then the tool is
  // written back to the retract plane: where it is whatever the control's return level.
  const cycle_rules& k = m_.cycles;
  // Z words through nc_z: a hole on a reversed (sub) spindle is drilled in the machine's Z.
  // A side cycle (G87) drills along X: R along X too, in radius (as the Fusion Doosan post
  // writes it), and the hole's Z is the turned frame's -X.
  const double r = side_hole_         ? (k.r_from_initial ? (h.clear - h.initial) * scale_ : nc_x(h.clear))
                   : k.r_from_initial ? (h.clear - h.initial) * scale_ * z_sign_
                                      : nc_z(h.clear);
  if (!fits('R', r, axis_style_.decimals)) return;
  if (pitch <= 0 && !(feed_value_ > 0))
    return error(line, "a drilling cycle with no feed rate in force (the CYCLE's MMPM/MMPR or a FEDRAT)");
  if (!k.plane.empty())
    out_.block(k.plane);
  else if (!c_mode_)
    restore_plane();  // a G18 arc before: the cycle would drill along Y (Fanuc FXY = 1)
  text_buffer& b = out_.open_block();
  word_start_ = b.size();
  if (!k.return_initial.empty()) b += k.return_initial, b += ' ';
  b += code;
  if (side_hole_) {
    // G87 X<the bottom's diameter> Z<the hole's Z>: on the radial line at the C position.
    axis_word(b, 'X', nc_x(h.bottom), last_x_, true);
    axis_word(b, 'Z', nc_z(-h.x), last_z_, true);
  } else {
    const auto [hx, hy] = c_frame(h.x, h.y);  // at a C position: in the frame C turned the part to
    axis_word(b, 'X', nc_x(hx), last_x_, true);
    if (has_y_) axis_word(b, 'Y', nc_y(hy), last_y_, true);
    axis_word(b, 'Z', nc_z(h.bottom), last_z_, true);
  }
  b += " R";
  append_number(b, r, axis_style_);
  if (q > 0) {
    b += " Q";
    if (k.q_increments)
      append_number(b, std::round(q * scale_ * std::pow(10, axis_style_.decimals)), {0, false});
    else
      append_number(b, q * scale_, axis_style_);
  }
  if (h.dwell > 0) {
    b += " P";
    append_number(b, std::round(h.dwell * 1000), {0, false});
  }
  last_f_.clear();
  if (pitch > 0) {
    b += " F";
    append_number(b, pitch, {4, m_.program.trailing_point});
  } else {
    append_feed(b);
  }
  out_.end_block();
  word_start_ = std::string::npos;
  out_.block(k.cancel);
  if (!k.plane.empty()) out_.block(fmt::format("G{}", plane_));
  motion_g_ = -1;
  last_z_.known = false;
  if (side_hole_) last_x_.known = false;  // the cycle ends on the R point or the initial level
  linear(true, h.x, h.y, h.initial, line);
}

void channel_writer::canned_hole(const hole& h, const std::string& code, int line) {
  if (h.dwell > 0 && !fits('P', std::round(h.dwell * 1000), 0)) return;
  if (h.first > 0 && !fits('Q', h.first * scale_, axis_style_.decimals)) return;
  to_hole(h, line);  // the cycle starts on the initial level
  cycle_block(h, code, h.first, 0, line);
}

void channel_writer::tap_hole(const hole& h, int line) {
  // A tap turns in step with the spindle all the way in and all the way out: never a rapid in
  // the hole, never an unsynchronised feed. The spindle must turn at a set speed.
  const cycle_rules& k = m_.cycles;
  if (!spindle_ || !last_speed_ || restart_blocks_.empty())
    return error(line, "CYCLE/TAP with the spindle stopped: give SPINDL/RPM,n before the tap");
  if (last_speed_->mode != spindle_mode::rpm)
    return error(line,
                 "CYCLE/TAP needs a set spindle speed (SPINDL/RPM), not constant surface speed: the "
                 "tap's feed follows the spindle");
  if (k.tap == "expanded" && work_ && spindle_ != work_)
    return error(
        line, fmt::format("CYCLE/TAP with a live tool on machine '{}', whose tapping is written as "
                          "moves ([cycles] tap = \"expanded\"): {} follows the workpiece spindle, "
                          "not the tool's; a live tap needs the control's tapping cycle",
                          m_.name, k.sync_feed.empty() ? std::string("the synchronised feed") : k.sync_feed));
  if (k.tap == "expanded") {
    // G32 in, the spindle reversed at the bottom, G32 out, the spindle forward again.
    const bool ccw = last_speed_->dir == rotation::ccw;
    const int forward = ccw ? spindle_->ccw : spindle_->cw;
    const int reverse = ccw ? spindle_->cw : spindle_->ccw;
    to_hole(h, line);
    if (h.initial != h.clear) linear(true, h.x, h.y, h.clear, line);
    for (const auto& [z, m] : {std::pair{h.bottom, reverse}, std::pair{h.clear, forward}}) {
      text_buffer& b = out_.open_block();
      word_start_ = b.size();
      b += k.sync_feed;
      axis_word(b, 'Z', nc_z(z), last_z_, true);
      b += " F";
      append_number(b, h.pitch, {4, m_.program.trailing_point});
      out_.end_block();
      word_start_ = std::string::npos;
      out_.block(fmt::format("M{}", m));
    }
    motion_g_ = -1;
    last_f_.clear();
    if (h.initial != h.clear) linear(true, h.x, h.y, h.initial, line);
    return;
  }
  if (side_hole_ && (h.left || k.side_tap_code.empty()))
    return error(line, fmt::format("CYCLE/TAP across the spindle axis: machine '{}' gives no {} side tapping "
                                   "cycle (cycles.side_tap_code, right-hand only)",
                                   m_.name, h.left ? "left-hand" : "right-hand"));
  const std::string& code = side_hole_ ? k.side_tap_code : h.left ? k.tap_left_code : k.tap_code;
  if (code.empty())
    return error(line, fmt::format("CYCLE/TAP: a left-hand tap (LEFT, or the spindle turning CCLW), and "
                                   "machine '{}' gives no left-hand tapping cycle (cycles.tap_left_code)",
                                   m_.name));
  const bool was_per_rev = per_rev_;
  to_hole(h, line);
  feed_mode(true);
  if (k.tap == "rigid" && !k.rigid_code.empty())
    out_.block(fmt::format("{} S{}", k.rigid_code, format_nc_number(last_speed_->speed, {0, false})));
  hole at_speed = h;
  at_speed.dwell = 0;
  cycle_block(at_speed, code, 0, h.pitch, line);
  // Rigid tapping leaves the spindle in position mode: the CL's spindle again, then its feed mode.
  if (k.tap == "rigid")
    for (const std::string& b : restart_blocks_) spindle_block(b);
  feed_mode(was_per_rev);
}

}  // namespace twinpost
