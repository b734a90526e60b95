// channel_writer: spindle, feed and tool blocks.
#include <cmath>
#include <fmt/format.h>

#include "formats/channel_writer.hpp"
#include "machines/name_template.hpp"

namespace twinpost {

namespace {
// `code words`, or just `words` when the machine has no such code (a mill has no G97).
std::string join_words(const std::string& code, std::string words) {
  return code.empty() ? words : code + " " + words;
}
}  // namespace

void channel_writer::spindle(const spindle_event& s, int line) {
  if (!s.spindle.empty()) {
    const spindle_def* sel = m_.spindle(s.spindle);
    if (!sel) return error(line, fmt::format("machine '{}' has no {} spindle", m_.name, s.spindle));
    if (sel != spindle_) {
      spindle_ = sel;
      if (sel->select) out_.block(fmt::format("M{}", *sel->select));
    }
  }
  if (!spindle_) return error(line, fmt::format("machine '{}' has no spindle '{}'", m_.name, ch_.spindle));
  spindle_held_ = false;  // this record says what the spindle does now
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
    return out_.block(fmt::format("M{}", sp.stop));
  }
  if (s.mode == spindle_mode::orient || s.mode == spindle_mode::lock)
    return error(line, "spindle ORIENT/LOCK is not supported on a lathe channel yet");
  int m = s.dir == rotation::ccw ? sp.ccw : sp.cw;
  if (s.mode == spindle_mode::sfm || s.mode == spindle_mode::smm) {
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
    for (const std::string& b : restart_blocks_) out_.block(b);
    last_speed_ = s;
    return;
  }
  if (sp.max_rpm > 0 && s.speed > sp.max_rpm)
    return error(
        line, fmt::format("{} rpm exceeds the {} spindle's limit of {} rpm", s.speed, sp.name, sp.max_rpm));
  if (!fits('S', s.speed, 0)) return;
  restart_blocks_ = {
      join_words(m_.codes.rpm, fmt::format("S{} M{}", format_nc_number(s.speed, {0, false}), m))};
  out_.block(restart_blocks_.front());
  last_speed_ = s;
}

void channel_writer::coolant(const coolant_event& c, int line) {
  if (c.mode == "OFF") {
    out_.block(coolant_off_block_.empty() ? m_.codes.coolant_off : coolant_off_block_);
    coolant_block_.clear();
    coolant_off_block_.clear();
    return;
  }
  // The kind's [on, off]: flood from coolant_on/coolant_off, the others from their pairs.
  const control_codes& k = m_.codes;
  const std::vector<std::string>* pair = nullptr;
  std::string_view key;
  if (c.mode == "MIST")
    pair = &k.coolant_mist, key = "coolant_mist";
  else if (c.mode == "THRU")
    pair = &k.coolant_through, key = "coolant_through";
  else if (c.mode == "AIR")
    pair = &k.coolant_air, key = "coolant_air";
  if ((pair == nullptr && c.mode != "ON" && c.mode != "FLOOD") || (pair != nullptr && pair->size() != 2))
    return error(line,
                 fmt::format("COOLNT/{}: machine '{}' gives no code for this kind of coolant{}; writing "
                             "flood instead could burn the tool or flood a dry cut",
                             c.mode, m_.name, key.empty() ? "" : fmt::format(" (codes.{})", key)));
  if (pair == nullptr && k.coolant_on.empty())
    return error(line, fmt::format("COOLNT/{}: machine '{}' has no coolant-on code", c.mode, m_.name));
  const std::string& on = pair ? (*pair)[0] : k.coolant_on.front();
  const std::string& off = pair ? (*pair)[1] : k.coolant_off;
  if (coolant_block_ == on) return;                             // already on
  if (!coolant_block_.empty()) out_.block(coolant_off_block_);  // another kind: off first
  out_.block(on);
  coolant_block_ = on;
  coolant_off_block_ = off;
}

void channel_writer::resume_spindle() {
  for (const std::string& b : restart_blocks_) out_.block(b);
  spindle_held_ = false;
}

