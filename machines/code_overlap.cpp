// The wait-code overlap rule (machines/code_overlap.hpp) and its load-time check of every
// code a machine file names.
#include "machines/code_overlap.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

#include <fmt/format.h>

#include "machines/kinematic_chain.hpp"
#include "machines/toml_reader.hpp"
#include "support/ascii.hpp"

namespace twinpost {

bool is_wait_word(const wait_rules& w, char address, long long code) {
  // A bang wait (!2L1) is its marker and partners first: no plain word is one.
  if (w.syntax == wait_syntax::bang) return false;
  if (address != w.address || code < 0 || code > std::numeric_limits<int>::max()) return false;
  return w.is_any_wait(static_cast<int>(code));
}

std::string wait_range_text(const wait_rules& w) {
  std::string out =
      w.syntax == wait_syntax::bang
          ? fmt::format("{0}<partners>{1}{2}-{0}<partners>{1}{3}", w.marker, w.address, w.first, w.last)
          : fmt::format("{}{}-{}{}", w.address, w.first, w.address, w.last);
  if (w.step != 1) out += fmt::format(" step {}", w.step);
  for (const wait_rules::fixed_wait& f : w.fixed) out += fmt::format(", {}{}", w.address, f.code);
  return out;
}

long long first_wait_word(std::string_view block, const wait_rules& w, char open, char close) {
  std::size_t i = 0;
  while (i < block.size()) {
    const char c = block[i];
    if (c == open || c == '{') {
      const std::size_t e = block.find(c == open ? close : '}', i + 1);
      if (e == std::string_view::npos) return -1;
      i = e + 1;
      continue;
    }
    const bool starts_word = c == w.address && (i == 0 || !ascii::is_upper(block[i - 1]));
    std::size_t j = i + 1;
    while (j < block.size() && ascii::is_digit(block[j])) ++j;
    if (!starts_word || j == i + 1 || (j < block.size() && block[j] == '.')) {
      i = j;
      continue;
    }
    long long code = 0;
    const auto r = std::from_chars(block.data() + i + 1, block.data() + j, code);
    if (r.ec == std::errc() && is_wait_word(w, c, code)) return code;
    i = j;
  }
  return -1;
}

std::string squeeze_blanks(std::string_view text, char open, char close) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    const char end = c == open ? close : c == '{' ? '}' : '\0';
    if (end != '\0') {  // a comment or a placeholder, as it stands
      const std::size_t e = end == '\n' ? std::string_view::npos : text.find(end, i + 1);
      const std::size_t stop = e == std::string_view::npos ? text.size() : e + 1;
      out.append(text.substr(i, stop - i));
      i = stop - 1;
      continue;
    }
    if (c != ' ' && c != '\t') out += c;
  }
  return out;
}

// The words of `text` as a control reads them: a letter and its number (blanks dropped,
// comments and placeholders skipped); a letter followed by no number gets NaN.
std::vector<std::pair<char, double>> words_of(std::string_view text, char open, char close) {
  std::vector<std::pair<char, double>> out;
  const std::string t = squeeze_blanks(text, open, close);
  for (std::size_t i = 0; i < t.size(); ++i) {
    const char c = t[i];
    if (c == open || c == '{') {
      const std::size_t e =
          c == open && close == '\n' ? std::string::npos : t.find(c == open ? close : '}', i + 1);
      if (e == std::string::npos) break;
      i = e;
      continue;
    }
    if (!ascii::is_letter(c)) continue;
    std::size_t j = i + 1;
    while (j < t.size() && (ascii::is_digit(t[j]) || t[j] == '.' || t[j] == '-' || t[j] == '+')) ++j;
    double v = std::numeric_limits<double>::quiet_NaN();
    if (j > i + 1) v = std::strtod(std::string(t.substr(i + 1, j - i - 1)).c_str(), nullptr);
    out.push_back({static_cast<char>(ascii::is_upper(c) ? c : c - 'a' + 'A'), v});
    i = j - 1;
  }
  return out;
}

// The last of the words G90 and G91 in `text` (not G90.1/G91.1, the arc centre's modes), or 0.
int distance_mode(std::string_view text, char open, char close) {
  int mode = 0;
  for (const auto& [letter, v] : words_of(text, open, close))
    if (letter == 'G' && (v == 90 || v == 91)) mode = static_cast<int>(v);
  return mode;
}

