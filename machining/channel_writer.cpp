#include "machining/channel_writer.hpp"
#include "parser/cam_tool.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <initializer_list>
#include <string_view>

#include "kinematics/vec3_ops.hpp"
#include "machines/code_overlap.hpp"
#include "machines/name_template.hpp"
#include "nc/nc_words.hpp"
#include "support/ascii.hpp"
#include "support/errors.hpp"

namespace twinpost {

namespace {
// The last of `codes` (whole words, "" ignored) the header blocks give, in order; "" if none.
// A word is an address letter and the digits and point after it ("G18G21" holds G18, G170
// does not).
// Comments are no words: neither `(...)`, nor the machine's own, nor `;` to the end of the line.
std::string header_modal(const std::vector<std::string>& header, const program_format& f,
                         std::initializer_list<std::string_view> codes) {
  std::string found;
  for (const std::string& given : header) {
    std::string block;
    for (std::size_t i = 0; i < given.size(); ++i) {
      const char c = given[i];
      if (c == ';' || (c == f.comment_open && f.comment_close == '\n')) break;
      const char close = c == f.comment_open ? f.comment_close : c == '(' ? ')' : '\0';
      if (close) {
        i = given.find(close, i + 1);
        if (i == std::string::npos) break;
        block += ' ';
        continue;
      }
      block += c;
    }
    for (std::size_t at = 0; at < block.size();) {
      std::size_t end = at + 1;
      while (end < block.size() && ((block[end] >= '0' && block[end] <= '9') || block[end] == '.')) ++end;
      const std::string_view word = std::string_view(block).substr(at, end - at);
      for (std::string_view c : codes)
        if (!c.empty() && word == c) found = c;
      at = end;
    }
  }
  return found;
}
}  // namespace

channel_writer::channel_writer(const machine& m, const channel_def& ch, const std::string& path,
                               diagnostic_sink& diags, std::string cl_file, block_writer::framing frame)
    : m_(m), ch_(ch), diags_(diags), cl_file_(std::move(cl_file)),
      out_(path, m.program, std::move(frame), m.formats['N']) {
  axis_style_ = {m.program.axis_decimals(), m.program.trailing_point};
  out_per_mm_ = m.program.output_units == output_unit::inch ? 1 / 25.4 : 1.0;
  scale_ = cl_mm_ * out_per_mm_;
  const axis_def* x = ch.axis('X');
  x_factor_ = (x && !x->diameter) ? 1.0 : 2.0;
  if (x && x->mirror) x_factor_ = -x_factor_;
  x_mirror_ = x && x->mirror;
  x_diameter_ = x && x->diameter;
  has_y_ = ch.axis('Y') != nullptr;
  // Mill/turn needs the machine's [milling] table (how it holds C, its modes): a C axis on a
  // machine without one (fanuc-31i-3path's mill head) is not driven by the post yet.
  has_c_ = ch.axis('C') != nullptr && m.milling.present();
  // The plane in force after the header (G18 on a lathe, G17 on a mill), and its feed mode
  // (the Fanuc lathes' safe start ends in G99, the mills' has G94): the first FEDRAT in that
  // mode writes no second G99 right after it.
  const std::string plane = header_modal(m.program.header, m.program, {"G17", "G18", "G19"});
  if (!plane.empty()) plane_ = header_plane_ = (plane[2] - '0') + 10;
  absolute_code_ = !header_modal(m.program.header, m.program, {"G90"}).empty();
  feed_g_ = header_modal(m.program.header, m.program, {m.codes.feed_per_rev, m.codes.feed_per_min});
  per_rev_ = !feed_g_.empty() && feed_g_ == m.codes.feed_per_rev;
  spindle_ = work_ = m.spindle(ch.spindle);
  if (work_) {
    z_sign_ = work_->reverse_z ? -1.0 : 1.0;
    // A channel that starts on a spindle whose offset the safe start does not give (the
    // sub's G55) writes it after its first tool call.
    offset_due_ = !work_->work_offset.empty();
    for (const std::string& block : m.program.header)
      if (block.find(work_->work_offset) != std::string::npos) offset_due_ = false;
  }
  for (const std::string& b : m.home(ch.number))
    home_cancels_length_ =
        home_cancels_length_ || cancels_length_offset(b, m.program.comment_open, m.program.comment_close);
  last_x_.max = m.formats['X'].max_count(axis_style_.decimals);
  if (x && x->min && x->max) {
    const double scale = std::pow(10.0, axis_style_.decimals);
    last_x_.lo = static_cast<std::int64_t>(std::llround(*x->min * scale));
    last_x_.hi = static_cast<std::int64_t>(std::llround(*x->max * scale));
  }
  last_y_.max = m.formats['Y'].max_count(axis_style_.decimals);
  last_z_.max = m.formats['Z'].max_count(axis_style_.decimals);
  last_c_.max = m.formats['C'].max_count(axis_style_.decimals);
  out_.set_line_hook([this](std::string_view line) { note_line(line); });
  note_every_block_ = m.interference.channels.size() >= 2 && m.interference.channel(ch.number);
  if (!m.events.empty()) ev_ = &m.events;
  sections_ = !m.events[event_point::section].before.empty() || !m.events[event_point::section].after.empty();
  chain_ = m.chain(ch.number);
  if (chain_) {
    for (std::size_t i = 0; i < chain_->rotaries.size(); ++i) {
      const rotary_axis_def& r = chain_->rotaries[i];
      if (r.kind != rotary_kind::head) continue;
      chain_heads_ = true;
      // A head along the tool (a spindle-axis C head) turns it about itself: it never tilts it,
      // whatever its angle, and the tip then does not depend on the length.
      if (kin::norm(kin::cross(r.direction, chain_->tool_direction)) > 1e-12) tilting_heads_ |= 1u << i;
    }
    // The rotary words' and I J K's largest counts are set by their first word (rotary_word).
    for (axis_memory& a : last_rot_) a.max = 0;
    for (axis_memory& a : last_ijk_) a.max = 0;
  }
}

void channel_writer::note_block_cl() {
  block_cl_mem_.push_back(line_);
  ++block_cl_count_;
  // Every 64k lines to an anonymous temporary file; where none can be made or written, they
  // stay in memory (the post's own writes then fail and say so).
  if (block_cl_mem_.size() < (std::size_t{1} << 16) || block_cl_failed_) return;
  if (!block_cl_) block_cl_.reset(std::tmpfile());
  if (!block_cl_ || std::fwrite(block_cl_mem_.data(), sizeof(std::int32_t), block_cl_mem_.size(),
                                block_cl_.get()) != block_cl_mem_.size()) {
    block_cl_failed_ = true;
    return;
  }
  block_cl_in_file_ += block_cl_mem_.size();
  block_cl_mem_.clear();
}

int channel_writer::block_cl_line(std::size_t i) const {
  if (i >= block_cl_in_file_) return block_cl_mem_.at(i - block_cl_in_file_);
  std::int32_t line = 0;
  if (std::fflush(block_cl_.get()) != 0 ||
      std::fseek(block_cl_.get(), static_cast<long>(i * sizeof line), SEEK_SET) != 0 ||
      std::fread(&line, sizeof line, 1, block_cl_.get()) != 1)
    throw config_error("cannot read back the CL lines' temporary file");
  std::fseek(block_cl_.get(), 0, SEEK_END);  // where the next write goes, should one come
  return line;
}

void channel_writer::observe_head() {
  // The head's lines, once written (at the first line after it, or the first record after it
  // when a script dropped that line: review 67 L2), before anything else.
  if (observed_head_ || out_.head_written().empty()) return;
  observed_head_ = true;
  std::string_view head = out_.head_written();
  while (!head.empty()) {
    const std::size_t end = head.find('\n');
    std::string_view l = head.substr(0, end);
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    observer_->line(l);
    head.remove_prefix(end == std::string_view::npos ? head.size() : end + 1);
  }
}

void channel_writer::note_line(std::string_view line) {
  if (observe_lines_) [[unlikely]] {
    observe_head();
    observer_->line(line);
  }
  if (plain_block_) {  // a move the writer built without G, M or S: nothing here to read
    if (note_every_block_) note_block_cl();
    return;
  }
  if (line.empty() || line.front() == m_.program.comment_open) return;
  if (note_every_block_) note_block_cl();
  // Most blocks are moves without G, M or S: one table look-up per character says so.
  static constexpr auto gms = [] {
    std::array<bool, 256> t{};
    t['G'] = t['M'] = t['S'] = true;
    return t;
  }();
  if (std::none_of(line.begin(), line.end(), [](char c) { return gms[static_cast<unsigned char>(c)]; }))
    return;
  bool sm = false, cut = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == m_.program.comment_open) break;
    if (c == 'S' || c == 'M') sm = true;
    if (c == 'G' && i + 1 < line.size() && line[i + 1] >= '1' && line[i + 1] <= '3' &&
        (i + 2 == line.size() || line[i + 2] < '0' || line[i + 2] > '9'))
      cut = true;
  }
  if (!sm && !(cut && cut_due_)) return;
  noted_.push_back({waits_, std::string(line), line_});
  cut_due_ = sm;
}