void channel_writer::go_home() {
  for (const std::string& b : m_.codes.home) out_.block(b);
}

void channel_writer::program_stop(bool optional) {
  out_.block(optional ? m_.codes.optional_stop : m_.codes.program_stop);
  for (const std::string& b : restart_blocks_) out_.block(b);
  if (!coolant_block_.empty()) out_.block(coolant_block_);
}

void channel_writer::feed(const feed_event& f, int line) {
  if (f.mode == feed_mode::inverse_time)
    return error(line, "inverse-time feed is not supported on a lathe channel");
  const double mm = f.value * (f.units == unit_system::inch ? 25.4 : 1.0);
  const double value = mm * out_per_mm_;  // in the output units
  // F is written with 4 decimals per revolution, 1 per minute in mm (append_feed).
  if (!fits('F', value, feed_decimals(f.mode == feed_mode::per_rev))) return;
  // A feed per revolution depends on the spindle speed: only per-minute feeds are held to it.
  const double max_feed = m_.limits.max_feed;
  if (f.mode == feed_mode::per_minute && max_feed > 0 && mm > max_feed)
    return error(line, fmt::format("feed {} mm/min exceeds the machine's limit of {} mm/min "
                                   "(limits.max_feed)",
                                   mm, max_feed));
  feed_value_ = value;
  feed_mode(f.mode == feed_mode::per_rev);
}

void channel_writer::feed_mode(bool per_rev) {
  per_rev_ = per_rev;
  const std::string& g = per_rev_ ? m_.codes.feed_per_rev : m_.codes.feed_per_min;
  if (g != feed_g_) {
    out_.block(g);
    feed_g_ = g;
    last_f_.clear();
  }
}

void channel_writer::tool(const tool_event& t, int line) {
  if (t.preselect) return;
  template_args a;  // template_uses::tool_call
  a.tool = t.tool;
  a.offset = t.offset.value_or(t.tool);
  a.channel = ch_.number;
  const std::string call = format_template(ch_.tool_call, a);
  // Offset 0 in a lathe tool call (T0300) cancels the tool's offset: the tip would run
  // where the turret's reference point is, not where the CL says.
  if (a.offset == 0 && ch_.tool_call.find("{offset") != std::string::npos) {
    tool_ = t.tool;  // the post has failed: its moves need no second error for a missing tool
    return error(line,
                 fmt::format("tool {} with offset 0 would be called as {}, which cancels the tool offset; "
                             "give the offset number",
                             t.tool, call));
  }
  if (t.tool == tool_) {
    // The same tool under another offset (TURRET/1,1 then TURRET/1,21 for the finish): the
    // turret stays where it is and only the offset changes, so the call goes out alone.
    if (call != tool_call_ && block_fits(call)) {
      out_.block(call, true);
      tool_call_ = call;
    }
    return;
  }
  if (!block_fits(call)) {  // T12345 on a four-digit T: the tool does not exist
    tool_ = t.tool;         // (the post has failed; no second error at its moves)
    return;
  }
  // Coolant off before the turret leaves the part and indexes, home X then Z, the call, and
  // the coolant the CL left on back on for the new tool (public Fanuc posts: M9, G28 U0.,
  // G28 W0., T0202, then coolant once the tool is there; docs/machines.md).
  const std::string coolant_was = coolant_block_;
  const std::string coolant_off_was = coolant_off_block_;
  if (ch_.tool_change_stops_spindle && spindle_ && !restart_blocks_.empty() && !spindle_held_) {
    out_.block(fmt::format("M{}", spindle_->stop));
    spindle_held_ = true;
  }
  if (!coolant_was.empty()) out_.block(coolant_off_was);
  go_home();
  forget_axes();
  motion_g_ = -1;
  out_.block(call, true);
  if (!coolant_was.empty()) out_.block(coolant_was);
  tool_ = t.tool;
  tool_call_ = call;
}

}  // namespace twinpost
