// [events] and [[events.record]] of a machine file (machines/machine_events.hpp).
#include "machines/machine_events.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "machines/machine.hpp"
#include "machines/toml_reader.hpp"
#include "support/ascii.hpp"

namespace twinpost {

namespace {

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// A major word as the CL writes it: a letter, then letters, digits and '_' (PARTS_CATCHER).
bool major_word(std::string_view w) {
  if (w.empty() || !ascii::is_letter(w.front())) return false;
  for (char c : w)
    if (!ascii::is_letter(c) && !ascii::is_digit(c) && c != '_' && c != '-') return false;
  return true;
}

// [events] script and script_records. The script is a plain file name, found beside the
// machine file: a machine file and its script travel together, and a name cannot reach
// elsewhere (the same rule as post.read_file's).
void read_script(const detail::table_reader& r, std::string_view source, event_templates& ev) {
  if (const toml::node* n = r.find("script")) {
    r.read("script", ev.script);
    const std::string& s = ev.script;
    if (s.empty() || s.find_first_of("/\\:") != std::string::npos || s.front() == '.')
      r.fail(*n, fmt::format("events.script \"{}\" must be a file name beside the machine file (no '/', "
                             "'\\', ':' or leading '.')",
                             s));
    if (std::any_of(s.begin(), s.end(),
                    [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
      r.fail(*n, "events.script: the name holds a control byte (a NUL, an escape): give a plain file name");
    const std::filesystem::path p = std::filesystem::path(source).parent_path() / s;
    // Not followed: a symbolic link beside the machine file could name any file (the script
    // is also opened with O_NOFOLLOW, scripting/confined_file.cpp).
    std::error_code ec;
    const std::filesystem::file_type t = std::filesystem::symlink_status(p, ec).type();
    if (t == std::filesystem::file_type::not_found || t == std::filesystem::file_type::none)
      r.fail(*n,
             fmt::format("events.script \"{}\": no such file beside the machine file ('{}')", s, p.string()));
    if (t != std::filesystem::file_type::regular)
      r.fail(*n, fmt::format(
                     "events.script \"{}\": '{}' is not a regular file (a symbolic link, a FIFO, a device "
                     "or a folder): only a regular file beside the machine file is read",
                     s, p.string()));
    ev.script_path = p.string();
  }
  r.read("script_records", ev.script_records);
  for (std::string& w : ev.script_records) {
    if (!major_word(w))
      r.fail(*r.find("script_records"),
             fmt::format("events.script_records: \"{}\" is not a CL major word", w));
    ascii::upper_in_place(w);
  }
  // The script's budgets for the whole job (docs/scripting.md, "What a script cannot do"):
  // 0 keeps the default.
  if (r.read("script_instructions", ev.script_instructions) &&
      !(ev.script_instructions >= 1e6 && ev.script_instructions <= 1e13))
    r.fail(*r.find("script_instructions"),
           fmt::format("events.script_instructions must be 1e6..1e13, not {}", ev.script_instructions));
  if (r.read("script_seconds", ev.script_seconds) && !(ev.script_seconds >= 1 && ev.script_seconds <= 86400))
    r.fail(*r.find("script_seconds"),
           fmt::format("events.script_seconds must be 1..86400, not {}", ev.script_seconds));
  if ((ev.script_instructions > 0 || ev.script_seconds > 0) && ev.script.empty())
    r.fail(*r.find(ev.script_instructions > 0 ? "script_instructions" : "script_seconds"),
           "events.script_instructions and script_seconds without events.script: no script to hold");
  if (!ev.script_records.empty() && ev.script.empty())
    r.fail(*r.find("script_records"), "events.script_records without events.script: no script to take them");
}

}  // namespace

const record_event* event_templates::record_for(std::string_view major, std::string_view args) const {
  for (const record_event& r : records) {
    if (r.major != major) continue;
    std::string_view rest = args;
    bool match = true;
    for (const std::string& w : r.words) {
      const std::size_t comma = rest.find(',');
      const std::string_view arg = trimmed(rest.substr(0, comma));
      if (!ascii::iequals(arg, w)) {
        match = false;
        break;
      }
      rest = comma == std::string_view::npos ? std::string_view() : rest.substr(comma + 1);
    }
    if (match) return &r;
  }
  return nullptr;
}

bool event_templates::names_record(std::string_view major) const {
  for (const record_event& r : records)
    if (r.major == major) return true;
  return false;
}

namespace detail {

void read_events(const table_reader& root, machine& m) {
  const toml::table* t = root.sub_table("events");
  if (!t) return;
  table_reader r(*t, "events", root.source(),
                 {"program_start", "program_end", "tool_change", "spindle_start", "spindle_stop",
                  "coolant_on", "coolant_off", "wait", "cycle", "transfer", "operation", "section", "record",
                  "script", "script_records", "script_instructions", "script_seconds"});
  read_script(r, root.source(), m.events);
  for (std::size_t i = 0; i < event_point_count; ++i) {
    const toml::table* e = r.sub_table(event_point_keys[i]);
    if (!e) continue;
    table_reader er(*e, fmt::format("events.{}", event_point_keys[i]), root.source(), {"before", "after"});
    const auto p = static_cast<event_point>(i);
    // The program's first and last blocks are [program] header and footer: a block before
    // the header or after the footer would be outside the frame the checker reads.
    if (p == event_point::program_start && er.find("before"))
      er.fail(*er.find("before"),
              "events.program_start takes `after` only (blocks before the safe start "
              "belong in program.header)");
    if (p == event_point::program_end && er.find("after"))
      er.fail(*er.find("after"),
              "events.program_end takes `before` only (blocks after the last ones belong "
              "in program.footer)");
    er.read_templates("before", m.events.at[i].before, event_uses::of[i]);
    er.read_templates("after", m.events.at[i].after, event_uses::of[i]);
  }
  for (const toml::table* e : r.tables("record")) {
    table_reader er(*e, "events.record", root.source(), {"major", "words", "blocks"});
    er.require("major");
    er.require("blocks");
    record_event rec;
    er.read("major", rec.major);
    rec.line = static_cast<int>(er.find("major")->source().begin.line);
    rec.column = static_cast<int>(er.find("major")->source().begin.column);
    if (!major_word(rec.major))
      er.fail(*er.find("major"), fmt::format("events.record.major \"{}\" is not a CL major word", rec.major));
    ascii::upper_in_place(rec.major);
    er.read("words", rec.words);
    for (std::string& w : rec.words) ascii::upper_in_place(w);
    er.read_templates("blocks", rec.blocks, event_uses::record);
    if (rec.blocks.empty())
      er.fail(*er.find("blocks"), "events.record.blocks is empty: give at least one block");
    m.events.records.push_back(std::move(rec));
  }
}

}  // namespace detail
}  // namespace twinpost