void channel_writer::error(int line, std::string message) {
  ++errors_;
  diagnostic d;
  d.file = cl_file_;
  d.line = line;
  d.column = line == line_ ? column_ : 0;
  if (held_source_ && line == line_) d.source_line = *held_source_;  // a record held and written later
  d.message = fmt::format("channel {}: {}", ch_.number, message);
  diags_.report(std::move(d));
}

void channel_writer::misfit(char address, double value) {
  // 12 significant digits: the value, without the binary noise of its conversions
  // ("142.10330499999998").
  error(line_, word_misfit_message(address, fmt::format("{:.12g}", value), m_.formats[address]));
}

bool channel_writer::fits(char address, double v, int decimals) {
  const word_format& f = m_.formats[address];
  std::int64_t n;
  if (round_fixed(v, decimals, n) &&
      (f.whole == 0 || (n <= f.max_count(decimals) && -n <= f.max_count(decimals))))
    return true;
  misfit(address, v);
  return false;
}

bool channel_writer::block_fits(const std::string& block) {
  std::string why = check_block_words(block, m_.formats, m_.program.comment_open, m_.program.comment_close);
  if (why.empty()) return true;
  error(line_, why);
  return false;
}

bool channel_writer::axis_word(text_buffer& out, char address, double value, axis_memory& last, bool always) {
  // The same value as last time prints the same word: no need to round it to know.
  if (!always && last.known && value == last.value) return false;
  std::int64_t n;
  if (!round_fixed(value, axis_style_.decimals, n) || n > last.max || n < -last.max) [[unlikely]] {
    // Past what the control reads: the post stops here, nothing is written.
    misfit(address, value);
    last.known = false;
    return false;
  }
  if (n < last.lo || n > last.hi) [[unlikely]] {
    // Past the axis's travel: an overtravel alarm at best, a crash into the guard at worst.
    const axis_def* a = ch_.axis(address);
    error(line_, fmt::format("{}{} is outside channel {}'s {} travel {}..{} (channel.axis min/max)", address,
                             format_nc_number(value, axis_style_), ch_.number, address, *a->min, *a->max));
    last.known = false;
    return false;
  }
  bool same = last.known && n == last.n;
  last.known = true;
  last.n = n;
  last.value = value;
  if (same && !always) return false;  // modal: the axis is already there
  separate(out);
  out += address;
  append_fixed(out, n, axis_style_);
  return true;
}

