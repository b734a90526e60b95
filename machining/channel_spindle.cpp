// channel_writer: which spindle turns and where the part is. A channel works on one
// workpiece spindle (main or sub: its work offset, its Z sense) and may have a live spindle
// (a mill head's milling spindle); SPINDL names one, or the tool's kind (TLDATA) chooses.
// Part transfers (TRANSFER/GRIP, RELEASE) move the channel's work to the sub spindle.
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <numbers>

#include "machines/name_template.hpp"
#include "machining/channel_writer.hpp"
#include "parser/cam_tool.hpp"

namespace twinpost {

namespace {
// `code words`, or just `words` when the machine has no such code (a mill has no G97).
std::string join_words(const std::string& code, std::string words) {
  return code.empty() ? words : code + " " + words;
}

std::string upper(std::string s) {
  for (char& c : s)
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  return s;
}
}  // namespace

void channel_writer::note_start() {
  if (job_spindles_ && !balance_copy_)
    job_spindles_->started[spindle_index(*spindle_)][static_cast<std::size_t>(ch_.number - 1)] = 1;
}

void channel_writer::work_on(const spindle_def& s) {
  unstarted_judged_ = false;
  offset_due_ = false;
  if (&s == work_) return;
  // The spindle held as the C axis is let go first, with its own codes (review 64 M7: live work
  // on the main spindle, then the sub: M212 and M202 never came, and the sub's empty unclamp
  // code was written as an empty block).
  leave_c_axis();
  work_ = &s;
  clear_n_ = 0;  // (the other spindle's levels: review 38 H2)
  z_sign_ = s.reverse_z ? -1.0 : 1.0;
  // Another frame: every axis word goes out again, and the old spindle's restart is void.
  forget_axes();
  motion_g_ = -1;
  restart_blocks_.clear();
  spindle_held_ = false;
  spindle_kept_ = false;
  if (!s.work_offset.empty()) out_.block(s.work_offset);
}

void channel_writer::select_spindle(const spindle_def* s) {
  if (!s || s == selected_ || balance_copy_) return;  // a copy commands no spindle
  if (s->select) spindle_block(fmt::format("M{}", *s->select));
  selected_ = s;  // also one without a code: the moves need not ask again
}

void channel_writer::spindle_record(const spindle_event& d, int line) {
  if (ev_) [[unlikely]] {
    const event_point p =
        d.mode == spindle_mode::off ? event_point::spindle_stop : event_point::spindle_start;
    // The copy of a balance cut writes no spindle block (spindle_block): no event either.
    const bool around = d.mode != spindle_mode::orient && d.mode != spindle_mode::lock && !balance_copy_;
    template_args a;
    a.rpm = d.speed;
    if (around) user_blocks(p, false, a);
    spindle(d, line);
    coolant_after_speed();  // the coolant a tool call held back for the speed (tool())
    if (around) user_blocks(p, true, a);
  } else {
    spindle(d, line);
    coolant_after_speed();
  }
}

void channel_writer::table_speed(int line) {
  // The tool's first move, and the CL gave no SPINDL since its call (NX operation files carry
  // none): the speed of the machine's [[tool]] table, as if the CL had given it right before
  // this move, so the comparison with the CL and every later check read the same start.
  table_speed_due_ = false;
  const tool_def* t = m_.tool(ch_.number, tool_);
  if (!t || !(t->rpm || t->surface_speed)) return;
  event e;
  e.line = line;
  e.column = line == line_ ? column_ : 0;
  spindle_event s;
  s.mode = t->rpm ? spindle_mode::rpm : spindle_mode::smm;
  s.speed = t->rpm ? *t->rpm : *t->surface_speed;
  s.dir = t->ccw ? rotation::ccw : rotation::cw;
  spindle_record(s, line);
  e.data = std::move(s);
  if (observer_ && errors_ == 0) [[unlikely]] {
    if (observe_lines_) observe_head();
    observer_->record(e, false);
  }
}

void channel_writer::tool_data(const tool_data_event& t) {
  if (t.major != "TLDATA" || t.words.empty()) return;
  const std::string& w = t.words.front();
  // NX TLDATA/MILL or DRILL, diameter, ...: the diameter a surface speed needs.
  if (const std::optional<double> d = tldata_diameter(t))
    (after_call_ ? diameter_ : next_diameter_) = *d * cl_mm_;
  // Its length: how deep a hole the tool can drill before its holder meets the part.
  if (const std::optional<double> l = tldata_length(t)) {
    if (after_call_) {
      reach_ = *l * cl_mm_;
      if (tool_ >= 0) reach_of_[tool_] = *reach_;
    } else
      next_reach_ = *l * cl_mm_;
  }
  const tool_kind k = w == "MILL"                                       ? tool_kind::mill
                      : w == "DRILL"                                    ? tool_kind::drill
                      : (w == "TURN" || w == "GROOVE" || w == "THREAD") ? tool_kind::turn
                                                                        : tool_kind::unknown;
  // NX writes TLDATA before the tool call; one right after a call describes that tool.
  if (after_call_) {
    kind_ = k;
    table_kind(tool_, line_);
    if (kind_ == tool_kind::unknown) kind_ = default_kind_;
  } else
    next_kind_ = k;
}

void channel_writer::table_kind(int tool, int line) {
  const std::string_view k = m_.tool_kind(ch_.number, tool);
  if (k.empty()) return;
  const tool_kind table = k == "mill" ? tool_kind::mill : k == "drill" ? tool_kind::drill : tool_kind::turn;
  if (kind_ == tool_kind::unknown) {
    kind_ = table;
    return;
  }
  if (kind_ == table) return;
  static constexpr const char* names[] = {"", "TURN", "MILL", "DRILL"};
  error(line, fmt::format("tool {}: the CL's TLDATA says {}, machine '{}' lists it as {} ([[tool]]): which "
                          "tool is in the turret?",
                          tool, names[static_cast<int>(kind_)], m_.name, k));
}

const spindle_def* channel_writer::spindle_for_tool(const spindle_event& s, int line) {
  const std::string tool = fmt::format("tool {} ({} at line {})", tool_, tool_word_, tool_line_);
  if (ch_.live_spindle.empty()) {
    if (kind_ != tool_kind::mill) return work_;
    error(line, fmt::format("SPINDL: {} is a milling tool (TLDATA/MILL) and channel {} has no live spindle "
                            "(channel.live_spindle): the part would turn against a still cutter",
                            tool, ch_.number));
    return nullptr;
  }
  const spindle_def* live = m_.spindle(ch_.live_spindle);
  if (live == work_) return work_;  // one spindle turns the tool (a mill): no choice to make
  switch (kind_) {
    case tool_kind::turn: return work_;
    case tool_kind::mill: return live;
    // On-centre axial drilling turns the part (the moves are held to the centre line);
    // a drill along another axis needs the live spindle.
    case tool_kind::drill: return std::abs(axis_.z) >= 0.9999 ? work_ : live;
    case tool_kind::unknown: break;
  }
  // Constant surface speed is a turning speed: it means the workpiece spindle.
  if (s.mode == spindle_mode::smm || s.mode == spindle_mode::sfm) return work_;
  error(line,
        fmt::format("SPINDL: the kind of {} is unknown, and channel {} has a workpiece spindle and a "
                    "live one ({}): give TLDATA/TURN, MILL or DRILL before the tool call, kind = ... under "
                    "the tool's [[tool]] in the machine file, or post --tool-kind for every tool without "
                    "one, or name the spindle (SPINDL/...,MAIN, SUB or LIVE)",
                    tool_ < 0 ? std::string("the tool (no tool called yet)") : tool, ch_.number,
                    ch_.live_spindle));
  return nullptr;
}

bool channel_writer::drill_on_centre(double x_cl, int line) {
  if (kind_ != tool_kind::drill || spindle_ != work_ || restart_blocks_.empty() || spindle_held_) return true;
  // A drill the part turns against cuts towards the chuck: its CL axis (tip to holder) is +Z in
  // the spindle's frame; (0,0,-1) points it away from the part (attack 65: posted, the
  // approach a rapid through the part).
  if (axis_.z <= -0.9999) {
    error(line, fmt::format(
                    "tool {} is a drill on the centre line of the {} spindle with the tool axis (0,0,-1): it "
                    "would point away from the part, which it drills towards the chuck (axis (0,0,1))",
                    tool_, work_->name));
    return false;
  }
  if (part_stands_still()) return true;  // a mill: the spindle turns the drill
  if (std::abs(x_cl * scale_) <= 1e-3) return true;
  error(line, fmt::format("tool {} is a drill (TLDATA/DRILL) and the part turns on the {} spindle, but this "
                          "feed move leaves the centre line (x = {}): off-centre drilling needs the live "
                          "spindle (SPINDL/...,LIVE)",
                          tool_, work_->name, x_cl));
  return false;
}

std::string channel_writer::off_centre_hole_needs() const {
  if (!has_c_)
    return fmt::format(
        "channel {} of machine '{}' has no C axis with live tools (a C axis and [milling]): with "
        "the part turning, the drill would cut a ring",
        ch_.number, m_.name);
  if (!c_mode_)
    return fmt::format(
        "the part turns on the {} spindle: drill it on the live spindle (SPINDL/...,LIVE), which "
        "holds the part as the C axis and turns it onto the hole",
        work_ ? work_->name : ch_.spindle);
  return fmt::format(
      "machine '{}' drills face holes off centre along Y (milling.face_holes = \"y_axis\"), and "
      "channel {} has no Y axis",
      m_.name, ch_.number);
}

void channel_writer::spindle(const spindle_event& s, int line) {
  // This record says what the spindle does now (or the post has failed).
  spindle_held_ = restate_spindle_ = transfer_since_speed_ = false;
  // A shared spindle kept turning through the tool change (channel_words.cpp): stopped here when
  // the new tool's SPINDL turns another one.
  const spindle_def* kept = spindle_kept_ ? spindle_ : nullptr;
  spindle_kept_ = false;
  stopped_by_user_ = nullptr;
  // A SPINDL refused here has failed the post: the cuts after it need no second error.
  struct judge_cuts {
    channel_writer& w;
    int errors;
    ~judge_cuts() { w.unstarted_judged_ = w.unstarted_ok_ = w.errors_ > errors; }
  } judge{*this, errors_};
  // A speed that writes S0 turns nothing, yet the cuts after it would count it as turning.
  if ((s.mode == spindle_mode::rpm || s.mode == spindle_mode::smm || s.mode == spindle_mode::sfm) &&
      !(s.speed >= 0.5))
    return error(line, fmt::format("SPINDL with a speed of {}: written S0, the spindle would not turn; give "
                                   "SPINDL/OFF to stop it, or a speed",
                                   kin::number_text(s.speed)));
  const spindle_def* target = spindle_;
  if (s.spindle == "main" || s.spindle == "sub") {
    const spindle_def* sel = m_.spindle(s.spindle);
    if (!sel)
      return error(line, fmt::format("SPINDL/...,{}: machine '{}' has no {} spindle", upper(s.spindle),
                                     m_.name, s.spindle));
    // The word says where the part is; a milling tool (or a drill off the axis) still turns
    // the live spindle, never the part against a still cutter.
    work_on(*sel);
    target = kind_ == tool_kind::mill || kind_ == tool_kind::drill ? spindle_for_tool(s, line) : sel;
    if (!target) return;
  } else if (s.spindle == "live") {
    if (ch_.live_spindle.empty())
      return error(line, fmt::format("SPINDL/...,LIVE: channel {} of machine '{}' has no live spindle "
                                     "(channel.live_spindle)",
                                     ch_.number, m_.name));
    target = m_.spindle(ch_.live_spindle);
  } else if (!s.spindle.empty()) {
    return error(line, fmt::format("machine '{}' has no {} spindle", m_.name, s.spindle));
  } else if (s.mode != spindle_mode::off && s.mode != spindle_mode::on && work_) {
    target = spindle_for_tool(s, line);
    if (!target) return;
  }
  if (!target) return error(line, fmt::format("machine '{}' has no spindle '{}'", m_.name, ch_.spindle));
  if (kept && target != kept && s.mode != spindle_mode::off)
    spindle_block(fmt::format("M{}", kept->stop), true);
  // The spindle the section works on is selected first (the Fusion Integrex post: M901/M902,
  // then the C axis); a live tool works on the part held in the workpiece spindle.
  if (s.mode != spindle_mode::on) select_spindle(target->select ? target : work_);
  // Mill/turn: a live tool holds the workpiece spindle as the C axis; a turning speed lets it go.
  if (has_c_ && s.mode != spindle_mode::off && s.mode != spindle_mode::on) {
    if (target != work_) {
      if (!enter_c_axis(line)) return;
    } else {
      leave_c_axis();
    }
  }
  spindle_ = target;
  if (!head_offset_chosen_.empty()) [[unlikely]] {
    // A SPINDL after the tool's approach gave the head's offset: that offset follows what turns
    // (index_head), and another spindle now would leave the other code in force (attack 69 H1: a
    // centre drill under the live tool's `G43 H#3020`).
    const head_index_rules& h = ch_.head_index;
    const bool live = spindle_ && work_ && spindle_ != work_;
    const std::string& want = !live && kind_ != tool_kind::mill ? h.offset_turning : h.offset_live;
    if (want != head_offset_chosen_ && s.mode != spindle_mode::off)
      return error(line,
                   fmt::format("SPINDL turns the {} spindle for this tool after its first move gave the "
                               "head's offset for a {} tool (`{}`); the tool wants `{}`: give the SPINDL "
                               "before the tool's first GOTO",
                               spindle_->name, live ? "stationary" : "live", head_offset_chosen_, want));
  }
  if (s.mode == spindle_mode::on) {
    // APT: ON turns the spindle on again at the last speed, mode and direction, never S0.
    if (!last_speed_)
      return error(line,
                   "SPINDL/ON with no spindle speed given before in this channel: give "
                   "SPINDL/RPM,n or SPINDL/SMM,n");
    spindle_event again = *last_speed_;
    if (s.dir != rotation::none) again.dir = s.dir;
    again.spindle.clear();  // the spindle selected now
    return spindle(again, line);
  }
  const spindle_def& sp = *spindle_;
  if (s.mode == spindle_mode::off) {
    restart_blocks_.clear();
    stopped_by_cl_ = spindle_;
    return spindle_block(fmt::format("M{}", sp.stop), true);
  }
  if (s.mode == spindle_mode::orient || s.mode == spindle_mode::lock)
    return error(line, "spindle ORIENT/LOCK is not supported on a lathe channel yet");
  int m = s.dir == rotation::ccw ? sp.ccw : sp.cw;
  double rpm = s.speed;
  const bool css = s.mode == spindle_mode::sfm || s.mode == spindle_mode::smm;
  if (css && (spindle_ != work_ || part_stands_still())) {
    // A surface speed for a rotating tool (a mill's spindle, a live tool) is the tool's rpm:
    // constant surface speed would follow the X position, not the cutter's diameter.
    const std::optional<double> r = tool_rpm(s, sp, line);
    if (!r) return;
    rpm = *r;
  } else if (css) {
    // G96 S is in m/min with mm output, in ft/min with inch output.
    const bool inch = out_per_mm_ < 1;
    const double smm = s.mode == spindle_mode::sfm ? (inch ? s.speed : s.speed * 0.3048)
                       : inch                      ? s.speed / 0.3048
                                                   : s.speed;
    if (!s.max_rpm && sp.max_rpm <= 0)
      return error(line, "constant surface speed needs MAXRPM (or a spindle limit in the machine)");
    double clamp = s.max_rpm ? *s.max_rpm : sp.max_rpm;
    if (sp.max_rpm > 0 && clamp > sp.max_rpm)
      return error(line, fmt::format("MAXRPM {} exceeds the {} spindle's limit of {} rpm", clamp, sp.name,
                                     sp.max_rpm));
    cl_clamp_ = clamp;
    template_args a;  // template_uses::clamp
    a.max = clamp;
    a.rpm = clamp;
    a.channel = ch_.number;
    if (!fits('S', smm, 0)) return;
    restart_blocks_.clear();
    if (!sp.clamp.empty()) {
      std::string b = format_template(sp.clamp, a);
      if (!block_fits(b)) return;
      restart_blocks_.push_back(b);
    }
    restart_blocks_.push_back(
        join_words(m_.codes.css, fmt::format("S{} M{}", format_nc_number(smm, {0, false}), m)));
    for (const std::string& b : restart_blocks_) spindle_block(b);
    last_speed_ = s;
    stopped_by_cl_ = nullptr;
    note_start();
    return;
  }
  if (sp.max_rpm > 0 && rpm > sp.max_rpm)
    return error(line,
                 fmt::format("{} rpm exceeds the {} spindle's limit of {} rpm", rpm, sp.name, sp.max_rpm));
  if (!fits('S', rpm, 0)) return;
  restart_blocks_ = {join_words(m_.codes.rpm, fmt::format("S{} M{}", format_nc_number(rpm, {0, false}), m))};
  spindle_block(restart_blocks_.front());
  // A surface speed made rpm is the rpm in force: a tap's M29 S.. and SPINDL/ON use it.
  last_speed_ = s;
  last_speed_->mode = spindle_mode::rpm;
  last_speed_->speed = rpm;
  stopped_by_cl_ = nullptr;
  note_start();
}

std::optional<double> channel_writer::tool_rpm(const spindle_event& s, const spindle_def& sp, int line) {
  const char* unit = s.mode == spindle_mode::sfm ? "SFM" : "SMM";
  const std::string what = fmt::format("SPINDL/{},{:g}", unit, s.speed);
  const std::string tool = fmt::format("tool {}", tool_);
  std::optional<double> d = diameter_;  // TLDATA's, in mm
  if (!d)
    if (const tool_def* t = m_.tool(ch_.number, tool_)) d = t->diameter;
  if (!d) {
    error(line,
          fmt::format("{}: a surface speed for {}, which turns on the {} spindle: its rpm = 1000 v / (pi D) "
                      "needs the tool's diameter; give TLDATA/MILL,<diameter>,... with the tool, or its "
                      "diameter in the tool table of machine '{}' ([[tool]] diameter)",
                      what, tool, sp.name, m_.name));
    return std::nullopt;
  }
  // m/min (SFM: ft/min, 0.3048 m each) over the circumference in m: rpm = 1000 v / (pi D),
  // the same as 12 v / (pi D) with v in ft/min and D in inches.
  const double v = s.mode == spindle_mode::sfm ? s.speed * 0.3048 : s.speed;
  const double rpm = std::round(1000 * v / (std::numbers::pi * *d));
  const std::string gives = fmt::format("{} gives {} rpm for the {:g} mm {}", what, rpm, *d, tool);
  // A rotating tool's diameter does not change along the path: a clamp would cut all of it
  // slower than the speed the CAM chose, with the feed per tooth raised by the same ratio.
  if (s.max_rpm && rpm > *s.max_rpm) {
    error(line, fmt::format("{}, over its MAXRPM of {:g}: a clamp would cut the whole path slower than the "
                            "surface speed asks, at a higher feed per tooth; give a lower surface speed or "
                            "SPINDL/RPM",
                            gives, *s.max_rpm));
    return std::nullopt;
  }
  if (sp.max_rpm > 0 && rpm > sp.max_rpm) {
    error(line, fmt::format("{}, over the {} spindle's limit of {:g} rpm ([[spindle]] max_rpm): give a lower "
                            "surface speed or SPINDL/RPM",
                            gives, sp.name, sp.max_rpm));
    return std::nullopt;
  }
  if (rpm < 1) {
    error(line, fmt::format("{}: the spindle would not turn", gives));
    return std::nullopt;
  }
  return rpm;
}

void channel_writer::transfer(const transfer_event& t, int line) {
  switch (t.step) {
    case transfer_event::phase::retract:
      // Out of the space between the spindles: coolant off, home X then Z (once: a channel
      // already home stays there). A spindle held as a C axis turns freely again first.
      leave_c_axis();
      if (!coolant_block_.empty()) coolant_block(coolant_off_block_, true);
      coolant_block_.clear();
      coolant_off_block_.clear();
      if (homed_) return;
      go_home();
      forget_axes();
      motion_g_ = -1;
      start_home_ = tool_ < 0;  // as a wait's home before the first tool call (on_wait)
      return;
    case transfer_event::phase::blocks: {
      // The blocks may set the feed mode, F and the motion (the grip's G98/G94 G1 approach):
      // the channel's own mode goes back on at once and its next move writes G and F again,
      // never a feed per revolution read per minute.
      bool mode_set = false;
      // After a part-off the main chuck holds the bar: the release that opens it would let the
      // bar go (a pick-off), so the machine's release_after_cutoff is written instead.
      const bool cut_off = t.release && t.cutoff_line != 0;
      if (cut_off && !m_.transfer.has_release_after_cutoff)
        return error(line,
                     fmt::format("TRANSFER/RELEASE after the part-off at line {}: machine '{}' gives no "
                                 "[transfer] release_after_cutoff, and its release ({}) would open the "
                                 "main chuck on the bar; give the blocks that take the part away and "
                                 "leave the bar clamped",
                                 t.cutoff_line, m_.name, fmt::join(m_.transfer.release, " / ")));
      if (ev_) [[unlikely]]
        user_blocks(event_point::transfer, false, {});
      for (const std::string& b : cut_off     ? m_.transfer.release_after_cutoff
                                  : t.release ? m_.transfer.release
                                              : m_.transfer.grip) {
        start_home_ = false;  // a shop's grip may move this channel's axes too
        out_.block(b);
        for (const std::string* g : {&m_.codes.feed_per_min, &m_.codes.feed_per_rev})
          mode_set = mode_set || (!g->empty() && b.find(*g) != std::string::npos);
      }
      if (mode_set && !feed_g_.empty()) out_.block(feed_g_);
      if (ev_) [[unlikely]]
        user_blocks(event_point::transfer, true, {});
      last_f_.clear();
      motion_g_ = -1;
      transfer_since_speed_ = true;
      spindle_ended_.clear();  // the transfer's own codes synchronise and start spindles: the footer's
      coolant_ended_.clear();  // stops are not known to be in force any more
      return;
    }
    case transfer_event::phase::on_sub:
      // The next SPINDL selects the sub (M902 on the Integrex) and starts it.
      if (const spindle_def* sub = m_.spindle("sub")) work_on(*sub);
      return;
    case transfer_event::phase::grip:
    case transfer_event::phase::release: return;  // the router sends the steps
  }
}

}  // namespace twinpost
