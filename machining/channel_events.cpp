// channel_writer: the machine file's [events] blocks and [[events.record]] records
// (machines/machine_events.hpp, docs/customising.md). Every block goes through the same
// block_writer as the post's own, so the self-check reads it like any other block: a wait code
// in it must pair, its words must fit the control's formats.
#include <charconv>
#include <cmath>
#include <string_view>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "formats/number_format.hpp"
#include "machines/code_overlap.hpp"
#include "machines/name_template.hpp"
#include "machining/channel_writer.hpp"
#include "support/ascii.hpp"

namespace twinpost {

namespace {

// Where the comment opened at b[i] closes; npos when it runs to the end of the block.
std::size_t comment_close(std::string_view b, std::size_t i, const program_format& f) {
  return b.find(f.comment_close, i + 1);
}

}  // namespace

namespace {

// Whether template `tpl` names placeholder {`c`} ({x}, {x:>9}); "{{" is a brace.
bool names_axis(std::string_view tpl, char c) {
  for (std::size_t i = 0; i + 2 < tpl.size(); ++i) {
    if (tpl[i] != '{') continue;
    if (tpl[i + 1] == '{') {
      ++i;
      continue;
    }
    if (tpl[i + 1] == c && (tpl[i + 2] == '}' || tpl[i + 2] == ':')) return true;
  }
  return false;
}

// The operation's name in an operation record: NX TOOL PATH/name,TOOL,tool (before the first
// comma), SolidWorks OPFEATSTART/name (all of it).
std::string operation_name(const text_event& t) {
  std::string_view s = t.text;
  if (t.kind == text_kind::toolpath) s = s.substr(0, s.find(','));
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return std::string(s);
}

}  // namespace

void channel_writer::position_args(template_args& a) const {
  // The last axis words the program commanded, as it wrote them: X in diameter on a lathe's
  // diameter axis (and with its sign on a mirrored turret), in the work frame, in the output
  // units; none before the channel's first move.
  if (!moved_) return;
  const double unit = std::pow(10.0, -axis_style_.decimals);
  a.x = format_nc_number(static_cast<double>(last_x_.n) * unit, axis_style_);
  a.z = format_nc_number(static_cast<double>(last_z_.n) * unit, axis_style_);
  if (has_y_) a.y = format_nc_number(static_cast<double>(last_y_.n) * unit, axis_style_);
}

bool channel_writer::position_given(std::string_view tpl, const template_args& a, std::string_view where) {
  for (const auto& [c, v] : {std::pair{'x', &a.x}, std::pair{'y', &a.y}, std::pair{'z', &a.z}}) {
    if (!v->empty() || !names_axis(tpl, c)) continue;
    error(line_,
          c == 'y' && !has_y_
              ? fmt::format("{}: \"{}\" names {{y}}, but channel {} has no Y axis", where, tpl, ch_.number)
              : fmt::format("{}: \"{}\" names {{{}}}, but channel {} has made no move before it (no "
                            "position yet)",
                            where, tpl, c, ch_.number));
    return false;
  }
  return true;
}

void channel_writer::section_at_move(bool rapid, int line) {
  // The tool the move needs is called first (as motion() would): its change ends a section.
  if (tool_ < 0 || cam_tool_due_) start_tool(line);
  if (section_open_ && (work_ != section_work_ || (rapid && (std::abs(axis_.x - section_axis_.x) > 1e-9 ||
                                                             std::abs(axis_.y - section_axis_.y) > 1e-9 ||
                                                             std::abs(axis_.z - section_axis_.z) > 1e-9))))
    section_end();
  if (tool_ < 0) return;  // no tool: the move is refused
  // The move goes out next: every later event has a position.
  const bool first_move = !moved_;
  moved_ = true;
  if (section_open_) return;
  section_open_ = true;
  section_work_ = work_;
  section_axis_ = axis_;
  section_args_ = {};
  section_args_.tool = tool_;
  section_args_.offset = tool_offset_;
  section_args_.name = op_name_;
  // Its `before` blocks stand before that move: the position is the one the tool left (none
  // before the channel's first move).
  moved_ = !first_move;
  user_blocks(event_point::section, false, section_args_);
  moved_ = true;
}

void channel_writer::user_motion(const motion_event& m, int line) {
  if (m.kind == motion_kind::go_to || m.kind == motion_kind::delta) {
    if (sections_)
      section_at_move(m.rapid, line);
    else
      moved_ = true;  // (a move without a tool is refused: the post has failed then)
  }
  motion(m, line);
}

void channel_writer::user_arc(const arc_event& a, int line) {
  if (sections_)
    section_at_move(false, line);
  else
    moved_ = true;
  arc(a, line);
}

void channel_writer::section_end() {
  if (!section_open_) return;
  section_open_ = false;
  user_blocks(event_point::section, true, section_args_);
}

void channel_writer::user_operation(const text_event& d, bool after) {
  template_args a;
  a.text = d.text;
  a.name = operation_name(d);
  if (!after) {
    section_end();  // an operation is a section of its own
    op_name_ = a.name;
  }
  user_blocks(event_point::operation, after, std::move(a));
}

void channel_writer::user_block(const std::string& tpl, const template_args& a, std::string_view where) {
  if (!position_given(tpl, a, where)) return;
  const std::string b = format_template(tpl, a);
  // A word past the control's format or an X past the travel: an error at the CL record.
  if (!user_block_passes(b)) return;
  user_writing_ = true;
  out_.block(b);
  user_writing_ = false;
  note_user_block(b, !filtered_);  // through on_block its waits are counted as written
}

void channel_writer::count_wait(int cl_line) {
  ++waits_;
  cut_due_ = true;
  wait_cl_lines_.push_back(cl_line);
  if (note_every_block_ && block_cl_count_ > 0) wait_block_.push_back(block_cl_count_ - 1);
}

void channel_writer::count_waits_in(std::string_view b, int cl_line) {
  for (int n = wait_words_in(b); n > 0; --n) count_wait(cl_line);
}

int channel_writer::wait_words_in(std::string_view b) const {
  // The wait words as the self-check reads them: the wait address and digits, outside comments.
  // Most blocks (moves) have no word of the wait address at all: one memchr says so.
  int n = 0;
  if (b.find(m_.waits.address) == std::string_view::npos) return n;
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b[i] == m_.program.comment_open) {
      if ((i = comment_close(b, i, m_.program)) == std::string_view::npos) break;
      continue;
    }
    if (b[i] != m_.waits.address || i + 1 >= b.size() || !ascii::is_digit(b[i + 1])) continue;
    long long code = 0;
    std::size_t j = i + 1;
    for (; j < b.size() && ascii::is_digit(b[j]) && code < 1000000000; ++j) code = code * 10 + (b[j] - '0');
    if (is_wait_word(m_.waits, m_.waits.address, code)) ++n;
    i = j - 1;
  }
  return n;
}