bool cancels_length_offset(std::string_view block, char open, char close) {
  for (const auto& [letter, v] : words_of(block, open, close))
    if ((letter == 'G' && v == 49) || ((letter == 'D' || letter == 'H') && v == 0)) return true;
  return false;
}

const char* reserved_m_code(long long code) {
  switch (code) {
    case 0: return "the program stop";
    case 1: return "the optional stop";
    case 2:
    case 30: return "the program's end";
    case 6: return "the tool change";
    case 98:
    case 198: return "a subprogram call";
    case 99: return "a subprogram's return (a main program's jump back to its start)";
    default: return code < 0 ? "no M code (below 0)" : nullptr;
  }
}

std::string code_text_fault(std::string_view text, char open, char close, code_use use) {
  const bool line_comment = close == '\n';
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '{') {  // a placeholder
      const std::size_t e = text.find('}', i + 1);
      if (e == std::string_view::npos) return {};  // the template's own check names it
      i = e;
      continue;
    }
    if (c == open) {
      if (line_comment) {
        if (use == code_use::part)
          return fmt::format(
              "'{}' makes a comment of the rest of the block: the words twinpost writes after this code "
              "would not be read (a comment to the end of the line belongs in a block of its own)",
              open);
        return {};
      }
      const std::size_t e = text.find(close, i + 1);
      if (e == std::string_view::npos)
        return fmt::format("'{}' opens a comment that no '{}' closes: the words after it would not be read",
                           open, close);
      i = e;
      continue;
    }
    // A ( is a comment's start on every ISO control, whatever comment the post writes.
    if (c == '(' && text.find(')', i + 1) == std::string_view::npos)
      return "'(' opens a comment on the control that no ')' closes: the words after it would not be read";
    // M2, M30, M99 (and M02, M030 ...): the program's end, or a jump back to its start.
    if ((c == 'M' || c == 'm') && (i == 0 || !ascii::is_letter(text[i - 1])) && use != code_use::end) {
      std::size_t j = i + 1;
      while (j < text.size() && ascii::is_digit(text[j])) ++j;
      long long code = -1;
      // M2=70 (Sinumerik: spindle 2's M70) is an address extension, no M2.
      if (j > i + 1 && !(j < text.size() && (text[j] == '.' || text[j] == '=')))
        std::from_chars(text.data() + i + 1, text.data() + j, code);
      if (code == 2 || code == 30 || code == 99)
        return fmt::format(
            "M{} ends the program (M99 goes back to its start) there: only program.end_code and the footer "
            "may end it",
            code);
    }
  }
  return {};
}

namespace detail {

namespace {

// One code of the file that is a wait code: where to report it and what to say.
struct finding {
  const toml::node* at;
  std::string message;
};

class overlap_finder {
 public:
  overlap_finder(const machine& m, const toml::node& waits) : m_(m), waits_(waits) {}

  // A block (fixed or a template) stored as `text`; `node` is its value in the file, or
  // null when the key is absent and `text` is the default, reported at `table`.
  // Words are read as a control reads them, blanks inside them dropped (a Fanuc reads `M 30` as
  // M30, attack 45).
  void block(std::string_view what, std::string_view text, const toml::node* node, const toml::node* table,
             code_use use = code_use::part, bool mode_checked = true) {
    const char open = m_.program.comment_open, close = m_.program.comment_close;
    const std::string words = squeeze_blanks(text, open, close);
    const long long code = first_wait_word(words, m_.waits, open, close);
    if (code >= 0) add(what, code, node, table);
    std::string fault = code_text_fault(words, open, close, use);
    if (fault.empty() && mode_checked && use != code_use::end && distance_mode(words, open, close) == 91)
      fault =
          "it leaves G91 (incremental) in force, and the post writes every move after it as absolute "
          "positions: end it with G90";
    if (!fault.empty()) found.push_back({at(node, table), fmt::format("{} \"{}\": {}", what, text, fault)});
  }

