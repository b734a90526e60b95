// channel_writer: live-tool work on a lathe channel with a C axis (mill/turn): the workpiece
// spindle held as a C axis, polar interpolation for face milling, holes at C positions (face
// and cross drilling), cylindrical interpolation for milling on the diameter and the indexing
// head (docs/machines.md, "Mill/turn").
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "machining/channel_writer.hpp"
#include "parser/cycle_words.hpp"

namespace twinpost {

namespace {
constexpr double along = 0.9999;   // |axis.z| at or above: along the spindle axis
constexpr double across = 1e-4;    // |axis.z| at or below: radial
constexpr double off_line = 1e-3;  // mm: a cross hole this far beside its radial line needs Y
constexpr double deg = 180.0 / std::numbers::pi;

// A length (mm) or an angle for a message, to the micron (0.001): "20", "1.25".
std::string microns(double v) { return fmt::format("{:g}", std::round(v * 1000) / 1000 + 0.0); }

double wrap_360(double a) {
  a = std::fmod(a, 360.0);
  if (a < 0) a += 360.0;
  if (a >= 360.0 - 5e-4) a = 0;  // 359.9999 is written as C0.
  return a;
}
}  // namespace

bool channel_writer::live_tool() const {
  return has_c_ && spindle_ && work_ && spindle_ != work_ && !restart_blocks_.empty();
}

bool channel_writer::enter_c_axis(int line) {
  if (c_mode_) return true;
  if (!work_ || !work_->c_axis.present()) {
    error(line, fmt::format("live-tool work on the {} spindle, which machine '{}' cannot hold as a C axis "
                            "(spindle.c_on): the part would be free to turn under the cutter",
                            work_ ? work_->name : std::string("workpiece"), m_.name));
    return false;
  }
  for (const std::string& b : work_->c_axis.on) out_.block(b);
  c_mode_ = true;
  c_clamped_ = false;
  last_c_.known = false;
  if (!m_.milling.radius_input.empty()) {
    for (const std::string& b : m_.milling.radius_input) out_.block(b);
    set_x_radius(true);
  }
  return true;
}

void channel_writer::leave_c_axis() {
  if (!c_mode_) return;
  leave_polar();
  leave_radial_frame();
  if (c_clamped_ && !work_->c_axis.unclamp.empty()) out_.block(work_->c_axis.unclamp);
  c_clamped_ = false;
  if (!m_.milling.diameter_input.empty()) {
    for (const std::string& b : m_.milling.diameter_input) out_.block(b);
    set_x_radius(false);
  }
  for (const std::string& b : work_->c_axis.off) out_.block(b);
  c_mode_ = false;
}

void channel_writer::set_x_radius(bool radius) {
  // X in radius (G10.9 X0) or diameter, keeping the mirror; the travel limits go with it.
  if (!x_diameter_) return;
  const double sign = x_factor_ < 0 ? -1.0 : 1.0;
  const double factor = radius ? 1.0 : 2.0;
  if (std::abs(x_factor_) == factor) return;
  x_factor_ = sign * factor;
  if (last_x_.lo != INT64_MIN) {
    last_x_.lo = radius ? last_x_.lo / 2 : last_x_.lo * 2;
    last_x_.hi = radius ? last_x_.hi / 2 : last_x_.hi * 2;
  }
  last_x_.known = false;
}

void channel_writer::enter_polar(const vec3& first, bool rapid) {
  // Y on the centre line first: the polar frame is the X-C plane through the spindle's axis,
  // and a Y left off it by an earlier tool (a flat, a hole off the centre line) would shift
  // every move of the mode by that much. Then the C axis at 0: the polar frame's X is the
  // part's X (UNVERIFIED in a Mazak manual; the Fusion Integrex post positions C before G12.1
  // as well).
  // A head's length offset due (the Integrex's `G43 H#3020` after its index) goes with it,
  // outside the mode: Fanuc's list of what G12.1 takes has no G43, and the Fusion Integrex post
  // gives the offset before G12.1 (review 54).
  // With the offset the block moves Z too (on a Fanuc-type control a G43 with no Z word moves Z
  // by the tool's length from where it stands, at home past its travel: review 55, M1): the
  // first point's height, and its radius at C0, so that the mode turns only C to reach it. A
  // first move the CL feeds keeps the offset (its block is a cut, not a rapid to its end).
  const bool offset = rapid && !pending_offset_.empty();
  // That block takes the tool to the first point's height: C turns to 0 before it, where the
  // tool stands (at home after the tool call and the head's index), not at that height
  // (review 56, M1: a first point 1 mm deep, and the part turned round the cutter).
  if (offset && has_y_) position_c(0);
  if (has_y_ && (!(last_y_.known && last_y_.n == 0) || offset)) {
    text_buffer& b = out_.open_block();
    word_start_ = b.size();
    b += "G0";
    motion_g_ = 0;
    if (offset) {
      add_offset_words(b);
      pending_offset_.clear();
      axis_word(b, 'X', nc_x(std::hypot(first.x, first.y)), last_x_, true);
    }
    axis_word(b, 'Y', 0.0, last_y_, true);
    if (offset) axis_word(b, 'Z', nc_z(first.z), last_z_, true);
    out_.end_block();
    word_start_ = std::string::npos;
    if (offset) homed_ = false;
  }
  position_c(0);
  // C free before the mode turns it (after a clamped hole, C may already stand at 0).
  if (c_clamped_) {
    out_.block(work_->c_axis.unclamp);
    c_clamped_ = false;
  }
  for (const std::string& b : m_.milling.polar_on) {
    out_.block(b);
    for (const char* g : {"G17", "G18", "G19"})
      if (b.find(g) != std::string::npos) plane_ = (g[2] - '0') + 10;
  }
  polar_ = true;
  motion_g_ = -1;
  last_y_.known = false;
}

void channel_writer::leave_polar() {
  if (!polar_) return;
  // Polar interpolation is set and cancelled with cutter compensation cancelled (review 38:
  // `G41 G1 X30.` stayed on through `G13.1` and the home blocks). Compensation the CL leaves on
  // is refused, and so is a CUTCOM/OFF with no move after it: the control takes the offset off
  // on a move, and a `G40` alone would shift the cutter by its radius where it stands, into the
  // wall it has just finished (review 38b P1; the Fusion Integrex post writes G40 only with a
  // feed move).
  if (comp_cl_on_ || pending_g_.starts_with("G40")) {
    error(line_, comp_cl_on_ ? "polar interpolation ends with cutter compensation on (CUTCOM/LEFT or RIGHT "
                               "without CUTCOM/OFF): it is cancelled with G40 in force; give CUTCOM/OFF and "
                               "a lead-out move before GOHOME, the tool change or the end of the face milling"
                             : "polar interpolation ends with CUTCOM/OFF given and no move after it: the "
                               "control takes the offset off on a move, and G40 alone would shift the cutter "
                               "by its radius where it stands; give a lead-out move after CUTCOM/OFF");
    comp_cl_on_ = false;  // (said once)
    pending_g_.clear();
  }
  for (const std::string& b : m_.milling.polar_off) out_.block(b);
  polar_ = false;
  motion_g_ = -1;
  last_y_.known = last_c_.known = false;
  for (const std::string& b : m_.milling.polar_off)
    for (const char* g : {"G17", "G18", "G19"})
      if (b.find(g) != std::string::npos) plane_ = (g[2] - '0') + 10;
}

void channel_writer::position_c(double degrees) {
  const double c = wrap_360(degrees);
  if (last_c_.known && std::abs(wrap_360(last_c_.value) - c) < 5e-4) return;
  if (c_clamped_) {
    out_.block(work_->c_axis.unclamp);
    c_clamped_ = false;
  }
  text_buffer& b = out_.open_block();
  word_start_ = b.size();
  b += "G0";
  motion_g_ = 0;
  axis_word(b, 'C', c, last_c_, true);
  out_.end_block();
  word_start_ = std::string::npos;
  c_cos_ = std::cos(c / deg);
  c_sin_ = std::sin(c / deg);
  if (c == 0) c_cos_ = 1, c_sin_ = 0;
  forget_axes();  // the part has turned under X and Y
}

void channel_writer::clamp_c() {
  if (c_clamped_ || work_->c_axis.clamp.empty()) return;
  out_.block(work_->c_axis.clamp);
  c_clamped_ = true;
  axes_free_ = false;
}

bool channel_writer::face_polar() const {
  // A drill's moves go to its holes: C positions, never the polar plane.
  return c_mode_ && m_.milling.face_milling == "polar" && std::abs(axis_.z) >= along &&
         kind_ != tool_kind::drill && !cycle_;
}

void channel_writer::polar_linear(bool rapid, const vec3& p, int line) {
  if (!polar_) enter_polar(p, rapid);
  if (c_clamped_) {
    out_.block(work_->c_axis.unclamp);
    c_clamped_ = false;
  }
  text_buffer& b = out_.open_block();
  word_start_ = b.size();
  if (!pending_g_.empty()) b += pending_g_;
  // A rapid is G0, or G1 at milling.polar_rapid_feed on a control that takes no G0 here.
  const bool g0 = rapid && m_.milling.polar_rapid_feed == 0;
  const int g = g0 ? 0 : 1;
  if (motion_g_ != g) {
    separate(b);
    b += g0 ? "G0" : "G1";
  }
  add_offset_words(b);
  // X and C here are the plane's Cartesian values: the real X is the radius hypot(x, y), held to
  // the axis's travel instead of the X word.
  const auto lo = last_x_.lo, hi = last_x_.hi;
  last_x_.lo = INT64_MIN, last_x_.hi = INT64_MAX;
  bool moved = axis_word(b, 'X', nc_x(p.x), last_x_);
  last_x_.lo = lo, last_x_.hi = hi;
  // The radius in the units of the X travel: X may be in diameter in the mode (Fanuc: X in
  // diameter, C, the hypothetical axis, in radius) or in radius (Integrex G10.9 X0).
  const double r = std::hypot(p.x, p.y) * scale_;
  if (const axis_def* x = ch_.axis('X'); x && x->max && r * (x_diameter_ ? 2 : 1) > *x->max) {
    out_.drop_block();
    word_start_ = std::string::npos;
    return error(line, fmt::format("polar interpolation to a radius of {} is outside channel {}'s X travel "
                                   "(channel.axis max {})",
                                   format_nc_number(r, axis_style_), ch_.number, *x->max));
  }
  moved = axis_word(b, 'C', nc_y(p.y), last_y_) || moved;  // the CL's Y: C's linear value (mm)
  moved = axis_word(b, 'Z', nc_z(p.z), last_z_) || moved;
  if (!moved) {
    out_.drop_block();
    word_start_ = std::string::npos;
    return;
  }
  homed_ = false;
  pending_g_.clear();
  pending_offset_.clear();
  motion_g_ = g;
  if (g0) {
  } else if (rapid) {
    const double f = m_.milling.polar_rapid_feed * out_per_mm_;
    text_buffer word;
    append_number(word, f, {feed_decimals(false), m_.program.trailing_point});
    if (std::string(word.view()) != last_f_) {
      separate(b);
      b += 'F';
      b += word.view();
      last_f_ = std::string(word.view());
    }
  } else if (feed_value_ > 0) {
    append_feed(b);
  } else {
    error(line, "feed move with no feed rate (FEDRAT) in force");
  }
  out_.end_block();
  word_start_ = std::string::npos;
}

std::string_view channel_writer::along_tool() const {
  if (!in_cut_ || tool_ < 0) return {};
  if (!x_diameter_ && !has_c_) {
    // A machining centre's tool: along Z, unless a head tilts it (a 5-axis head off 0: machine
    // Z is not its axis; attack 65). A turning tool of a lathe programmed in radius is not one.
    if (kind_ == tool_kind::turn) return {};
    if (chain_)
      for (std::size_t i = 0; i < chain_->rotaries.size(); ++i)
        if ((tilting_heads_ >> i & 1u) && std::abs(joints_.rotary[i]) > 1e-9) return {};
    return "Z";
  }
  // A drill along the spindle axis, on a turret or a head, the part turning against it or not
  // (review 64 H1: a centre drill 30 mm deep went home X first). Not on a spindle that faces
  // the main one (Z reversed): Z's home lies beyond its face, deeper into its part.
  const bool axial = std::abs(axis_.z) >= along;
  if (axial && work_ && work_->reverse_z) return {};  // (retract_facing)
  if (axial) return leaves_axially() ? "ZW" : "";
  if (std::abs(axis_.z) <= across && head_live()) return "XU";
  return {};
}

bool channel_writer::head_live() const {
  const bool live = spindle_ && work_ && spindle_ != work_;
  return ch_.head_index.present() && head_angle_ && live;
}

bool channel_writer::leaves_axially() const {
  return std::abs(axis_.z) >= along && (kind_ == tool_kind::drill || head_live());
}

void channel_writer::retract_facing() {
  if (!in_cut_ || tool_ < 0 || !work_ || !work_->reverse_z || !leaves_axially()) return;
  in_cut_ = false;
  if (errors_ > 0) return;  // (no file is written: a retract would only say the error again)
  // The most retracted level the tool stood at at rapid above the point it stands at (review
  // 38 H1: the last rapid may be an expanded peck's, inside the hole, or an R level in a
  // counterbore; attack 69 M2: not a level it only reached elsewhere, 400 mm out at the tool
  // change, which here would run it along the centre line towards the other spindle).
  const double up = axis_.z > 0 ? 1.0 : -1.0;
  std::optional<double> level;
  for (std::size_t i = 0; i < std::min(clear_n_, clear_at_.size()); ++i) {
    const vec3& r = clear_at_[i];
    if (std::abs(r.x - pos_.x) * cl_mm_ > 1e-3 || std::abs(r.y - pos_.y) * cl_mm_ > 1e-3) continue;
    if (!level || (r.z - *level) * up > 0) level = r.z;
  }
  if (level && (*level - pos_.z) * up <= 1e-6) return;  // the CL fed out to that level or above
  if (!level)
    return error(line_,
                 fmt::format("the tool is left in a cut on the {} spindle, which faces the main one, with "
                             "no retract in the CL and no rapid of this tool above that point on that "
                             "spindle to go back to: its home blocks would move it across its hole, then "
                             "towards that spindle; give the retract before GOHOME, the tool change or "
                             "the end",
                             work_->name));
  if (c_mode_ || polar_)
    return error(line_,
                 fmt::format("the tool is left in a cut on the {} spindle, which faces the main one, with "
                             "no retract in the CL, and the spindle is held as a C axis: the post does "
                             "not take it out there; give the retract before GOHOME, the tool change or "
                             "the end",
                             work_->name));
  // Back the way the tool came in, along its axis, to that level: as the CL's own retract would
  // be (F-INTGX keeps a separate Z home for the second spindle's work).
  motion_event mv;
  mv.rapid = true;
  mv.pos = {pos_.x, pos_.y, *level};
  motion(mv, line_);
  in_cut_ = false;
}

bool channel_writer::index_head(int line) {
  const head_index_rules& h = ch_.head_index;
  if (!h.present() || tool_ < 0) return true;
  // Where the tool must point: turning tools (and centre drills on the turning spindle) as
  // the channel turns, live tools along or across the spindle axis as the CL's axis says.
  const bool live = spindle_ && work_ && spindle_ != work_;
  const bool axial = std::abs(axis_.z) >= along;
  const bool radial = std::abs(axis_.z) <= across;
  // On a spindle that faces the main one (the sub, Z reversed) the head must turn to face it:
  // its own angles (Integrex B180), never the main spindle's, which point the tool away.
  const bool sub = work_ && work_->reverse_z;
  std::optional<double> want;
  const char* which;
  const bool turning = !live && kind_ != tool_kind::mill && !(kind_ == tool_kind::drill && axial);
  if (turning) {
    want = sub ? h.turning_sub : h.turning, which = "turning";
  } else if (axial) {
    want = sub ? h.axial_sub : h.axial, which = "axial";
  } else if (radial) {
    want = sub ? h.radial_sub : h.radial, which = "radial";
  } else {
    return true;  // a tilted axis: the move's own check refuses it
  }
  if (!want) {
    error(line,
          fmt::format("channel {} indexes its {} head for every tool, and channel.head_index.{}{} is not "
                      "given: where the {} tool must point{} is unknown",
                      ch_.number, h.address, which, sub ? "_sub" : "", which,
                      sub ? fmt::format(" on the {} spindle", work_->name) : ""));
    return false;
  }
  // The offset follows what turns: a tool that stands still while the part turns (a turning
  // tool, a drill on the centre line of the workpiece spindle) takes the turning form (Integrex
  // `G43 P1 H#3020`, as public Integrex posts give a turning section's tool, stationary drills
  // included); a tool its own spindle turns, the live form (issue 37, item 10).
  const bool stationary = !live && kind_ != tool_kind::mill;
  const std::string& offset = stationary ? h.offset_turning : h.offset_live;
  if (head_angle_ && std::abs(*head_angle_ - *want) < 5e-4) {
    if (after_index_)
      pending_offset_ = head_offset_chosen_ = offset;  // a new tool at the same angle: its own
    after_index_ = false;
    write_coolant_due();
    return true;
  }
  if (!homed_) {
    // The head never turns at the part: out to home first, then in again at the new angle.
    leave_polar();
    go_home();
    forget_axes();
    motion_g_ = -1;
  }
  if (!h.unclamp.empty()) out_.block(h.unclamp);
  text_buffer& b = out_.open_block();
  word_start_ = b.size();
  b += h.move;
  b += ' ';
  b += h.address;
  append_number(b, *want, axis_style_);
  out_.end_block();
  word_start_ = std::string::npos;
  if (!h.clamp.empty()) out_.block(h.clamp);
  axes_free_ = false;
  head_angle_ = want;
  motion_g_ = -1;  // the move block was G0 in machine coordinates
  pending_offset_ = head_offset_chosen_ = offset;
  after_index_ = false;
  write_coolant_due();
  return true;
}

void channel_writer::add_offset_words(text_buffer& b) {
  if (pending_offset_.empty()) return;
  separate(b);
  b += pending_offset_;
}

bool channel_writer::c_axis_hole(const vec3& p) {
  // An axial hole off centre: C turns it onto the X axis, where X is its radius.
  if (!(c_mode_ && m_.milling.face_holes == "c_axis" && std::abs(axis_.z) >= along)) return false;
  if (std::hypot(p.x, p.y) * cl_mm_ <= 1e-3) return false;  // on the centre line: as always
  leave_polar();
  leave_radial_frame();
  c_hole_deg_ = std::atan2(p.y, p.x) * deg;
  return true;
}

bool channel_writer::c_frame_move(bool rapid, double& x, double& y, double& z, int line) {
  if (!index_head(line)) return false;
  if (!c_mode_) return tool_along_z(line);  // turning: as on any lathe channel
  const bool axial = std::abs(axis_.z) >= along;
  const bool radial = std::abs(axis_.z) <= across;
  if (axial && face_polar() && live_tool()) {
    leave_radial_frame();
    polar_linear(rapid, {x, y, z}, line);
    return false;
  }
  leave_polar();
  if (radial && side_holes()) return side_move(rapid, x, y, z, line);  // Fanuc: along X at a C position
  if (radial) {
    // The tool points across the spindle axis: C turns the part so that it points along the
    // turned frame's Z. A hole's own moves come in that frame already.
    if (radial_ok_) return true;
    if (!rapid) return cylinder_feed(x, y, z, line);
    leave_cylinder();  // no G0 in cylindrical interpolation: the rapid is the turned frame's
    vec3 q;
    if (!radial_point({x, y, z}, q, line)) return false;
    x = q.x, y = q.y, z = q.z;
    return true;
  }
  leave_radial_frame();
  if (!axial) {
    return tool_along_z(line);  // tilted: refused
  } else if (!last_c_.known) {
    position_c(0);
  }
  auto [u, v] = c_frame(x, y);
  // A drill's rapid to a hole off the X axis on a machine that drills face holes at C
  // positions turns C to it rather than moving Y (with C still at the last hole's angle, the
  // approach would cross the centre line in Y).
  const bool xzc = rapid && m_.milling.face_holes == "c_axis" && kind_ == tool_kind::drill;
  if ((!has_y_ || xzc) && std::abs(v) * cl_mm_ > 1e-4) {
    if (!rapid || radial) {
      error(line, fmt::format("a feed move to Y {} in the frame of C{} on a channel without a Y axis: it "
                              "needs polar interpolation (milling.face_milling = \"polar\")",
                              v, format_nc_number(last_c_.value, axis_style_)));
      return false;
    }
    // A rapid in XZC: C first, then X as the radius. A rapid that also rises (out of a hole
    // drilled with moves, up to the CL's clearance) rises first: the part turns with the tip as
    // high as the CL's move goes, not at the bottom it leaves (attack 60 F4; the comparison
    // holds it to that: docs/emulator.md, "A C turn").
    const double to_z = nc_z(z);
    const double up = (to_z - last_z_.value) * z_sign_ * (axis_.z < 0 ? -1.0 : 1.0);
    if (last_z_.known && pending_g_.empty() && pending_offset_.empty() && up > 0 &&
        !(last_c_.known && std::abs(wrap_360(last_c_.value) - wrap_360(std::atan2(y, x) * deg)) < 5e-4)) {
      text_buffer& b = out_.open_block();
      word_start_ = b.size();
      b += "G0";
      motion_g_ = 0;
      axis_word(b, 'Z', to_z, last_z_);
      homed_ = false;
      out_.end_block();
      word_start_ = std::string::npos;
    }
    position_c(std::atan2(y, x) * deg);
    std::tie(u, v) = c_frame(x, y);
  }
  // A drill fed at a C position (a hole drilled with moves, not a canned cycle) holds the part
  // with C clamped, as a cycle does (review 61 B3; the Fusion "Mazak Integrex i" post clamps C
  // for its C-axis positioning).
  if (!rapid && m_.milling.face_holes == "c_axis" && kind_ == tool_kind::drill) clamp_c();
  x = u;
  y = v;
  return true;
}

bool channel_writer::enter_radial_frame(double degrees, int line) {
  // The Fusion Integrex post's indexed cross drilling: C to the hole's angle and clamped, then
  // the frame turned about Y so that the tool axis is Z (G68 ... R90.).
  if (m_.milling.radial_frame_on.empty()) {
    error(line, fmt::format("a move with the tool across the spindle axis: machine '{}' gives no frame for "
                            "it (milling.radial_frame_on), so cross holes cannot be posted",
                            m_.name));
    return false;
  }
  if (std::abs(x_factor_) != 1.0) {
    error(line, "a move with the tool across the spindle axis needs X in radius (milling.radius_input)");
    return false;
  }
  const double c = wrap_360(degrees);
  // After cylindrical interpolation C may stand past 360 (continuous): the same angle.
  if (radial_frame_ && last_c_.known && std::abs(wrap_360(last_c_.value) - c) < 5e-4) return true;
  leave_radial_frame();
  position_c(c);
  clamp_c();
  for (const std::string& b : m_.milling.radial_frame_on) out_.block(b);
  radial_frame_ = true;
  // X is now the part's -Z: its lathe travel limits do not apply.
  saved_x_limits_ = {last_x_.lo, last_x_.hi};
  last_x_.lo = INT64_MIN;
  last_x_.hi = INT64_MAX;
  forget_axes();
  motion_g_ = -1;
  return true;
}

void channel_writer::leave_radial_frame() {
  leave_cylinder();
  if (!radial_frame_) return;
  for (const std::string& b : m_.milling.radial_frame_off) out_.block(b);
  radial_frame_ = false;
  last_x_.lo = saved_x_limits_.first;
  last_x_.hi = saved_x_limits_.second;
  forget_axes();
  motion_g_ = -1;
}

bool channel_writer::radial_point(const vec3& p, vec3& q, int line) {
  leave_cylinder();
  const double a = std::atan2(axis_.y, axis_.x);
  if (!enter_radial_frame(a * deg, line)) return false;
  // In the turned frame: X the part's -Z, Y the distance beside the radial line, Z the radius.
  const double ca = std::cos(a), sa = std::sin(a);
  q = {-p.z, -p.x * sa + p.y * ca, p.x * ca + p.y * sa};
  return true;
}

bool channel_writer::cylinder_feed(double& x, double& y, double& z, int line) {
  // Milling on the diameter (docs/machines.md, "Mill/turn"): the tool along the radius through
  // its point, the part turned by C under it. Fanuc's cylindrical interpolation (G7.1, 15i-MA
  // B-63324EN/03 §4; 16i/18i/21i-TB) takes the cylinder's radius, C in degrees, no G0 inside and
  // cutter compensation started and ended inside. A cut keeps the tip on one cylinder, whose
  // radius the mode is opened with, so F is the CL's feed at the tip; plunges and retracts go
  // along the radius (the turned frame's Z).
  if (m_.milling.cylindrical_on.empty()) {
    if (refused_axis_ && refused_axis_->x == axis_.x && refused_axis_->y == axis_.y) return false;
    refused_axis_ = axis_;  // once per tool axis, as tool_along_z
    error(line, fmt::format("a feed move with the tool across the spindle axis (milling on the diameter): "
                            "machine '{}' gives no cylindrical interpolation (milling.cylindrical_on), so it "
                            "cannot be posted",
                            m_.name));
    return false;
  }
  if (z_sign_ < 0 || work_->name == "sub") {
    error(line, fmt::format("a feed move with the tool across the spindle axis on the {} spindle: twinpost "
                            "writes cylindrical interpolation on the main spindle only (the second spindle's "
                            "C turns the other way)",
                            work_->name));
    return false;
  }
  const double a = std::atan2(axis_.y, axis_.x);
  const double ca = std::cos(a), sa = std::sin(a);
  const double beside = (-x * sa + y * ca) * cl_mm_, out = (x * ca + y * sa) * cl_mm_;
  if (std::abs(beside) > 1e-3 || out <= 1e-3) {
    if (refused_axis_ && refused_axis_->x == axis_.x && refused_axis_->y == axis_.y) return false;
    refused_axis_ = axis_;  // once per tool axis: a flat milled across the axis is one error
    error(line,
          fmt::format("a feed move across the spindle axis to X {} Y {}, which the tool axis ({:g},{:g},"
                      "{:g}) does not point at along the radius ({} mm beside it): cylindrical "
                      "interpolation moves the tool along the radius through its point only",
                      x, y, axis_.x, axis_.y, axis_.z, microns(beside)));
    return false;
  }
  const vec3 from = pos_;
  const double r = std::hypot(x, y) * cl_mm_, r0 = std::hypot(from.x, from.y) * cl_mm_;
  const double a0 = std::atan2(from.y, from.x);
  // Where the tool is: on the radius the turned frame (or the mode) stands at.
  // With the side cycles (Fanuc) there is no turned frame: C stands at the tool's angle.
  const bool side = side_holes();
  if (!(radial_frame_ || side) || !last_c_.known || r0 <= 1e-3 ||
      r0 * std::abs(std::remainder(a0 * deg - last_c_.value, 360.0)) / deg > 1e-3) {
    error(line,
          "a feed move across the spindle axis from a point the tool was not taken to along its "
          "radius: start a cut on the diameter with a RAPID under the same tool axis");
    return false;
  }
  const double turn = std::remainder((std::atan2(y, x) - a0) * deg, 360.0);  // degrees, -180..180
  const double dz = (z - from.z) * cl_mm_;
  const bool along_radius = std::abs(dz) <= 1e-4 && r * std::abs(turn) / deg <= 1e-4;
  if (along_radius && !cylinder_) {
    // A plunge (or retract) before the cut: in the turned frame, C clamped.
    if (comp_starting()) {
      error(line, fmt::format("cutter compensation ({}) would start outside cylindrical interpolation, on "
                              "a plunge: it must start and end inside the mode (Fanuc 15i-MA B-63324EN/03 "
                              "§4): put CUTCOM after the plunge",
                              pending_g_));
      return false;
    }
    clamp_c();
    if (side)
      x = out / cl_mm_, y = beside / cl_mm_;  // along X at the hole's Z (Fanuc: X the diameter)
    else
      x = -z, y = beside / cl_mm_, z = out / cl_mm_;
    return true;
  }
  if (!along_radius) {
    if (std::abs(r - r0) > 1e-3) {
      error(line, fmt::format("a cut across the spindle axis changes the tip's radius from {} to {} mm: "
                              "cylindrical interpolation keeps the tip on one cylinder; only a plunge or a "
                              "retract along the radius (C and Z still) may change it",
                              microns(r0), microns(r)));
      return false;
    }
    if (std::abs(turn) >= 179.999) {
      error(line,
            fmt::format("a cut across the spindle axis turns the part {} degrees in one move: which way "
                        "round is not known; give points less than half a turn apart",
                        microns(std::abs(turn))));
      return false;
    }
    if (cylinder_ && std::abs(cylinder_r_ - r) > 5e-4) leave_cylinder();  // a new depth: a new cylinder
    if (!cylinder_) enter_cylinder(r);
  }
  text_buffer& b = out_.open_block();
  word_start_ = b.size();
  if (!pending_g_.empty()) b += pending_g_;
  if (motion_g_ != 1) {
    separate(b);
    b += "G1";
  }
  bool moved = false;
  if (side) {
    // The lathe's own axes: Z along the part, C in degrees, X the diameter (Fanuc G7.1 on a
    // lathe: the cylinder in the Z-C plane).
    moved = axis_word(b, 'Z', nc_z(z), last_z_);
    if (!along_radius) {
      cylinder_c_ += turn;
      moved = axis_word(b, 'C', cylinder_c_, last_c_) || moved;
    }
    moved = axis_word(b, 'X', nc_x(std::hypot(x, y)), last_x_) || moved;
  } else {
    moved = axis_word(b, 'X', nc_x(-z), last_x_);
    if (!along_radius) {
      cylinder_c_ += turn;
      moved = axis_word(b, 'C', cylinder_c_, last_c_) || moved;
    }
    moved = axis_word(b, 'Z', nc_z(std::hypot(x, y)), last_z_) || moved;  // the turned frame's Z: the radius
  }
  if (!moved) {
    out_.drop_block();
    word_start_ = std::string::npos;
    return false;
  }
  if (comp_starting()) cylinder_comp_ = true;
  if (pending_g_ == "G40") cylinder_comp_ = false;
  homed_ = false;
  pending_g_.clear();
  motion_g_ = 1;
  cut_feed(b, line);
  out_.end_block();
  word_start_ = std::string::npos;
  return false;
}

void channel_writer::enter_cylinder(double radius) {
  // C turns in the mode: unclamped first (Mazak M212), then the mode with its radius.
  if (c_clamped_) {
    out_.block(work_->c_axis.unclamp);
    c_clamped_ = false;
  }
  for (const std::string& block : m_.milling.cylindrical_on) {
    std::string b = block;
    for (const auto& [hole, factor] : {std::pair{std::string_view("{radius}"), 1.0}, {"{diameter}", 2.0}})
      if (const std::size_t at = b.find(hole); at != std::string::npos) {
        text_buffer w;
        append_number(w, radius * factor * out_per_mm_, axis_style_);
        b.replace(at, hole.size(), w.view());
      }
    out_.block(b);
    for (const char* g : {"G17", "G18", "G19"})
      if (b.find(g) != std::string::npos) plane_ = (g[2] - '0') + 10;
  }
  cylinder_ = true;
  cylinder_r_ = radius;
  cylinder_c_ = last_c_.value;
  cylinder_comp_ = false;
  motion_g_ = -1;
}

void channel_writer::leave_cylinder() {
  if (!cylinder_) return;
  if (cylinder_comp_)
    error(line_,
          "cutter compensation is still on where cylindrical interpolation ends: it must start and "
          "end inside the mode (Fanuc 15i-MA B-63324EN/03 §4): give CUTCOM/OFF before the retract");
  cylinder_comp_ = false;
  for (const std::string& b : m_.milling.cylindrical_off) {
    out_.block(b);
    for (const char* g : {"G17", "G18", "G19"})
      if (b.find(g) != std::string::npos) plane_ = (g[2] - '0') + 10;
  }
  cylinder_ = false;
  motion_g_ = -1;
  // The part stands where the last cut turned it: the C frame of the moves after follows.
  c_cos_ = std::cos(cylinder_c_ / deg);
  c_sin_ = std::sin(cylinder_c_ / deg);
}

bool channel_writer::millturn_to_multiaxis(int line) {
  // A tilted tool on the mill/turn head: the multi-axis writer turns B and C together, so the
  // spindle must be held as C, the modes of this file ended and both axes unclamped (the
  // Fusion Integrex post's UNLOCK_MULTI_AXIS: M108, then M212).
  if (!c_mode_) {
    error(line,
          fmt::format("a tilted tool axis ({:g},{:g},{:g}) needs a live tool with the spindle held as the "
                      "C axis (SPINDL on the live spindle)",
                      axis_.x, axis_.y, axis_.z));
    return false;
  }
  leave_polar();
  leave_radial_frame();
  if (!axes_free_) {  // once for a stretch of tilted moves; clamping again ends it
    if (!ch_.head_index.unclamp.empty()) out_.block(ch_.head_index.unclamp);
    if (!work_->c_axis.unclamp.empty()) out_.block(work_->c_axis.unclamp);
    axes_free_ = true;
  }
  c_clamped_ = false;
  head_angle_.reset();  // B and C are the multi-axis writer's now: index and position again after
  last_c_.known = false;
  return true;
}

}  // namespace twinpost