void channel_writer::check_side(double x_nc, double x_cl, int line) {
  // A diameter below -5 mm is not facing past centre any more: the tool is on the other
  // side of the spindle. On a mirrored (lower) turret that means the CL gave this head
  // positive x, i.e. the upper side: its own frame, or a head mix-up. Say so, once.
  constexpr double past_centre = -5.0;
  if (warned_side_ || !x_diameter_ || x_nc >= past_centre || !std::isfinite(x_nc)) return;
  warned_side_ = true;
  diagnostic d;
  d.level = severity::warning;
  d.file = cl_file_;
  d.line = line;
  d.column = line == line_ ? column_ : 0;
  d.message = fmt::format(
      "channel {}: X{} is past the spindle centre line (CL x = {}){}", ch_.number,
      format_nc_number(x_nc, axis_style_), x_cl,
      mirrored() ? "; a lower turret's tools sit at CL x < 0: check the head's coordinates or the "
                   "machine's mirror setting"
                 : "");
  diags_.report(std::move(d));
}

void channel_writer::on_wait(const wait_mark& w) {
  release_held(std::nullopt);
  // A channel that meets the others before its first tool call goes home first: a head left in
  // the work zone (an aborted program) would stand in the way of the channels cutting meanwhile
  // (the machinist's review of the thirtieth session, M2: the 31i's path 3 waited out the whole
  // cycle wherever it stood). After the program's start events, as any block of the body.
  if (ev_ && !program_started_) [[unlikely]]
    user_program_start();
  // The last wait, before the footers: a tool the CL leaves in the cut goes out along its axis
  // first, before the others go on (their footers stop the spindles and the coolant) and before
  // this footer releases the C axis, stops the spindle or homes across the tool (review 37 H1:
  // a centre drill 15 mm deep went home X and Y first, the spindle stopped in the hole).
  if (w.ends_job) leave_cut(true);
  if (tool_ < 0 && !homed_ && !balance_copy_) {
    go_home();
    forget_axes();
    motion_g_ = -1;
    start_home_ = true;
  }
  // A balance cut pairs the two channels' moves (G68, M562): a head index of the new tool
  // (Integrex M108 G0 G53 B0. M107) goes before its opening wait, not as extra blocks inside it.
  // Its error (no angle for the tool) is reported there; the wait is written all the same.
  if (w.both == wait_mark::section::opens_both && has_c_ && ch_.head_index.present() && tool_ >= 0)
    (void)index_head(w.cl_line);
  // Balance cutting: wait, G68 ... cut ... G69, wait, in both channels.
  if (w.both == wait_mark::section::closes_both && !m_.codes.balance_off.empty())
    out_.block(m_.codes.balance_off);
  std::string b = fmt::format("{}{}", m_.waits.address, w.code);
  if (!w.partner_text.empty()) b += fmt::format(" {}{}", m_.waits.partner_address, w.partner_text);
  if (ev_) [[unlikely]] {
    if (!program_started_) user_program_start();
    template_args a;
    a.code = w.code;
    user_blocks(event_point::wait, false, a);
  }
  wait_line_ = w.cl_line;
  out_.block(b);
  wait_line_ = 0;
  // Through the script's on_block the wait is counted as written (block_written()): dropped, none.
  if (!filtered_) count_wait(w.cl_line);
  if (ev_) [[unlikely]] {
    template_args a;
    a.code = w.code;
    user_blocks(event_point::wait, true, a);
  }
  if (w.both == wait_mark::section::opens_both && !m_.codes.balance_on.empty())
    out_.block(m_.codes.balance_on);
}