  // The array of blocks `key` of `table`, stored as `texts`: the mode they leave is the last's.
  void blocks(std::string_view what, const std::vector<std::string>& texts, const toml::table* table,
              std::string_view key, code_use use = code_use::part) {
    const toml::array* values = table && table->get(key) ? table->get(key)->as_array() : nullptr;
    int mode = 0;
    for (std::size_t i = 0; i < texts.size(); ++i) {
      block(what, texts[i], values ? values->get(i) : nullptr, table, use, false);
      if (const int m = distance_mode(texts[i], m_.program.comment_open, m_.program.comment_close)) mode = m;
    }
    if (use != code_use::end && mode == 91)
      found.push_back(
          {at(values, table),
           fmt::format("{}: its blocks leave G91 (incremental) in force, and the post writes every "
                       "move after them as absolute positions: end them with G90",
                       what)});
  }

  // An M code given as a number (spindle codes).
  void m_code(std::string_view what, int code, const toml::node* node, const toml::node* table) {
    if (is_wait_word(m_.waits, 'M', code)) add(what, code, node, table);
    if (const char* is = reserved_m_code(code))
      found.push_back({at(node, table), fmt::format("{} M{} is {}, no spindle code", what, code, is)});
  }

  std::vector<finding> found;

 private:
  void add(std::string_view what, long long code, const toml::node* node, const toml::node* table) {
    found.push_back(
        {node    ? node
         : table ? table
                 : &waits_,
         fmt::format("{} {}{}{} {}; a program could not tell it from a wait", what, m_.waits.address, code,
                     node ? "" : " (the default)",
                     m_.waits.fixed_wait_of(static_cast<int>(code))
                         ? std::string("is a fixed wait ([[waits.fixed]])")
                         : fmt::format("lies in the wait range {} ([waits])", wait_range_text(m_.waits)))});
  }

  const toml::node* at(const toml::node* node, const toml::node* table) const {
    return node ? node : table ? table : &waits_;
  }

