// channel_writer on a channel with a kinematic chain ([[kinematics]]): every GOTO solved by
// kin::inverse from the joints the machine is at, feed moves of joints output cut to the
// chordal tolerance by kin::linearise and fed in inverse time (G93) where a rotary axis moves,
// tool-tip control (G43.4 with the rotary values, G43.5 with I J K) as the chain says, and
// every written point taken back through the forward transform before it goes out
// (docs/machines.md, "Multi-axis output").
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "kinematics/forward.hpp"
#include "kinematics/linearise.hpp"
#include "kinematics/vec3_ops.hpp"
#include "machines/code_overlap.hpp"
#include "machining/channel_writer.hpp"
#include "parser/cam_tool.hpp"

namespace twinpost {

using kin::joint_values;
using kin::tool_pose;

namespace {

constexpr int rotary_decimals = 3;   // degrees, as the Fanuc posts write A/B/C
constexpr int vector_decimals = 6;   // G43.5 I J K
constexpr int inverse_decimals = 3;  // G93 F, 1/min
constexpr double still = 1e-9;       // a rotary axis that moves less does not move

// `v` as the control reads it after writing it with `decimals` places; `counted` says whether
// it rounds to a count `n` (else `v` itself).
double as_written(double v, int decimals, std::int64_t& n, bool& counted) {
  counted = round_fixed(v, decimals, n);
  if (!counted) return v;
  static constexpr double scale[] = {1, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};
  return static_cast<double>(n) / scale[decimals];
}
double as_written(double v, int decimals) {
  std::int64_t n;
  bool counted;
  return as_written(v, decimals, n, counted);
}

// The angle (degrees) of `axis` from the line of `pole` (either sense).
double off_pole(const vec3& axis, const vec3& pole) {
  const double a = kin::angle_between(axis, pole);
  return std::min(a, 180 - a);
}

}  // namespace

const kin::chain_plan& channel_writer::plan() {
  if (plan_.chain != chain_) [[unlikely]]
    plan_ = kin::chain_plan(*chain_);
  return plan_;
}

void channel_writer::tool_data_length(const tool_data_event& t, bool after_call) {
  // Every TLDATA form whose length is known for certain (parser/cam_tool.hpp).
  const std::optional<double> cl = tldata_length(t);
  if (!cl) return;
  const double mm = *cl * cl_mm_;
  if (after_call) {
    length_cl_ = mm;
    length_known_ = length_refused_ = length_free_ = false;
  } else {
    next_length_cl_ = mm;
  }
}

void channel_writer::multiaxis_tool(const tool_event& t, int) {
  offset_ = t.offset.value_or(t.tool);
  length_cl_ = next_length_cl_;
  next_length_cl_.reset();
  length_known_ = length_refused_ = length_free_ = false;
  offset_on_ = false;
  pose_known_ = false;  // the tool change moved the machine
  clear_height_ = -std::numeric_limits<double>::infinity();
  for (axis_memory& a : last_rot_) a.known = false;
  for (axis_memory& a : last_ijk_) a.known = false;
}

void channel_writer::heads_upright() {
  // A tool changer takes the tool with the heads at 0 (the spindle along its axis): after a tilted
  // plane (G69 does not turn the heads back) or tilted moves the heads turn back at the tool-change
  // height before the call. Tables may stay where they are: the part turns, not the spindle.
  const kinematic_chain& c = *chain_;
  bool tilted = false;
  for (std::size_t i = 0; i < c.rotaries.size(); ++i)
    tilted =
        tilted || (c.rotaries[i].kind == rotary_kind::head && (!last_rot_[i].known || last_rot_[i].n != 0));
  if (!tilted) return;
  text_buffer& b = out_.open_block();
  word_start_ = b.size();
  b += "G0";
  const std::array<std::size_t, 2> order = rotary_words(c);
  for (std::size_t n = 0; n < c.rotaries.size(); ++n)
    if (const std::size_t i = order[n]; c.rotaries[i].kind == rotary_kind::head) {
      rotary_word(b, c.rotaries[i].address, 0.0, last_rot_[i], rotary_decimals, true);
      joints_.rotary[i] = 0;  // the next tool's first point is solved from there
    }
  out_.end_block();
  word_start_ = std::string::npos;
  motion_g_ = 0;
}

void channel_writer::multiaxis_off() {
  if (plane_on_) close_plane();
  if (inverse_time_) {
    out_.block(m_.codes.feed_per_min);
    inverse_time_ = false;
    last_f_.clear();
  }
  if (offset_on_) cancel_length_offset();
}

void channel_writer::cancel_length_offset() {
  offset_on_ = false;
  // G49 away from home would move Z by the tool's length, towards the part on a control that
  // cancels at once: the Autodesk posts retract first (writeRetract(Z), then
  // disableLengthCompensation, which refuses "if the machine is not fully retracted").
  if (homed_)
    out_.block(chain_->tool_tip_off);
  else
    length_cancel_due_ = true;
}

bool channel_writer::tool_length_known(int line) {
  if (length_known_ || length_free_) return true;
  if (length_refused_) return false;  // one error per tool
  const std::optional<double> table = m_.tool_length(ch_.number, tool_);
  if (chain_->output == multiaxis_output::pivot) return pivot_length_fits(table, line);
  if (lengths_differ(*chain_, table, length_cl_)) {
    const std::string both = fmt::format(
        "tool {} ({} at line {}): the CL's TLDATA gives a length of {} mm, machine '{}' lists {} mm "
        "([[tool]] length)",
        tool_, tool_word_, tool_line_, kin::number_text(*length_cl_), m_.name, kin::number_text(*table));
    if (chain_->tool_length == length_source::agree) {
      length_refused_ = true;
      error(line, both +
                      ": which tool is in the spindle? ([[kinematics]] tool_length = \"table\" or \"cl\" "
                      "says which wins)");
      return false;
    }
    // The machine file says which wins; the other is said, for the tip moves with the length on
    // a tilted head (docs/machines.md, "Multi-axis output").
    const bool table_wins = chain_->tool_length == length_source::table;
    warning(
        fmt::format("{}: the {} is used ([[kinematics]] tool_length = \"{}\"); on a tilted head the tip "
                    "lies where that length puts it",
                    both, table_wins ? "table's" : "CL's", table_wins ? "table" : "cl"));
  }
  if (!table && !length_cl_) {
    // With every head that tilts the tool at 0 the tip is the linear values whatever the
    // length (docs/kinematics.md, "Frames and signs"): a 3-axis job posts, and the first
    // point that tilts the tool is refused (write_point).
    tool_length_ = 0;
    length_free_ = true;
    return true;
  }
  tool_length_ = *chosen_length(*chain_, table, length_cl_);
  length_known_ = true;
  return true;
}

bool channel_writer::pivot_length_fits(std::optional<double> table, int line) {
  // Every point is the pivot for the programmed length: a tool the CL or the table says is
  // another length has its tip that much off along the tool, unless the machine's length code
  // makes up the difference (docs/machines.md, "Pivot output").
  const kinematic_chain& c = *chain_;
  tool_length_ = c.programmed_length;
  length_known_ = true;
  if (!table && !length_cl_) {
    // Even upright the written Z is the tip + the programmed length: a tool of no known length
    // would cut air, or run its tip into the part by what it is longer.
    length_known_ = false;
    length_refused_ = true;
    error(line,
          fmt::format("tool {} ({} at line {}) has no length, and machine '{}' writes every point for a "
                      "{} mm tool ([[kinematics]] programmed_length); give TLDATA/MILL with the length, or "
                      "length = ... under the tool's [[tool]] in the machine file",
                      tool_, tool_word_, tool_line_, m_.name, kin::number_text(c.programmed_length)));
    return false;
  }
  // The CL and the table disagree, and the machine file says which counts: said, as joints
  // output says it (tool_length_known).
  if (lengths_differ(c, table, length_cl_) && c.tool_length != length_source::agree)
    warning(fmt::format(
        "tool {} ({} at line {}): the CL's TLDATA gives a length of {} mm, machine '{}' lists "
        "{} mm ([[tool]] length): the {} is compared with the programmed {} mm "
        "([[kinematics]] tool_length = \"{}\")",
        tool_, tool_word_, tool_line_, kin::number_text(*length_cl_), m_.name, kin::number_text(*table),
        c.tool_length == length_source::table ? "table's" : "CL's", kin::number_text(c.programmed_length),
        c.tool_length == length_source::table ? "table" : "cl"));
  // The lengths that count: both under `agree`, else the one tool_length names (or the other
  // where it is not given).
  const bool table_counts = table && !(c.tool_length == length_source::cl && length_cl_);
  const bool cl_counts = length_cl_ && !(c.tool_length == length_source::table && table);
  const auto off = [&](const std::optional<double>& v, bool counts) {
    return counts && std::abs(*v - c.programmed_length) > c.tolerance;
  };
  const bool table_off = off(table, table_counts);
  if (!table_off && !off(length_cl_, cl_counts)) return true;
  const double own = table_off ? *table : *length_cl_;
  const std::string what = fmt::format(
      "tool {} ({} at line {}) is {} mm long ({}), and machine '{}' writes the pivot for a {} mm tool "
      "([[kinematics]] programmed_length)",
      tool_, tool_word_, tool_line_, kin::number_text(own), table_off ? "[[tool]] length" : "the CL's TLDATA",
      m_.name, kin::number_text(c.programmed_length));
  if (c.length_on.empty()) {
    length_known_ = false;
    length_refused_ = true;
    error(line,
          what + fmt::format(
                     ": its tip would be {} mm off along the tool; post it with a tool of that length, or "
                     "name the control's length code ([[kinematics]] length_on) that makes up the difference",
                     kin::number_text(std::abs(own - c.programmed_length))));
    return false;
  }
  warning(what + fmt::format(": {} H{} must make up {} mm along the tool", c.length_on, offset_,
                             kin::number_text(own - c.programmed_length)));
  return true;
}

bool channel_writer::untilted_without_length(const joint_values& read, int line) {
  std::string tilt;
  for (std::size_t i = 0; i < chain_->rotaries.size(); ++i)
    if ((tilting_heads_ >> i & 1u) && read.rotary[i] != 0)
      tilt += fmt::format(" {}{}", chain_->rotaries[i].address, kin::number_text(read.rotary[i]));
  if (tilt.empty()) return true;
  if (!length_refused_)
    error(line, fmt::format("tool {} ({} at line {}) has no length, and this move tilts it ({}): the joint "
                            "values of machine '{}' then depend on it (a head turns the tool about its "
                            "pivot); give TLDATA/MILL with the length, or length = ... under the tool's "
                            "[[tool]] in the machine file",
                            tool_, tool_word_, tool_line_, tilt.substr(1), m_.name));
  length_refused_ = true;  // one error per tool; its later tilted moves are left out silently
  return false;
}

bool channel_writer::upright() {
  // Every table at 0 (the part frame is the machine's), and the heads where they leave the tip
  // on the linear values with the tool along Z: all at 0, or a head about the tool's own axis (a
  // C head over an A tilt at 0) at any angle. X Y Z then are the tip, as the 3-axis writer
  // writes them.
  const kinematic_chain& c = *chain_;
  joint_values j = joints_;
  for (std::size_t i = 0; i < c.rotaries.size(); ++i)
    if (c.rotaries[i].kind == rotary_kind::table && std::abs(j.rotary[i]) > still) return false;
  j.linear = {};
  const tool_pose at = kin::forward(plan(), j, tool_length_);
  return kin::norm(at.tip) <= 1e-6 && at.axis.z >= 1 - 1e-12;
}

bool channel_writer::multiaxis_takes() {
  const kinematic_chain& c = *chain_;
  if (c.moves == multiaxis_moves::all || plane_on_) return true;
  // A mill/turn channel writes its own moves along and across the spindle axis (C positions,
  // polar interpolation, the turned frame of cross holes): only tilted tools come here. After a
  // tool call (or a home) the rotary axes the last tilted tool left are no reason: an indexing
  // head is indexed for the new tool at home (review 64: an axial drill after a tilted end mill
  // came down under tool-tip control, then went home to index inside its first cut).
  if (has_c_ && (std::abs(axis_.z) >= 0.9999 || std::abs(axis_.z) <= 1e-4) &&
      ((!pose_known_ && ch_.head_index.present()) ||
       std::all_of(joints_.rotary.begin(), joints_.rotary.end(),
                   [](double v) { return std::abs(v) <= still; })))
    return false;
  const double len = std::sqrt(axis_.x * axis_.x + axis_.y * axis_.y + axis_.z * axis_.z);
  const bool along = len > 0 && kin::angle_between(axis_, c.tool_direction) <= c.angle_tolerance;
  const bool at_zero = std::all_of(joints_.rotary.begin(), joints_.rotary.end(),
                                   [](double v) { return std::abs(v) <= still; });
  if (!along || !at_zero) return true;
  // Back to the 3-axis writer: it writes feeds per minute or per revolution, never G93.
  if (inverse_time_) {
    out_.block(m_.codes.feed_per_min);
    inverse_time_ = false;
    last_f_.clear();
  }
  return false;
}

bool channel_writer::multiaxis_arc(int line) {
  if (plane_on_) return plane_takes(line);  // G17 of the tilted working plane (channel_plane.cpp)
  if (chain_->output == multiaxis_output::pivot) {
    error(line,
          "an arc or a drilling cycle under pivot output: the control would run it with the pivot "
          "where the tip belongs; output the move as GOTO points");
    return false;
  }
  if (!upright() || std::abs(axis_.z) < 0.9999) {
    std::string where;
    for (std::size_t i = 0; i < chain_->rotaries.size(); ++i)
      where += fmt::format(" {}{}", chain_->rotaries[i].address, kin::number_text(joints_.rotary[i]));
    error(line, fmt::format(
                    "an arc or a drilling cycle with the tool axis ({:g},{:g},{:g}) and the rotary axes "
                    "at{}: twinpost writes them only with the tool along Z, every table and every head that "
                    "tilts the tool at 0 (a head about the tool's own axis may stand anywhere); "
                    "output the move as GOTO points",
                    axis_.x, axis_.y, axis_.z, where));
    return false;
  }
  const std::string& on = offset_code(*chain_);
  if (!offset_on_ && !on.empty()) {
    error(line,
          "an arc or a drilling cycle as the first move after a tool call: the length offset goes out "
          "with a straight move (give a GOTO first)");
    return false;
  }
  if (inverse_time_) {
    out_.block(m_.codes.feed_per_min);
    inverse_time_ = false;
    last_f_.clear();
  }
  return true;
}

bool channel_writer::turn_at_pole(const tool_pose& at, const tool_pose& to, double length, int line) {
  const kinematic_chain& c = *chain_;
  const kin::orientation_form& f = plan().form;
  if (f.outer < 0 || f.inner < 0 || c.output == multiaxis_output::vector) return true;
  const vec3& pole = c.rotaries[f.outer].direction;
  const auto on_pole = [&](const vec3& k) { return kin::norm(kin::cross(pole, k)) < 1e-9; };
  if (!on_pole(at.axis) || on_pole(to.axis)) return true;
  const bool joints = solves_joints(c);
  const kin::ik_result end =
      kin::inverse(plan_, to, length, joints_, joints ? kin::ik_need::joints : kin::ik_need::angles);
  if (!end.ok()) return true;  // the move itself says why
  double turn = end.joints.rotary[f.outer] - joints_.rotary[f.outer];
  if (c.rotaries[f.outer].rollover == rotary_rollover::shortest) turn = kin::wrap_180(turn);
  if (std::abs(turn) <= still) return true;
  // The tool lies along the outer axis: turning that axis turns the part (or the head) about
  // a line along the tool, which stays where it is on the part, the tip on its point. After a
  // rapid the turn is a rapid too; after a feed it is fed (with the tip held: under tool-tip
  // control by the control, else in steps whose chord stays within the tolerance).
  joint_values target = joints_;
  target.rotary[f.outer] = end.joints.rotary[f.outer];
  if (motion_g_ == 0 || !joints) {
    if (joints) target = kin::positions(c, at.tip, target, length);
    if (!write_point(motion_g_ == 0, target, at, 0, line)) return false;
    joints_ = target;
    return true;
  }
  if (per_rev_) {
    error(
        line,
        "a feed per revolution on a move that turns a rotary axis: inverse-time feed (G93) needs a feed per "
        "minute (FEDRAT/MMPM)");
    return false;
  }
  const joint_values start = joints_;
  const auto step = [&](int k, int n) {
    joint_values j = start;
    j.rotary[f.outer] = start.rotary[f.outer] + turn * k / n;
    return kin::positions(c, at.tip, j, length);
  };
  // Steps halved until the tip between two of them stays within the tolerance of its point.
  int n = 1;
  for (;; n *= 2) {
    double worst = 0;
    for (int k = 0; k < n; ++k) {
      const joint_values a = step(k, n), b = step(k + 1, n);
      for (double t : {0.25, 0.5, 0.75})
        worst =
            std::max(worst, kin::distance(kin::forward_tip(c, kin::interpolate(c, a, b, t), length), at.tip));
    }
    if (worst <= c.chordal_tolerance) break;
    if (n >= 4096) {
      error(line,
            fmt::format("the turn of {} at the pole needs more than 4096 steps to keep the tip within {} "
                        "mm of its point",
                        c.rotaries[f.outer].address, kin::number_text(c.chordal_tolerance)));
      return false;
    }
  }
  // A turn on the spot: its degrees at the feed read as degrees per minute (as a sub-move's,
  // UNVERIFIED, docs/machines.md).
  const double feed_mm = feed_value_ / out_per_mm_;
  const double inverse_f = feed_value_ > 0 ? feed_mm / (std::abs(turn) / n) : 0;
  for (int k = 1; k <= n; ++k) {
    const joint_values j = step(k, n);
    if (!write_point(false, j, at, inverse_f, line)) return false;
    joints_ = j;
  }
  return true;
}

bool channel_writer::same_branch(const joint_values& from, const joint_values& to, int line) {
  // The two solutions of one tool axis differ by about half a turn of the outer axis; the
  // path turns it that fast only beside the pole, where the outer axis is nearly free.
  const kin::orientation_form& f = plan().form;
  if (f.outer < 0 || f.inner < 0) return true;
  const double turn = kin::wrap_180(to.rotary[f.outer] - from.rotary[f.outer]);
  if (std::abs(turn) <= 90) return true;
  const vec3& pole = chain_->rotaries[f.outer].direction;
  const vec3 a0 = kin::tool_axis(*chain_, from), a1 = kin::tool_axis(*chain_, to);
  if (off_pole(a0, pole) < 1 || off_pole(a1, pole) < 1) return true;
  auto joints_text = [&](const joint_values& j) {
    std::string s;
    for (std::size_t i = 0; i < chain_->rotaries.size(); ++i)
      s += fmt::format("{}{}{}", i ? " " : "", chain_->rotaries[i].address, kin::number_text(j.rotary[i]));
    return s;
  };
  error(line, fmt::format("the rotary axes would change solution inside a cut, from {} to {} ({} turns {} "
                          "degrees while the tool cuts): retract, reposition with RAPID and re-engage",
                          joints_text(from), joints_text(to), chain_->rotaries[f.outer].address,
                          kin::number_text(std::abs(turn))));
  return false;
}

void channel_writer::multiaxis_move(bool rapid, const vec3& p, int line) {
  const kinematic_chain& c = *chain_;
  plan();  // plan_ is made before anything reads it, also when the move was worked out ahead
  const double len = std::sqrt(axis_.x * axis_.x + axis_.y * axis_.y + axis_.z * axis_.z);
  const tool_pose pose{{p.x * cl_mm_, p.y * cl_mm_, p.z * cl_mm_},
                       len > 0 ? vec3{axis_.x / len, axis_.y / len, axis_.z / len} : axis_};
  approach_from_ = last_cl_tip_;  // where the CL last put the tip, also across a plane's end
  last_cl_tip_ = pose.tip;
  {
    const double h = kin::dot(pose.tip, c.tool_direction);
    if (rapid) {  // only a rapid reads it (write_point)
      const double was = approach_from_ ? kin::dot(*approach_from_, c.tool_direction) : h;
      turn_clear_ = std::max(h, was) >= clear_height_ - c.tolerance;
    }
    clear_height_ = std::max(clear_height_, h);
  }
  if (!c.plane.empty() && (rapid || plane_on_) && plane_move(rapid, pose, line)) {
    pose_mm_ = pose;
    return;
  }
  const tool_pose from = pose_mm_;
  const bool had_from = pose_known_;
  pose_mm_ = pose;
  // Until the point is written the machine is not where the CL puts it: after an error the
  // next move starts afresh (solved, not linearised from a start it never reached).
  pose_known_ = false;
  if (comp_starting() && std::abs(pose.axis.z) < 0.9999)
    return error(line, fmt::format("cutter compensation ({}) under the tool axis ({:g},{:g},{:g}): twinpost "
                                   "writes no 3-D compensation (G41.2/G42.2)",
                                   pending_g_, axis_.x, axis_.y, axis_.z));
  const bool joints = solves_joints(c);
  if (joints && (chain_heads_ || c.output == multiaxis_output::pivot) && !tool_length_known(line)) return;
  // Tool-tip control: the control holds the length (H); the rotary values do not depend on it.
  const double length = joints ? tool_length_ : 0;
  if (!rapid && had_from && !turn_at_pole(from, pose, length, line)) return;
  if (rapid || !joints || !had_from) {
    joint_values previous = joints_;
    if (pole_hint_ && rapid) {  // looked ahead from the pole (channel_pole.cpp)
      previous.rotary[plan().form.outer] = *pole_hint_;
      pole_hint_.reset();
    }
    const kin::ik_need need = joints ? kin::ik_need::joints : kin::ik_need::angles;
    // Worked out ahead on another thread from these very inputs, or here (machining/kin_lookahead.hpp).
    const kin::ik_result* ahead = ahead_ ? ahead_->inverse(chain_, pose, length, previous, need) : nullptr;
    const kin::ik_result ik = ahead ? *ahead : kin::inverse(plan(), pose, length, previous, need);
    if (!ik.ok())
      return error(line, fmt::format("machine '{}' cannot reach this point: {}", m_.name, ik.message));
    if (!rapid && had_from && !same_branch(joints_, ik.joints, line)) return;
    if (!write_point(rapid, ik.joints, pose, 0, line)) return;
    joints_ = ik.joints;
    pose_known_ = true;
    return;
  }
  if (!ahead_ || !ahead_->linearise(chain_, from, joints_, pose, length, c.chordal_tolerance, lin_))
    kin::linearise(plan(), from, joints_, pose, length, c.chordal_tolerance, lin_);
  if (!lin_.ok()) {
    if (lin_.error != kin::ik_error::too_many_points)
      return error(line, fmt::format("machine '{}' cannot reach this point: {}", m_.name, lin_.message));
    // Most often the move leaves the pole (the tool along the outer axis, whose angle was
    // kept) towards an axis that needs that axis at another angle: it would turn while the
    // tool cuts. Say so.
    const kin::orientation_form& f = plan_.form;
    if (f.outer >= 0 && f.inner >= 0 &&
        kin::angle_between(from.axis, c.rotaries[f.outer].direction) <= c.angle_tolerance) {
      const kin::ik_result end = kin::inverse(plan_, pose, length, joints_);
      if (end.ok()) {
        const rotary_axis_def& o = c.rotaries[f.outer];
        return error(
            line, fmt::format("{}; the move leaves the pole of {} (the tool along it, {} kept at {}) "
                              "towards a tool axis that needs {}{}: {} would turn while the tool cuts; "
                              "give a RAPID to the start of the cut under its tool axis",
                              lin_.message, o.address, o.address, kin::number_text(joints_.rotary[f.outer]),
                              o.address, kin::number_text(end.joints.rotary[f.outer]), o.address));
      }
    }
    return error(line, lin_.message);
  }
  if (length_free_ && joints) {  // the move's end names the tilt, before any sub-move is written
    joint_values end = lin_.points.back();
    for (double& v : end.rotary) v = as_written(v, rotary_decimals);
    if (!untilted_without_length(end, line)) return;
  }
  const double cl_length = kin::distance(from.tip, pose.tip);
  const double feed_mm = feed_value_ / out_per_mm_;
  double s0 = 0;
  for (std::size_t k = 0; k < lin_.points.size(); ++k) {
    const joint_values& j = lin_.points[k];
    const double s = lin_.fractions[k];
    if (!same_branch(joints_, j, line)) return;
    double turned = 0;  // the largest rotary move of the sub-move, degrees
    for (std::size_t i = 0; i < c.rotaries.size(); ++i) {
      double d = j.rotary[i] - joints_.rotary[i];
      if (c.rotaries[i].rollover == rotary_rollover::shortest) d = kin::wrap_180(d);
      turned = std::max(turned, std::abs(d));
    }
    double inverse_f = 0;
    if (turned > still && feed_value_ > 0) {
      if (per_rev_)
        return error(line,
                     "a feed per revolution on a move that turns a rotary axis: inverse-time feed (G93) "
                     "needs a feed per minute (FEDRAT/MMPM)");
      // The sub-move's CL length at the programmed feed; a turn on the spot: its degrees at the
      // feed read as degrees per minute (UNVERIFIED, docs/machines.md).
      const double sub = (s - s0) * cl_length;
      const double minutes = sub > 1e-6 ? sub / feed_mm : turned / feed_mm;
      inverse_f = 1 / minutes;
    }
    if (!write_point(false, j, kin::segment_pose(from, pose, s), inverse_f, line)) return;
    joints_ = j;
    s0 = s;
  }
  pose_known_ = true;
}

bool channel_writer::rotary_word(text_buffer& out, char address, double value, axis_memory& last,
                                 int decimals, bool always, const std::int64_t* counted) {
  if (last.max == 0) [[unlikely]] {  // the control's largest count for the address, once
    const word_format& f = m_.formats[address];
    last.max = f.whole == 0 ? INT64_MAX : f.max_count(decimals);
  }
  std::int64_t n = counted ? *counted : 0;
  if ((!counted && !round_fixed(value, decimals, n)) || n > last.max || n < -last.max) [[unlikely]] {
    misfit(address, value);  // past what the control reads: the post stops here
    last.known = false;
    return false;
  }
  const bool same = last.known && n == last.n;
  last.known = true;
  last.n = n;
  last.value = value;
  if (same && !always) return false;
  separate(out);
  out += address;
  append_fixed(out, n, {decimals, m_.program.trailing_point});
  return true;
}

double channel_writer::head_turn_dip(const joint_values& j, const tool_pose& pose, const double factor[3]) {
  // A head turns the tool about its pivot: a rapid that turns it with the linear axes held
  // swings the tip on an arc, which may pass below both points (A+30 to A-30 on a 150 mm tool
  // dips the tip 20 mm at A0). How far (mm, along the tool direction) it would pass below the
  // higher of the tip where the turn starts and the point the rapid goes to; 0 where it does
  // not, under tool-tip control (the control holds the tip), or where a table turns too (the
  // part moves under the tool: no one height says clear). Before the length offset is on the
  // words are no tip's; pivot output (and joints without length_on) writes none: they are.
  const kinematic_chain& c = *chain_;
  if (!solves_joints(c) || (!offset_on_ && !c.length_on.empty())) return 0;
  joint_values a = j;
  axis_memory* mem[3] = {&last_x_, &last_y_, &last_z_};
  double lin[3];
  for (int i = 0; i < 3; ++i) {
    if (!mem[i]->known) return 0;
    lin[i] = mem[i]->value / factor[i];
  }
  for (std::size_t i = 0; i < c.rotaries.size(); ++i) {
    if (c.rotaries[i].kind != rotary_kind::head || !last_rot_[i].known) return 0;
    a.rotary[i] = last_rot_[i].value;
  }
  const vec3 shift = c.output == multiaxis_output::pivot ? pivot_shift(c) : vec3{};
  a.linear = {lin[0] - shift.x, lin[1] - shift.y, lin[2] - shift.z};
  joint_values b = a;
  b.rotary = j.rotary;
  const auto height = [&](const joint_values& at) {
    return kin::dot(kin::forward(plan(), at, tool_length_).tip, c.tool_direction);
  };
  const double top = std::max(height(a), kin::dot(pose.tip, c.tool_direction));
  double low = top;
  constexpr int steps = 64;
  for (int n = 1; n <= steps; ++n) low = std::min(low, height(kin::interpolate(c, a, b, double(n) / steps)));
  const double dip = top - low;
  return dip > 0.001 ? dip : 0;
}

double channel_writer::turn_sweep(const joint_values& j, const double factor[3]) {
  const kinematic_chain& c = *chain_;
  if (!solves_joints(c) || (!offset_on_ && !c.length_on.empty())) return 0;
  joint_values a = j;
  axis_memory* mem[3] = {&last_x_, &last_y_, &last_z_};
  for (int i = 0; i < 3; ++i)
    if (!mem[i]->known) return 0;
  bool turns = false;  // a head that turns (most rapids turn none: nothing to follow)
  for (std::size_t i = 0; i < c.rotaries.size(); ++i) {
    if (!last_rot_[i].known) return 0;
    a.rotary[i] = last_rot_[i].value;
    turns = turns || (c.rotaries[i].kind == rotary_kind::head && std::abs(j.rotary[i] - a.rotary[i]) > 1e-9);
  }
  if (!turns) return 0;
  const vec3 shift = c.output == multiaxis_output::pivot ? pivot_shift(c) : vec3{};
  a.linear = {mem[0]->value / factor[0] - shift.x, mem[1]->value / factor[1] - shift.y,
              mem[2]->value / factor[2] - shift.z};
  joint_values b = a;  // the heads turned, the tables held: what moves the tip in the machine
  for (std::size_t i = 0; i < c.rotaries.size(); ++i)
    if (c.rotaries[i].kind == rotary_kind::head) b.rotary[i] = j.rotary[i];
  const vec3 from = kin::forward(plan(), a, tool_length_).tip;
  double sweep = 0;
  constexpr int steps = 64;
  for (int n = 1; n <= steps; ++n) {
    const vec3 d = kin::operator-(
        kin::forward(plan(), kin::interpolate(c, a, b, double(n) / steps), tool_length_).tip, from);
    const double up = std::max(0.0, kin::dot(d, c.tool_direction));
    sweep = std::max(sweep, kin::norm(kin::operator-(d, kin::operator*(up, c.tool_direction))));
  }
  return sweep;
}

bool channel_writer::reposition_rotaries(const joint_values& j, const tool_pose& pose, const double nc[3],
                                         bool force) {
  // The Autodesk Fusion multi-axis posts (positionABC, initialPositioning: the Fanuc and Mazak
  // mill posts, rev. 44083) turn the rotary axes in a block of their own with the tool at the
  // tool-change height, then position X Y, then bring Z down with the length offset: a tool
  // never tilts (nor the table turns) while it comes down to the part. After a tool call the
  // tool stands at the tool-change position; later, a rapid that turns an axis turns it at the
  // higher of the two points along the tool's approach axis (the CAM's clearance), not on the
  // way down.
  const kinematic_chain& c = *chain_;
  const bool vector = c.output == multiaxis_output::vector;
  // At the tool-change position (home: no move since the home blocks) the tool is as high as it
  // goes; the first point with the length offset (`force`) writes every word.
  const bool home = homed_;
  // Which rotary words the rapid changes (a word the control has not been given yet counts).
  bool turns = home || force;
  for (std::size_t i = 0; i < c.rotaries.size() && !turns; ++i) {
    std::int64_t n;
    turns = !last_rot_[i].known || !round_fixed(j.rotary[i], rotary_decimals, n) || n != last_rot_[i].n;
  }
  if (vector && offset_on_ && !turns) {
    const double v[3] = {pose.axis.x, pose.axis.y, pose.axis.z};
    for (int i = 0; i < 3 && !turns; ++i) {
      std::int64_t n;
      turns = !last_ijk_[i].known || !round_fixed(v[i], vector_decimals, n) || n != last_ijk_[i].n;
    }
  }
  if (!turns) return false;
  // The approach axis: the linear axis the tool points along at home (Z on the mills and on the
  // Integrex head at B0), "up" the way the tool points (from the tip towards the spindle).
  int k = 0;
  const double dir[3] = {c.tool_direction.x, c.tool_direction.y, c.tool_direction.z};
  for (int i = 1; i < 3; ++i)
    if (std::abs(dir[i]) > std::abs(dir[k])) k = i;
  const double factor[3] = {x_factor_ * side_ * out_per_mm_, z_sign_ * out_per_mm_, z_sign_ * out_per_mm_};
  const double up = dir[k] * factor[k] > 0 ? 1.0 : -1.0;  // the sense of "up" in the written word
  axis_memory* mem[3] = {&last_x_, &last_y_, &last_z_};
  bool wrote = false;
  const auto block = [&](auto&& words) {
    text_buffer& b = out_.open_block();
    word_start_ = b.size();
    b += "G0";
    if (words(b)) {
      out_.end_block();
      wrote = true;
      motion_g_ = 0;
      homed_ = false;
    } else {
      out_.drop_block();
    }
    word_start_ = std::string::npos;
  };
  // Up first when the point is higher than where the tool is: the axes turn at the higher one.
  // Where the word's frame changed (the end of a tilted plane) the CL's last tip says it.
  const bool higher =
      mem[k]->known ? (nc[k] - mem[k]->value) * up > 0
      : approach_from_
          ? kin::dot(pose.tip, c.tool_direction) - kin::dot(*approach_from_, c.tool_direction) > 1e-6
          : false;
  if (!home && higher) block([&](text_buffer& b) { return axis_word(b, c.linear[k], nc[k], *mem[k], true); });
  // Then higher still by what the tip would dip while the heads turn there (head_turn_dip).
  if (!home) {
    const double dip = head_turn_dip(j, pose, factor);
    if (dip > 0) {
      const double lifted = mem[k]->value + dip * dir[k] * factor[k];
      block([&](text_buffer& b) { return axis_word(b, c.linear[k], lifted, *mem[k], true); });
    }
  }
  // The rotary axes alone. Before G43.5 is on its I J K mean nothing: the machine's own axes.
  block([&](text_buffer& b) {
    bool any = false;
    if (vector && offset_on_) {
      const double v[3] = {pose.axis.x, pose.axis.y, pose.axis.z};
      for (int i = 0; i < 3; ++i)
        any = rotary_word(b, "IJK"[i], v[i], last_ijk_[i], vector_decimals, false) || any;
      return any;
    }
    const std::array<std::size_t, 2> order = rotary_words(c);
    for (std::size_t n = 0; n < c.rotaries.size(); ++n) {
      const std::size_t i = order[n];
      any = rotary_word(b, c.rotaries[i].address, j.rotary[i], last_rot_[i], rotary_decimals, force) || any;
    }
    return any;
  });
  // Then over the point in the two other linear axes; the rapid itself goes down.
  block([&](text_buffer& b) {
    bool any = false;
    for (int i = 0; i < 3; ++i)
      if (i != k) any = axis_word(b, c.linear[i], nc[i], *mem[i], force) || any;
    return any;
  });
  return wrote;
}

bool channel_writer::write_point(bool rapid, const joint_values& j, const tool_pose& pose, double inverse_f,
                                 int line) {
  const kinematic_chain& c = *chain_;
  const bool joints = solves_joints(c);
  const bool vector = c.output == multiaxis_output::vector;
  // The linear words: the joints, the pivot, or under tool-tip control the tip itself in the
  // part frame.
  const bool pivot = c.output == multiaxis_output::pivot;
  const vec3 shift = pivot ? pivot_shift(c) : vec3{};
  const vec3 lin = joints ? vec3{j.linear.x + shift.x, j.linear.y + shift.y, j.linear.z + shift.z} : pose.tip;
  const double factor[3] = {x_factor_ * side_ * out_per_mm_, z_sign_ * out_per_mm_, z_sign_ * out_per_mm_};
  const double nc[3] = {lin.x * factor[0], lin.y * factor[1], lin.z * factor[2]};
  const int dec = axis_style_.decimals;
  // The point as the control reads the words, through the forward transform.
  joint_values read = j;
  const vec3 lin_read{as_written(nc[0], dec) / factor[0], as_written(nc[1], dec) / factor[1],
                      as_written(nc[2], dec) / factor[2]};
  // The rotary words' counts, for rotary_word() below (one rounding of each value).
  std::int64_t rotary_n[2] = {0, 0};
  bool rotary_counted[2] = {false, false};
  for (std::size_t i = 0; i < c.rotaries.size(); ++i)
    read.rotary[i] = as_written(j.rotary[i], rotary_decimals, rotary_n[i], rotary_counted[i]);
  tool_pose back;
  if (length_free_ && joints && !untilted_without_length(read, line)) [[unlikely]]
    return false;
  if (joints) {
    read.linear = {lin_read.x - shift.x, lin_read.y - shift.y, lin_read.z - shift.z};
    back = kin::forward(plan(), read, tool_length_);
  } else {
    back.tip = lin_read;
    back.axis = vector
                    ? vec3{as_written(pose.axis.x, vector_decimals), as_written(pose.axis.y, vector_decimals),
                           as_written(pose.axis.z, vector_decimals)}
                    : kin::tool_axis(plan(), kin::joint_turns(plan_, read));
  }
  const double tip_error = kin::distance(back.tip, pose.tip);
  const double axis_error = kin::angle_between(back.axis, pose.axis);
  if (!(tip_error <= c.tolerance && axis_error <= c.angle_tolerance)) [[unlikely]] {
    error(line,
          fmt::format("the written point fails the forward transform: tip {} mm and tool axis {} degrees "
                      "from the CL point ({}, {}, {}) (tolerance {} mm, {} degrees)",
                      kin::number_text(tip_error), kin::number_text(axis_error), kin::number_text(pose.tip.x),
                      kin::number_text(pose.tip.y), kin::number_text(pose.tip.z),
                      kin::number_text(c.tolerance), kin::number_text(c.angle_tolerance)));
    return false;
  }

  if (length_lost_) [[unlikely]] {
    length_lost_ = false;  // said once
    error(line,
          "the home blocks written before this move (GOHOME) cancel the tool's length offset, which "
          "the tool call gives on this machine (kinematics.length_on = \"\"): the move would run the "
          "tip a tool length low; call the tool again (LOADTL) after GOHOME");
    return false;
  }
  // A rapid that would swing the tip sideways while a head turns about its pivot, and that
  // neither starts nor ends as high as the CL has had the tip since the tool call (the CAM's
  // clearance), turns the heads at the tool-change height, as after a tool call and between
  // two tilted planes: the CL's RAPID is a straight line for the tip, and below the clearance
  // the swing is through space the CAM did not check (review 45: a 10 degree turn at the
  // bottom of a slot put a 150 mm tool 6 mm into its end wall). A C about the tool's own axis
  // moves no tip; a table turns the part about its own axis: both in place, as before.
  if (rapid && !homed_ && joints && !turn_clear_ && turn_sweep(j, factor) > c.tolerance) [[unlikely]] {
    if (m_.home(ch_.number).empty()) {
      error(line,
            "the heads would turn below the CAM's clearance, swinging the tip sideways, and the machine "
            "has no home blocks (codes.home) to lift the tool first: give the rapid at the clearance");
      return false;
    }
    // The control's own length offset (length_on = "": the tool call gives it, `T1 D1 M6`) is
    // gone after home blocks that cancel it (`SUPA G0 Z0 D0`), and the post has no code to give
    // it back: the tip would run a tool length low (verify 46).
    if (c.output == multiaxis_output::joints && c.length_on.empty())
      for (const std::string& h : m_.home(ch_.number))
        if (cancels_length_offset(h, m_.program.comment_open, m_.program.comment_close)) {
          error(line,
                fmt::format("the heads would turn below the CAM's clearance, swinging the tip sideways, "
                            "and the home blocks that lift the tool first cancel the tool's length "
                            "offset (\"{}\"), which the tool call gives on this machine "
                            "(kinematics.length_on = \"\"): give the rapid at the clearance",
                            h));
          return false;
        }
    if (offset_on_) cancel_length_offset();
    go_home();
    forget_axes();
    restore_plane();
  }
  const std::string& on = joints ? c.length_on : c.tool_tip_on;
  const bool offset_block = !offset_on_ && !on.empty();  // "": the control's offset is not the post's
  const bool repositioned = rapid && reposition_rotaries(j, pose, nc, offset_block);

  text_buffer& b = out_.open_block();
  word_start_ = b.size();
  if (!pending_g_.empty()) b += pending_g_;
  // The feed mode before the motion code: G93 G1 ... F (the Fusion posts' order).
  const bool to_inverse = !rapid && inverse_f > 0 && !inverse_time_;
  const bool to_minute = !rapid && inverse_f == 0 && inverse_time_;
  if (to_inverse) {
    separate(b);
    b += c.inverse_time;
  } else if (to_minute) {
    separate(b);
    b += m_.codes.feed_per_min;
  }
  const int g = rapid ? 0 : 1;
  if (g != motion_g_ || to_inverse || to_minute || (repositioned && offset_block)) {
    separate(b);
    b += rapid ? "G0" : "G1";
  }
  if (offset_block) {
    separate(b);
    b += on;
    if (on.find('H') == std::string::npos) {  // a code that names its register (H#3020) as it is
      b += " H";
      b += fmt::format_int(offset_).c_str();
    }
  }
  // Nothing before the axis words (no G word, no offset): the block is axis words and a feed,
  // which the line hook need not read (plain_block_); a filter may replace it, so not with one.
  const bool plain = b.size() == word_start_ && !out_.has_filter();
  axis_memory* mem[3] = {&last_x_, &last_y_, &last_z_};
  bool moved = false;
  for (int i = 0; i < 3; ++i) moved = axis_word(b, c.linear[i], nc[i], *mem[i], offset_block) || moved;
  if (vector) {
    const double v[3] = {pose.axis.x, pose.axis.y, pose.axis.z};
    for (int i = 0; i < 3; ++i)
      moved = rotary_word(b, "IJK"[i], v[i], last_ijk_[i], vector_decimals, offset_block) || moved;
  } else {
    // The rotary words in the order of their addresses (A, B, C), as most controls list them, or
    // in the chain's ([[kinematics]] rotary_order).
    const std::array<std::size_t, 2> order = rotary_words(c);
    for (std::size_t k = 0; k < c.rotaries.size(); ++k) {
      const std::size_t i = order[k];
      moved = rotary_word(b, c.rotaries[i].address, j.rotary[i], last_rot_[i], rotary_decimals, offset_block,
                          rotary_counted[i] ? &rotary_n[i] : nullptr) ||
              moved;
    }
  }
  if (!moved) {
    out_.drop_block();  // already there
    word_start_ = std::string::npos;
    return true;
  }
  homed_ = false;
  pending_g_.clear();
  motion_g_ = g;
  if (offset_block) offset_on_ = true;
  if (!rapid) {
    if (feed_value_ <= 0) {
      error(line, "feed move with no feed rate (FEDRAT) in force");
    } else if (inverse_f > 0) {
      // fits('F', ...) and append_number() in one rounding, the format's limit found once.
      if (inverse_f_max_ == 0) [[unlikely]] {
        const word_format& f = m_.formats['F'];
        inverse_f_max_ = f.whole == 0 ? INT64_MAX : f.max_count(inverse_decimals);
      }
      std::int64_t n;
      if (round_fixed(inverse_f, inverse_decimals, n) && n <= inverse_f_max_ && -n <= inverse_f_max_) {
        separate(b);
        b += 'F';
        append_fixed(b, n, {inverse_decimals, m_.program.trailing_point});
      } else {
        misfit('F', inverse_f);
      }
      inverse_time_ = true;
    } else {
      if (to_minute) last_f_.clear();
      inverse_time_ = false;
      append_feed(b);
    }
    spindle_turning(line);
  }
  plain_block_ = plain;
  out_.end_block();
  plain_block_ = false;
  word_start_ = std::string::npos;
  return true;
}

}  // namespace twinpost