void channel_writer::call_tool(const tool_event& d, int line) {
  if (cycle_ && !d.preselect) {
    // The cycle's depth and feed were the last tool's; every move of the next tool
    // would be drilled as a hole. The CL must end the cycle first.
    error(line, fmt::format("a tool change while CYCLE/{} (line {}) is in force: give CYCLE/OFF "
                            "before it, or each move of the next tool would be drilled as a hole",
                            cycle_->type, cycle_line_));
    cycle_.reset();
  }
  // A tool change ends the section before anything of the change goes out (G49 included).
  if (ev_ && !d.preselect && d.tool != tool_) [[unlikely]]
    section_end();
  if (chain_ && !d.preselect) multiaxis_off();
  if (!d.preselect) cam_tool_due_ = false;  // the CL calls its tool itself (the same one too)
  tool(d, line);
  if (chain_ && !d.preselect) multiaxis_tool(d, line);
}

void channel_writer::on_event(const event& e, bool both) {
  if (!feed_back_.empty()) [[unlikely]]
    feed_back_due(e);
  if (ev_ && !program_started_) [[unlikely]] {
    line_ = e.line;
    column_ = e.column;
    user_program_start();
  }
  if (msys_) [[unlikely]] {  // NX MSYS turned the CL's frame (machining/channel_frames.cpp)
    event turned = e;
    if (!turn_to_msys(turned)) return;
    if (chain_ && may_hold(turned) && hold_multiaxis(turned, both)) return;
    return process_event(turned, both);
  }
  if (csys_axis_ && !csys_axis_fits(e)) [[unlikely]]
    return;
  if (chain_ && may_hold(e) && hold_multiaxis(e, both))
    return;  // machining/channel_pole.cpp, channel_plane.cpp
  process_event(e, both);
}

