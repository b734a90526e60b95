// channel_writer: straight moves and arcs in the XZ plane (cycles: channel_cycles.cpp).
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "machining/channel_writer.hpp"

namespace twinpost {

namespace {
constexpr double y_tolerance = 1e-4;
// How far the end of an arc may lie off the circle of its start (output units): the CAM's
// rounding of its points (4 decimals) is far below it, and a control's own tolerance (Fanuc's
// arc radius error parameter) is of its order.
constexpr double arc_radius_tolerance = 0.01;
}  // namespace

void channel_writer::append_feed(text_buffer& out) {
  // The F word is modal: formatted once per feed value, written when it changes.
  if (feed_value_ != feed_text_value_ || per_rev_ != feed_text_per_rev_) {
    feed_text_.clear();
    append_number(feed_text_, feed_value_, {feed_decimals(per_rev_), m_.program.trailing_point});
    feed_text_value_ = feed_value_;
    feed_text_per_rev_ = per_rev_;
  }
  if (feed_text_ == last_f_) return;
  separate(out);
  out += 'F';
  out += feed_text_;
  last_f_ = feed_text_;
}

void channel_writer::cut_feed(text_buffer& out, int line) {
  if (feed_value_ > 0)
    append_feed(out);
  else
    error(line, "feed move with no feed rate (FEDRAT) in force");
  spindle_turning(line);
}

bool channel_writer::tool_along_z(int line) {
  if (axis_.z >= 0.9999) return true;  // the drilling cycles' rule too
  // A machining centre without rotary axes holds its tool pointing down: a CL axis of -Z is a
  // tool pointing up, and every point written for it lies on the wrong side of the cut (an
  // MCS with Z down turned into the absolute frame, a CAM frame upside down). A lathe's tool
  // axis says nothing of the turret: it passes.
  if (axis_.z <= -0.9999 && (chain_ || !part_stands_still())) return true;
  if (refused_axis_ && refused_axis_->x == axis_.x && refused_axis_->y == axis_.y &&
      refused_axis_->z == axis_.z)
    return false;
  if (axis_.z <= -0.9999) {
    refused_axis_ = axis_;
    error(line,
          fmt::format("tool axis ({:g},{:g},{:g}) points the tool up, and machine '{}' gives channel {} "
                      "no rotary axes to turn it: the points were written for a tool coming from "
                      "below (is the CL's frame turned? NX MSYS: [program] cl_frame, post --cl-frame)",
                      axis_.x, axis_.y, axis_.z, m_.name, ch_.number));
    return false;
  }
  if (refused_axis_ && refused_axis_->x == axis_.x && refused_axis_->y == axis_.y &&
      refused_axis_->z == axis_.z)
    return false;
  refused_axis_ = axis_;
  error(line, fmt::format(
                  "tool axis ({:g},{:g},{:g}) is not along Z, and machine '{}' gives channel {} no kinematic "
                  "chain ([[kinematics]]): without rotary axes a tilted or radial tool cannot be posted",
                  axis_.x, axis_.y, axis_.z, m_.name, ch_.number));
  return false;
}

void channel_writer::linear(bool rapid, double x_cl, double y_cl, double z_cl, int line) {
  if (has_c_) {
    if (!c_frame_move(rapid, x_cl, y_cl, z_cl, line)) return;
  } else if (!plane_hole_ && !tool_along_z(line)) {  // a hole in a plane comes in the plane's frame
    return;
  }
  if (!has_y_ && std::abs(y_cl * cl_mm_) > y_tolerance)
    return error(line, fmt::format("Y {} on a channel without a Y axis", y_cl));
  int g = rapid ? 0 : 1;
  if (comp_on_rapid_refused(rapid, line)) return;
  if (!radial_frame_) check_side(nc_x(x_cl), x_cl, line);
  if (!rapid && !drill_on_centre(x_cl, line)) return;
  // Built in place, in the writer's buffer: the most common block goes out without a copy.
  // No G word and no offset: the block is axis words and a feed, which the line hook need not
  // read (plain_block_); a filter may replace it, so not with one.
  const bool plain = pending_g_.empty() && pending_offset_.empty() && g == motion_g_ && !out_.has_filter();
  text_buffer& b = out_.open_block();
  word_start_ = b.size();
  if (!pending_g_.empty()) b += pending_g_;
  if (g != motion_g_ || !pending_offset_.empty()) {  // G0 G43 ...: the offset's move says its G
    separate(b);
    b += rapid ? "G0" : "G1";
  }
  add_offset_words(b);
  bool moved = axis_word(b, 'X', nc_x(x_cl), last_x_);
  if (has_y_) moved = axis_word(b, 'Y', nc_y(y_cl), last_y_) || moved;
  moved = axis_word(b, 'Z', nc_z(z_cl), last_z_) || moved;
  if (moved) {
    homed_ = false;
    pending_g_.clear();
    pending_offset_.clear();
    motion_g_ = g;
    if (!rapid) cut_feed(b, line);
    plain_block_ = plain;
    out_.end_block();
    plain_block_ = false;
  } else {
    out_.drop_block();  // already there: nothing to write, the modal codes wait for a move
  }
  word_start_ = std::string::npos;
}

void channel_writer::comp_on_rapid_error(int line) {
  error(line,
        fmt::format("tool nose radius compensation ({}) would start on a rapid move; machine '{}' starts "
                    "it only on a feed move (codes.cutcom_on_rapid = false): make the first move after "
                    "CUTCOM a feed move",
                    pending_g_, m_.name));
}

void channel_writer::cutcom(const cutcom_event& c, int line) {
  const bool left = c.side == "LEFT", right = c.side == "RIGHT";
  comp_cl_on_ = left || right;
  if (!left && !right) {
    pending_g_ = c.side == "OFF" ? "G40" : "";
    return;
  }
  // The plane the compensation works in: the CUTCOM's, else the one in force. A frame that
  // turns it over (a mirrored turret, the Z-reversed sub) puts the tool's left on its right,
  // as it turns G2 into G3.
  // Without a plane of its own, the header's (G17 on a mill) again: an arc about Y before would
  // leave the compensation in G18, no offset in X Y (verify 46).
  if (c.plane.empty() && !c_mode_) restore_plane();
  const int plane = c.plane == "XYPLAN" ? 17 : c.plane == "ZXPLAN" ? 18 : c.plane == "YZPLAN" ? 19 : plane_;
  std::string g = left != sense_reversed(plane) ? "G41" : "G42";
  // The D register (codes.cutcom_offset): without one the control compensates with whatever
  // D is active (public Fanuc mill posts write D with every G41/G42: docs/machines.md).
  const std::string& rule = m_.codes.cutcom_offset;
  if (!rule.empty()) {
    auto refuse = [&](const std::string& why) {
      pending_g_.clear();
      error(line, fmt::format("CUTCOM/{} {}; without a D word the control would compensate with whatever D "
                              "register is active",
                              c.side, why));
    };
    std::optional<int> d = c.reg;
    if (!d && rule == "cutcom")
      return refuse(
          fmt::format("gives no register, and machine '{}' takes the D register from the CUTCOM "
                      "record (codes.cutcom_offset = \"cutcom\"): give CUTCOM/{},n",
                      m_.name, c.side));
    if (!d && tool_ < 0)
      return refuse(
          fmt::format("comes before any tool call, and machine '{}' writes the tool's D register "
                      "with G41/G42",
                      m_.name));
    if (!d && rule == "tool") d = tool_;
    if (!d) {
      const tool_def* t = m_.tool(ch_.number, tool_);
      if (!t || !t->diameter_offset)
        return refuse(
            fmt::format("gives no register, and machine '{}' takes tool {}'s D register from its "
                        "tool table (codes.cutcom_offset = \"table\"), which gives none ([[tool]] "
                        "diameter_offset)",
                        m_.name, tool_));
      d = t->diameter_offset;
    }
    if (*d < 1) {
      pending_g_.clear();
      return error(line, fmt::format("CUTCOM/{},{}: D{} is no compensation (the cutter would run on the "
                                     "path's centre); give the tool's register",
                                     c.side, *d, *d));
    }
    if (!fits('D', *d, 0)) {
      pending_g_.clear();
      return;
    }
    g += fmt::format(" D{}", *d);
  }
  pending_g_ = std::move(g);
}

bool channel_writer::sense_reversed(int plane) const {
  // Mirroring X reflects the XY and ZX planes, which reverses their sense; YZ has no X.
  // A reversed spindle's half turn about X turns the XY and ZX planes over (G2/G3 swap, J and
  // K negated); the YZ plane keeps its sense. Both together give the sense back.
  if (plane == 19) return false;
  return mirrored() != (z_sign_ < 0);
}

bool channel_writer::spindle_turning(int line) {
  // A feed after this channel's own SPINDL/OFF of the spindle it cuts on drives a turning tool
  // into a still part (or a still cutter into the work).
  // A balance cut's copy cuts on the spindle its master turns.
  if (balance_copy_ || !spindle_) return true;
  if (stopped_by_cl_ && stopped_by_cl_ == spindle_) {
    error(line, fmt::format("feed move with the {} spindle stopped by SPINDL/OFF: give SPINDL with a speed "
                            "before cutting (the tool would be driven into a part that does not turn)",
                            spindle_->name));
    return false;
  }
  if (stopped_by_user_ && stopped_by_user_ == spindle_) {
    error(line,
          fmt::format("feed move with the {} spindle stopped by {} of a user block (the machine's [events] "
                      "or script) and not started again: the tool would be driven into a part that does "
                      "not turn (or a still cutter into the work); start it in the user block, or give "
                      "SPINDL with a speed before the cut",
                      spindle_->name, user_stop_));
    stopped_by_user_ = nullptr;  // one report a stop
    return false;
  }
  if (!restart_blocks_.empty()) return true;  // this channel started it (or restarts it before the move)
  // A tool that cuts with no spindle (a roller, a scribe) says so in the machine's tool table.
  if (const tool_def* t = m_.tool(ch_.number, tool_); t && !t->spindle) return true;
  if (unstarted_judged_) return unstarted_ok_;  // one report a stretch
  unstarted_judged_ = true;
  unstarted_ok_ = true;
  // A spindle another channel may start (a twin lathe's main spindle): that channel's start
  // counts, ordered by the waits (analysis/shared_resources); none by another channel in the
  // whole job is an error at this cut, found once the job is read (finish()).
  const std::size_t index = spindle_index(*spindle_);
  if (job_spindles_ && m_.shared_spindle(static_cast<int>(index))) {
    unstarted_.push_back({index, line, line == line_ ? column_ : 0,
                          job_spindles_->quote ? job_spindles_->quote(line) : std::string()});
    return true;
  }
  error(line, not_started(*spindle_, false));
  unstarted_ok_ = false;
  return false;
}

std::string channel_writer::not_started(const spindle_def& s, bool job) const {
  return fmt::format(
      "feed move with the {} spindle not started: {} (a turning tool would be driven into a still "
      "part, a still cutter into the work); give the tool's speed in the machine's [[tool]] table "
      "(rpm or surface_speed) when the CL has none, or mark a tool that cuts with no spindle turning "
      "spindle = false there",
      s.name,
      job ? "no channel gives a SPINDL with a speed for it in this job"
          : "no SPINDL with a speed in this channel before the cut");
}

void channel_writer::motion(const motion_event& mv, int line) {
  switch (mv.kind) {
    case motion_kind::from:
      pos_ = mv.pos;
      pose_known_ = false;  // where the tool is, but not the joints that put it there
      at_pos_ = false;
      hole_exit_.reset();
      return;
    case motion_kind::home:
      at_pos_ = false;
      hole_exit_.reset();
      go_home();
      forget_axes();
      motion_g_ = -1;
      pos_ = mv.pos;
      pose_known_ = false;
      return;
    case motion_kind::go_to:
    case motion_kind::delta:
      if ((tool_ < 0 || cam_tool_due_) && !start_tool(line)) return no_tool(line);
      if (table_speed_due_) [[unlikely]]
        table_speed(line);
      if (!selected_) select_spindle(work_);  // a section that moves before its SPINDL
      if (spindle_held_ || spindle_kept_ || restate_spindle_) resume_spindle(line);
      if (cycle_refused_) {
        // the post has already failed at the CYCLE record
      } else if (cycle_ && cycle_->type == "THREAD") {
        at_pos_ = false;
        hole_exit_.reset();
        thread_cycle_point(mv.pos, line);
        return;  // the control ends the cycle where it started (pos_)
      } else if (cycle_ && cycle_->type == "GROOVE") {
        at_pos_ = false;
        hole_exit_.reset();
        groove_cycle_point(mv.pos, line);
        return;
      } else if (cycle_) {
        if (from_cut_ && hole_from_cut(mv.pos, line)) return;
        // A hole as the first move after a tool call (NX writes CYCLE before the first GOTO):
        // the length offset goes out with a rapid to the hole's retract plane first, as a
        // GOTO there would; the canned cycle starts from that plane.
        // On a chain with a tilted working plane, a hole under a new tilted tool axis opens
        // its plane by that rapid too (the cycle is then written in the plane).
        if (chain_ && multiaxis_takes() && ((!offset_on_ && !(offset_code(*chain_)).empty()) || plane_due()))
          multiaxis_move(true, cycle_approach(mv.pos), line);
        if (!chain_ || !multiaxis_takes() || multiaxis_arc(line)) cycle_point(mv.pos, line);
        pos_ = mv.pos;
        cl_moved_ = true;
        return;
      } else if (threading_ && !mv.rapid) {
        thread_pass(mv.pos, line);
      } else if (chain_ && multiaxis_takes()) {
        if (has_c_ && !millturn_to_multiaxis(line)) return;
        multiaxis_move(mv.rapid, mv.pos, line);
      } else {
        linear(mv.rapid, mv.pos.x, mv.pos.y, mv.pos.z, line);
        if (chain_) {
          // A chain with moves = "tilted" left this move to the 3-axis writer: the rotary axes
          // stand at 0, so the joints are the tip; a tilt that follows starts from here.
          pose_mm_ = {{mv.pos.x * cl_mm_, mv.pos.y * cl_mm_, mv.pos.z * cl_mm_}, axis_};
          joints_.linear = pose_mm_.tip;
          joints_.rotary = {};  // (not where the last tilted tool left them: review 64)
          pose_known_ = true;
        }
      }
      // The tool stands at the CL's point (the next hole starts from it); no hole left it.
      pos_ = mv.pos;
      if (mv.rapid) note_clear(mv.pos);
      cl_moved_ = at_pos_ = true;
      hole_exit_.reset();
      return;
  }
}

void channel_writer::arc(const arc_event& cl, int line) {
  if ((tool_ < 0 || cam_tool_due_) && !start_tool(line)) return no_tool(line);
  if (table_speed_due_) [[unlikely]]
    table_speed(line);
  // In a tilted working plane the arc is written in the plane's frame (G17 there when its
  // axis is the plane's Z); pos_ and the pose stay the CL's.
  const bool in_plane = chain_ && plane_on_;
  std::optional<arc_event> turned;  // built only in a plane
  if (in_plane) turned = plane_arc(cl);
  const arc_event& a = in_plane ? *turned : cl;
  if (has_c_ && c_mode_ && std::abs(axis_.z) <= 1e-4) {
    pos_ = cl.end;
    return error(line,
                 "a CIRCLE with the tool across the spindle axis: twinpost writes no arcs on the cylinder "
                 "(G2/G3 in cylindrical interpolation); give the path as GOTO points");
  }
  if (comp_starting() || pending_g_.starts_with("G40")) [[unlikely]] {
    // Fanuc PS0034 (and the others): compensation starts and ends on a linear move, where the
    // control builds the offset path's first or last vector.
    pos_ = cl.end;
    return error(line, fmt::format("cutter compensation would {} on an arc ({}): the control starts and ends "
                                   "it on a straight move; give a straight lead-in or lead-out between the "
                                   "CUTCOM and the CIRCLE",
                                   comp_starting() ? "start" : "end", pending_g_));
  }
  if (cl.turns_axis) [[unlikely]] {
    // An arc is written with the tool's axis held: the turn would move to the next cut, the
    // tool and holder not where the CAM checked them (attack 45).
    pos_ = cl.end;
    return error(line,
                 "the CIRCLE's GOTO turns the tool axis: an arc holds the tool's axis; give the move "
                 "as GOTO points");
  }
  if (chain_ && multiaxis_takes() ? !multiaxis_arc(line) : !tool_along_z(line)) {
    pos_ = cl.end;
    return;
  }
  if (has_c_ && !index_head(line)) return;
  // In C mode: in polar interpolation (the CL's Y as C), or in XY with C at 0.
  if (c_mode_ && face_polar() && live_tool()) {
    if (!polar_) enter_polar(pos_, false);
  } else if (c_mode_) {
    if (!last_c_.known) position_c(0);
    if (c_sin_ != 0 || c_cos_ != 1) {
      pos_ = cl.end;
      return error(line,
                   "an arc with the C axis turned from 0: arcs in C mode are written at C0 or in polar "
                   "interpolation (milling.face_milling = \"polar\")");
    }
  }
  if (threading_) {
    pos_ = cl.end;
    return error(line, "an arc while THREAD/TURN is on: a threading pass is a straight G32 move");
  }
  if (!selected_) select_spindle(work_);
  if (spindle_held_ || spindle_kept_ || restate_spindle_) resume_spindle(line);
  // The plane comes from the arc's axis: +-Z G17 (XY), +-Y G18 (ZX, the lathe's), +-X G19 (YZ).
  // In each, counter-clockwise about the positive axis is G3 (Z = X x Y, Y = Z x X, X = Y x Z).
  double nlen = std::sqrt(a.normal.x * a.normal.x + a.normal.y * a.normal.y + a.normal.z * a.normal.z);
  auto along = [&](double c) { return nlen > 0 && std::abs(std::abs(c) / nlen - 1) <= 1e-6; };
  int plane = along(a.normal.z) ? 17 : along(a.normal.y) ? 18 : along(a.normal.x) ? 19 : 0;
  auto fail = [&](std::string message) {
    error(line, std::move(message));
    pos_ = cl.end;
  };
  auto fail_quietly = [&] { pos_ = cl.end; };
  if (!spindle_turning(line)) return fail_quietly();
  if (plane == 0)
    return fail(fmt::format("arc about ({},{},{}) is not in the XY, ZX or YZ plane{}", cl.normal.x,
                            cl.normal.y, cl.normal.z, in_plane ? " of the tilted working plane" : ""));
  if (plane != 18 && !has_y_ && !polar_)
    return fail(fmt::format("arc in the {} plane on a channel without a Y axis", plane == 17 ? "XY" : "YZ"));
  if (!has_y_ && !polar_ && std::abs(a.end.y * cl_mm_) > y_tolerance)
    return fail(fmt::format("Y {} on a channel without a Y axis", a.end.y));
  {
    // The start and the end on one circle about the centre (in its plane): a control whose arc
    // ends off its circle alarms at best, or spirals to it (Fanuc's arc radius tolerance).
    const auto in_plane_radius = [&](const vec3& p) {
      const vec3 d{p.x - a.center.x, p.y - a.center.y, p.z - a.center.z};
      const double h = (d.x * a.normal.x + d.y * a.normal.y + d.z * a.normal.z) / (nlen * nlen);
      const vec3 r{d.x - a.normal.x * h, d.y - a.normal.y * h, d.z - a.normal.z * h};
      return std::sqrt(r.x * r.x + r.y * r.y + r.z * r.z);
    };
    const double r0 = in_plane_radius(a.start), r1 = in_plane_radius(a.end);
    if (std::abs(r1 - r0) * scale_ > arc_radius_tolerance)
      return fail(fmt::format(
          "the arc ends {} mm from its centre ({}, {}, {}) and starts {} mm from it: no "
          "circle about that centre goes through both",
          kin::number_text(r1 * scale_), kin::number_text(a.center.x), kin::number_text(a.center.y),
          kin::number_text(a.center.z), kin::number_text(r0 * scale_)));
    // A radius under one unit of the written words is no arc a control makes (its start and
    // end radius differ by the rounding, or it is 0: an alarm, or a spiral).
    if (r0 * scale_ < decimal_unit(axis_style_.decimals))
      return fail(
          fmt::format("the arc's radius, {} mm, is under one unit of the written words: give the "
                      "move as a GOTO",
                      kin::number_text(r0 * scale_)));
  }
  // TIMES,n (NX): n full turns about the axis; a GOTO at another depth along the axis makes
  // them a helix (NX's CLSF: "a tool path arc ... or a helical motion", x,y,z "the center of
  // the curve or helix"). A GOTO elsewhere on the circle (a helical entry that ends where the
  // pocket's first cut starts) adds the arc on to it after the n turns. The depth is spread over
  // the whole sweep at one pitch: each full turn is one block whose axis word moves 2pi/sweep of
  // the depth, the last block the part turn to the GOTO. Of the two readings of TIMES (whole
  // turns, or every turn begun), whole turns is the longer sweep and so the shallower ramp.
  // The angle from the start to the end in the arc's sense, in [0, 2pi): the two radii in the
  // plane, their cross product along the axis gives the counter-clockwise angle.
  const auto part_angle = [&]() {
    const double two_pi = 2 * std::numbers::pi;
    const vec3 n{a.normal.x / nlen, a.normal.y / nlen, a.normal.z / nlen};
    const auto radial = [&](const vec3& p) {
      const vec3 r{p.x - a.center.x, p.y - a.center.y, p.z - a.center.z};
      const double h = r.x * n.x + r.y * n.y + r.z * n.z;
      return vec3{r.x - n.x * h, r.y - n.y * h, r.z - n.z * h};
    };
    const vec3 r0 = radial(a.start), r1 = radial(a.end);
    const vec3 c{r0.y * r1.z - r0.z * r1.y, r0.z * r1.x - r0.x * r1.z, r0.x * r1.y - r0.y * r1.x};
    double ccw_angle = std::atan2(c.x * n.x + c.y * n.y + c.z * n.z, r0.x * r1.x + r0.y * r1.y + r0.z * r1.z);
    if (ccw_angle < 0) ccw_angle += two_pi;
    return a.ccw ? ccw_angle : two_pi - ccw_angle;
  };
  double sweep = 0;       // radians round the circle, all blocks together (a plain arc's: 0, not needed)
  vec3 rise{0, 0, 0};     // the travel along the axis from the start to the end, CL units
  double turn_share = 1;  // the part of the rise one full turn takes
  bool part_turn = true;  // a last block that ends away from the start in the plane
  {
    const vec3 d{a.end.x - a.start.x, a.end.y - a.start.y, a.end.z - a.start.z};
    const double along = (d.x * a.normal.x + d.y * a.normal.y + d.z * a.normal.z) / (nlen * nlen);
    rise = {a.normal.x * along, a.normal.y * along, a.normal.z * along};
    const double gap =
        std::max({std::abs(d.x - rise.x), std::abs(d.y - rise.y), std::abs(d.z - rise.z)}) * scale_;
    // An end within one unit of the written words of the start is the start (the CL's print
    // rounding): its in-plane words are written as the start's, never rounded apart from them
    // (a 0.001 mm arc that drops a turn's depth is a plunge), nor together where a part turn
    // was meant (the control runs an arc whose end is its start as a full circle).
    const double unit = decimal_unit(axis_style_.decimals);
    part_turn = gap > std::max(y_tolerance, unit);
    // The angle from the start to the end in the arc's sense, in [0, 2pi): the two radii in the
    // plane, their cross product along the axis gives the counter-clockwise angle.
    const double two_pi = 2 * std::numbers::pi;
    double part = 0;
    // The end on the start itself, in mm (not in the words' units: an inch word's 0.0001 is
    // 0.00254 mm, verify 46): a full circle as the CL gives it.
    const bool on_start = gap / out_per_mm_ <= y_tolerance;
    if (!on_start && (a.turns > 0 || !part_turn)) part = part_angle();
    if (a.turns == 0 && !part_turn && !on_start && part < std::numbers::pi) {
      // A few microns on round the circle (attack 45: written as a full 100 mm circle): the
      // tool is there within a unit of the words; an axis move with it would be a plunge.
      if (std::max({std::abs(rise.x), std::abs(rise.y), std::abs(rise.z)}) * scale_ > unit)
        return fail(
            fmt::format("the arc goes {} mm round its circle, under one unit of the written words, "
                        "and {} mm along its axis: give the move as a GOTO",
                        kin::number_text(gap / out_per_mm_), kin::number_text(kin::norm(rise) * cl_mm_)));
      pos_ = cl.end;
      return;
    }
    if (a.turns > 0) turn_share = part_turn ? two_pi / (a.turns * two_pi + part) : 1.0 / a.turns;
    sweep = a.turns * two_pi + (part_turn ? part : a.turns == 0 ? two_pi : 0);  // part: 0 on a plain arc
    // In polar interpolation (G12.1) the arc is in the X-C plane the control builds; whether it
    // takes a Z word into a helix there is not verified in a control's manual.
    if (a.turns > 0 && polar_ &&
        std::max({std::abs(rise.x), std::abs(rise.y), std::abs(rise.z)}) * scale_ > y_tolerance)
      return fail(
          fmt::format("CIRCLE TIMES {}: a helix in polar interpolation (G12.1) is not written: "
                      "helical interpolation in that mode is not verified; give the ramp as GOTO points",
                      a.turns));
  }
  check_side(nc_x(a.end.x), a.end.x, line);
  if (const double r = std::hypot(a.start.x - a.center.x, a.start.z - a.center.z);
      x_diameter_ && plane == 18 && !warned_side_ &&
      std::min(nc_x(a.center.x - r), nc_x(a.center.x + r)) < -5.0) [[unlikely]] {
    // A lathe arc may pass the centre line between its ends (attack 45: a three-quarter arc to
    // X-16 on the diameter): its X along the way, 64 points a turn, where its circle reaches
    // past the centre (check_side's 5 mm on the diameter).
    const double a0 = std::atan2(a.start.x - a.center.x, a.start.z - a.center.z);  // about +Y: z to x
    const double s = (a.ccw == (a.normal.y > 0)) ? 1.0 : -1.0;
    if (a.turns == 0 && part_turn) sweep = part_angle();
    const int steps = std::max(8, static_cast<int>(std::ceil(sweep / (2 * std::numbers::pi) * 64)));
    double low = a.end.x;
    for (int i = 1; i < steps; ++i)
      low = std::min(low, a.center.x + r * std::sin(a0 + s * sweep * i / steps));
    check_side(nc_x(low), low, line);
  }
  double axis_sign = plane == 17 ? a.normal.z : plane == 18 ? a.normal.y : a.normal.x;
  bool ccw = a.ccw == (axis_sign > 0);
  const double mirror = mirrored() ? -1.0 : 1.0;
  if (sense_reversed(plane)) ccw = !ccw;
  int g = ccw ? 3 : 2;

  arc_.clear();
  if (!pending_g_.empty()) arc_ += ' ', arc_ += pending_g_;
  if (plane != plane_) {
    arc_ += fmt::format(" G{}", plane);
    plane_ = plane;
  }
  arc_ += g == 3 ? " G3" : " G2";
  if (feed_value_ <= 0) error(line, "arc with no feed rate (FEDRAT) in force");
  const int blocks = std::max(1, a.turns + (part_turn && a.turns > 0 ? 1 : 0));
  for (int turn = 1; turn <= blocks; ++turn) {
    // Full turns (TIMES): each block ends a turn's share further along the axis, the last at
    // the GOTO (the end of the last full turn, or of the part turn after them). A full circle's
    // end is its start in the plane.
    const double k = std::min(1.0, turn * turn_share);
    const vec3 end = turn == blocks && part_turn
                         ? a.end
                         : vec3{a.start.x + rise.x * k, a.start.y + rise.y * k, a.start.z + rise.z * k};
    if (!arc_block(a, end, plane, axis_sign, mirror, line)) return fail_quietly();
    if (turn < blocks) {
      out_.block(arc_.view().substr(1));
      arc_.clear();
      arc_ += g == 3 ? " G3" : " G2";
    }
  }
  if (in_plane && !plane_arc_checked(cl, a, line)) return fail_quietly();
  pending_g_.clear();
  motion_g_ = g;
  homed_ = false;
  out_.block(arc_.view().substr(1));
  pos_ = cl.end;
  cl_moved_ = at_pos_ = true;
  hole_exit_.reset();
  pose_mm_.tip = {cl.end.x * cl_mm_, cl.end.y * cl_mm_, cl.end.z * cl_mm_};
  // The rotary axes stand at 0 (multiaxis_arc): joints = tip; in a plane G53.1 holds them.
  if (!in_plane) joints_.linear = pose_mm_.tip;
}

bool channel_writer::arc_block(const arc_event& a, const vec3& end, int plane, double axis_sign,
                               double mirror, int line) {
  // Both axes of the plane always; the third only when it moves (a helix).
  axis_word(arc_, 'X', nc_x(end.x), last_x_, plane != 19);
  if (plane != 18 || has_y_ || polar_) axis_word(arc_, polar_ ? 'C' : 'Y', nc_y(end.y), last_y_, plane != 18);
  axis_word(arc_, 'Z', nc_z(end.z), last_z_, plane != 17);

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
    auto [eu, ev] = uv(end);
    if (std::abs(su - eu) < 1e-9 && std::abs(sv - ev) < 1e-9) {
      error(line, "a full circle cannot be written with R; the machine must take I/K arcs");
      return false;
    }
    // The long way round (over 180 degrees) takes a negative R.
    bool short_way_ccw = su * ev - sv * eu > 0;
    bool over_half = short_way_ccw != (a.ccw == (axis_sign > 0));
    // The radius the points lie on, not the record's (attack 45: R60. written for a circle of
    // 50 through the same two points).
    const double r = (over_half ? -1 : 1) * std::hypot(su, sv) * scale_;
    if (!fits('R', r, axis_style_.decimals)) return false;
    arc_ += " R";
    append_number(arc_, r, axis_style_);
  }
  if (feed_value_ > 0) append_feed(arc_);
  return true;
}

}  // namespace twinpost
