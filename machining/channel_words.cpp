// channel_writer: coolant, feed and tool blocks (the spindle: machining/channel_spindle.cpp).
#include <cmath>
#include <fmt/format.h>

#include "machines/name_template.hpp"
#include "machining/channel_writer.hpp"
#include "nc/nc_words.hpp"

namespace twinpost {

void channel_writer::coolant(const coolant_event& c, int line) {
  if (c.mode == "OFF") {
    coolant_due_.clear();
    coolant_block(coolant_off_block_.empty() ? m_.codes.coolant_off : coolant_off_block_, true);
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
  if (coolant_block_ == on) return;  // already on
  if (!coolant_block_.empty() && coolant_due_.empty())
    coolant_block(coolant_off_block_, true);  // another kind: off first
  // A tool whose head is not indexed yet: the coolant waits for the index (index_head).
  if (ch_.head_index.present() && has_c_ && after_index_)
    coolant_due_ = on;
  else
    coolant_block(on, false);
  coolant_block_ = on;
  coolant_off_block_ = off;
}

void channel_writer::resume_spindle(int line) {
  // A held spindle turns again; one that turned on through the call is said again, then the
  // coolant.
  const bool restart = spindle_held_ || restate_spindle_;
  restate_spindle_ = false;
  spindle_held_ = spindle_kept_ = false;
  stopped_by_user_ = nullptr;  // the post starts it again before the move
  // On a head with a workpiece and a live spindle, the spindle stopped for the tool change
  // turns again only for a tool of the same kind: a milling cutter after a turning tool
  // needs the other spindle.
  if (!ch_.live_spindle.empty()) {
    const spindle_def* live = m_.spindle(ch_.live_spindle);
    const spindle_def* wanted = kind_ == tool_kind::turn    ? work_
                                : kind_ == tool_kind::mill  ? live
                                : kind_ == tool_kind::drill ? (std::abs(axis_.z) >= 0.9999 ? work_ : live)
                                                            : nullptr;
    if (wanted != spindle_) {
      restart_blocks_.clear();
      unstarted_judged_ = unstarted_ok_ = true;  // the error below says it: no second one at the cut
      return error(line, fmt::format("tool {} ({} at line {}) would start with the {} spindle that turned "
                                     "before the tool change{}: give SPINDL for this tool before its first "
                                     "move",
                                     tool_, tool_word_, tool_line_, spindle_->name,
                                     wanted ? fmt::format(", but it needs the {} spindle", wanted->name)
                                            : " and its kind is unknown (no TLDATA)"));
    }
  }
  if (restart)
    for (const std::string& b : restart_blocks_) spindle_block(b);
  coolant_after_speed();
}

void channel_writer::coolant_after_speed() {
  if (coolant_after_speed_.empty()) return;
  std::string b;
  b.swap(coolant_after_speed_);
  coolant_block(b, false);
}

// Whether a home block moves an axis of `along` (a word of one of its addresses), its words
// read as the checker reads them: glued (`G28U0.`), lower case, comments skipped (attack 67 H7:
// `G28U0.` then `G28W0.` took a drill out of its hole X first).
static bool moves_along(const std::string& b, std::string_view along) {
  for (const nc_word& w : split_nc_words(std::string_view(b)))
    if (along.find(w.address) != std::string_view::npos) return true;
  return false;
}

// Home block `b` without its axis words across the tool (an axis address not in `along`), the
// rest as written, comments included (attack 67 M8: `G28 U0. (RETURN Z AND X)` came out
// `G28 (RETURN Z`), and the blanks after a word left out with it.
static std::string along_words(const std::string& b, std::string_view along) {
  std::string out;
  std::size_t from = 0;
  for (const nc_word& w : split_nc_words(std::string_view(b))) {
    if (std::string_view("XYZUVWABC").find(w.address) == std::string_view::npos ||
        along.find(w.address) != std::string_view::npos)
      continue;
    const auto at = static_cast<std::size_t>(w.column - 1);
    std::size_t end =
        w.value.empty() ? at + 1 : static_cast<std::size_t>(w.value.data() - b.data()) + w.value.size();
    while (end < b.size() && (b[end] == ' ' || b[end] == '\t')) ++end;
    out.append(b, from, at - from);
    from = end;
  }
  out.append(b, from, std::string::npos);
  while (!out.empty() && (out.back() == ' ' || out.back() == '\t')) out.pop_back();
  return out;
}

// The home blocks leave_cut() writes: those that move along the tool, each with the blocks
// that move nothing right after it (`G91 G28 Z0.` and its `G90`), as bits by index.
static std::uint64_t along_blocks(const std::vector<std::string>& home, std::string_view along) {
  std::uint64_t bits = 0;
  bool with = false;
  for (std::size_t i = 0; i < home.size() && i < 64; ++i) {
    if (moves_along(home[i], along))
      with = true;
    else if (moves_along(home[i], "XYZUVWABC"))
      with = false;
    if (with) bits |= std::uint64_t{1} << i;
  }
  return bits;
}

void channel_writer::leave_cut(bool at_end) {
  // From a cut (a GOHOME or a tool call with no retract in the CL; review
  // 61 A2: a drill at the bottom of its hole went home X and Y first) the tool leaves along its
  // axis first: the home blocks that move that axis, before its spindle and coolant stop
  // (review 64: an end mill stopped at the bottom of its pocket). The public posts take the
  // CAM's retract for granted here (the Fusion "Mazak Integrex i" post: writeRetract(X, Y),
  // then writeRetract(Z)); after a rapid the machine's order stands.
  retract_facing();
  const std::string_view along = along_tool();
  if (along.empty()) {
    // A tool whose way out the post cannot know (a turning tool in a bore, a groove, under a
    // shoulder: review 64 H3; a tilted 5-axis tool: attack 65) is said.
    if (in_cut_ && tool_ >= 0 && !(at_end && !chain_)) [[unlikely]]
      warning(
          "the tool goes home straight from a feed move, with no retract in the CL: the home blocks move "
          "it as the machine file lists them, from where the feed left it; in a bore, a groove or under a "
          "shoulder it would run into the part: give the retract before GOHOME or the tool change");
    in_cut_ = false;
    return;
  }
  leave_polar();  // no reference return inside polar interpolation or a turned frame
  leave_radial_frame();
  const std::vector<std::string>& home = m_.home(ch_.number);
  left_blocks_ = along_blocks(home, along);
  bool again = false;  // the block before was cut down: it and its followers go home again
  for (std::size_t i = 0; i < home.size() && i < 64; ++i) {
    if (!(left_blocks_ >> i & 1u)) continue;
    // A block that moves an axis across the tool as well (the Integrex upper head's
    // `G0 G90 G53 X0. Y0.`, the 31i path 3's `G28 U0. V0.` for a radial drill) would drag the
    // tool sideways out of its hole: its words along the tool go first, and the whole block
    // (with the blocks that move nothing after it, `G90` after `G91 G28 ..`) after, with the
    // other home blocks.
    const std::string own = along_words(home[i], along);
    if (own != home[i])
      again = true;
    else if (moves_along(home[i], "XYZUVWABC"))
      again = false;
    out_.block(own);
    if (again)
      left_blocks_ &= ~(std::uint64_t{1} << i);
    else if (at_end && !filtered_)  // (a script's on_block may have written another: attack 68 H1)
      end_home_.push_back(own);     // the footer need not write it again
  }
  in_cut_ = false;
}

void channel_writer::go_home() {
  user_x_.reset();  // the user blocks' X (the gate's) is the post's home from here
  leave_cut();      // (its blocks along the tool first, from a cut)
  leave_polar();    // no reference return inside polar interpolation or a turned frame
  leave_radial_frame();
  const std::vector<std::string>& home = m_.home(ch_.number);
  for (std::size_t i = 0; i < home.size(); ++i)
    if (i >= 64 || !(left_blocks_ >> i & 1u)) out_.block(home[i]);
  left_blocks_ = 0;
  homed_ = true;
  in_cut_ = false;
  // Home blocks that cancel the tool's length offset (`G49`, `D0`; attack 47: a GOHOME in the
  // middle of an operation, and the cuts after it ran a tool length low): the next move gives
  // it again (`G43 H..`, the chain's length or tool-tip code), or, where the tool call gives it
  // and the post has no code for it, the next move of the same tool is an error.
  if (home_cancels_length_) [[unlikely]] {
    if (chain_) {
      const std::string& on = solves_joints(*chain_) ? chain_->length_on : chain_->tool_tip_on;
      offset_on_ = false;
      length_lost_ = on.empty() && chain_->output != multiaxis_output::pivot;
    } else if (!length_offset_text_.empty()) {
      pending_offset_ = length_offset_text_;
    }
  }
  // (A length offset turned on again since, the same tool called again, needs no cancel.)
  if (length_cancel_due_ && !offset_on_) out_.block(chain_->tool_tip_off);
  length_cancel_due_ = false;
}

void channel_writer::program_stop(bool optional) {
  out_.block(optional ? m_.codes.optional_stop : m_.codes.program_stop);
  for (const std::string& b : restart_blocks_) spindle_block(b);
  if (!coolant_block_.empty()) coolant_block(coolant_block_, false);
}

void channel_writer::feed(const feed_event& f, int line) {
  if (f.mode == feed_mode::inverse_time)
    return error(line, "inverse-time feed is not supported on a lathe channel");
  const double mm = f.value * (f.units == unit_system::inch ? 25.4 : 1.0);
  const double value = mm * out_per_mm_;  // in the output units
  // F is written with 4 decimals per revolution, 1 per minute in mm (append_feed).
  if (value != 0 && !feed_writable(value, f.mode == feed_mode::per_rev, "FEDRAT", line)) return;
  // A feed per revolution depends on the spindle speed: only per-minute feeds are held to it.
  const double max_feed = m_.limits.max_feed;
  if (f.mode == feed_mode::per_minute && max_feed > 0 && mm > max_feed)
    return error(line, fmt::format("feed {} mm/min exceeds the machine's limit of {} mm/min "
                                   "(limits.max_feed)",
                                   mm, max_feed));
  feed_value_ = value;
  fedrat_before_cycle_.reset();  // the FEDRAT in force from here, after the cycle too
  feed_mode(f.mode == feed_mode::per_rev);
}

bool channel_writer::feed_writable(double value, bool per_rev, std::string_view record, int line) {
  const int decimals = feed_decimals(per_rev);
  if (!(value > 0)) {
    error(line, fmt::format("{}: a feed of {} is no feed (above 0)", record, kin::number_text(value)));
    return false;
  }
  if (value < 0.5 * decimal_unit(decimals)) {
    error(line, fmt::format("{}: a feed of {} is written F0 (F keeps {} decimal{}): no control moves at it",
                            record, kin::number_text(value), decimals, decimals == 1 ? "" : "s"));
    return false;
  }
  return fits('F', value, decimals);
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
  // Cutter compensation the CL never turned off reaches the next tool (attack 69 L9: `G42` of a
  // turning tool in force through the tool change to the end): said once a tool change.
  if (comp_cl_on_) [[unlikely]]
    warning(
        "the tool changes with cutter compensation still on (CUTCOM/LEFT or RIGHT without CUTCOM/OFF): the "
        "control carries G41 or G42 to the next tool; give CUTCOM/OFF with a move before the tool change");
  template_args a;  // template_uses::tool_call
  a.tool = t.tool;
  a.offset = t.offset.value_or(t.tool);
  a.channel = ch_.number;
  const std::string call = format_template(ch_.tool_call, a);
  // A B head on a Fanuc lathe system takes the tool's offset in a block of its own (T0707 after
  // M6 T0700: the Fusion Doosan Mill/Turn post); a turret's call carries it (T0707).
  const std::string offset_block =
      ch_.offset_call.empty() ? std::string() : format_template(ch_.offset_call, a);
  const bool names_offset = ch_.tool_call.find("{offset") != std::string::npos ||
                            ch_.offset_call.find("{offset") != std::string::npos ||
                            ch_.length_offset.find("{offset") != std::string::npos;
  // A mill head without a chain or an indexing head takes the tool's length offset with the
  // first move after the call (channel.length_offset: G43 H..); so do the channel's own moves of
  // a chain that takes only the tilted ones (moves = "tilted": its plunge along Z ran at the
  // gauge line, found by the comparison with the CL).
  const bool length_offset = !ch_.length_offset.empty() && !ch_.head_index.present() &&
                             (!chain_ || chain_->moves == multiaxis_moves::tilted);
  static constexpr const char* words[] = {"LOADTL", "LOAD/TOOL",     "SELECT/TOOL",
                                          "TURRET", "[[tool]] name", "post --tool"};
  const char* word = words[static_cast<int>(t.source)];
  // Offset 0 in a lathe tool call (T0300) cancels the tool's offset: the tip would run
  // where the turret's reference point is, not where the CL says.
  if (a.offset == 0 && !ch_.offset_zero && names_offset) {
    error(line, fmt::format("tool {} with offset 0 would be called as {}, which cancels the tool offset; "
                            "give the offset number (or set channel.offset_zero where the control's tool "
                            "table applies it)",
                            t.tool, call));
    return take_tool(t.tool, line, word);
  }
  // A call template without {offset} (the Integrex mill head's T01 M6) cannot select another
  // offset: TURRET/1,21 for the finish would run on the roughing offset without a word.
  // A channel whose every move goes through its chain writes the offset itself, in the length
  // code of the first move after the call (G43 H<offset>, G43.4 H<offset>).
  const bool chain_offset = [&] {
    if (!chain_ || chain_->moves != multiaxis_moves::all) return false;
    const std::string& on = offset_code(*chain_);
    return !on.empty() && on.find('H') == std::string::npos;
  }();
  if (t.offset && *t.offset != t.tool && !chain_offset && !names_offset) {
    error(line, fmt::format("{} asks for tool {} on offset {}, but the channel's tool call {} writes no "
                            "offset (channel.tool_call has no {{offset}}): the tool would cut on "
                            "whatever offset is active",
                            word, t.tool, *t.offset, call));
    return take_tool(t.tool, line, word);
  }
  if (t.tool == tool_) {
    // The same tool under another offset (TURRET/1,1 then TURRET/1,21 for the finish): the
    // turret stays where it is and only the offset changes, so the call goes out alone.
    const std::string& block = offset_block.empty() ? call : offset_block;
    if (call + offset_block != tool_call_ && block_fits(block)) {
      // Not inside polar interpolation: the control takes no offset change in the mode, and
      // leaving it turns C back to 0 where the tool stands for the next start, which in the
      // face (or at a height a helix or a lead-in from outside reached) turns the part round
      // the cutter (reviews 55 and 56). After a GOHOME the mode is off.
      if (polar_)
        return error(line,
                     fmt::format("{} changes tool {}'s offset inside polar interpolation: the control "
                                 "takes no offset change in the mode, and leaving it turns C back to 0 "
                                 "where the tool stands, which may turn the part round the cutter; give "
                                 "a GOHOME before the offset change",
                                 word, t.tool));
      if (ev_) [[unlikely]] {  // the same tool on another offset: a section of its own
        section_end();
        tool_offset_ = a.offset;
      }
      // Not inside polar or cylindrical interpolation or a turned frame (a T code there is no
      // offset change the control takes: review 54), and every axis said again at its next
      // move: the control applies the new offset to each axis as it next moves, and a Y left
      // where the old offset put it would shift a polar cut (the next one sets Y0 again).
      leave_polar();
      leave_cylinder();
      leave_radial_frame();
      forget_axes();
      out_.block(block, true);
      tool_call_ = call + offset_block;
      if (length_offset) pending_offset_ = length_offset_text_ = format_template(ch_.length_offset, a);
    }
    return;
  }
  if (!block_fits(call) || (!offset_block.empty() && !block_fits(offset_block)))
    return take_tool(t.tool, line, word);  // T12345 on a four-digit T
  // Coolant off before the turret leaves the part and indexes, home X then Z, the call, and
  // the coolant the CL left on back on for the new tool (public Fanuc posts: M9, G28 U0.,
  // G28 W0., T0202, then coolant once the tool is there; docs/machines.md). From a cut, the
  // tool leaves along its axis first, its spindle still turning.
  leave_cut();
  const std::string coolant_was = coolant_block_;
  const std::string coolant_off_was = coolant_off_block_;
  template_args ea;  // events.tool_change
  if (ev_) [[unlikely]] {
    section_end();
    tool_offset_ = a.offset;
    ea = a;
    ea.name = cam_tool_;  // the CAM's name of the tool (TOOL PATH, TPRINT before the call)
    if (const tool_def* d = m_.tool(ch_.number, t.tool)) ea.text = d->name;
    user_blocks(event_point::tool_change, false, ea);
  }
  // The tool changer needs the spindle that drives the tool stopped. A shared workpiece spindle
  // (another turret may be cutting on it) keeps turning when the next tool is a turning tool,
  // which wants that spindle the same way: its SPINDL changes the speed if it asks another
  // (issue 37, item 9). Any other next tool (a live tool holds the spindle as C, a tool of
  // unknown kind) has it stopped, as before.
  if (ch_.tool_change_stops_spindle && spindle_ && !restart_blocks_.empty() && !spindle_held_) {
    tool_kind next = next_kind_;
    if (next == tool_kind::unknown) {
      const std::string_view k = m_.tool_kind(ch_.number, t.tool);
      next = k == "turn" ? tool_kind::turn : k.empty() ? tool_kind::unknown : tool_kind::mill;
    }
    const bool drives_tool = spindle_->name == ch_.live_spindle;
    const bool shared = m_.shared_spindle(static_cast<int>(spindle_index(*spindle_)));
    if (!drives_tool && shared && next == tool_kind::turn) {
      spindle_kept_ = true;
    } else {
      spindle_block(fmt::format("M{}", spindle_->stop), true);
      spindle_held_ = true;
    }
  }
  if (!coolant_was.empty()) coolant_block(coolant_off_was, true);
  // The first call after a wait that sent the channel home (on_wait), nothing moved since: once.
  if (!(start_home_ && homed_ && tool_ < 0)) go_home();
  start_home_ = false;
  length_lost_ = false;                                      // the tool call gives the offset
  if (chain_ && !ch_.head_index.present()) heads_upright();  // an indexing head turns with its own clamps
  forget_axes();
  motion_g_ = -1;
  out_.block(call, true);
  if (!offset_block.empty()) out_.block(offset_block);
  restore_plane();
  if (length_offset) pending_offset_ = length_offset_text_ = format_template(ch_.length_offset, a);
  // The tool changer may leave an indexing head anywhere (public Integrex posts send B to 0 at
  // every tool change and index it again): the next tool's angle is written, even the same one.
  head_angle_.reset();
  // A channel that starts on the sub spindle: its work offset once the tool is there.
  if (offset_due_) {
    out_.block(work_->work_offset);
    offset_due_ = false;
  }
  // Each section selects the spindle it works on, whatever an earlier one left selected (the
  // Fusion "Mazak Integrex i" post writes M901 or M902 in every section's start): its SPINDL,
  // or else its first move, writes the select code again.
  selected_ = nullptr;
  if (ev_) [[unlikely]]
    user_blocks(event_point::tool_change, true, ea);
  // A restart at this tool call finds its speed and its feed: both written again before its
  // first cut, where the CL gives no SPINDL (resume_spindle) and however the last F read. Not
  // on a spindle another channel may command: what it turns at then is the two channels'
  // (the review of this change, H1: a speed said again over the other channel's M5 or S600
  // turned the spindle on, or back to this channel's speed, in an uninterrupted run).
  restate_spindle_ = spindle_ && !restart_blocks_.empty() && !spindle_held_ && !transfer_since_speed_ &&
                     !m_.shared_spindle(static_cast<int>(spindle_index(*spindle_)));
  last_f_.clear();
  if (!coolant_was.empty()) {
    if (ch_.head_index.present() && has_c_)
      coolant_due_ = coolant_was;  // after the head's index (index_head)
    else if (restate_spindle_)
      coolant_after_speed_ = coolant_was;  // after the speed, as at the first call (review 52, L1)
    else
      coolant_block(coolant_was, false);
  }
  tool_call_ = call + offset_block;
  after_index_ = true;
  head_offset_chosen_.clear();
  take_tool(t.tool, line, word);
  if (script_) [[unlikely]]
    script_tool(t.tool, a.offset);
}

void channel_writer::restore_plane() {
  // An arc in G18 or G19 (a CIRCLE about Y or X) leaves that plane in force: the next tool's
  // G43 and a canned cycle would take Y (or X) as the tool's axis (Fanuc: length offset type
  // B, FXY = 1), the hole drilled along Y.
  if (header_plane_ == 0 || plane_ == header_plane_) return;
  out_.block(fmt::format("G{}", header_plane_));
  plane_ = header_plane_;
}

void channel_writer::take_tool(int tool, int line, const char* word) {
  unstarted_judged_ = false;
  diameter_ = next_diameter_;
  next_diameter_.reset();
  at_pos_ = false;  // the tool change moved the tool
  hole_exit_.reset();
  // A TLDATA before the call describes the tool; a tool called again without one keeps the
  // length it had (NX writes TLDATA once per operation, a reload may come without).
  if (next_reach_) reach_of_[tool] = *next_reach_;
  if (const auto known = reach_of_.find(tool); known != reach_of_.end())
    reach_ = known->second;
  else
    reach_.reset();
  // The tool table's length (measured on the machine) limits the hole as well: the shorter.
  reach_from_table_ = false;
  if (const std::optional<double> table = m_.tool_length(ch_.number, tool);
      table && (!reach_ || *table < *reach_)) {
    reach_ = *table;
    reach_from_table_ = true;
  }
  next_reach_.reset();
  const tool_def* table = m_.tool(ch_.number, tool);
  table_speed_due_ = table && (table->rpm || table->surface_speed);
  tool_ = tool;
  clear_n_ = 0;
  tool_line_ = line;
  tool_word_ = word;
  tool_cam_name_ = cam_tool_;
  tool_cam_line_ = cam_tool_line_;
  kind_ = next_kind_;
  next_kind_ = tool_kind::unknown;
  table_kind(tool, line);
  // Neither TLDATA nor [[tool]]: the kind post --tool-kind gives every such tool.
  if (kind_ == tool_kind::unknown) kind_ = default_kind_;
  after_call_ = true;
}

}  // namespace twinpost