  const machine& m_;
  const toml::node& waits_;
};

const toml::node* key_of(const toml::table* t, std::string_view key) { return t ? t->get(key) : nullptr; }

void program_codes(overlap_finder& f, const program_format& p, const toml::table* t) {
  f.block("program.program_line", p.program_line, key_of(t, "program_line"), t, code_use::line);
  f.blocks("program.header", p.header, t, "header", code_use::line);
  f.blocks("program.footer", p.footer, t, "footer", code_use::end);
  f.block("program.end_code", p.end_code, key_of(t, "end_code"), t, code_use::end);
  f.block("program.section_marker", p.section_marker, key_of(t, "section_marker"), t, code_use::line);
}

void control_codes_of(overlap_finder& f, const control_codes& c, const toml::table* t) {
  const std::pair<std::string_view, const std::string*> fixed[] = {
      {"css", &c.css},
      {"rpm", &c.rpm},
      {"feed_per_rev", &c.feed_per_rev},
      {"feed_per_min", &c.feed_per_min},
      {"dwell", &c.dwell},
      {"coolant_off", &c.coolant_off},
      {"balance_on", &c.balance_on},
      {"balance_off", &c.balance_off},
      {"spindle_sync_on", &c.spindle_sync_on},
      {"spindle_sync_off", &c.spindle_sync_off},
      {"program_stop", &c.program_stop},
      {"optional_stop", &c.optional_stop},
  };
  for (const auto& [key, text] : fixed) f.block(fmt::format("codes.{}", key), *text, key_of(t, key), t);
  f.blocks("codes.coolant_on", c.coolant_on, t, "coolant_on");
  f.blocks("codes.home", c.home, t, "home");
  f.blocks("codes.coolant_mist", c.coolant_mist, t, "coolant_mist");
  f.blocks("codes.coolant_through", c.coolant_through, t, "coolant_through");
  f.blocks("codes.coolant_air", c.coolant_air, t, "coolant_air");
}

void cycle_codes(overlap_finder& f, const cycle_rules& c, const toml::table* t) {
  for (const auto& [key, field] : cycle_rules::code_keys)
    f.block(fmt::format("cycles.{}", key), c.*field, key_of(t, key), t);
}

void spindle_codes(overlap_finder& f, const spindle_def& s, const toml::table& t) {
  const std::string what = fmt::format("spindle '{}':", s.name);
  f.m_code(what + " cw", s.cw, t.get("cw"), &t);
  f.m_code(what + " ccw", s.ccw, t.get("ccw"), &t);
  f.m_code(what + " stop", s.stop, t.get("stop"), &t);
  if (s.select) f.m_code(what + " select", *s.select, t.get("select"), &t);
  f.block(what + " clamp", s.clamp, t.get("clamp"), &t);
  f.block(what + " work_offset", s.work_offset, t.get("work_offset"), &t);
  f.blocks(what + " c_on", s.c_axis.on, &t, "c_on");
  f.blocks(what + " c_off", s.c_axis.off, &t, "c_off");
  f.block(what + " c_clamp", s.c_axis.clamp, t.get("c_clamp"), &t);
  f.block(what + " c_unclamp", s.c_axis.unclamp, t.get("c_unclamp"), &t);
  f.block(what + " chuck_open", s.chuck_open, t.get("chuck_open"), &t);
  f.block(what + " chuck_close", s.chuck_close, t.get("chuck_close"), &t);
}

// The file's [[channel]] table of channel `number` (channels are sorted by number).
const toml::table* channel_table(const table_reader& root, int number) {
  for (const toml::table* t : root.tables("channel"))
    if (const toml::node* n = t->get("number"); n && n->as_integer() && n->as_integer()->get() == number)
      return t;
  return nullptr;
}

bool before(const toml::node& a, const toml::node& b) {
  const toml::source_position pa = a.source().begin, pb = b.source().begin;
  return pa.line != pb.line ? pa.line < pb.line : pa.column < pb.column;
}

}  // namespace

void check_code_overlaps(const table_reader& root, const machine& m) {
  const toml::table* waits = root.sub_table("waits");
  overlap_finder f(m, waits ? static_cast<const toml::node&>(*waits) : root.table());
  program_codes(f, m.program, root.sub_table("program"));
  control_codes_of(f, m.codes, root.sub_table("codes"));
  cycle_codes(f, m.cycles, root.sub_table("cycles"));
  const std::vector<const toml::table*> spindles = root.tables("spindle");
  for (std::size_t i = 0; i < m.spindles.size() && i < spindles.size(); ++i)
    spindle_codes(f, m.spindles[i], *spindles[i]);
  f.blocks("transfer.grip", m.transfer.grip, root.sub_table("transfer"), "grip");
  f.blocks("transfer.release", m.transfer.release, root.sub_table("transfer"), "release");
  f.blocks("transfer.release_after_cutoff", m.transfer.release_after_cutoff, root.sub_table("transfer"),
           "release_after_cutoff");
  for (const channel_def& c : m.channels) {
    const toml::table* t = channel_table(root, c.number);
    f.block(fmt::format("channel {}: tool_call", c.number), c.tool_call, key_of(t, "tool_call"), t);
    if (!c.offset_call.empty())
      f.block(fmt::format("channel {}: offset_call", c.number), c.offset_call, key_of(t, "offset_call"), t);
    if (!c.length_offset.empty())
      f.block(fmt::format("channel {}: length_offset", c.number), c.length_offset, key_of(t, "length_offset"),
              t);
    if (!c.home.empty()) f.blocks(fmt::format("channel {}: home", c.number), c.home, t, "home");
    const toml::table* h = t && t->get("head_index") ? t->get("head_index")->as_table() : nullptr;
    for (const auto& [key, block] : {std::pair{"unclamp", &c.head_index.unclamp},
                                     {"move", &c.head_index.move},
                                     {"clamp", &c.head_index.clamp}})
      f.block(fmt::format("channel {}: head_index.{}", c.number, key), *block, key_of(h, key), h);
  }
  const toml::table* g = root.sub_table("milling");
  for (const auto& [key, blocks] : {std::pair{"radius_input", &m.milling.radius_input},
                                    {"diameter_input", &m.milling.diameter_input},
                                    {"polar_on", &m.milling.polar_on},
                                    {"polar_off", &m.milling.polar_off},
                                    {"radial_frame_on", &m.milling.radial_frame_on},
                                    {"radial_frame_off", &m.milling.radial_frame_off},
                                    {"cylindrical_on", &m.milling.cylindrical_on},
                                    {"cylindrical_off", &m.milling.cylindrical_off}})
    f.blocks(fmt::format("milling.{}", key), *blocks, g, key);
  const std::vector<const toml::table*> chains = root.tables("kinematics");
  for (std::size_t i = 0; i < m.kinematics.size() && i < chains.size(); ++i) {
    const kinematic_chain& c = m.kinematics[i];
    for (const auto& [key, code] : {std::pair{"tool_tip_on", &c.tool_tip_on},
                                    {"tool_tip_off", &c.tool_tip_off},
                                    {"length_on", &c.length_on},
                                    {"inverse_time", &c.inverse_time},
                                    {"plane", &c.plane},
                                    {"plane_index", &c.plane_index},
                                    {"plane_off", &c.plane_off}})
      f.block(fmt::format("kinematics.{}", key), *code, key_of(chains[i], key), chains[i]);
  }
  // What the chains' codes do: inverse time must be ended by a feed-per-minute code and must not
  // be one, and a joints chain's length code is a length offset along Z (attack 45: feed_per_min
  // = "" left G93 on, inverse_time = "G94" read 1/min values as mm/min, length_on = "G49" ran
  // the tip a tool length low).
  const char open = m.program.comment_open, close = m.program.comment_close;
  const auto g_in = [&](const std::string& code, std::initializer_list<double> gs) -> double {
    for (const auto& [letter, v] : words_of(code, open, close))
      if (letter == 'G')
        for (const double g : gs)
          if (std::abs(v - g) < 1e-9) return g;
    return -1;
  };
  const auto m_in = [&](const std::string& code) {
    const auto w = words_of(code, open, close);
    return std::any_of(w.begin(), w.end(), [](const auto& x) { return x.first == 'M'; });
  };
  const toml::table* codes = root.sub_table("codes");
  for (std::size_t i = 0; i < m.kinematics.size() && i < chains.size(); ++i) {
    const kinematic_chain& c = m.kinematics[i];
    if (!solves_joints(c)) continue;
    const toml::node* where =
        key_of(chains[i], "inverse_time") ? key_of(chains[i], "inverse_time") : chains[i];
    if (const double g = g_in(c.inverse_time, {0, 1, 2, 3, 94, 95});
        g >= 0 || m_in(c.inverse_time) || g_in(c.inverse_time, {93}) < 0)
      f.found.push_back(
          {where, fmt::format("kinematics.inverse_time \"{}\" holds {}: it must be the inverse-time "
                              "feed code alone (G93), the F of the moves after it 1/min",
                              c.inverse_time,
                              g >= 0                 ? fmt::format("G{}", g)
                              : m_in(c.inverse_time) ? std::string("an M code")
                                                     : std::string("no G93"))});
    const std::string& per_min = m.codes.feed_per_min;
    if (per_min.empty() || g_in(per_min, {93}) >= 0 || g_in(per_min, {94, 98}) < 0 ||
        (!c.inverse_time.empty() &&
         squeeze_blanks(per_min, open, close) == squeeze_blanks(c.inverse_time, open, close)))
      f.found.push_back({key_of(codes, "feed_per_min") ? key_of(codes, "feed_per_min") : where,
                         fmt::format("codes.feed_per_min \"{}\" must end inverse time ({}): the feed moves "
                                     "after a turning move would keep reading F as 1/min",
                                     per_min, c.inverse_time)});
    // The post homes in the middle of a tool (a 3+2 plane opened or closed, a head turned below
    // the CAM's clearance, GOHOME): home blocks that cancel the length offset where the post has
    // no code to give it back (the control's own offset, length_on = "") leave the tip a tool
    // length low after them (verify 46, attacks 47 and 48).
    if (const std::string& on = c.output == multiaxis_output::joints ? c.length_on : c.tool_tip_on;
        c.output != multiaxis_output::pivot && on.empty())
      for (const std::string& h : m.home(c.channel))
        if (cancels_length_offset(h, open, close)) {
          f.found.push_back(
              {key_of(codes, "home") ? key_of(codes, "home") : chains[i],
               fmt::format(
                   "codes.home \"{}\" cancels the tool length offset, and kinematics.{} is \"\": the post "
                   "goes home in the middle of a tool (a 3+2 plane, a head turned low, GOHOME) and has "
                   "no code to give the offset back; give kinematics.{} (G43), or home blocks that "
                   "keep the offset",
                   h, c.output == multiaxis_output::joints ? "length_on" : "tool_tip_on",
                   c.output == multiaxis_output::joints ? "length_on" : "tool_tip_on")});
          break;
        }
    if (c.output == multiaxis_output::joints && !c.length_on.empty())
      if (const double g = g_in(c.length_on, {49, 44, 43.4, 43.5});
          g >= 0 || m_in(c.length_on) || g_in(c.length_on, {43}) < 0)
        f.found.push_back(
            {key_of(chains[i], "length_on") ? key_of(chains[i], "length_on") : chains[i],
             fmt::format("kinematics.length_on \"{}\" under joints output holds {}: the joints "
                         "are solved for the tool's length made up along Z by a length offset (G43)",
                         c.length_on,
                         g >= 0              ? fmt::format("G{}", g)
                         : m_in(c.length_on) ? std::string("an M code")
                                             : std::string("no G43"))});
  }
  // A cycle code that is a motion code: the control would move to the hole's bottom as the code
  // says (attack 45: drill_code = "G0" rapided to the bottom).
  const toml::table* cycles = root.sub_table("cycles");
  for (const auto& [key, field] : cycle_rules::code_keys)
    if (const double g = g_in(m.cycles.*field, {0, 1, 2, 3}); g >= 0)
      f.found.push_back({key_of(cycles, key) ? key_of(cycles, key) : &root.table(),
                         fmt::format("cycles.{} \"{}\" holds G{}, a motion code: the hole's words would move "
                                     "the tool to its bottom at that motion",
                                     key, m.cycles.*field, g)});
  // A coolant code that is an indexing head's clamp or unclamp code: the post writes it at every
  // index, and the control turns the coolant on or off there (attack 71 F6: coolant_through =
  // M108, the Integrex's unclamp, sprayed at every head index, and the emulator warned of
  // coolant before the index at each one).
  for (const channel_def& c : m.channels)
    for (const auto& [key, block] :
         {std::pair{"unclamp", &c.head_index.unclamp}, {"clamp", &c.head_index.clamp}})
      for (const auto& [letter, v] : words_of(*block, open, close)) {
        if (letter != 'M') continue;
        std::vector<std::pair<std::string, const std::string*>> coolant = {
            {"coolant_off", &m.codes.coolant_off}};
        for (const std::string& on : m.codes.coolant_on) coolant.emplace_back("coolant_on", &on);
        for (const auto& [kind, pair] : {std::pair{"coolant_mist", &m.codes.coolant_mist},
                                         {"coolant_through", &m.codes.coolant_through},
                                         {"coolant_air", &m.codes.coolant_air}})
          for (const std::string& code : *pair) coolant.emplace_back(kind, &code);
        for (const auto& [kind, code] : coolant)
          for (const auto& [cl, cv] : words_of(*code, open, close))
            if (cl == 'M' && std::abs(cv - v) < 1e-9)
              f.found.push_back(
                  {key_of(codes, kind) ? key_of(codes, kind) : &root.table(),
                   fmt::format("codes.{} \"{}\" holds M{}, channel {}'s head_index.{} code: the post writes "
                               "it at every index of the head, where the control would turn the coolant {} "
                               "too; give the coolant a code of its own",
                               kind, *code, v, c.number, key,
                               kind == std::string("coolant_off") ? "off" : "on")});
      }
  // A wait range over the codes every control gives a meaning of its own (M30 taken for a wait
  // would end the program at the meeting).
  if (m.waits.address == 'M' && m.waits.syntax != wait_syntax::bang)
    for (const long long code : {0, 1, 2, 6, 30, 98, 99})
      if (m.waits.is_any_wait(static_cast<int>(code)))
        f.found.push_back(
            {waits ? static_cast<const toml::node*>(waits) : &root.table(),
             fmt::format("the waits take M{}, which is {}: a wait code must have no other meaning", code,
                         reserved_m_code(code))});
  // The first in the file, as a reader goes through it.
  const finding* first = nullptr;
  for (const finding& x : f.found)
    if (!first || before(*x.at, *first->at)) first = &x;
  if (first) fail_at(root.source(), first->at->source(), first->message);
}

}  // namespace detail

}  // namespace twinpost
