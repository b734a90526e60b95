// channel_writer: the machine file's [events] blocks and [[events.record]] records
// (machines/machine_events.hpp, docs/customising.md). Every block goes through the same
// block_writer as the post's own, so the self-check reads it like any other block: a wait code
// in it must pair, its words must fit the control's formats.
#include <charconv>
#include <string_view>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "machines/code_overlap.hpp"
#include "machines/name_template.hpp"
#include "machining/channel_writer.hpp"
#include "support/ascii.hpp"

namespace twinpost {

namespace {

// The G codes after which an X word is no position in the work frame: a dwell (G4 X1.5), data
// or offset setting (G10, G50 X, G92 X), machine coordinates (G53), a macro's argument (G65),
// incremental (G91).
bool x_not_a_position(std::string_view b, char comment_open) {
  for (std::size_t i = 0; i + 1 < b.size() && b[i] != comment_open; ++i) {
    if (b[i] != 'G' || (i > 0 && ascii::is_letter(b[i - 1]))) continue;
    std::size_t j = i + 1;
    int g = 0;
    while (j < b.size() && ascii::is_digit(b[j]) && g < 1000) g = g * 10 + (b[j++] - '0');
    if (j < b.size() && b[j] == '.') continue;  // G12.1 and the like
    if (g == 4 || g == 10 || g == 50 || g == 53 || g == 65 || g == 91 || g == 92) return true;
  }
  return false;
}

// Where the comment opened at b[i] closes; npos when it runs to the end of the block.
std::size_t comment_close(std::string_view b, std::size_t i, const program_format& f) {
  return b.find(f.comment_close, i + 1);
}

}  // namespace

bool channel_writer::user_block_in_travel(std::string_view b) {
  const axis_def* x = ch_.axis('X');
  if (!x || !x->min || !x->max || x_not_a_position(b, m_.program.comment_open)) return true;
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b[i] == m_.program.comment_open) {
      if ((i = comment_close(b, i, m_.program)) == std::string_view::npos) break;
      continue;
    }
    if (b[i] != 'X') continue;
    double v = 0;
    const char* end = b.data() + b.size();
    const auto r = std::from_chars(b.data() + i + 1, end, v);
    if (r.ec != std::errc()) continue;  // X#501: the control's value, not known here
    if (v < *x->min || v > *x->max) {
      error(line_, fmt::format("{} is outside channel {}'s X travel {}..{} (channel.axis min/max)",
                               std::string_view(b.data() + i, r.ptr - (b.data() + i)), ch_.number, *x->min,
                               *x->max));
      return false;
    }
  }
  return true;
}

void channel_writer::user_block(const std::string& tpl, const template_args& a) {
  const std::string b = format_template(tpl, a);
  // A word past the control's format or an X past the travel: an error at the CL record.
  if (!block_fits(b) || !user_block_in_travel(b)) return;
  out_.block(b);
  note_user_block(b, true);
}

void channel_writer::note_user_block(std::string_view b, bool waits) {
  // The words of the block, outside comments: a wait code is numbered like the post's own
  // waits (post/sync_at_cl reports the checker's findings at this CL record); a G code may
  // move the axes or change the motion mode, so the next move writes them all again.
  bool g = false;
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b[i] == m_.program.comment_open) {
      if ((i = comment_close(b, i, m_.program)) == std::string_view::npos) break;
      continue;
    }
    if (b[i] == 'G') g = true;
    if (!waits || b[i] != m_.waits.address || i + 1 >= b.size() || !ascii::is_digit(b[i + 1])) continue;
    long long code = 0;
    std::size_t j = i + 1;
    for (; j < b.size() && ascii::is_digit(b[j]) && code < 1000000000; ++j) code = code * 10 + (b[j] - '0');
    if (is_wait_word(m_.waits, m_.waits.address, code)) {
      ++waits_;
      cut_due_ = true;
      wait_cl_lines_.push_back(line_);
    }
    i = j - 1;
  }
  if (g) {
    forget_axes();
    motion_g_ = -1;
  }
  // What the user's codes do to the spindle or the coolant is not known (as after AUXFUN).
  spindle_ended_.clear();
  coolant_ended_.clear();
}

void channel_writer::user_blocks(event_point p, bool after, template_args a) {
  const event_blocks& e = (*ev_)[p];
  const std::vector<std::string>& blocks = after ? e.after : e.before;
  if (blocks.empty()) return;
  a.channel = ch_.number;
  for (const std::string& t : blocks) user_block(t, a);
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
  for (const std::string& t : rec->blocks) user_block(t, a);
}

}  // namespace twinpost