void channel_writer::process_event(const event& e, bool both) {
  // A HEAD/BOTH copy on a mirrored channel runs on the opposite side of the spindle centre.
  side_ = (both && x_mirror_) ? -1.0 : 1.0;
  // The copy of a balance cut cuts on the master's workpiece spindle and leaves the spindle
  // to the master (set_balance_master).
  balance_copy_ = both && balance_master_ && balance_master_ != this;
  if (balance_copy_ && balance_master_->work_ && balance_master_->work_ != work_) {
    work_on(*balance_master_->work_);
    spindle_ = work_;
  }
  line_ = e.line;
  column_ = e.column;
  // A TLDATA right after a tool call (comments between) describes that tool.
  const bool after_call = after_call_;
  after_call_ = after_call && keeps_tool_call_open(e);
  std::visit(
      [&](const auto& d) {
        using T = std::decay_t<decltype(d)>;
        if constexpr (std::is_same_v<T, motion_event>) {
          if (d.axis) axis_ = *d.axis;
          // Where the CL leaves the tool: in a cut after a feed move (a CL cycle's holes end
          // at the cycle's return level), clear after a rapid.
          if (d.kind == motion_kind::go_to || d.kind == motion_kind::delta) {
            from_cut_ = in_cut_;
            in_cut_ = !d.rapid && !cycle_;
          }
          // With [events], through user_motion (a section may open); the plain path stays a tail call.
          if (ev_) [[unlikely]]
            return user_motion(d, e.line);
          motion(d, e.line);
        } else if constexpr (std::is_same_v<T, arc_event>) {
          in_cut_ = true;
          if (ev_) [[unlikely]]
            return user_arc(d, e.line);
          arc(d, e.line);
        } else if constexpr (std::is_same_v<T, spindle_event>) {
          if (tool_ < 0 || cam_tool_due_) start_tool(e.line);  // a job that starts without a tool call
          table_speed_due_ = false;                            // the CL gives the tool's speed itself
          spindle_record(d, e.line);
        } else if constexpr (std::is_same_v<T, feed_event>)
          feed(d, e.line);
        else if constexpr (std::is_same_v<T, tool_event>) {
          call_tool(d, e.line);
        } else if constexpr (std::is_same_v<T, tool_data_event>) {
          after_call_ = after_call;
          if (chain_) tool_data_length(d, after_call);
          tool_data(d);
        } else if constexpr (std::is_same_v<T, transfer_event>)
          transfer(d, e.line);
        else if constexpr (std::is_same_v<T, coolant_event>) {
          if (tool_ < 0 || cam_tool_due_) start_tool(e.line);
          if (ev_) [[unlikely]] {
            const event_point p = d.mode == "OFF" ? event_point::coolant_off : event_point::coolant_on;
            user_blocks(p, false, {});
            coolant(d, e.line);
            user_blocks(p, true, {});
          } else
            coolant(d, e.line);
        } else if constexpr (std::is_same_v<T, stop_event>) {
          program_stop(d.optional);
        } else if constexpr (std::is_same_v<T, cutcom_event>) {
          if (tool_ < 0 || cam_tool_due_) start_tool(e.line);
          cutcom(d, e.line);
        } else if constexpr (std::is_same_v<T, cycle_event>) {
          // Threading and grooving go to channel_thread.cpp, drilling and tapping to
          // channel_cycles.cpp. A refused cycle has stopped the post: its points are passed
          // over, not fed as moves.
          if (d.type == "OFF") {
            cycle_.reset();
            cycle_refused_ = false;
            if (fedrat_before_cycle_) {
              feed_value_ = fedrat_before_cycle_->first;
              feed_mode(fedrat_before_cycle_->second);
              fedrat_before_cycle_.reset();
            }
            if (ev_ && !user_cycle_.empty()) [[unlikely]] {
              template_args a;
              a.text = std::move(user_cycle_);
              user_cycle_.clear();
              user_blocks(event_point::cycle, true, a);
            }
          } else if (d.type != "ON" && d.type != "INIT") {
            if (tool_ < 0 || cam_tool_due_) start_tool(e.line);
            if (ev_ && sections_) [[unlikely]]
              section_at_move(false, e.line);
            const bool lathe = d.type == "THREAD" || d.type == "GROOVE";
            cycle_refused_ = !(lathe ? lathe_cycle_supported(d, e.line) : cycle_supported(d, e.line));
            if (cycle_refused_)
              cycle_.reset();
            else
              cycle_ = d, cycle_line_ = e.line;
            // events.cycle: `before` as the cycle starts, `after` at its CYCLE/OFF.
            if (ev_ && !cycle_refused_ && user_cycle_.empty()) [[unlikely]] {
              user_cycle_ = d.type;
              template_args a;
              a.text = d.type;
              user_blocks(event_point::cycle, false, a);
            }
          }
        } else if constexpr (std::is_same_v<T, thread_event>) {
          thread_mode(d, e.line);
        } else if constexpr (std::is_same_v<T, delay_event>) {
          if (d.revolutions) return error(e.line, "DELAY in revolutions is not supported; give seconds");
          write_dwell(d.value);
        } else if constexpr (std::is_same_v<T, aux_event>) {
          // The control would take a wait code for a wait, and so would the checker.
          const char address = d.prefun ? 'G' : 'M';
          if (is_wait_word(m_.waits, address, d.code))
            return error(e.line, fmt::format("{}/{} gives {}{}, a wait code of this machine (waits {}): the "
                                             "control would take it for a wait",
                                             d.prefun ? "PREFUN" : "AUXFUN", d.code, address, d.code,
                                             wait_range_text(m_.waits)));
          // The program's end or a jump back to its start (M2, M30, M99): the checker's reading
          // would stop there, and nothing after it would be checked (attack 67 H1).
          if (!d.prefun && (d.code == 2 || d.code == 30 || d.code == 99))
            return error(e.line,
                         fmt::format("AUXFUN/{} gives M{}, which ends the program (M99 goes back to its "
                                     "start) in the middle of the job: only the machine's end code "
                                     "may end it",
                                     d.code, d.code));
          std::string b = fmt::format("{}{}", address, d.code);
          if (block_fits(b)) out_.block(b);
          start_home_ = false;     // what the code moves is not known
          spindle_ended_.clear();  // what the code does to the spindle or the coolant is not known
          coolant_ended_.clear();
        } else if constexpr (std::is_same_v<T, text_event>) {
          if (d.kind == text_kind::insert) {
            if (!insert_passes(d.text, e.line)) return;
            out_.raw(d.text);
            start_home_ = false;
            // (a GOHOME, then `G0 U-200. W-300.`: the transfer went on from there)
            if (names_an_axis(d.text)) homed_ = false, end_home_.clear();
            spindle_ended_.clear();  // the user's text may turn either on again
            coolant_ended_.clear();
            // It may move an axis or change the motion mode: the next move writes all its words
            // (the comparison with the CL found `Z-5.` cut at the X of an INSERT's text), the
            // next feed move its F, and the channel's modes go back on as after a user's block
            // (a G20 in a metric program is refused).
            forget_axes();
            motion_g_ = -1;
            last_f_.clear();
            restore_modes_after({d.text}, "INSERT");
          } else if (d.kind == text_kind::pprint || d.kind == text_kind::tprint ||
                     d.kind == text_kind::op_start || d.kind == text_kind::toolpath) {
            if (d.kind != text_kind::pprint && d.kind != text_kind::op_start) note_cam_tool(d, e.line);
            const bool op = ev_ && (d.kind == text_kind::op_start || d.kind == text_kind::toolpath);
            if (op) [[unlikely]]
              user_operation(d, false);
            out_.comment(d.text);
            if (op) [[unlikely]]
              user_operation(d, true);
          }
        } else if constexpr (std::is_same_v<T, tool_axis_event>) {
          axis_ = d.axis;
        } else if constexpr (std::is_same_v<T, units_event>) {
          set_units(d.units);
        } else if constexpr (std::is_same_v<T, coordsys_event>) {
          frame(d, e.line);
        } else if constexpr (std::is_same_v<T, passthrough_event>) {
          if (d.user) user_record(d, e.line);  // only a machine with [[events.record]] makes these
        }
        // FROM-only state, tool data, coordinate systems, comments, ends: no block.
      },
      e.data);
  // After the channel's first error the post has failed: a refused record wrote nothing the
  // comparison could follow.
  if (observer_ && errors_ == 0) [[unlikely]] {
    if (observe_lines_) observe_head();
    observer_->record(e, both);
  }
}

