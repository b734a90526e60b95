// channel_writer: straight moves, arcs in the XZ plane, drilling cycles expanded to moves.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "formats/channel_writer.hpp"

namespace twinpost {

namespace {
constexpr double y_tolerance = 1e-4;
}

void channel_writer::append_feed(text_buffer& out) {
  // The F word is modal: formatted once per feed value, written when it changes.
  if (feed_value_ != feed_text_value_ || per_rev_ != feed_text_per_rev_) {
    feed_text_.clear();
    append_number(feed_text_, feed_value_, {per_rev_ ? 4 : 1, m_.program.trailing_point});
    feed_text_value_ = feed_value_;
    feed_text_per_rev_ = per_rev_;
  }
  if (feed_text_ == last_f_) return;
  separate(out);
  out += 'F';
  out += feed_text_;
  last_f_ = feed_text_;
}

void channel_writer::linear(bool rapid, double x_cl, double y_cl, double z_cl, int line) {
  if (!has_y_ && std::abs(y_cl * scale_) > y_tolerance)
    return error(line, fmt::format("Y {} on a channel without a Y axis", y_cl));
  int g = rapid ? 0 : 1;
  if (rapid && !m_.codes.cutcom_on_rapid && (pending_g_ == "G41" || pending_g_ == "G42"))
    return error(line, fmt::format("tool nose radius compensation ({}) would start on a rapid move; machine "
                                   "'{}' starts it only on a feed move (codes.cutcom_on_rapid = false): make "
                                   "the first move after CUTCOM a feed move",
                                   pending_g_, m_.name));
  check_side(nc_x(x_cl), x_cl, line);
  if (!rapid && !drill_on_centre(x_cl, line)) return;
  // Built in place, in the writer's buffer: the most common block goes out without a copy.
  text_buffer& b = out_.open_block();
  word_start_ = b.size();
  if (!pending_g_.empty()) b += pending_g_;
  if (g != motion_g_) {
    separate(b);
    b += rapid ? "G0" : "G1";
  }
  bool moved = axis_word(b, 'X', nc_x(x_cl), last_x_);
  if (has_y_) moved = axis_word(b, 'Y', nc_y(y_cl), last_y_) || moved;
  moved = axis_word(b, 'Z', nc_z(z_cl), last_z_) || moved;
  if (moved) {
    homed_ = false;
    pending_g_.clear();
    motion_g_ = g;
    if (!rapid && feed_value_ > 0)
      append_feed(b);
    else if (!rapid)
      error(line, "feed move with no feed rate (FEDRAT) in force");
    out_.end_block();
  } else {
    out_.drop_block();  // already there: nothing to write, the modal codes wait for a move
  }
  word_start_ = std::string::npos;
}

void channel_writer::no_tool(int line) {
  // The turret's tool and offset would be whatever the last program left: a move with no tool
  // call (HEAD/BOTH's second channel, a job that starts moving before LOADTL) is refused.
  error(line, "a move with no tool called in this channel: give LOADTL or TURRET before the first move");
}

void channel_writer::motion(const motion_event& mv, int line) {
  switch (mv.kind) {
    case motion_kind::from: pos_ = mv.pos; return;
    case motion_kind::home:
      go_home();
      forget_axes();
      motion_g_ = -1;
      pos_ = mv.pos;
      return;
    case motion_kind::go_to:
    case motion_kind::delta:
      if (tool_ < 0) return no_tool(line);
      if (spindle_held_) resume_spindle(line);
      if (cycle_) {
        cycle_point(mv.pos, line);
      } else {
        linear(mv.rapid, mv.pos.x, mv.pos.y, mv.pos.z, line);
      }
      pos_ = mv.pos;
      return;
  }
}

void channel_writer::arc(const arc_event& a, int line) {
  if (tool_ < 0) return no_tool(line);
  if (spindle_held_) resume_spindle(line);
  // The plane comes from the arc's axis: +-Z G17 (XY), +-Y G18 (ZX, the lathe's), +-X G19 (YZ).
  // In each, counter-clockwise about the positive axis is G3 (Z = X x Y, Y = Z x X, X = Y x Z).
  double nlen = std::sqrt(a.normal.x * a.normal.x + a.normal.y * a.normal.y + a.normal.z * a.normal.z);
  auto along = [&](double c) { return nlen > 0 && std::abs(std::abs(c) / nlen - 1) <= 1e-6; };
  int plane = along(a.normal.z) ? 17 : along(a.normal.y) ? 18 : along(a.normal.x) ? 19 : 0;
  auto fail = [&](std::string message) {
    error(line, std::move(message));
    pos_ = a.end;
  };
  auto fail_quietly = [&] { pos_ = a.end; };
  if (plane == 0)
    return fail(fmt::format("arc about ({},{},{}) is not in the XY, ZX or YZ plane", a.normal.x, a.normal.y,
                            a.normal.z));
  if (plane != 18 && !has_y_)
    return fail(fmt::format("arc in the {} plane on a channel without a Y axis", plane == 17 ? "XY" : "YZ"));
  if (!has_y_ && std::abs(a.end.y * scale_) > y_tolerance)
    return fail(fmt::format("Y {} on a channel without a Y axis", a.end.y));
  if (a.turns > 0) {
    // TIMES,n repeats a full circle: the move must end where it starts.
    const double gap = std::max({std::abs(a.end.x - a.start.x), std::abs(a.end.y - a.start.y),
                                 std::abs(a.end.z - a.start.z)}) *
                       scale_;
    if (gap > y_tolerance)
      return fail(
          fmt::format("CIRCLE TIMES {}: the move must end where it starts to be repeated as full "
                      "circles (it ends {} mm away)",
                      a.turns, gap));
  }
  check_side(nc_x(a.end.x), a.end.x, line);
  double axis_sign = plane == 17 ? a.normal.z : plane == 18 ? a.normal.y : a.normal.x;
  bool ccw = a.ccw == (axis_sign > 0);
  // Mirroring X reflects the XY and ZX planes, which reverses their sense; YZ has no X.
  double mirror = mirrored() ? -1.0 : 1.0;
  if (mirror < 0 && plane != 19) ccw = !ccw;
  // A reversed spindle's half turn about X turns the XY and ZX planes over (G2/G3 swap, J and
  // K negated); the YZ plane keeps its sense.
  if (z_sign_ < 0 && plane != 19) ccw = !ccw;
  int g = ccw ? 3 : 2;

  arc_.clear();
  if (!pending_g_.empty()) arc_ += ' ', arc_ += pending_g_;
  if (plane != plane_) {
    arc_ += fmt::format(" G{}", plane);
    plane_ = plane;
  }
  arc_ += g == 3 ? " G3" : " G2";
  // Both axes of the plane always; the third only when it moves (a helix).
  axis_word(arc_, 'X', nc_x(a.end.x), last_x_, plane != 19);
  if (plane != 18 || has_y_) axis_word(arc_, 'Y', nc_y(a.end.y), last_y_, plane != 18);
  axis_word(arc_, 'Z', nc_z(a.end.z), last_z_, plane != 17);

  // In-plane coordinates of start and end about the centre, (u, v) with the normal = u x v.
  auto uv = [&](const vec3& p) -> std::pair<double, double> {
    vec3 d{p.x - a.center.x, p.y - a.center.y, p.z - a.center.z};
    if (plane == 17) return {d.x, d.y};
    if (plane == 18) return {d.z, d.x};
    return {d.y, d.z};
  };
  if (m_.program.arcs_ijk) {
    // I, J, K run from the start point to the centre; I is a radius value in the channel's X sense.
    auto offset = [&](char address, double v) {
      if (!fits(address, v * scale_, axis_style_.decimals)) return;
      arc_ += ' ';
      arc_ += address;
      append_number(arc_, v * scale_, axis_style_);
    };
    if (plane != 19) offset('I', (a.center.x - a.start.x) * mirror);
    if (plane != 18) offset('J', (a.center.y - a.start.y) * z_sign_);
    if (plane != 17) offset('K', (a.center.z - a.start.z) * z_sign_);
  } else {
    auto [su, sv] = uv(a.start);
    auto [eu, ev] = uv(a.end);
    if (std::abs(su - eu) < 1e-9 && std::abs(sv - ev) < 1e-9)
      return fail("a full circle cannot be written with R; the machine must take I/K arcs");
    // The long way round (over 180 degrees) takes a negative R.
    bool short_way_ccw = su * ev - sv * eu > 0;
    bool over_half = short_way_ccw != (a.ccw == (axis_sign > 0));
    const double r = (over_half ? -1 : 1) * a.radius * scale_;
    if (!fits('R', r, axis_style_.decimals)) return fail_quietly();
    arc_ += " R";
    append_number(arc_, r, axis_style_);
  }
  if (feed_value_ > 0)
    append_feed(arc_);
  else
    error(line, "arc with no feed rate (FEDRAT) in force");
  pending_g_.clear();
  motion_g_ = g;
  homed_ = false;
  // A full circle TIMES n: the same block n times, one turn each.
  for (int turn = 0; turn < std::max(1, a.turns); ++turn) out_.block(arc_.view().substr(1));
  pos_ = a.end;
}

bool channel_writer::cycle_supported(const cycle_event& c, int line) {
  // Drilling is written as plain moves (below): a tap, a bore, a ream or a thread cycle
  // written that way would break the tool or mark the bore, so only what the moves really
  // do is taken, and anything else stops the post at the CYCLE record.
  if (c.type != "DRILL" && c.type != "DEEP") {
    error(line,
          fmt::format("CYCLE/{} is not supported by the post: only DRILL and DEEP are written (as plain "
                      "G0/G1 moves); a tapping, boring or threading cycle cannot be",
                      c.type));
    return false;
  }
  static constexpr std::string_view known[] = {"FEDTO", "DEPTH", "RAPTO", "CLEAR", "STEP",
                                               "MMPR",  "IPR",   "MMPM",  "IPM"};
  for (const auto& [name, value] : c.params) {
    const bool pecks_ignored = name == "STEP" && c.type != "DEEP";  // only DEEP is written in pecks
    if (!pecks_ignored && std::find(std::begin(known), std::end(known), name) != std::end(known)) continue;
    error(line,
          fmt::format("CYCLE/{}: {} is not carried out by the post (it knows FEDTO, DEPTH, RAPTO, CLEAR, "
                      "STEP and the feed)",
                      c.type, name));
    return false;
  }
  if (!c.words.empty() || !c.positional.empty()) {
    error(line,
          fmt::format("CYCLE/{}: {} is not carried out by the post (it knows FEDTO, DEPTH, RAPTO, CLEAR, "
                      "STEP and the feed, each with its value)",
                      c.type,
                      c.words.empty() ? fmt::format("the value {}", c.positional.front()) : c.words.front()));
    return false;
  }
  return true;
}

void channel_writer::cycle_point(const vec3& p, int line) {
  // Drilling along the spindle axis, written as plain moves every control reads: rapid to
  // the clearance plane, feed to depth (in pecks with STEP), rapid back out. The tool axis
  // says which way is into the part: -Z for a tool looking down +Z, +Z for one facing back.
  const cycle_event& c = *cycle_;
  auto param = [&](std::string_view name) -> std::optional<double> {
    for (const auto& [k, v] : c.params)
      if (k == name) return v;
    return std::nullopt;
  };
  // Only along the spindle axis: a radial or tilted tool (cross drilling with a live tool)
  // would be fed along Z, through the side of the part.
  if (std::abs(axis_.z) < 0.9999)
    return error(line,
                 fmt::format("CYCLE/{} with the tool axis ({}, {}, {}): only drilling along Z is written; "
                             "cross and tilted drilling is not supported yet",
                             c.type, axis_.x, axis_.y, axis_.z));
  double into = axis_.z < 0 ? 1.0 : -1.0;  // the direction of drilling along Z
  double clear = p.z - into * param("RAPTO").value_or(param("CLEAR").value_or(0));
  std::optional<double> bottom = param("FEDTO");
  if (!bottom && param("DEPTH")) bottom = p.z + into * *param("DEPTH");
  if (!bottom) return error(line, fmt::format("CYCLE/{} needs FEDTO or DEPTH", c.type));
  // FEDTO is a Z here; a dialect that writes it as a depth below the hole (SolidWorks CAM)
  // puts it behind the clearance plane, and the drill would feed away from the part.
  if ((*bottom - clear) * into <= 0)
    return error(line,
                 fmt::format("CYCLE/{}: the bottom Z {} is not beyond the clearance plane Z {} in the "
                             "drilling direction: the tool would feed away from the part (is FEDTO a depth "
                             "in this CL?)",
                             c.type, *bottom, clear));
  for (const char* unit : {"MMPR", "IPR", "MMPM", "IPM"}) {
    if (auto f = param(unit)) {
      const bool per_rev = std::string_view(unit).back() == 'R';
      const double value = *f * ((unit[0] == 'I') ? 25.4 : 1.0);
      if (!fits('F', value, per_rev ? 4 : 1)) return;
      feed_value_ = value;
      feed_mode(per_rev);
    }
  }
  double step = param("STEP").value_or(0);
  // A peck count past any real hole (a depth of 1e300 or a STEP of 1e-9) would write moves
  // without end: refuse it before the first move.
  constexpr double max_pecks = 10000;
  if (step > 0 && c.type == "DEEP" && !(std::abs(*bottom - clear) / step <= max_pecks))
    return error(line, fmt::format("CYCLE/DEEP: a depth of {} in pecks of STEP {} makes more than {} pecks",
                                   std::abs(*bottom - clear), step, max_pecks));
  linear(true, p.x, p.y, clear, line);
  double z = clear;
  if (step > 0 && c.type == "DEEP") {
    while ((*bottom - (z + into * step)) * into > 0) {
      z += into * step;
      linear(false, p.x, p.y, z, line);
      linear(true, p.x, p.y, clear, line);
      linear(true, p.x, p.y, z - into * 0.5 / scale_, line);  // back down near the last depth
    }
  }
  linear(false, p.x, p.y, *bottom, line);
  linear(true, p.x, p.y, clear, line);
}

}  // namespace twinpost