namespace {

// Whether fixed block `block` of the machine file ("M8", "M8 M26") has the word M`code`.
bool has_m(std::string_view block, long long code) {
  for (std::size_t i = 0; i < block.size(); ++i) {
    if (block[i] != 'M' || (i > 0 && ascii::is_letter(block[i - 1]))) continue;
    long long c = 0;
    std::size_t j = i + 1;
    for (; j < block.size() && ascii::is_digit(block[j]) && c < 1000000000; ++j)
      c = c * 10 + (block[j] - '0');
    if (j > i + 1 && c == code && (j == block.size() || block[j] != '.')) return true;
  }
  return false;
}

}  // namespace

void channel_writer::note_user_m(long long code) {
  // What the machine file says the code is. A spindle start or a coolant-on code turns that
  // one on again: the footer must stop it, with the stop or off code of that spindle or kind
  // (finish()); a spindle stop or a coolant-off code turns nothing on. Any other M code is the
  // machine's own (M10 a parts catcher, M13 spindle and coolant on together on some controls,
  // M98 a subprogram): what it does is not known here, so both count as on again, as after
  // AUXFUN.
  bool stop = false;
  for (const spindle_def& s : m_.spindles) {
    if (code == s.cw || code == s.ccw) {
      if (&s == stopped_by_user_) stopped_by_user_ = nullptr;  // started again, at the S in force
      spindle_ended_.clear();
      if (std::find(user_spindles_.begin(), user_spindles_.end(), &s) == user_spindles_.end())
        user_spindles_.push_back(&s);
      return;
    }
    stop = stop || code == s.stop;
    // The spindle the channel cuts on, stopped by the user: no cut may follow until it turns
    // again (spindle_turning), as after the CL's own SPINDL/OFF.
    if (code == s.stop && &s == spindle_ && !balance_copy_) {
      stopped_by_user_ = spindle_;
      user_stop_ = fmt::format("M{}", code);
    }
  }
  const control_codes& k = m_.codes;
  const std::string* on = nullptr;
  const std::string* off = nullptr;
  for (const std::string& b : k.coolant_on)
    if (has_m(b, code)) on = &b, off = &k.coolant_off;
  for (const auto* kind : {&k.coolant_mist, &k.coolant_through, &k.coolant_air})
    if (kind->size() == 2 && has_m((*kind)[0], code)) on = &(*kind)[0], off = &(*kind)[1];
  if (on) {
    coolant_ended_.clear();
    coolant_block_ = *on;  // the post's own state: a tool change and the end turn it off
    coolant_off_block_ = *off;
    return;
  }
  bool is_off = has_m(k.coolant_off, code);
  for (const auto* kind : {&k.coolant_mist, &k.coolant_through, &k.coolant_air})
    is_off = is_off || (kind->size() == 2 && has_m((*kind)[1], code));
  if (stop || is_off) return;
  spindle_ended_.clear();
  coolant_ended_.clear();
}

