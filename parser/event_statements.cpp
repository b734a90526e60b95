// event_builder: statements (MAJOR/args) other than motion, found through one table of
// handlers by major word.
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

bool known_passthrough(std::string_view m);
bool ignorable_in_post(const cl_record& r);

template <class T>
void push_some(event_queue& out, int line, std::optional<T> e) {
  if (e) out.push_back({line, std::move(*e)});
}

constexpr char upper_ascii(char c) { return c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c; }

}  // namespace

void event_builder::statement(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  end_of_motion_record();
  const std::string_view m = r.major;
  handler_cache& c = last_handler_;
  statement_handler h = c.handler;
  if (h == nullptr || m.size() != c.size || std::memcmp(m.data(), c.word.data(), m.size()) != 0) {
    h = handler_of(m);
    if (m.size() <= c.word.size()) {  // a longer word is looked up each time
      c.size = m.size();
      std::memcpy(c.word.data(), m.data(), m.size());
      c.handler = h;
    }
  }
  (this->*h)(r, line, out, issues);
}

// This runs once per record: a table sorted by word, cut into one run per first letter, so a
// lookup is an index and a few length compares (GOTO: two), with no allocation and no
// indirect call beyond the handler itself.
event_builder::statement_handler event_builder::handler_of(std::string_view major) {
  struct entry {
    std::string_view word;  // upper case
    statement_handler handler;
  };
  using b = event_builder;
  static constexpr entry table[] = {
      {"AUXFUN", &b::on_aux<false>},
      {"CHANNEL", &b::on_channel},
      {"CHANNL", &b::on_channel},
      {"CIRCLE", &b::circle},
      {"COOLNT", &b::on_coolnt},
      {"CSYS", &b::on_coordsys},
      {"CUTCOM", &b::on_cutcom},
      {"CUTTER", &b::on_tool_data},
      {"CYCLE", &b::on_cycle},
      {"DELAY", &b::on_delay},
      {"END", &b::on_end},
      {"END-OF-PATH", &b::on_end},
      {"FEDRAT", &b::on_fedrat},
      {"FINI", &b::on_end},
      {"FROM", &b::on_motion<motion_kind::from>},
      {"GODLTA", &b::on_motion<motion_kind::delta>},
      {"GOHOME", &b::on_motion<motion_kind::home>},
      {"GOTO", &b::on_motion<motion_kind::go_to>},
      {"HEAD", &b::on_head},
      {"LOAD", &b::on_load_or_select},
      {"LOADTL", &b::on_tool<tool_source::loadtl>},
      {"MACHIN", &b::on_machin},
      {"MSYS", &b::on_coordsys},
      {"MULTAX", &b::on_multax},
      {"OPSTOP", &b::on_stop},
      {"PREFUN", &b::on_aux<true>},
      {"RAPID", &b::on_rapid},
      {"SELCTL", &b::on_tool<tool_source::select_tool>},
      {"SELECT", &b::on_load_or_select},
      {"SPINDL", &b::on_spindl},
      {"STOP", &b::on_stop},
      {"SYNC", &b::on_sync},
      {"SYNCTR", &b::on_synctr},
      {"TLAXIS", &b::on_tlaxis},
      {"TLDATA", &b::on_tool_data},
      {"TURRET", &b::on_tool<tool_source::turret>},
      {"UNIT", &b::on_units},
      {"UNITS", &b::on_units},
  };
  constexpr std::size_t n = std::size(table);
  // first[c]..first[c + 1]: the entries whose word starts with letter 'A' + c.
  static constexpr auto first = [] {
    for (std::size_t i = 1; i < n; ++i)
      if (!(table[i - 1].word < table[i].word)) throw "the statement table must be sorted and unique";
    std::array<unsigned char, 27> f{};
    std::size_t i = 0;
    for (int c = 0; c < 26; ++c) {
      f[c] = static_cast<unsigned char>(i);
      while (i < n && table[i].word[0] == 'A' + c) ++i;
    }
    if (i != n) throw "every word of the statement table must start with a letter A-Z";
    f[26] = static_cast<unsigned char>(n);
    return f;
  }();
  if (major.empty()) return &b::other;
  const char c = upper_ascii(major[0]);
  if (c < 'A' || c > 'Z') return &b::other;
  for (std::size_t i = first[c - 'A'], end = first[c - 'A' + 1]; i < end; ++i)
    if (word_is(major, table[i].word)) return table[i].handler;
  return &b::other;
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

void event_builder::on_cycle(const cl_record& r, int line, event_queue& out, build_issues&) {
  out.push_back({line, detail::read_cycle(r)});
}

void event_builder::on_delay(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  push_some(out, line, detail::read_delay(r, issues));
}

// LOAD/TOOL and SELECT/TOOL call a tool; LOAD or SELECT of anything else is another record.
void event_builder::on_load_or_select(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  const bool tool_word =
      !r.args.empty() && r.args[0].kind == arg_kind::word && word_is(r.args[0].word, "TOOL");
  if (!tool_word) return other(r, line, out, issues);
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

void event_builder::on_end(const cl_record& r, int line, event_queue& out, build_issues&) {
  out.push_back({line, end_event{upper(r.major)}});
}

void event_builder::other(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  std::string_view m = r.major;
  bool known = known_passthrough(m);
  if (!known && posting_) {
    // Nothing silent in a post: a record twinpost cannot carry out stops it.
    issues.push_back({severity::error, r.major_offset,
                      fmt::format("unknown major word '{}': this record cannot be posted", upper(m))});
    return;
  }
  if (known && posting_ && !ignorable_in_post(r)) {
    // Known, but a post cannot do what it asks (STOP, THREAD, NURBS, ORIGIN, ...): dropping
    // it would write a program that differs from the CL without a word.
    issues.push_back(
        {severity::error, r.major_offset,
         fmt::format("{} is not supported by the post: this record cannot be carried out", upper(m))});
    return;
  }
  if (!known)
    issues.push_back({severity::warning, r.major_offset,
                      fmt::format("unknown major word '{}' (a post stops here with an error)", upper(m))});
  out.push_back({line, passthrough_event{upper(m), detail::args_text(r), known}});
}

namespace {
// Records that only inform (display, tolerances, feature and tool labels): a post may pass
// over them, since the program does the same with or without them.
bool ignorable_in_post(const cl_record& r) {
  static constexpr std::string_view words[] = {"PAINT",
                                               "BOX",
                                               "MOVE_ATTRIB",
                                               "TRNTYP",
                                               "TOOLNO",
                                               "CSI_SET_FLUTE_LENGTH",
                                               "CSI_SET_EXTENSION_LENGTH",
                                               "INTOL",
                                               "OUTTOL",
                                               "LINTOL",
                                               "FEATNO",
                                               "MFGNO",
                                               "CUTCOM_GEOMETRY_TYPE",
                                               "REWIND",
                                               "DMIS"};
  for (std::string_view w : words)
    if (word_is(r.major, w)) return true;
  // SET/MODE,ABSOL (Makino) says what twinpost does anyway: absolute coordinates.
  return word_is(r.major, "SET") && r.args.size() == 2 && r.args[0].kind == arg_kind::word &&
         word_is(r.args[0].word, "MODE") && r.args[1].kind == arg_kind::word &&
         word_is(r.args[1].word, "ABSOL");
}

bool known_passthrough(std::string_view m) {
  static constexpr std::string_view words[] = {"PAINT",
                                               "BOX",
                                               "MOVE_ATTRIB",
                                               "TRNTYP",
                                               "SET",
                                               "REWIND",
                                               "TOOLNO",
                                               "SWITCH",
                                               "LOCAL_ORIGIN",
                                               "ROTABL",
                                               "NURBS",
                                               "KNOT",
                                               "CNTRL",
                                               "CSI_SET_FLUTE_LENGTH",
                                               "CSI_SET_EXTENSION_LENGTH",
                                               "MODE",
                                               "COUPLE",
                                               "CLAMP",
                                               "THREAD",
                                               "ORIGIN",
                                               "INTOL",
                                               "OUTTOL",
                                               "LINTOL",
                                               "CALSUB",
                                               "DEFSUB",
                                               "ENDSUB",
                                               "DMIS",
                                               "FEATNO",
                                               "MFGNO",
                                               "SETSTART",
                                               "CUTCOM_GEOMETRY_TYPE",
                                               "OPSKIP",
                                               "PITCH"};
  for (std::string_view w : words)
    if (word_is(m, w)) return true;
  return false;
}
}  // namespace

}  // namespace twinpost
