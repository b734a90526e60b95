// event_builder: statements (MAJOR/args) other than motion, found through one table of
// handlers by major word.
#include <algorithm>
#include <array>
#include <cstring>

#include <fmt/format.h>

#include "parser/detail/word_events.hpp"
#include "parser/event_builder.hpp"
#include "parser/event_text.hpp"

namespace twinpost {

using detail::numbers_of;
using detail::upper;

namespace {

template <class T>
void push_some(event_queue& out, int line, std::optional<T> e) {
  if (e) out.push_back({line, std::move(*e)});
}

}  // namespace

void event_builder::statement(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  end_of_motion_record();
  const std::string_view m = r.major;
  handler_cache& c = last_handler_;
  statement_handler h = c.handler;
  // At most eight bytes compared in line: a call of memcmp costs more than the compare.
  bool same = h != nullptr && m.size() == c.size;
  for (std::size_t k = 0; same && k < m.size(); ++k) same = m[k] == c.word[k];
  if (!same) {
    h = handler_of(m);
    if (m.size() <= c.word.size()) {  // a longer word is looked up each time
      c.size = m.size();
      std::memcpy(c.word.data(), m.data(), m.size());
      c.handler = h;
    }
  }
  (this->*h)(r, line, out, issues);
}

template <tool_source S>
void event_builder::on_tool(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  push_some(out, line, detail::read_tool(r, S, issues));
}

template <bool Prefun>
void event_builder::on_aux(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  push_some(out, line, detail::read_aux(r, Prefun, issues));
}

void event_builder::on_rapid(const cl_record&, int, event_queue&, build_issues&) { rapid_ = true; }

void event_builder::on_spindl(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  out.push_back({line, detail::read_spindl(r, issues)});
}

void event_builder::on_fedrat(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  out.push_back({line, detail::read_fedrat(r, units_, issues)});
}

void event_builder::on_coolnt(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  out.push_back({line, detail::read_coolnt(r, issues)});
}

void event_builder::on_cutcom(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  out.push_back({line, detail::read_cutcom(r, issues)});
}

void event_builder::on_cycle(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  cycle_event c = detail::read_cycle(r, issues);
  c.meaning = cycle_meaning(dialect_);
  out.push_back({line, std::move(c)});
}

void event_builder::on_thread(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  push_some(out, line, detail::read_thread(r, issues));
}

void event_builder::on_delay(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  push_some(out, line, detail::read_delay(r, issues));
}

// LOAD/TOOL and SELECT/TOOL (the table sends any other LOAD or SELECT elsewhere).
void event_builder::on_load_tool(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  const tool_source s = word_is(r.major, "LOAD") ? tool_source::load_tool : tool_source::select_tool;
  push_some(out, line, detail::read_tool(r, s, issues));
}

void event_builder::on_tool_data(const cl_record& r, int line, event_queue& out, build_issues&) {
  tool_data_event t;
  t.major = upper(r.major);
  for (const cl_arg& a : r.args) {
    if (a.kind == arg_kind::word) t.words.push_back(upper(a.word));
    if (a.kind == arg_kind::number) t.values.push_back(a.number);
  }
  out.push_back({line, std::move(t)});
}

void event_builder::on_units(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  if (r.args.empty() || r.args[0].kind != arg_kind::word)
    return issues.push_back({severity::error, detail::args_offset(r), "UNITS needs MM or INCHES"});
  std::string_view w = r.args[0].word;
  if (word_is(w, "MM"))
    units_ = unit_system::mm;
  else if (word_is(w, "INCHES") || word_is(w, "INCH"))
    units_ = unit_system::inch;
  else
    return issues.push_back({severity::error, r.args[0].offset, fmt::format("unknown units '{}'", w)});
  out.push_back({line, units_event{units_}});
}

void event_builder::on_machin(const cl_record& r, int line, event_queue& out, build_issues&) {
  machin_event e;
  for (std::size_t i = 0; i < r.args.size(); ++i) {
    const cl_arg& a = r.args[i];
    std::string s = a.kind == arg_kind::word     ? std::string(a.word)
                    : a.kind == arg_kind::number ? format_number(a.number)
                                                 : std::string();
    if (i == 0)
      e.name = std::move(s);
    else
      e.args.push_back(std::move(s));
  }
  out.push_back({line, std::move(e)});
}

void event_builder::on_multax(const cl_record& r, int line, event_queue& out, build_issues&) {
  const bool on = r.args.empty() || r.args[0].kind != arg_kind::word || !word_is(r.args[0].word, "OFF");
  out.push_back({line, multax_event{on}});
}

void event_builder::on_coordsys(const cl_record& r, int line, event_queue& out, build_issues&) {
  out.push_back({line, coordsys_event{upper(r.major), numbers_of(r)}});
}

void event_builder::on_tlaxis(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  std::vector<double> n = numbers_of(r);
  if (n.size() != 3)
    return issues.push_back({severity::error, detail::args_offset(r), "TLAXIS takes 3 numbers"});
  axis_ = vec3{n[0], n[1], n[2]};
  out.push_back({line, tool_axis_event{*axis_}});
}

void event_builder::on_head(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  push_some(out, line, detail::read_head(r, issues));
}

void event_builder::on_channel(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  push_some(out, line, detail::read_channel(r, issues));
}

void event_builder::on_sync(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  push_some(out, line, detail::read_sync(r, issues));
}

void event_builder::on_synctr(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  push_some(out, line, detail::read_synctr(r, issues));
}

void event_builder::on_stop(const cl_record& r, int line, event_queue& out, build_issues&) {
  out.push_back({line, stop_event{word_is(r.major, "OPSTOP")}});
}

void event_builder::on_transfer(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  // TRANSFER/GRIP or TRANSFER/RELEASE, nothing else (docs/records.md).
  const bool one_word = r.args.size() == 1 && r.args[0].kind == arg_kind::word;
  const bool grip = one_word && word_is(r.args[0].word, "GRIP");
  const bool release = one_word && word_is(r.args[0].word, "RELEASE");
  if (!grip && !release)
    return issues.push_back({severity::error, detail::args_offset(r), "TRANSFER needs GRIP or RELEASE"});
  transfer_event t;
  t.step = grip ? transfer_event::phase::grip : transfer_event::phase::release;
  t.release = release;
  out.push_back({line, t});
}

void event_builder::on_end(const cl_record& r, int line, event_queue& out, build_issues&) {
  out.push_back({line, end_event{upper(r.major)}});
}

template <text_kind K>
void event_builder::on_text(const cl_record& r, int line, event_queue& out, build_issues&) {
  out.push_back({line, text_event{K, upper(r.major), std::string(r.text)}});
}

// APT's INSERT is a raw NC block; SolidWorks CAM writes information text with it
// (`INSERT/Stock Size X144. ...`), which must never reach the control as a block.
void event_builder::on_insert(const cl_record& r, int line, event_queue& out, build_issues&) {
  const text_kind k = dialect_ == dialect::solidworks ? text_kind::pprint : text_kind::insert;
  out.push_back({line, text_event{k, upper(r.major), std::string(r.text)}});
}

void event_builder::by_args(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  const rule_row* row = rule_of(r);  // the word's last row takes any arguments
  (this->*(row ? row->handler : &event_builder::other))(r, line, out, issues);
}

void event_builder::on_ignored(const cl_record& r, int line, event_queue& out, build_issues&) {
  out.push_back({line, passthrough_event{upper(r.major), detail::args_text(r), true}});
}

void event_builder::on_refused(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  if (!posting_) {
    out.push_back({line, passthrough_event{upper(r.major), detail::args_text(r), true}});
    return;
  }
  // A record the post cannot carry out stops it: dropping it would write a program that
  // differs from the CL without a word. A word with rows for given minor words is named
  // with its arguments (SET/MODE,INCR).
  const rule_row* row = rule_of(r);
  std::string name = upper(r.major);
  if (handler_of(r.major) == &event_builder::by_args && !r.args.empty())
    name = fmt::format("{}/{}", name, detail::args_text(r));
  issues.push_back({severity::error, r.major_offset,
                    fmt::format("{} is not supported by the post: {}", name, row ? row->rule.note : "")});
}

void event_builder::other(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  const std::string m = upper(r.major);
  if (!user_records_.empty() &&
      std::find(user_records_.begin(), user_records_.end(), m) != user_records_.end()) {
    out.push_back({line, passthrough_event{m, detail::args_text(r), false, true}});
    return;
  }
  if (unknown_to_script_) {
    out.push_back({line, passthrough_event{m, detail::args_text(r), false, true}});
    return;
  }
  if (posting_ && !permissive_) {
    // Nothing silent in a post: a word twinpost does not know stops it.
    issues.push_back({severity::error, r.major_offset,
                      fmt::format("unknown major word '{}': this record cannot be posted", m)});
    return;
  }
  issues.push_back({severity::warning, r.major_offset,
                    posting_ ? fmt::format("unknown major word '{}': passed over in a permissive post, "
                                           "nothing is written for it",
                                           m)
                             : fmt::format("unknown major word '{}' (a post stops here with an error)", m)});
  out.push_back({line, passthrough_event{m, detail::args_text(r), false}});
}

// The record table (parser/record_table.cpp) takes the addresses of these.
template void event_builder::on_tool<tool_source::loadtl>(const cl_record&, int, event_queue&, build_issues&);
template void event_builder::on_tool<tool_source::select_tool>(const cl_record&, int, event_queue&,
                                                               build_issues&);
template void event_builder::on_tool<tool_source::turret>(const cl_record&, int, event_queue&, build_issues&);
template void event_builder::on_aux<false>(const cl_record&, int, event_queue&, build_issues&);
template void event_builder::on_aux<true>(const cl_record&, int, event_queue&, build_issues&);
template void event_builder::on_text<text_kind::partno>(const cl_record&, int, event_queue&, build_issues&);
template void event_builder::on_text<text_kind::pprint>(const cl_record&, int, event_queue&, build_issues&);
template void event_builder::on_text<text_kind::tprint>(const cl_record&, int, event_queue&, build_issues&);
template void event_builder::on_text<text_kind::op_start>(const cl_record&, int, event_queue&, build_issues&);
template void event_builder::on_text<text_kind::op_end>(const cl_record&, int, event_queue&, build_issues&);
template void event_builder::on_text<text_kind::toolpath>(const cl_record&, int, event_queue&, build_issues&);
template void event_builder::on_text<text_kind::other>(const cl_record&, int, event_queue&, build_issues&);

}  // namespace twinpost
