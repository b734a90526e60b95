// channel_writer on a channel whose chain has a tilted working plane (`plane = "G68.2"`): 3+2
// work. A RAPID that turns the tool to a new axis not along Z opens a plane whose Z is that
// axis (G68.2 with Fanuc's Z-X-Z Euler angles, then G53.1 to turn the rotary axes to it);
// the moves under that axis are written as 3-axis X Y Z in the plane; a RAPID to another axis
// closes it (G69). Every written point goes back through the plane's rotation to the CL tip
// and axis, as the other multi-axis points go through the forward transform (docs/machines.md,
// "Tilted working plane").
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <variant>

#include "kinematics/forward.hpp"
#include "kinematics/vec3_ops.hpp"
#include "machining/channel_writer.hpp"

namespace twinpost {

using kin::operator*;
using kin::operator+;
using kin::operator-;

namespace {

constexpr int euler_decimals = 3;
// Records held after a rapid before the cut is taken for 3+2 work: an operation's moves under
// one axis, not a whole job (a later turn inside the plane is refused, naming its record).
constexpr std::size_t max_plane_held = 4096;

double written(double v, int decimals) {
  std::int64_t n = 0;
  if (!round_fixed(v, decimals, n)) return v;
  static constexpr double scale[] = {1, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6};
  return static_cast<double>(n) / scale[decimals];
}

// The plane for tool axis `k` as the control builds it from the angles as written (X, Y, Z
// in the part frame); the angles in `euler`. Z-X-Z Euler angles: the plane's Z = Rz(a) Rx(b)
// ez = (sin a sin b, -cos a sin b, cos b); the third angle -a keeps the plane's X near the part's.
std::array<vec3, 3> plane_frame_of(const vec3& k, double* euler = nullptr) {
  const double b = std::atan2(std::hypot(k.x, k.y), k.z) / kin::deg;
  const double a = std::hypot(k.x, k.y) < 1e-12 ? 0 : std::atan2(k.x, -k.y) / kin::deg;
  const double e[3] = {written(a, euler_decimals), written(b, euler_decimals), written(-a, euler_decimals)};
  if (euler) std::copy(e, e + 3, euler);
  const vec3 z{0, 0, 1}, x{1, 0, 0};
  auto turn = [&](const vec3& v) {
    return kin::rotate(kin::rotate(kin::rotate(v, z, e[2]), x, e[1]), z, e[0]);
  };
  return {turn({1, 0, 0}), turn({0, 1, 0}), turn({0, 0, 1})};
}

}  // namespace

bool channel_writer::hold_multiaxis(const event& e, bool both) {
  if (!plane_held_.empty()) {
    const auto* m = std::get_if<motion_event>(&e.data);
    bool decided = false, plane = plane_held_cut_;  // rapids alone position, they cut nothing
    if (m && m->kind != motion_kind::from && m->kind != motion_kind::home) {
      const vec3 axis = m->axis ? *m->axis : plane_held_axis_;
      const double len = kin::norm(axis);
      const bool turns =
          len > 0 && kin::angle_between((1 / len) * axis, plane_held_axis_) > chain_->angle_tolerance;
      if (turns) {
        decided = true;  // a rapid to another axis ends the cut; a feed move turns the tool in it
        plane = plane_held_cut_ && m->rapid;
      } else if (!m->rapid) {
        plane_held_cut_ = true;  // a cut under the held axis
      }
    } else if (std::holds_alternative<arc_event>(e.data)) {
      plane_held_cut_ = true;
    } else if (m ||
               !(std::holds_alternative<feed_event>(e.data) || std::holds_alternative<cutcom_event>(e.data) ||
                 std::holds_alternative<cycle_event>(e.data) ||
                 std::holds_alternative<spindle_event>(e.data) ||
                 std::holds_alternative<coolant_event>(e.data) ||
                 std::holds_alternative<delay_event>(e.data) ||
                 std::holds_alternative<comment_event>(e.data) ||
                 std::holds_alternative<text_event>(e.data) ||
                 std::holds_alternative<passthrough_event>(e.data))) {
      // FROM, GOHOME, a tool change, a frame (CSYS, MSYS: checked as they come), the end: the
      // cut ends with the axis it kept. The records of a cut are held.
      decided = true;
    }
    if (!decided && plane_held_.size() < max_plane_held) {
      plane_held_.push_back(held_of(e, both));
      return true;
    }
    release_plane_held(plane);
  }
  if (hold_for_pole(e, both)) return true;
  // A rapid that would open a plane: a tilted axis, not the open plane's.
  const kinematic_chain& c = *chain_;
  const auto* m = std::get_if<motion_event>(&e.data);
  if (c.plane.empty() || !m || m->kind != motion_kind::go_to || !m->rapid || tool_ < 0 || cycle_)
    return false;
  const vec3 axis = m->axis ? *m->axis : axis_;
  const double len = kin::norm(axis);
  if (!(len > 0)) return false;
  const vec3 k = (1 / len) * axis;
  if (kin::angle_between(k, c.tool_direction) <= c.angle_tolerance ||
      (plane_on_ && kin::angle_between(k, plane_axis_) <= c.angle_tolerance))
    return false;
  plane_held_axis_ = k;
  plane_held_cut_ = false;
  plane_held_.push_back(held_of(e, both));
  return true;
}

channel_writer::held_record channel_writer::held_of(const event& e, bool both) const {
  return {e, both, job_spindles_ && job_spindles_->quote ? job_spindles_->quote(e.line) : ""};
}

void channel_writer::release_plane_held(bool plane) {
  std::vector<held_record> events;
  events.swap(plane_held_);
  plane_veto_ = !plane;
  for (const held_record& r : events) {
    held_source_ = r.source.empty() ? nullptr : &r.source;
    process_event(r.e, r.both);
  }
  held_source_ = nullptr;
  plane_veto_ = false;
  events.clear();
  plane_held_.swap(events);  // keep the capacity for the next cut
}

bool channel_writer::plane_comp_off(int line) {
  // Fanuc's G68.2 and G69 are given with cutter compensation cancelled (G40): a G40 still
  // waiting for its move goes out on its own first; compensation the CL leaves on is refused.
  if (comp_cl_on_) {
    pose_known_ = false;
    error(line, fmt::format("the tool axis turns with cutter compensation on: the tilted working plane ({}) "
                            "is set and cancelled with G40 in force; give CUTCOM/OFF and a move before "
                            "the RAPID",
                            chain_->plane));
    return false;
  }
  if (pending_g_.starts_with("G40")) {
    out_.block(pending_g_);
    pending_g_.clear();
  }
  return true;
}

bool channel_writer::plane_move(bool rapid, const kin::tool_pose& pose, int line) {
  const kinematic_chain& c = *chain_;
  if (plane_on_) {
    if (kin::angle_between(pose.axis, plane_frame_[2]) <= c.angle_tolerance) {
      plane_point(rapid, pose, line);
      return true;
    }
    if (!rapid) {
      pose_known_ = false;
      error(line, fmt::format("the tool axis turns from ({:g},{:g},{:g}) to ({:g},{:g},{:g}) in a feed move "
                              "inside a tilted working plane ({}): a 3+2 operation keeps its axis; give a "
                              "RAPID to change it",
                              plane_axis_.x, plane_axis_.y, plane_axis_.z, pose.axis.x, pose.axis.y,
                              pose.axis.z, c.plane));
      return true;
    }
    if (!plane_comp_off(line)) return true;
    close_plane();
    // The rotaries turn next: the tool goes to its tool-change height first, as after a tool
    // call (reposition_rotaries). A table machine's tool-tip control is off with the plane, and
    // a head swings the tip by its pivot length (400 mm at B20 moves the tip 137 mm), so the
    // tip is never left by the part while they turn (issue 37, item 7).
    if (!homed_) go_home();
  }
  // A plane opens at a rapid that turns the tool to a new axis not along the spindle's (feed
  // moves outside a plane return first: no angle computed for them).
  if (!rapid || plane_veto_) return false;
  const bool turned = !pose_known_ || kin::angle_between(pose.axis, pose_mm_.axis) > c.angle_tolerance;
  if (!turned || kin::angle_between(pose.axis, c.tool_direction) <= c.angle_tolerance) return false;
  if (!plane_comp_off(line)) return true;
  // The rotary axes G53.1 turns to it must reach it within their limits.
  const kin::ik_result ik = kin::inverse(c, pose, 0, joints_, kin::ik_need::angles);
  if (!ik.ok()) {
    pose_known_ = false;
    error(line, fmt::format("machine '{}' cannot reach this point: {}", m_.name, ik.message));
    return true;
  }
  // The tables (heads) at the rotary values the inverse gave must turn the plane's Z (as the
  // angles are written) onto the spindle: the forward transform's tool axis.
  if (const double off = kin::angle_between(kin::tool_axis(c, ik.joints), plane_frame_of(pose.axis)[2]);
      off > c.angle_tolerance) {
    pose_known_ = false;
    error(line, fmt::format("the tilted working plane's Z is {} degrees from the tool axis the rotary values "
                            "give (tolerance {} degrees)",
                            kin::number_text(off), kin::number_text(c.angle_tolerance)));
    return true;
  }
  if (inverse_time_) {
    out_.block(m_.codes.feed_per_min);
    inverse_time_ = false;
    last_f_.clear();
  }
  // G43.4/G43.5 do not go with G68.2: the plane's length offset is G43 along its Z, commanded
  // in the plane. A G43 from before G68.2 stays along the work frame's Z (Fanuc), so a joints
  // chain's G43 is cancelled too and given again after G53.1 with the first Z move, as the
  // Autodesk Fanuc posts write G43 Z.. H.. after every retract and new work plane.
  if (offset_on_) cancel_length_offset();
  // G53.1 turns the rotaries with the tool at its tool-change height, as between two planes: a
  // table machine turns the part under the tool, a head swings the tip about its pivot. The
  // plane's words are X Y Z in G17 (an arc about Y before left G18: verify 46).
  if (!homed_) go_home();
  restore_plane();
  double euler[3];
  const std::array<vec3, 3> frame = plane_frame_of(pose.axis, euler);
  for (int i = 0; i < 3; ++i) plane_frame_[i] = frame[i];
  plane_axis_ = pose.axis;
  // The plane's origin is the work zero (X0 Y0 Z0), its angles I J K.
  std::string b68 = c.plane;
  const number_style style{euler_decimals, m_.program.trailing_point};
  for (int i = 0; i < 3; ++i) {
    b68 += fmt::format(" {}", "XYZ"[i]);
    append_number(b68, 0.0, axis_style_);
  }
  for (int i = 0; i < 3; ++i) {
    b68 += fmt::format(" {}", "IJK"[i]);
    append_number(b68, euler[i], style);
  }
  out_.block(b68);
  out_.block(c.plane_index);
  plane_on_ = true;
  joints_.rotary = ik.joints.rotary;
  for (axis_memory& r : last_rot_) r.known = false;
  forget_axes();
  motion_g_ = -1;
  plane_point(rapid, pose, line);
  return true;
}

void channel_writer::close_plane() {
  out_.block(chain_->plane_off);
  // The plane's G43 is along the plane's Z, not the chain's tool-tip control: cancelled, so that
  // the next move turns G43.4 (G43.5) on again with the rotary values, or a joints chain's G43
  // along the work frame's Z.
  if (offset_on_) cancel_length_offset();
  plane_on_ = false;
  forget_axes();
  motion_g_ = -1;
  pose_known_ = false;  // the next move starts from the joints, not along a CL segment
}

void channel_writer::plane_point(bool rapid, const kin::tool_pose& pose, int line) {
  const kinematic_chain& c = *chain_;
  // The tip in the plane: p' = R^T p (the plane's origin is the work zero).
  const vec3 p = to_plane(pose.tip);
  const vec3 back = plane_written(p);
  const double tip_error = kin::distance(back, pose.tip);
  const double axis_error = kin::angle_between(plane_frame_[2], pose.axis);
  if (!(tip_error <= c.tolerance && axis_error <= c.angle_tolerance)) {
    pose_known_ = false;
    return error(
        line,
        fmt::format("the written point fails the tilted plane's rotation: tip {} mm and tool "
                    "axis {} degrees from the CL point ({}, {}, {}) (tolerance {} mm, {} degrees)",
                    kin::number_text(tip_error), kin::number_text(axis_error), kin::number_text(pose.tip.x),
                    kin::number_text(pose.tip.y), kin::number_text(pose.tip.z), kin::number_text(c.tolerance),
                    kin::number_text(c.angle_tolerance)));
  }
  if (comp_on_rapid_refused(rapid, line)) return;
  const bool offset_block = !offset_on_ && !c.length_on.empty();
  // The first rapid in a plane just opened (G53.1 turned the head where the tool stood) goes
  // over the point in X Y and then down the plane's Z, or up first when the point is higher
  // than the CL's last one: never down and across at once (docs/machines.md, "Multi-axis
  // output", the approach). The length offset goes with the Z move.
  // From the tool-change height (after a tool call, or a table machine's plane change) the
  // tool comes from above the work: over the point first, then down.
  bool z_first = false;
  if (rapid && !last_x_.known && !last_z_.known) {
    z_first = approach_from_ && !homed_ && p.z > kin::dot(plane_frame_[2], *approach_from_) + 1e-9;
    text_buffer& pre = out_.open_block();
    word_start_ = pre.size();
    pre += "G0";
    if (z_first && offset_block) {
      separate(pre);
      pre += c.length_on;
      pre += " H";
      pre += fmt::format_int(offset_).c_str();
      offset_on_ = true;
    }
    const bool moved = z_first ? axis_word(pre, 'Z', p.z * out_per_mm_, last_z_, true)
                               : axis_word(pre, 'X', p.x * out_per_mm_, last_x_, true) |
                                     axis_word(pre, 'Y', p.y * out_per_mm_, last_y_, true);
    if (moved) {
      out_.end_block();
      motion_g_ = 0;
      homed_ = false;
    } else {
      out_.drop_block();
    }
    word_start_ = std::string::npos;
  }
  const bool offset_now = offset_block && !z_first;
  text_buffer& b = out_.open_block();
  word_start_ = b.size();
  if (!pending_g_.empty()) b += pending_g_;
  const int g = rapid ? 0 : 1;
  if (g != motion_g_) {
    separate(b);
    b += rapid ? "G0" : "G1";
  }
  if (offset_now) {
    separate(b);
    b += c.length_on;
    b += " H";
    b += fmt::format_int(offset_).c_str();
  }
  bool moved = axis_word(b, 'X', p.x * out_per_mm_, last_x_, offset_now);
  moved = axis_word(b, 'Y', p.y * out_per_mm_, last_y_, offset_now) || moved;
  moved = axis_word(b, 'Z', p.z * out_per_mm_, last_z_, offset_now) || moved;
  if (!moved) {
    out_.drop_block();
  } else {
    homed_ = false;
    pending_g_.clear();
    motion_g_ = g;
    if (offset_now) offset_on_ = true;
    if (!rapid) cut_feed(b, line);
    out_.end_block();
  }
  word_start_ = std::string::npos;
  pose_mm_ = pose;
  pose_known_ = true;
}

vec3 channel_writer::to_plane(const vec3& v) const {
  return {kin::dot(plane_frame_[0], v), kin::dot(plane_frame_[1], v), kin::dot(plane_frame_[2], v)};
}

vec3 channel_writer::plane_written(const vec3& v) const {
  const int dec = axis_style_.decimals;
  return written(v.x * out_per_mm_, dec) / out_per_mm_ * plane_frame_[0] +
         written(v.y * out_per_mm_, dec) / out_per_mm_ * plane_frame_[1] +
         written(v.z * out_per_mm_, dec) / out_per_mm_ * plane_frame_[2];
}

bool channel_writer::plane_due() const {
  const kinematic_chain& c = *chain_;
  if (c.plane.empty()) return false;
  const double len = kin::norm(axis_);
  if (!(len > 0)) return false;
  const vec3 k = (1 / len) * axis_;
  if (plane_on_) return kin::angle_between(k, plane_frame_[2]) > c.angle_tolerance;
  return kin::angle_between(k, c.tool_direction) > c.angle_tolerance;
}

bool channel_writer::plane_takes(int line) {
  const double len = kin::norm(axis_);
  if (len > 0 && kin::angle_between((1 / len) * axis_, plane_frame_[2]) <= chain_->angle_tolerance)
    return true;
  const vec3& z = plane_frame_[2];
  error(line,
        fmt::format("an arc or a drilling cycle with the tool axis ({:g},{:g},{:g}) in a tilted working "
                    "plane ({}) whose Z is ({:g},{:g},{:g}): give a RAPID under the new tool axis first",
                    axis_.x, axis_.y, axis_.z, chain_->plane, z.x, z.y, z.z));
  return false;
}

arc_event channel_writer::plane_arc(const arc_event& cl) const {
  arc_event w = cl;
  w.start = to_plane(cl.start);
  w.end = to_plane(cl.end);
  w.center = to_plane(cl.center);
  w.normal = to_plane(cl.normal);
  return w;
}

bool channel_writer::plane_arc_checked(const arc_event& cl, const arc_event& w, int line) {
  // The control reads the end as written and the centre as the written start plus the
  // written I J K (each rounded on its own); both, turned back, must land on the CL's.
  const vec3 end = plane_written(cl_mm_ * w.end);
  const vec3 start = plane_written(cl_mm_ * w.start);
  const vec3 centre = start + plane_written(cl_mm_ * (w.center - w.start));
  const double end_error = kin::distance(end, cl_mm_ * cl.end);
  const double centre_error = m_.program.arcs_ijk ? kin::distance(centre, cl_mm_ * cl.center) : 0;
  const double tolerance = chain_->tolerance;
  if (end_error <= tolerance && centre_error <= tolerance) return true;
  error(line, fmt::format(
                  "the written arc fails the tilted plane's rotation: end {} mm and centre {} mm from "
                  "the CL's (tolerance {} mm)",
                  kin::number_text(end_error), kin::number_text(centre_error), kin::number_text(tolerance)));
  return false;
}

}  // namespace twinpost