bool channel_writer::names_an_axis(std::string_view b) const {
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b[i] == m_.program.comment_open) {
      if ((i = comment_close(b, i, m_.program)) == std::string_view::npos) return false;
      continue;
    }
    switch (ascii::upper(b[i])) {
      case 'X':
      case 'Y':
      case 'Z':
      case 'U':
      case 'V':
      case 'W':
      case 'A':
      case 'B':
      case 'C':
      case 'H': return true;
      default: break;
    }
  }
  return false;
}

void channel_writer::note_user_block(std::string_view b, bool waits) {
  // Its wait codes are numbered like the post's own waits (post/sync_at_cl reports the
  // checker's findings at this CL record).
  if (waits) count_waits_in(b, line_);
  // Its other words, outside comments: a G code may move the axes or change the motion mode,
  // so the next move writes them all again; an M code may turn the spindle or the coolant on
  // (note_user_m). A block of neither (a comment, #501=#501+1, G30's axes aside) leaves the
  // footer's spindle stop and coolant off in force.
  bool g = false;
  const bool moves = names_an_axis(b);
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b[i] == m_.program.comment_open) {
      if ((i = comment_close(b, i, m_.program)) == std::string_view::npos) break;
      continue;
    }
    // A G code, or an axis word without one (`X20.` moves X in the modal G0/G1): the post no
    // longer knows where the axes are (issue 38, eighth attack: the next cut left X out).
    if (const char u = ascii::upper(b[i]); u == 'G' || u == 'X' || u == 'Y' || u == 'Z' || u == 'U' ||
                                           u == 'V' || u == 'W' || u == 'A' || u == 'B' || u == 'C' ||
                                           u == 'H')
      g = true;
    if (b[i] != 'M' || i + 1 >= b.size() || !ascii::is_digit(b[i + 1]) ||
        (i > 0 && ascii::is_letter(b[i - 1])))
      continue;
    long long code = 0;
    std::size_t j = i + 1;
    for (; j < b.size() && ascii::is_digit(b[j]) && code < 1000000000; ++j) code = code * 10 + (b[j] - '0');
    if (m_.waits.address != 'M' || !is_wait_word(m_.waits, 'M', code)) note_user_m(code);
    i = j - 1;
  }
  if (g) {
    forget_axes();
    motion_g_ = -1;
    start_home_ = false;  // it may have moved the channel from the home it went to at a wait
  }
  // An axis word may have moved it from any home: a transfer or a tilted plane goes home again
  // first (a G code alone, G94, moves nothing: review 67 L4).
  if (moves) {
    homed_ = false;
    end_home_.clear();  // the footer homes it again
  }
}

void channel_writer::user_blocks(event_point p, bool after, template_args a) {
  const event_blocks& e = (*ev_)[p];
  const std::vector<std::string>& blocks = after ? e.after : e.before;
  if (blocks.empty()) return;
  a.channel = ch_.number;
  position_args(a);
  const std::string where =
      fmt::format("events.{}.{}", event_point_keys[static_cast<std::size_t>(p)], after ? "after" : "before");
  for (const std::string& t : blocks) user_block(t, a, where);
  restore_modes_after(blocks, where);
}

void channel_writer::user_program_start() {
  program_started_ = true;
  user_blocks(event_point::program_start, true, {});
  if (script_) [[unlikely]]
    script_program(true);
}

void channel_writer::user_record(const passthrough_event& r, int line) {
  // The script takes its script_records, and every record no [[events.record]] names.
  if (script_ &&
      (!ev_->names_record(r.major) || std::find(ev_->script_records.begin(), ev_->script_records.end(),
                                                r.major) != ev_->script_records.end()))
    return script_record(r, line);
  const record_event* rec = ev_->record_for(r.major, r.text);
  if (!rec) {
    std::string forms;
    for (const record_event& e : ev_->records)
      if (e.major == r.major) {
        if (!forms.empty()) forms += ", ";
        forms += e.words.empty() ? e.major : fmt::format("{}/{}", e.major, fmt::join(e.words, ","));
      }
    return error(line, fmt::format("{}/{} matches no [[events.record]] of machine '{}' (it has {})", r.major,
                                   r.text, m_.name, forms));
  }
  template_args a;
  a.channel = ch_.number;
  a.text = r.text;
  position_args(a);
  for (const std::string& t : rec->blocks) user_block(t, a, "events.record.blocks");
  restore_modes_after(rec->blocks, "events.record.blocks");
}

}  // namespace twinpost