bool channel_writer::dwell_fits(double seconds) {
  // The dwell's address is the letter before {seconds} or {ms} in the machine's template.
  const std::string& t = m_.codes.dwell;
  for (std::string_view key : {"{seconds", "{ms"}) {
    const std::size_t at = t.find(key);
    if (at == std::string::npos || at == 0) continue;
    const char address = t[at - 1];
    if (address < 'A' || address > 'Z') continue;
    const bool ms = key == "{ms";
    return fits(address, ms ? seconds * 1000 : seconds, ms ? 0 : m_.formats[address].decimals);
  }
  // A template whose dwell word has no address letter: at least keep {ms} within an int.
  if (std::isfinite(seconds) && std::abs(seconds) < 2.0e6) return true;
  error(line_, fmt::format("DELAY/{} is longer than any dwell the control takes", seconds));
  return false;
}

void channel_writer::write_dwell(double seconds) {
  if (!(seconds >= 0)) {
    error(line_, fmt::format("DELAY/{}: a dwell of a negative time; give the seconds to wait", seconds));
    return;
  }
  if (!dwell_fits(seconds)) return;
  template_args a;  // template_uses::dwell
  a.channel = ch_.number;
  a.seconds = seconds;
  a.ms = static_cast<int>(std::lround(seconds * 1000));
  std::string b = format_template(m_.codes.dwell, a);
  if (!block_fits(b)) return;
  // A time the word writes as 0 (DELAY/0, DELAY/0.0004 as P0) is no dwell: left out, and said
  // (review 40; the Fusion post the Integrex's file cites writes at least P1).
  for (std::string_view key : {"{seconds", "{ms"})
    if (const std::size_t at = m_.codes.dwell.find(key); at != std::string::npos && at > 0)
      for (const nc_word& w : split_nc_words(std::string_view(b)))
        if (w.address == ascii::upper(m_.codes.dwell[at - 1]) && w.numeric && w.number == 0) {
          warning(fmt::format("DELAY/{}: the dwell is written as no time ({}{}): left out",
                              kin::number_text(seconds), w.address, w.value));
          return;
        }
  // Under feed per revolution a dwell may count spindle revolutions, not seconds (Fanuc
  // parameter 3405#1 DWL: "dwell per rotation in the feed per rotation mode"; Mazak alike): the
  // dwell is written under feed per minute, where it is seconds whatever the parameter, and the
  // channel's mode follows at once (issue 37, item 10; the Integrex transfer's `G94 G4 P1000`).
  // A mode not known yet (the Integrex header sets none, and a control may keep G95 from the
  // last program: attack 71 F3) is set to feed per minute for the dwell, and stays.
  // The mode put back waits for the next record (feed_back_due): a FEDRAT per minute after the
  // dwell keeps it, and a dwell at the end leaves the program in it.
  const control_codes& c = m_.codes;
  if (!c.feed_per_min.empty() && !c.feed_per_rev.empty() && feed_g_ != c.feed_per_min) {
    out_.block(c.feed_per_min + ' ' + b);
    feed_back_ = feed_g_;  // (empty: no mode was set, per minute stays)
    feed_g_ = c.feed_per_min;
    return;
  }
  out_.block(b);
}

