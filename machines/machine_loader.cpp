// Machine definitions: TOML text -> validated struct machine. The schema is documented in
// docs/machines.md; each table of the file is read by one function below, and checks that
// need more than one table run at the end.
#include "machines/machine_loader.hpp"

#include <array>

#include <algorithm>
#include <map>
#include <span>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "machines/builtin_machines.hpp"
#include "machines/layout_names.hpp"
#include "machines/layout_rules.hpp"
#include "machines/machine_search.hpp"
#include "machines/toml_reader.hpp"
#include "support/ascii.hpp"

namespace twinpost {

namespace {

using detail::table_reader;

// Nodes that the checks across tables report at.
struct anchors {
  const toml::node* layout = nullptr;          // machine.layout, when given
  const toml::table* program = nullptr;        // [program], when given
  const toml::table* waits = nullptr;          // [waits]
  const toml::node* partners = nullptr;        // waits.partners, when given
  const toml::node* program_number = nullptr;  // program.program_number, when given
  const toml::table* format = nullptr;         // [format], when given
};

// Reads `key` as one of the names; anything else fails with "T.key must be a, b or c".
// Returns the key's node (for later messages), or nullptr when the key is absent.
template <class E, std::size_t N>
const toml::node* read_enum(const table_reader& r, std::string_view key,
                            const std::array<std::pair<std::string_view, E>, N>& names, E& out) {
  std::string text;
  if (!r.read(key, text)) return nullptr;
  std::string choices;
  for (std::size_t i = 0; i < N; ++i) {
    if (text == names[i].first) {
      out = names[i].second;
      return r.find(key);
    }
    choices += i == 0 ? "" : (i + 1 == N ? " or " : ", ");
    choices += names[i].first;
  }
  r.fail(*r.find(key), fmt::format("{} must be {}, not '{}'", r.key_path(key), choices, text));
  return nullptr;
}

void read_machine_table(const table_reader& root, machine& m, anchors& at) {
  const toml::table* t = root.sub_table("machine");
  if (!t) root.fail_here("machine.name is required");
  table_reader r(*t, "machine", root.source(), {"name", "description", "control", "layout", "check_only"});
  r.require("name");
  r.read("name", m.name);
  if (m.name.empty()) r.fail(*r.find("name"), "machine.name must not be empty");
  r.read("description", m.description);
  r.read("control", m.control);
  r.read("check_only", m.check_only);
  at.layout = read_enum(r, "layout", layout_file_names(), m.layout);
}

constexpr int max_wait_code = 99'999'999;

// [[waits.fixed]]: codes outside the range that are waits of fixed channels (Star M82/M83).
// Their channels are checked against the machine's in check_fixed_waits, once channels are read.
void read_fixed_waits(const table_reader& r, wait_rules& w) {
  const toml::node* node = r.find("fixed");
  if (!node) return;
  const toml::array* list = node->as_array();
  if (!list || !list->is_array_of_tables())
    r.fail(*node, "waits.fixed must be an array of tables ([[waits.fixed]])");
  if (w.syntax != wait_syntax::m_code)
    r.fail(*node, "waits.fixed is read only with waits.syntax = \"m_code\"");
  for (const toml::node& item : *list) {
    table_reader f(*item.as_table(), "waits.fixed", r.source(), {"code", "channels"});
    wait_rules::fixed_wait fw;
    f.require("code");
    f.require("channels");
    f.read("code", fw.code);
    f.read("channels", fw.channels);
    if (fw.code < 0 || fw.code > max_wait_code)
      f.fail(*f.find("code"), fmt::format("waits.fixed code must be 0..{}, not {}", max_wait_code, fw.code));
    if (fw.code >= w.first && fw.code <= w.last)
      f.fail(*f.find("code"),
             fmt::format("waits.fixed code {} lies in the wait range {}..{}: a fixed wait is "
                         "a code outside it",
                         fw.code, w.first, w.last));
    if (w.fixed_wait_of(fw.code))
      f.fail(*f.find("code"), fmt::format("waits.fixed code {} is given twice", fw.code));
    std::sort(fw.channels.begin(), fw.channels.end());
    if (fw.channels.size() < 2 ||
        std::adjacent_find(fw.channels.begin(), fw.channels.end()) != fw.channels.end())
      f.fail(*f.find("channels"), "waits.fixed channels must name at least two different channels");
    w.fixed.push_back(std::move(fw));
  }
}

void read_waits(const table_reader& root, wait_rules& w, anchors& at) {
  const toml::table* t = root.sub_table("waits");
  if (!t) root.fail_here("waits.first is required");
  at.waits = t;
  table_reader r(*t, "waits", root.source(),
                 {"syntax", "marker", "address", "first", "last", "step", "excluded", "reuse", "partners",
                  "partner_address", "partner_list", "fixed"});
  using syntax_name = std::pair<std::string_view, wait_syntax>;
  const toml::node* syntax = read_enum(
      r, "syntax", std::array<syntax_name, 2>{{{"m_code", wait_syntax::m_code}, {"bang", wait_syntax::bang}}},
      w.syntax);
  if (w.syntax == wait_syntax::bang) {
    w.address = 'L';  // Mitsubishi's label address; the marker defaults to '!'
    w.partners = partner_style::others;
  }
  if (r.read_char("marker", w.marker, false)) {
    if (w.syntax != wait_syntax::bang)
      r.fail(*r.find("marker"), "waits.marker is read only with waits.syntax = \"bang\"");
    if (ascii::is_letter(w.marker) || ascii::is_digit(w.marker) || w.marker == '(' || w.marker == ';' ||
        w.marker == ' ')
      r.fail(*r.find("marker"),
             fmt::format("waits.marker must be a sign that is no address, digit or comment, not '{}'",
                         w.marker));
  }
  r.read_char("address", w.address, true);
  r.require("first");
  r.require("last");
  r.read("first", w.first);
  r.read("last", w.last);
  if (w.first < 0) r.fail(*r.find("first"), fmt::format("waits.first must be >= 0, not {}", w.first));
  // A control reads at most eight digits of an M code; the bound also keeps every sum of a
  // code and a step (the allocator's, the checker's) far from the end of an int.
  for (std::string_view key : {"first", "last"})
    if ((key == "first" ? w.first : w.last) > max_wait_code)
      r.fail(*r.find(key), fmt::format("waits.{} must be <= {} (a code has at most 8 digits), "
                                       "not {}",
                                       key, max_wait_code, key == "first" ? w.first : w.last));
  if (w.first > w.last)
    r.fail(*r.find("first"), fmt::format("waits.first ({}) must be <= waits.last ({})", w.first, w.last));
  if (r.read("step", w.step) && w.step < 1)
    r.fail(*r.find("step"), fmt::format("waits.step must be >= 1, not {}", w.step));
  if (w.step > max_wait_code)
    r.fail(*r.find("step"), fmt::format("waits.step must be <= {} (a code has at most 8 "
                                        "digits), not {}",
                                        max_wait_code, w.step));
  if (r.read("excluded", w.excluded)) {
    const toml::array& codes = *r.find("excluded")->as_array();
    for (std::size_t i = 0; i < w.excluded.size(); ++i)
      if (w.excluded[i] < w.first || w.excluded[i] > w.last)
        r.fail(*codes.get(i), fmt::format("waits.excluded: {} is outside the wait range {}..{}",
                                          w.excluded[i], w.first, w.last));
  }
  r.read("reuse", w.reuse);
  using partner_name = std::pair<std::string_view, partner_style>;
  at.partners = read_enum(r, "partners",
                          std::array<partner_name, 4>{{{"none", partner_style::none},
                                                       {"path_numbers", partner_style::path_numbers},
                                                       {"binary", partner_style::binary},
                                                       {"others", partner_style::others}}},
                          w.partners);
  // A bang wait always names the other channels (!2L1); an M-code wait never does so.
  if ((w.syntax == wait_syntax::bang) != (w.partners == partner_style::others))
    r.fail(at.partners ? *at.partners : *syntax,
           w.syntax == wait_syntax::bang ? "waits.partners must be others with waits.syntax = \"bang\""
                                         : "waits.partners = others needs waits.syntax = \"bang\"");
  if (w.syntax == wait_syntax::bang && r.find("partner_address"))
    r.fail(*r.find("partner_address"),
           "waits.partner_address is not read with waits.syntax = \"bang\": the "
           "partners follow waits.marker");
  r.read_char("partner_address", w.partner_address, true);
  using list_name = std::pair<std::string_view, bool>;
  read_enum(r, "partner_list", std::array<list_name, 2>{{{"required", false}, {"optional", true}}},
            w.partners_optional);
  if (w.partners_optional && w.partners != partner_style::path_numbers && w.partners != partner_style::binary)
    r.fail(*r.find("partner_list"),
           "waits.partner_list = \"optional\" needs waits.partners = path_numbers or binary");
  read_fixed_waits(r, w);
}

// File names are built from these, so a separator could write outside the output directory.
void check_file_part(const table_reader& r, std::string_view key, const std::string& value) {
  if (value.find_first_of("/\\") != std::string::npos)
    r.fail(*r.find(key), fmt::format("{} must not contain a path separator", r.key_path(key)));
}

void check_min(const table_reader& r, std::string_view key, int value, int min) {
  if (value < min) r.fail(*r.find(key), fmt::format("{} must be >= {}, not {}", r.key_path(key), min, value));
}

void read_program(const table_reader& root, program_format& p, anchors& at) {
  const toml::table* t = root.sub_table("program");
  if (!t) return;
  at.program = t;
  table_reader r(*t, "program", root.source(), {"extension",      "file_name",       "program_number",
                                                "program_line",   "header",          "footer",
                                                "end_code",       "percent_lines",   "section_marker",
                                                "sequence_start", "sequence_step",   "sequence_numbers",
                                                "comment_open",   "comment_close",   "comment_max",
                                                "output_units",   "decimals_metric", "decimals_inch",
                                                "trailing_point", "arcs_ijk",        "reserved_variables",
                                                "cl_frame"});
  if (r.read("extension", p.extension)) check_file_part(r, "extension", p.extension);
  r.read_template("file_name", p.file_name, template_uses::file);
  if (r.read("program_number", p.program_number)) at.program_number = r.find("program_number");
  r.read_template("program_line", p.program_line, template_uses::file);
  r.read_templates("header", p.header, template_uses::section);
  r.read_templates("footer", p.footer, template_uses::section);
  r.read_fixed("end_code", p.end_code);
  r.read("percent_lines", p.percent_lines);
  r.read_template("section_marker", p.section_marker, template_uses::section_marker);
  if (r.read("sequence_start", p.sequence_start)) check_min(r, "sequence_start", p.sequence_start, 0);
  if (r.read("sequence_step", p.sequence_step)) check_min(r, "sequence_step", p.sequence_step, 1);
  using sequence_name = std::pair<std::string_view, sequence_mode>;
  read_enum(r, "sequence_numbers",
            std::array<sequence_name, 2>{
                {{"all", sequence_mode::all}, {"tool_change", sequence_mode::tool_change}}},
            p.sequence_numbers);
  r.read_char("comment_open", p.comment_open, false);
  // A comment to the end of the line (Sinumerik's and Heidenhain's `;`): comment_close = "",
  // or no comment_close under comment_open = ";". Held as '\n', which no block contains.
  std::string close;
  if (r.read("comment_close", close) && close.empty())
    p.comment_close = '\n';
  else if (r.find("comment_close"))
    r.read_char("comment_close", p.comment_close, false);
  else if (p.comment_open == ';')
    p.comment_close = '\n';
  // A comment character that is also a word's (a letter, a digit, a sign, a point), a block's
  // own (%, /, #, [, ], =), a program number's (ISO's :), a system's or a wait's mark (Citizen's
  // $ and !) or a blank would turn the comments' text into code, or code into comments, for the
  // control and the post's own readers alike.
  const auto unfit = [](char ch) {
    return static_cast<unsigned char>(ch) <= ' ' || static_cast<unsigned char>(ch) >= 0x7f ||
           ascii::is_letter(ch) || (ch >= '0' && ch <= '9') ||
           std::string_view("%/#[]=+-.,*:$!").find(ch) != std::string_view::npos;
  };
  if (unfit(p.comment_open))
    r.fail(*r.find("comment_open"),
           "program.comment_open must be a character no block word uses, such as ( or ;");
  if (p.comment_close != '\n' && unfit(p.comment_close))
    r.fail(*r.find("comment_close"),
           "program.comment_close must be a character no block word uses, such as ), "
           "or \"\" (to the end of the line)");
  const toml::node* close_at = r.find("comment_close") ? r.find("comment_close") : r.find("comment_open");
  if (p.comment_close == p.comment_open)
    r.fail(*close_at,
           fmt::format("program.comment_close must differ from comment_open ('{}')", p.comment_open));
  if (p.comment_open == ')' || p.comment_close == '(')
    r.fail(*(p.comment_open == ')' ? r.find("comment_open") : close_at),
           "program.comment_open may not be ) nor comment_close (: every control reads ( as a comment's "
           "start and ) as its end");
  if (p.comment_open == '(' && p.comment_close != ')')
    r.fail(*close_at,
           "program.comment_open = \"(\" is closed by \")\": a control reads a ( comment on until its )");
  if (r.read("comment_max", p.comment_max)) check_min(r, "comment_max", p.comment_max, 0);
  if (r.read("reserved_variables", p.reserved_variables))
    for (int v : p.reserved_variables)
      if (v < 1)
        r.fail(*r.find("reserved_variables"),
               fmt::format("program.reserved_variables: #{} is no variable a program could write (>= 1)", v));
  using unit_name = std::pair<std::string_view, output_unit>;
  read_enum(r, "output_units",
            std::array<unit_name, 2>{{{"mm", output_unit::mm}, {"inch", output_unit::inch}}}, p.output_units);
  for (auto [key, decimals] : {std::pair<std::string_view, int*>{"decimals_metric", &p.decimals_metric},
                               {"decimals_inch", &p.decimals_inch}})
    if (r.read(key, *decimals) && (*decimals < 0 || *decimals > 6))
      r.fail(*r.find(key), fmt::format("program.{} must be in 0..6, not {}", key, *decimals));
  r.read("trailing_point", p.trailing_point);
  r.read("arcs_ijk", p.arcs_ijk);
  using frame_name = std::pair<std::string_view, cl_frame>;
  read_enum(r, "cl_frame",
            std::array<frame_name, 2>{{{"mcs", cl_frame::mcs}, {"absolute", cl_frame::absolute}}}, p.frame);
}

// [format]: one key per address letter, "5.3" (digits before and after the point) or 4.
void read_formats(const table_reader& root, word_formats& f, anchors& at) {
  const toml::table* t = root.sub_table("format");
  if (!t) return;
  at.format = t;
  table_reader r(*t, "format", root.source(),
                 {"A", "B", "C", "D", "E", "F", "G", "H", "I", "J", "K", "L", "M",
                  "N", "O", "P", "Q", "R", "S", "T", "U", "V", "W", "X", "Y", "Z"});
  for (char a = 'A'; a <= 'Z'; ++a) {
    const std::string key(1, a);
    const toml::node* n = r.find(key);
    if (!n) continue;
    std::string text;
    if (n->is_integer()) {
      int digits = 0;
      r.read(key, digits);
      text = std::to_string(digits);
    } else if (!n->is_string()) {
      r.fail(*n, fmt::format("format.{} must be a string such as \"5.3\" or an integer, not {}", a,
                             detail::type_phrase(n->type())));
    } else {
      r.read(key, text);
    }
    std::string why;
    if (!parse_word_format(text, f[a], why)) r.fail(*n, fmt::format("format.{} \"{}\" {}", a, text, why));
  }
}

// A dwell reads as the time it says whatever the control's decimal-point setting only as seconds
// written with their point ({seconds} always has one: U2.) or as whole milliseconds in P, which
// takes no point. A U or X of milliseconds (U2000) is 2 s or 2000 s by parameter 3401#0, and a
// P of seconds (P2.) is refused or misread. "" when the template's dwell word is one of the two.
std::string dwell_problem(std::string_view t) {
  for (const std::string_view key : {std::string_view("{ms"), std::string_view("{seconds")}) {
    const std::size_t at = t.find(key);
    if (at == std::string_view::npos || at == 0 || !ascii::is_upper(t[at - 1])) continue;
    const char address = t[at - 1];
    if (key == "{ms" && address != 'P')
      return fmt::format(
          "codes.dwell \"{}\": {}{{ms}} writes {}2000 for 2 s, which a Fanuc reads as 2 s or 2000 s "
          "by its decimal-point setting; write P{{ms}} (P is always milliseconds) or {}{{seconds}} "
          "(written with its point)",
          t, address, address, address);
    if (key == "{seconds" && address == 'P')
      return fmt::format(
          "codes.dwell \"{}\": P{{seconds}} writes P2. for 2 s, but a Fanuc's P is milliseconds "
          "without a point; write P{{ms}}, or U{{seconds}} / X{{seconds}}",
          t);
  }
  return {};
}

void read_codes(const table_reader& root, control_codes& c) {
  const toml::table* t = root.sub_table("codes");
  if (!t) return;
  table_reader r(
      *t, "codes", root.source(),
      {"css", "rpm", "feed_per_rev", "feed_per_min", "home", "dwell", "coolant_on", "coolant_off",
       "balance_on", "balance_off", "program_stop", "optional_stop", "cutcom_on_rapid", "coolant_mist",
       "coolant_through", "coolant_air", "cutcom_offset", "spindle_sync_on", "spindle_sync_off"});
  r.read_fixed("css", c.css);
  r.read_fixed("rpm", c.rpm);
  r.read_fixed("feed_per_rev", c.feed_per_rev);
  r.read_fixed("feed_per_min", c.feed_per_min);
  r.read_fixed("home", c.home);
  r.read_template("dwell", c.dwell, template_uses::dwell);
  if (const std::string why = dwell_problem(c.dwell); !why.empty()) r.fail(*r.find("dwell"), why);
  r.read_fixed("coolant_on", c.coolant_on);
  r.read_fixed("coolant_off", c.coolant_off);
  r.read_fixed("balance_on", c.balance_on);
  r.read_fixed("balance_off", c.balance_off);
  r.read_fixed("spindle_sync_on", c.spindle_sync_on);
  r.read_fixed("spindle_sync_off", c.spindle_sync_off);
  r.read_fixed("program_stop", c.program_stop);
  r.read_fixed("optional_stop", c.optional_stop);
  r.read("cutcom_on_rapid", c.cutcom_on_rapid);
  if (r.read("cutcom_offset", c.cutcom_offset) && c.cutcom_offset != "tool" && c.cutcom_offset != "cutcom" &&
      c.cutcom_offset != "table")
    r.fail(*r.find("cutcom_offset"),
           fmt::format("codes.cutcom_offset must be \"tool\", \"cutcom\" or \"table\", not \"{}\"",
                       c.cutcom_offset));
  for (auto [key, codes] :
       {std::pair<std::string_view, std::vector<std::string>*>{"coolant_mist", &c.coolant_mist},
        {"coolant_through", &c.coolant_through},
        {"coolant_air", &c.coolant_air}})
    if (r.read_fixed(key, *codes) && codes->size() != 2)
      r.fail(*r.find(key),
             fmt::format("{} must be [on, off], two blocks, not {}", r.key_path(key), codes->size()));
}

void read_positive(const table_reader& r, std::string_view key, double& out, bool zero_ok) {
  if (r.read(key, out) && (out < 0 || (!zero_ok && out == 0)))
    r.fail(*r.find(key), fmt::format("{} must be {} 0, not {}", r.key_path(key), zero_ok ? ">=" : ">", out));
}

void read_limits(const table_reader& root, motion_limits& l) {
  const toml::table* t = root.sub_table("limits");
  if (!t) return;
  table_reader r(*t, "limits", root.source(), {"max_feed", "blocks_per_second"});
  read_positive(r, "max_feed", l.max_feed, false);
  read_positive(r, "blocks_per_second", l.blocks_per_second, false);
  if (l.blocks_per_second > 1e5)
    r.fail(*r.find("blocks_per_second"),
           fmt::format("limits.blocks_per_second must be at most 100000, not {}", l.blocks_per_second));
}

// [cycles]: which of the control's own cycles the post writes (docs/machines.md).
void read_spindles(const table_reader& root, std::vector<spindle_def>& out) {
  auto reader = [&](const toml::table& t) {
    return table_reader(
        t, "spindle", root.source(),
        {"name", "cw", "ccw", "stop", "select", "clamp", "max_rpm", "work_offset", "reverse_z", "per_channel",
         "c_on", "c_off", "c_clamp", "c_unclamp", "chuck_open", "chuck_close"});
  };
  for (const toml::table* t : root.tables("spindle")) {
    const table_reader r = reader(*t);
    spindle_def s;
    r.require("name");
    r.read("name", s.name);
    for (const spindle_def& earlier : out)
      if (earlier.name == s.name) r.fail(*r.find("name"), fmt::format("duplicate spindle name '{}'", s.name));
    r.read("cw", s.cw);
    r.read("ccw", s.ccw);
    r.read("stop", s.stop);
    r.read("select", s.select);
    r.read_template("clamp", s.clamp, template_uses::clamp);
    read_positive(r, "max_rpm", s.max_rpm, true);
    r.read_fixed("work_offset", s.work_offset);
    r.read("reverse_z", s.reverse_z);
    r.read("per_channel", s.per_channel);
    read_c_axis(r, s.c_axis);
    r.read_fixed("chuck_open", s.chuck_open);
    r.read_fixed("chuck_close", s.chuck_close);
    out.push_back(std::move(s));
  }
  // Once every spindle is known: no C-axis code is another spindle function's code.
  std::size_t i = 0;
  for (const toml::table* t : root.tables("spindle")) {
    check_c_axis_codes(reader(*t), out[i++].c_axis, out);
  }
}

// The header tells the control the units the words are in: G20 for inch output, and never
// the other one (a control left in G21 would read every inch value as millimetres).
void check_units_code(const table_reader& root, const machine& m, const anchors& at) {
  const bool inch = m.program.output_units == output_unit::inch;
  bool says_inch = false, says_mm = false;
  for (const std::string& block : m.program.header) {
    std::size_t i = 0;
    while ((i = block.find('G', i)) != std::string::npos) {
      const std::size_t end = block.find_first_not_of("0123456789", i + 1);
      const std::string_view word =
          std::string_view(block).substr(i, end == std::string::npos ? end : end - i);
      says_inch = says_inch || word == "G20";
      says_mm = says_mm || word == "G21";
      i = i + 1;
    }
  }
  std::string why;
  if (inch && says_mm)
    why = "program.header writes G21 (millimetres) but program.output_units is inch";
  else if (inch && !says_inch)
    why = "program.output_units = inch needs G20 in program.header";
  else if (!inch && says_inch)
    why = "program.header writes G20 (inches) but program.output_units is mm";
  if (why.empty()) return;
  if (at.program && at.program->get("header")) root.fail(*at.program->get("header"), why);
  root.fail_here(why);
}

// The grip's last move brings the sub spindle onto the part with its chuck open: a rapid there
// crashes the jaws into the part at the first error in the grip position. It must be a feed with
// its own F (G1 or a G31 torque skip), after a rapid to a position short of the part, as the
// Fusion Doosan post's stock transfer writes it (G0 to the feed position, then G1 or G31 P99 to
// the chuck position at the cycle's feed). On a Fanuc control (`g53_rapid`) a G53 block moves
// at rapid traverse whatever the motion mode (Fanuc's G53, machine coordinate selection; the
// Fusion Doosan post's useG53ForXfer: "G53 = in rapid mode with G53, G53.2 = in feed mode (must
// have G53.2 enabled on control)"), so `G1 G53 B.. F..` is a rapid. "" when it is; else what
// is wrong.
std::string grip_approach_problem(const std::vector<std::string>& grip, bool g53_rapid) {
  int motion = -1;  // the G0/G1/G31 in force in the grip (-1: the program's, unknown)
  const std::string* last = nullptr;
  int last_motion = -1;
  bool last_f = false;
  for (const std::string& block : grip) {
    std::string b;
    bool comment = false;  // without comments, each ended at its first ')' as a control ends it
    for (const char c : block) {
      if (c == '(') comment = true;
      if (!comment) b += ascii::upper(c);
      if (c == ')') comment = false;
    }
    if (b.starts_with("IF") || b.starts_with("#") || b.starts_with("WHILE")) continue;  // macro statements
    bool axis = false, f = false, g53 = false, dwell = false;
    for (std::size_t i = 0; i + 1 < b.size(); ++i) {
      const char c = b[i], n = b[i + 1];
      const bool value = ascii::is_digit(n) || n == '-' || n == '+' || n == '.' || n == '#' || n == '[';
      if (c == 'G' && value) {
        std::size_t k = i + 1;
        std::string g;
        while (k < b.size() && (ascii::is_digit(b[k]) || b[k] == '.')) g += b[k++];
        if (g == "0" || g == "00") motion = 0;
        if (g == "1" || g == "01" || g == "31") motion = 1;
        if (g == "53") g53 = true;
        if (g == "4" || g == "04") dwell = true;  // G4 U1.: a time, no move
      }
      if (std::string_view("XYZUVWABC").find(c) != std::string_view::npos && value) axis = true;
      if (c == 'F' && value) f = true;
    }
    if (!axis || dwell) continue;
    last = &block;
    last_motion = g53 && g53_rapid ? 2 : motion;  // one block: the modal G1 stays in force
    last_f = f;
  }
  if (!last) return {};
  if (last_motion == 1 && last_f) return {};
  return fmt::format(
      "transfer.grip brings the sub spindle onto the part with \"{}\", {}: its chuck is open and the part "
      "is there; make the last move a feed with its own F (G1 ... F.. or a G31 torque skip), after a rapid "
      "to a position short of the part",
      *last,
      last_motion == 0   ? "a rapid"
      : last_motion == 1 ? "a feed with no F of its own"
      : last_motion == 2 ? "a rapid on a Fanuc control (G53 moves at rapid traverse whatever the motion "
                           "mode; G53.2 feeds in machine coordinates where the control has it)"
                         : "in the motion the program left in force");
}

void read_transfer(const table_reader& root, machine& m) {
  const toml::table* t = root.sub_table("transfer");
  if (!t) return;
  table_reader r(*t, "transfer", root.source(), {"channel", "grip", "release", "release_after_cutoff"});
  r.require("channel");
  r.read("channel", m.transfer.channel);
  if (m.transfer.channel < 1 || m.transfer.channel > static_cast<int>(m.channels.size()))
    r.fail(*r.find("channel"), fmt::format("transfer.channel {} names no channel (the machine has {})",
                                           m.transfer.channel, m.channels.size()));
  if (!m.spindle("sub"))
    r.fail(*r.find("channel"), "[transfer] needs a [[spindle]] named 'sub' to take the part");
  r.read_fixed("grip", m.transfer.grip);
  if (const std::string why = grip_approach_problem(m.transfer.grip, m.control.starts_with("fanuc"));
      !why.empty())
    r.fail(*r.find("grip"), why);
  r.read_fixed("release", m.transfer.release);
  m.transfer.has_release_after_cutoff = r.read_fixed("release_after_cutoff", m.transfer.release_after_cutoff);
}

// [[tool]] rpm or surface_speed, and direction: the speed a CL without SPINDL cuts at.
void read_tool_speed(const table_reader& r, tool_def& d) {
  double v = 0;
  // A speed no spindle reaches (inf, 1e300) is a typing error: refused here, naming the key.
  constexpr double most = 1e6;
  if (r.read("rpm", v)) {
    if (!(v >= 1 && v <= most))
      r.fail(*r.find("rpm"), fmt::format("tool.rpm must be in 1..{}, not {}", most, v));
    d.rpm = v;
  }
  if (r.read("surface_speed", v)) {
    if (!(v > 0 && v <= most))
      r.fail(*r.find("surface_speed"),
             fmt::format("tool.surface_speed must be in 0..{} (m/min, above 0), not {}", most, v));
    if (d.rpm)
      r.fail(*r.find("surface_speed"),
             fmt::format("tool {}: give rpm or surface_speed, not both (which would the spindle run at?)",
                         d.number));
    d.surface_speed = v;
  }
  std::string direction;
  if (r.read("direction", direction)) {
    if (direction != "cw" && direction != "ccw")
      r.fail(*r.find("direction"), fmt::format("tool.direction must be cw or ccw, not '{}'", direction));
    if (!d.rpm && !d.surface_speed)
      r.fail(*r.find("direction"),
             fmt::format("tool {}: a direction without a speed (rpm or surface_speed)", d.number));
    d.ccw = direction == "ccw";
  }
  if ((d.rpm || d.surface_speed) && !d.spindle)
    r.fail(*r.find(d.rpm ? "rpm" : "surface_speed"),
           fmt::format("tool {}: a speed for a tool marked spindle = false", d.number));
}

void read_tools(const table_reader& root, machine& m) {
  for (const toml::table* t : root.tables("tool")) {
    table_reader r(*t, "tool", root.source(),
                   {"number", "channel", "kind", "name", "length", "diameter", "diameter_offset", "spindle",
                    "rpm", "surface_speed", "direction"});
    tool_def d;
    r.require("number");
    r.read("number", d.number);
    if (d.number < 0) r.fail(*r.find("number"), fmt::format("tool.number must be >= 0, not {}", d.number));
    if (r.read("channel", d.channel) && (d.channel < 1 || d.channel > static_cast<int>(m.channels.size())))
      r.fail(*r.find("channel"), fmt::format("tool.channel {} names no channel (the machine has {})",
                                             d.channel, m.channels.size()));
    r.require("kind");
    r.read("kind", d.kind);
    if (d.kind != "turn" && d.kind != "drill" && d.kind != "mill")
      r.fail(*r.find("kind"), fmt::format("tool.kind must be turn, drill or mill, not '{}'", d.kind));
    double length = 0;
    if (r.read("length", length)) {
      // A tool is at least a millimetre and less than 10 m long (attack 45: 1e-300 posted as a tool
      // of 0 mm, every tilted point 150 mm off).
      if (!(length >= 1 && length < 1e4))
        r.fail(*r.find("length"), fmt::format("tool.length must be >= 1 and < 10000 (mm), not {}", length));
      d.length = length;
    }
    double diameter = 0;
    if (r.read("diameter", diameter)) {
      if (!(diameter > 0))
        r.fail(*r.find("diameter"), fmt::format("tool.diameter must be > 0, not {}", diameter));
      d.diameter = diameter;
    }
    int d_register = 0;
    if (r.read("diameter_offset", d_register)) {
      // D0 is no compensation on a Fanuc control: the cutter would run on the path's centre.
      if (d_register < 1)
        r.fail(*r.find("diameter_offset"),
               fmt::format("tool.diameter_offset must be >= 1, not {}", d_register));
      d.diameter_offset = d_register;
    }
    r.read("spindle", d.spindle);
    read_tool_speed(r, d);
    for (const tool_def& earlier : m.tools)
      if (earlier.number == d.number && earlier.channel == d.channel)
        r.fail(*r.find("number"),
               d.channel ? fmt::format("tool {} of channel {} is listed twice", d.number, d.channel)
                         : fmt::format("tool {} is listed twice", d.number));
    // One name, one tool: a job that starts without a tool call is given the tool by its name.
    if (r.read("name", d.name))
      for (const tool_def& earlier : m.tools)
        if (earlier.channel == d.channel && !earlier.name.empty() &&
            m.tool_named(d.channel, d.name) == &earlier)
          r.fail(*r.find("name"),
                 fmt::format("tool.name '{}' is given to tools {} and {}", d.name, earlier.number, d.number));
    m.tools.push_back(std::move(d));
  }
}

void check_across_tables(const table_reader& root, const machine& m, const anchors& at) {
  if (const std::string why = layout_problem(m, m.layout); !why.empty()) {
    if (at.program) root.fail(*at.program, why);
    root.fail(*at.layout, why);
  }
  // Axes are written with decimals_metric (decimals_inch) places: the control must read them all.
  const bool inch = m.program.output_units == output_unit::inch;
  for (char a : std::string_view("XYZIJKR")) {
    const word_format& f = m.formats[a];
    if (f.decimals < m.program.axis_decimals()) {
      const std::string message =
          fmt::format("format.{} ({}) has fewer decimals than program.{} ({})", a, f.text(),
                      inch ? "decimals_inch" : "decimals_metric", m.program.axis_decimals());
      if (at.format && at.format->get(std::string(1, a)))
        root.fail(*at.format->get(std::string(1, a)), message);
      if (at.format) root.fail(*at.format, message);
      root.fail(*at.program, message);
    }
  }
  check_units_code(root, m, at);
  // O0000 is not a program number; the default must fit the O format.
  const word_format& o = m.formats['O'];
  if (m.program.program_number < 1 || m.program.program_number > o.max_count(0)) {
    const std::string message = fmt::format("program.program_number must be in 1..{} (format.O {}), not {}",
                                            o.max_text(), o.text(), m.program.program_number);
    if (at.program_number) root.fail(*at.program_number, message);
    if (at.format) root.fail(*at.format, message);
    root.fail_here(message);
  }
  // The first N number must be one the control reads (N5: up to 99999).
  const word_format& n = m.formats['N'];
  if (n.whole > 0 && m.program.sequence_start > n.max_count(0)) {
    const std::string message = fmt::format("program.sequence_start must be at most {} (format.N {}), not {}",
                                            n.max_text(), n.text(), m.program.sequence_start);
    if (at.program && at.program->get("sequence_start"))
      root.fail(*at.program->get("sequence_start"), message);
    if (at.format) root.fail(*at.format, message);
    root.fail_here(message);
  }
  // Path numbers are single digits (P12, P123): channel 10 cannot be named.
  if (m.channels.size() >= 10 &&
      (m.waits.partners == partner_style::path_numbers || m.waits.partners == partner_style::others))
    root.fail(*at.partners, fmt::format("waits.partners = path_numbers names channels by one digit each "
                                        "(P12): a machine with {} channels needs binary",
                                        m.channels.size()));
  if (m.channels.size() >= 3 && m.waits.partners == partner_style::none) {
    const std::string message = fmt::format(
        "waits.partners must be path_numbers or binary on a machine with {} channels", m.channels.size());
    if (at.partners) root.fail(*at.partners, message);
    root.fail(*at.waits, message);
  }
  for (const wait_rules::fixed_wait& f : m.waits.fixed)
    if (f.channels.front() < 1 || f.channels.back() > static_cast<int>(m.channels.size()))
      root.fail(*at.waits,
                fmt::format("waits.fixed code {} names channel {}, which this machine does not have", f.code,
                            f.channels.front() < 1 ? f.channels.front() : f.channels.back()));
}

}  // namespace

machine parse_machine(std::string_view toml_text, std::string_view source) {
  // toml++ follows a dotted key (`a.a.a...`) by one recursion a part: 200 000 parts on one line
  // overflowed the stack (issue 38, sixth attack). A line of a machine file is short: the
  // built-ins' longest has 152 bytes, and arrays may span lines.
  constexpr std::size_t longest_line = 4096, largest_file = std::size_t{1} << 20;
  if (toml_text.size() > largest_file)  // the built-ins have 30 KB; a 20 MB file took 2.3 GB
    throw config_error::at(
        source, 1, 1,
        fmt::format("a machine file of {} bytes: at most {} (1 MB)", toml_text.size(), largest_file));
  for (std::size_t at = 0, line = 1; at < toml_text.size(); ++line) {
    const std::size_t end = std::min(toml_text.find('\n', at), toml_text.size());
    if (end - at > longest_line)
      throw config_error::at(
          source, static_cast<long>(line), 1,
          fmt::format("a line of {} bytes: a machine file's lines have at most {}; break a "
                      "long array over several lines",
                      end - at, longest_line));
    at = end + 1;
  }
  toml::table doc;
  try {
    doc = toml::parse(toml_text, source);
  } catch (const toml::parse_error& e) {
    detail::fail_at(source, e.source(), e.description());
  }
  table_reader root(
      doc, "", source,
      {"machine", "channel", "spindle", "waits", "program", "format", "codes", "limits", "cycles", "transfer",
       "tool", "timing", "kinematics", "milling", "interference", "events"});
  machine m;
  m.source = std::string(source);
  anchors at;
  read_machine_table(root, m, at);
  read_waits(root, m.waits, at);
  read_program(root, m.program, at);
  m.formats = default_word_formats(m.control, m.program.output_units == output_unit::inch);
  read_formats(root, m.formats, at);
  read_codes(root, m.codes);
  read_limits(root, m.limits);
  detail::read_cycles(root, m.cycles);
  detail::read_milling(root, m);
  read_spindles(root, m.spindles);
  detail::read_channels(root, m);
  detail::read_timing(root, m);
  read_transfer(root, m);
  read_tools(root, m);
  detail::read_kinematics(root, m);
  detail::read_interference(root, m);
  detail::read_events(root, m);
  check_across_tables(root, m, at);
  detail::check_code_overlaps(root, m);
  return m;
}

machine load_machine(std::string_view name_or_path) {
  return find_machine(name_or_path, {}).def;  // the one reader of machine files
}

std::vector<machine_summary> builtin_machines() {
  std::vector<machine_summary> out;
  for (const builtin_machine_file& f : builtin_machine_files()) {
    machine m = load_machine(f.name);
    out.push_back({m.name, m.description});
  }
  std::sort(out.begin(), out.end(),
            [](const machine_summary& a, const machine_summary& b) { return a.name < b.name; });
  return out;
}

}  // namespace twinpost
