// channel_writer: the machine's Lua script ([events] script, docs/scripting.md). The script
// runs here only, on the post's main thread (the reader and the self-check run on others). A
// block the script writes or puts in place of one of the post's goes through the same checks
// as a block of [events]: its words must fit the control's formats, its wait codes are the
// self-check's to pair.
#include <filesystem>

#include <fmt/format.h>

#include "machining/channel_writer.hpp"
#include "support/ascii.hpp"

namespace twinpost {

diagnostic script_diagnostic(const scripting::script_error& e) {
  diagnostic d;
  d.file = e.file;
  d.line = e.line;
  d.message = e.message;
  d.source_line = e.source_line;
  // Lua gives the line only: the caret under the line's first word (its statement).
  const std::size_t first = e.source_line.find_first_not_of(" \t");
  if (first != std::string::npos) d.caret = static_cast<int>(first) + 1;
  return d;
}

void channel_writer::use_script(job_script* s) {
  script_ = s;
  // on_block costs a test of one pointer per block, and only when the script defines it.
  if (s && s->lua && s->lua->has_on_block()) {
    out_.set_filter(this);
    filtered_ = true;
  }
}

void channel_writer::block_written(std::string_view block, bool replaced) {
  // The waits of every block the filter saw, as written: of the post's wait block and of a
  // user block, kept or replaced; of any replacement (a wait it adds). The post's other blocks
  // carry no wait code (the loader holds the machine's codes to that, the post AUXFUN's), so a
  // kept one is not read. The CL line of the post's own wait is the wait's.
  if (replaced || wait_line_ > 0 || user_writing_) count_waits_in(block, wait_line_ > 0 ? wait_line_ : line_);
}

void channel_writer::script_failed(const scripting::script_error& e) {
  script_->failed = true;
  ++errors_;
  diags_.report(script_diagnostic(e));
  diagnostic n;
  n.level = severity::note;
  n.file = cl_file_;
  n.line = line_;
  n.column = line_ > 0 ? column_ : 0;
  // In a header or footer block's on_block the record is the one being posted when the frame
  // was asked for (none for a footer of a channel that had no record of its own).
  n.message = std::string_view(block_part_) != "body"
                  ? fmt::format("channel {}: the script failed on a block of the program's {}{}", ch_.number,
                                block_part_, line_ > 0 ? ", asked for while this record was posted" : "")
                  : fmt::format("channel {}: the script failed while this record was posted", ch_.number);
  diags_.report(std::move(n));
}

scripting::script_context channel_writer::script_context() const {
  scripting::script_context ctx;
  ctx.channel = ch_.number;
  ctx.program = program_name_;
  ctx.cl_line = line_;
  return ctx;
}

void channel_writer::script_program(bool start) {
  if (program_name_.empty()) program_name_ = std::filesystem::path(out_.name()).filename().string();
  const scripting::script_context ctx = script_context();
  run_script([&](scripting::lua_script& s) {
    if (start)
      s.on_program_start(ctx, *this);
    else
      s.on_program_end(ctx, *this);
  });
  restore_after_emits();
}

void channel_writer::script_tool(int tool, int offset) {
  scripting::script_tool t;
  t.number = tool;
  t.offset = offset;
  t.channel = ch_.number;
  const tool_def* d = m_.tool(ch_.number, tool);
  if (d) {
    t.name = d->name;
    t.length = d->length.value_or(0);
    t.diameter = d->diameter.value_or(0);
  }
  t.kind = kind_ == tool_kind::turn    ? "turn"
           : kind_ == tool_kind::mill  ? "mill"
           : kind_ == tool_kind::drill ? "drill"
                                       : "";
  run_script([&](scripting::lua_script& s) { s.on_tool_change(t, *this); });
  restore_after_emits();
}

void channel_writer::script_record(const passthrough_event& r, int line) {
  scripting::script_record rec;
  rec.major = r.major;
  rec.line = line;
  // The arguments as the CL writes them, split at the commas, each without its blanks.
  std::string_view rest = r.text;
  while (!rest.empty()) {
    const std::size_t comma = rest.find(',');
    std::string_view w = rest.substr(0, comma);
    while (!w.empty() && (w.front() == ' ' || w.front() == '\t')) w.remove_prefix(1);
    while (!w.empty() && (w.back() == ' ' || w.back() == '\t')) w.remove_suffix(1);
    rec.words.emplace_back(w);
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  run_script([&](scripting::lua_script& s) { s.on_record(rec, *this); });
  restore_after_emits();
}

void channel_writer::restore_after_emits() {
  // The blocks of one call are the user's blocks of one event: the channel's modes go back on
  // after them, as after an [events] block's (channel_user_modes.cpp).
  if (script_emitted_.empty()) return;
  std::vector<std::string> blocks;
  blocks.swap(script_emitted_);
  if (!script_->failed) restore_modes_after(blocks, "post.emit");
}

bool channel_writer::emit(std::string_view block) {
  // Called inside a Lua call: reports, never throws (script_host).
  const std::string b(block);
  // The same checks as an [events] block's: the control's word formats, the X travel (the
  // scripting layer has refused a '%', a line break, NUL and control bytes).
  if (!user_block_passes(b)) {
    script_block_note(b, "post.emit");  // at the CL record
    return false;
  }
  if (frame_out_)
    frame_out_->push_back(b);  // in on_block of a header or footer block: before it, in the frame
  else
    out_.block_as_is(b);
  note_user_block(b, !frame_out_);
  script_emitted_.push_back(b);
  return true;
}

std::vector<std::string> channel_writer::frame_block(const std::string& b, bool header, std::size_t index) {
  if (!filtered_) return {b};
  // Asked before: the same answer, so that the head written again numbers its blocks as the
  // first one did (the body's numbers follow them). A block whose text the program's name
  // changed ({name} in it) and that was kept as it was is kept in its new text.
  for (const frame_edit& e : frame_edits_)
    if (e.header == header && e.index == index)
      return e.out.size() == 1 && e.out[0] == e.in ? std::vector<std::string>{b} : e.out;
  std::vector<std::string> out;
  std::string replacement;
  block_writer::verdict v = block_writer::verdict::keep;
  frame_out_ = &out;
  block_part_ = header ? "header" : "footer";
  try {
    v = filter(b, replacement);
  } catch (...) {
    frame_out_ = nullptr;
    block_part_ = "body";
    throw;
  }
  frame_out_ = nullptr;
  block_part_ = "body";
  if (v != block_writer::verdict::drop) out.push_back(v == block_writer::verdict::replace ? replacement : b);
  // The channels meet in the body, where the post counts and places its waits: a wait the
  // script puts into the frame would pair with none of the other channel's.
  if (!script_->failed)
    for (const std::string& w : out)
      if (!frame_waits(w).empty()) {
        error(line_, fmt::format("on_block puts \"{}\" into the program's {}, with a wait code: the post "
                                 "places, counts and proves the waits of the body only; give a wait from an "
                                 "event or by the CL's SYNC records",
                                 w, header ? "header" : "footer"));
        script_block_note(w, "on_block");
        script_->failed = true;
        break;
      }
  frame_edits_.push_back({b, header, index, out});
  return out;
}

void channel_writer::script_block_note(std::string_view block, std::string_view how) {
  diagnostic n;
  n.level = severity::note;
  n.file = script_->lua->name();
  n.message = fmt::format("channel {}: the block '{}' came from the script ({})", ch_.number,
                          scripting::escape_controls(block), how);
  diags_.report(std::move(n));
}

void channel_writer::warning(std::string_view message) {
  diagnostic d;
  d.level = severity::warning;
  d.file = cl_file_;
  d.line = line_;
  d.column = line_ > 0 ? column_ : 0;
  d.message = fmt::format("channel {}: {}", ch_.number, message);
  diags_.report(std::move(d));
}

block_writer::verdict channel_writer::filter(std::string_view block, std::string& replacement) {
  if (script_->failed) return block_writer::verdict::keep;
  // The header may be asked for before on_program_start (a channel that goes home before its
  // first wait): ctx.program is the file's name there too.
  if (program_name_.empty()) program_name_ = std::filesystem::path(out_.name()).filename().string();
  scripting::block_verdict v = scripting::block_verdict::keep;
  run_script([&](scripting::lua_script& s) {
    scripting::script_context ctx = script_context();
    ctx.part = block_part_;
    v = s.on_block(block, ctx, *this, replacement);
  });
  // What on_block emitted stands among the post's blocks: no block restores a mode after it.
  for (const std::string& e : script_emitted_)
    if (!script_->failed && !refuse_mode_changes(e, "post.emit in on_block")) {
      script_->failed = true;
      break;
    }
  script_emitted_.clear();
  const bool frame = frame_out_ != nullptr;  // a header or footer block (frame_block)
  if (v == scripting::block_verdict::drop && frame && !frame_words(block).empty()) {
    // The header sets the modes, the footer stops the spindle and the coolant and sends the
    // axes home (attack 51: the footer's M5 and M9 dropped, M30 with both still on).
    error(line_,
          fmt::format("on_block drops the {} block \"{}\": the header and the footer set the modes and "
                      "end the program safely; give it back, or add to it",
                      block_part_, block));
    script_->failed = true;
    return block_writer::verdict::keep;
  }
  if (v == scripting::block_verdict::drop) {
    // A block with a G code or an axis word holds the post's modes and positions (the G90 after
    // an event's G91, a move the next block's words count from): dropping it is refused (issue
    // 38, eighth attack).
    bool holds = false;
    for (std::size_t i = 0; i < block.size() && !holds; ++i) {
      if (block[i] == m_.program.comment_open) {
        if (m_.program.comment_close == '\n' ||
            (i = block.find(m_.program.comment_close, i + 1)) == std::string_view::npos)
          break;
        continue;
      }
      holds = std::string_view("GXYZUVWABCH").find(ascii::upper(block[i])) != std::string_view::npos;
    }
    if (holds) {
      error(line_,
            fmt::format("on_block drops \"{}\": a block with a G code or an axis word holds the modes and "
                        "positions the post's next blocks rely on; give it back, or replace it with "
                        "one that does the same",
                        block));
      script_->failed = true;
      return block_writer::verdict::keep;
    }
    return block_writer::verdict::drop;
  }
  // The block given back as it came (`return text`) is kept: the writer's modal state still holds.
  if (v == scripting::block_verdict::keep || script_->failed || replacement == block)
    return block_writer::verdict::keep;
  // A block of the post's with a mode code or axis words is replaced only by one that keeps them:
  // `(G90)` for the G90 after an event's G91 left the program incremental (issue 38, ninth
  // attack). The codes of the modes the post restores, and each axis word as written.
  // A header or footer block keeps every word as the control reads it (G28 may become G30);
  // when it only gains M codes, the codes it had are the post's own (its G54, G49, G50 S..)
  // and its modes stay the post's (attack 51: G50 S3000 given X and Z, G54 given P7, a
  // G68.2's angle changed, an X1 kept in a comment).
  bool kept = false;
  const std::string lost =
      frame ? frame_words_lost(block, replacement, kept) : lost_words(block, replacement);
  if (!lost.empty()) {
    error(
        line_,
        frame
            ? fmt::format("on_block replaces the {} block \"{}\" with \"{}\", which leaves out {}: the "
                          "header and the footer set the modes and end the program safely; keep each of its "
                          "words (G28 may become G30) and add to them",
                          block_part_, block, replacement, lost)
            : fmt::format("on_block replaces \"{}\" with \"{}\", which leaves out {}: the post's next blocks "
                          "rely on it; keep it in the block you give back",
                          block, replacement, lost));
    script_->failed = true;
    return block_writer::verdict::keep;
  }
  if (!user_block_passes(replacement, kept ? block : std::string_view()) ||
      (!kept && !refuse_mode_changes(replacement, "on_block"))) {  // at the CL record
    script_block_note(replacement, "on_block");
    script_->failed = true;  // the post has failed: no more on_block calls, no error per block
    return block_writer::verdict::drop;
  }
  // Its waits are counted as it is written (block_written()); its G and M codes change the modal state.
  note_user_block(replacement, false);
  return block_writer::verdict::replace;
}

}  // namespace twinpost