void channel_writer::feed_back_due(const event& e) {
  // A FEDRAT sets its own mode (none written when it is per minute); a record that may move
  // the tool or write a move of its own (GOTO, CIRCLE, CYCLE, THREAD, a transfer, INSERT) first
  // has the mode the dwell left; the others (another dwell, a tool call, SPINDL, COOLNT, the
  // end) leave it waiting, and at the end of the program it is not written.
  const bool moves = std::visit(
      [](const auto& d) {
        using T = std::decay_t<decltype(d)>;
        if constexpr (std::is_same_v<T, text_event>)
          return d.kind == text_kind::insert;  // NC text as written: a move of its own (review 41 H1)
        else
          return std::is_same_v<T, motion_event> || std::is_same_v<T, arc_event> ||
                 std::is_same_v<T, cycle_event> || std::is_same_v<T, thread_event> ||
                 std::is_same_v<T, transfer_event> || std::is_same_v<T, passthrough_event>;
      },
      e.data);
  if (moves) {
    out_.block(feed_back_);
    feed_g_ = feed_back_;
    last_f_.clear();  // the next feed move writes its F again under the mode put back
  }
  if (moves || std::holds_alternative<feed_event>(e.data)) feed_back_.clear();
}

void channel_writer::finish() {
  release_held(std::nullopt);
  if (ev_) [[unlikely]] {  // the last section ends before the channel's closing blocks (G49 ...)
    if (!program_started_) user_program_start();
    section_end();
  }
  if (chain_) multiaxis_off();
  leave_cut(true);  // a channel without a last wait (one channel): out of the cut before the footer
  if (length_cancel_due_) footer_cancels_length();
  if (ev_) [[unlikely]] {
    user_blocks(event_point::program_end, false, {});
    if (script_) script_program(false);
  }
  // The footer stops the spindles its file names (M5; the Integrex M5 M205 M305). A spindle
  // still turning whose stop code the footer lacks (the sub spindle's M105 on the 0i-TD, the
  // main spindle on a file without M5) is stopped first, as the Fusion Doosan post does
  // (M5 before M9 and the retract).
  if (spindle_ && !restart_blocks_.empty() && !spindle_held_) {
    const std::string stop = fmt::format("M{}", spindle_->stop);
    const auto& footer = m_.program.footer;
    if (std::find(footer.begin(), footer.end(), stop) == footer.end()) spindle_block(stop, true);
  }
  // A spindle a user block started ([events], the script), whose stop the footer lacks.
  for (const spindle_def* s : user_spindles_) {
    const std::string stop = fmt::format("M{}", s->stop);
    const auto& footer = m_.program.footer;
    if (spindle_ended_ != stop && std::find(footer.begin(), footer.end(), stop) == footer.end())
      spindle_block(stop, true);
  }
  // Likewise the coolant: the footer's M9 does not turn off through-tool (M109, Mazak M163)
  // or air coolant, which would blow through the final retract.
  if (!coolant_block_.empty()) {
    const auto& footer = m_.program.footer;
    if (std::find(footer.begin(), footer.end(), coolant_off_block_) == footer.end())
      coolant_block(coolant_off_block_, true);
  }
  leave_c_axis();  // the next program starts with a turning spindle
  // Cuts on a shared spindle this channel had not started: now that the whole job is read, an
  // error where no other channel starts that spindle at all (its own later start comes after
  // the cut).
  for (const unstarted_cut& c : unstarted_)
    if (!job_spindles_->started_by_other(c.spindle, ch_.number)) {
      diagnostic d;
      d.file = cl_file_;
      d.line = c.line;
      d.column = c.column;
      d.source_line = c.source;
      d.message = fmt::format("channel {}: {}", ch_.number, not_started(m_.spindles[c.spindle], true));
      diags_.report(std::move(d));
    }
  out_.close();
}

void channel_writer::footer_cancels_length() {
  // The built-in footers home Z and then cancel (M9 M5 G91 G28 Z0. G90 G49, as the Autodesk
  // posts' onClose: writeRetract(Z), then disableLengthCompensation(true)).
  const auto& footer = m_.program.footer;
  const auto cancel = std::find(footer.begin(), footer.end(), chain_->tool_tip_off);
  const auto home = m_.home(ch_.number).empty()
                        ? footer.end()
                        : std::find(footer.begin(), footer.end(), m_.home(ch_.number).front());
  if (cancel != footer.end() && home < cancel) {
    length_cancel_due_ = false;
    return;
  }
  go_home();  // a footer that does not: home and cancel here, before it
}

std::vector<std::string> channel_writer::footer_in_force() const {
  std::vector<std::string> v = end_home_;
  if (!coolant_ended_.empty()) v.push_back(coolant_ended_);
  if (!spindle_ended_.empty()) v.push_back(spindle_ended_);
  return v;
}

}  // namespace twinpost
