// channel_writer: the gate every user block passes before it is written, whoever wrote it (an
// [events] template, post.emit, a block on_block gave back; docs/customising.md and
// docs/scripting.md, "What a script cannot do"). The post's own words are held to the
// control's formats and the axis travel as it writes them; a user block is text, so its words
// are read here, as a control that skips blanks would read them:
// - every word within the control's format (block_fits);
// - no blank inside a word: `M1 00` is M100, a wait, to a control that skips blanks;
// - an X within the channel's travel, in whatever form the control reads one: X+9000.,
//   U9000. (incremental X on a lathe), G91 X, and no X the post cannot read (X#100, X[...]);
// - no change of the coordinate system under the post's positions (G10, G50, G52, G92 with an
//   axis word);
// - no program number (O2000, :2000): a control that loads the file starts another program.
#include <algorithm>
#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "machines/code_overlap.hpp"
#include "machines/macro_variables.hpp"
#include "machining/channel_writer.hpp"
#include "machining/user_block_form.hpp"
#include "support/ascii.hpp"

namespace twinpost {

namespace {

// The G codes of block `b` outside comments, as numbers the way a control reads them: G92.0 is
// 92, G054.1 is 54.1.
template <class F>
void each_g(std::string_view b, const program_format& f, F&& on_g) {
  int bracket = 0;  // a G inside [...] is an expression's letter or text to print, no G code
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b[i] == f.comment_open) {
      if ((i = b.find(f.comment_close, i + 1)) == std::string_view::npos) return;
      continue;
    }
    if (b[i] == '[') ++bracket;
    if (b[i] == ']' && bracket > 0) --bracket;
    if (bracket > 0) continue;
    if (b[i] != 'G') continue;
    double g = 0;
    const auto r = std::from_chars(b.data() + i + 1, b.data() + b.size(), g, std::chars_format::fixed);
    if (r.ec == std::errc() && g >= 0) on_g(g);
  }
}

bool is(double g, double code) { return std::abs(g - code) < 1e-9; }

bool is_axis_letter(char c) {  // H: a lathe's incremental C
  return c == 'X' || c == 'Y' || c == 'Z' || c == 'U' || c == 'V' || c == 'W' || c == 'A' || c == 'B' ||
         c == 'C' || c == 'H';
}

// Whether block `b` may have the word `letter` with one of `values` (L2, L20 of G10): a value
// the post cannot read (L#1, L[2]) may be one of them.
bool has_word(std::string_view b, char letter, std::initializer_list<int> values) {
  for (std::size_t i = 0; i + 1 < b.size(); ++i) {
    if (b[i] != letter) continue;
    std::size_t j = i + 1;
    if (b[j] == '+') ++j;
    if (j < b.size() && (b[j] == '#' || b[j] == '[')) return true;
    double v = 0;
    const auto r = std::from_chars(b.data() + j, b.data() + b.size(), v, std::chars_format::fixed);
    if (r.ec != std::errc()) continue;
    for (const int want : values)
      if (v == static_cast<double>(want)) return true;
  }
  return false;
}

// A Fanuc custom macro output statement (DPRNT, BPRNT, POPEN, PCLOS), after an optional block
// delete and sequence number, and nothing after it but blanks: its letters are text to print
// (`DPRNT[X#5041[44]]`). Words after the statement (`DPRNT[A] G0 X9000.`, `POPEN G55`) are read
// like any block's, as are other macro statements (IF, WHILE, an assignment): `IF [..] THEN G0
// X9000.` moves.
bool print_statement(std::string_view b) {
  std::size_t i = 0;
  if (i < b.size() && b[i] == '/') ++i;
  while (i < b.size() && b[i] == ' ') ++i;
  if (i < b.size() && b[i] == 'N') {
    ++i;
    while (i < b.size() && ascii::is_digit(b[i])) ++i;
    while (i < b.size() && b[i] == ' ') ++i;
  }
  const std::string_view rest = b.substr(i);
  const auto blank_after = [&](std::size_t at) {
    return rest.find_first_not_of(' ', at) == std::string_view::npos;
  };
  for (const std::string_view k : {"popen", "pclos"})
    if (rest.starts_with(k)) return blank_after(k.size());
  for (const std::string_view k : {"dprnt [", "bprnt ["}) {
    if (!rest.starts_with(k)) continue;
    int depth = 0;
    for (std::size_t j = k.size() - 1; j < rest.size(); ++j) {
      if (rest[j] == '[') ++depth;
      if (rest[j] == ']' && --depth == 0) return blank_after(j + 1);
    }
    return false;
  }
  return false;
}

// Block `b` with its comments taken out and its letters in upper case (`g55` is G55; the checker
// reads lower case too, docs/checker.md); blanks kept.
std::string without_comments(std::string_view b, const program_format& f) {
  std::string out;
  out.reserve(b.size());
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b[i] == f.comment_open && f.comment_close != '\n') {
      const std::size_t close = b.find(f.comment_close, i + 1);
      if (close == std::string_view::npos) break;
      i = close;
      continue;
    }
    if (b[i] == f.comment_open) break;  // a comment to the end of the line (`;`)
    out += ascii::upper(b[i]);
  }
  return out;
}

// The macro statements' keywords (Fanuc custom macro B): outside [...], a control reads them
// whatever follows, blanks or not (`IF[#1EQ0]THENG50X100.` is `IF [..] THEN G50 X100.`).
// `next`: what must follow for the letters to be the keyword ('[' after IF, a digit after DO),
// 0 for anything.
// After an assignment's '=' outside [...], the operators and functions of its expression too
// (`#1=#2 XOR #3`, `#1=SQRT[#2]`).
constexpr std::string_view expression_words[] = {
    "XOR",  "AND",  "OR",   "MOD", "EQ",  "NE",  "GT",    "LT",  "GE",  "LE", "SIN", "COS", "TAN", "ASIN",
    "ACOS", "ATAN", "SQRT", "ABS", "BIN", "BCD", "ROUND", "FIX", "FUP", "LN", "EXP", "POW", "ADP",
};

constexpr std::pair<std::string_view, char> keywords[] = {
    {"IF", '['},  {"WHILE", '['}, {"THEN", 0},    {"GOTO", 0},  {"DO", '0'},
    {"END", '0'}, {"DPRNT", '['}, {"BPRNT", '['}, {"POPEN", 0}, {"PCLOS", 0},
};

// Block `b` as a control that skips blanks and comments reads it: upper case, no comments, no
// blanks, each keyword in lower case with a blank on each side. Every upper-case letter outside
// [...] is then an address (`G0ZX9000.` has the word X9000.), as a control reads it. `glued`:
// a letter outside [...] follows another letter with no blank between them (`PCLOSG20`, `XG20`,
// `UM100`), other than inside a keyword: the post's other readers (the modes it restores, the
// waits it counts, the checker) skip a letter after a letter.
std::string control_reading(std::string_view b, const program_format& f, bool& glued) {
  glued = false;
  const std::string flat = without_comments(b, f);
  std::string out;
  out.reserve(flat.size() + 8);
  int bracket = 0;
  bool assignment = false;  // a '=' outside [...] was read
  for (std::size_t i = 0; i < flat.size(); ++i) {
    const char c = flat[i];
    if (c == ' ') continue;
    if (c == '[') ++bracket;
    if (c == ']' && bracket > 0) --bracket;
    if (c == '=' && bracket == 0) assignment = true;
    if (bracket == 0 && ascii::is_upper(c) && assignment) {
      const auto word = std::find_if(std::begin(expression_words), std::end(expression_words),
                                     [&](std::string_view k) { return flat.compare(i, k.size(), k) == 0; });
      if (word != std::end(expression_words)) {
        out += ' ';
        for (const char kc : *word) out += static_cast<char>(kc - 'A' + 'a');
        out += ' ';
        i += word->size() - 1;
        continue;
      }
    }
    if (bracket == 0 && ascii::is_upper(c)) {
      // (An axis name list, the Mazak `G17 XC`: axis letters with no value after them.)
      const auto axis = [](char a) {
        return std::string_view("XYZUVWABC").find(a) != std::string_view::npos;
      };
      const char after = i + 1 < flat.size() ? flat[i + 1] : ' ';
      const bool name_list = axis(c) && i > 0 && axis(flat[i - 1]) && !ascii::is_digit(after) &&
                             after != '.' && after != '-' && after != '+' && after != '#' && after != '[';
      if (i > 0 && ascii::is_letter(flat[i - 1]) && !name_list) glued = true;
      bool matched = false;
      for (const auto& [k, next] : keywords) {
        std::size_t j = i, n = 0;  // the keyword's letters, blanks between them skipped
        while (n < k.size() && j < flat.size()) {
          if (flat[j] == ' ') {
            ++j;
            continue;
          }
          if (flat[j] != k[n]) break;
          ++j, ++n;
        }
        if (n < k.size()) continue;
        std::size_t after = j;
        while (after < flat.size() && flat[after] == ' ') ++after;
        const char a = after < flat.size() ? flat[after] : '\0';
        if ((next == '[' && a != '[') || (next == '0' && !ascii::is_digit(a))) continue;
        out += ' ';
        for (const char kc : k) out += static_cast<char>(kc - 'A' + 'a');
        out += ' ';
        i = j - 1;
        matched = true;
        break;
      }
      if (matched) continue;
    }
    out += c;
  }
  return out;
}

// The first comment of `b` that stands inside a word (`G(C)55`, `X(C)9000.`, `M1(C)00`, `G (C)
// 55`, `G(C)(D)55`): a control that skips comments and blanks reads the word across it. npos:
// none.
std::size_t comment_inside_word(std::string_view b, const program_format& f) {
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b[i] != f.comment_open || f.comment_close == '\n') continue;
    const std::size_t close = b.find(f.comment_close, i + 1);
    if (close == std::string_view::npos) return std::string_view::npos;
    // The characters either side, past blanks and other comments.
    char before = ' ';
    for (std::size_t p = i; p > 0;) {
      const char c = b[--p];
      if (c == ' ') continue;
      if (c == f.comment_close) {
        const std::size_t open = b.rfind(f.comment_open, p);
        if (open == std::string_view::npos) break;
        p = open;
        continue;
      }
      before = c;
      break;
    }
    char after = ' ';
    for (std::size_t q = close + 1; q < b.size();) {
      const char c = b[q];
      if (c == ' ') {
        ++q;
        continue;
      }
      if (c == f.comment_open) {
        const std::size_t end = b.find(f.comment_close, q + 1);
        if (end == std::string_view::npos) break;
        q = end + 1;
        continue;
      }
      after = c;
      break;
    }

    if ((ascii::is_letter(before) || ascii::is_digit(before) || before == '.' || before == '-' ||
         before == '+') &&
        (ascii::is_digit(after) || after == '.' || after == '-' || after == '+' || after == '#' ||
         after == '['))
      return i;
    i = close;
  }
  return std::string_view::npos;
}

// The system variables of the work offsets and the external shift (Fanuc #5201-#5335 lathe and
// mill, #7001-#7948 G54.1, #14001-#19988 more of them): a write moves every later position,
// as G10 L2 does.
// #2500-#2806: the same offsets in the mills' older numbering (#2501 G54 X, #2601 Y, #2701 Z,
// #2801 the fourth axis).
bool work_offset_variable(int n) {
  return (n >= 2500 && n <= 2806) || (n >= 5000 && n <= 5999) || (n >= 7000 && n <= 7999) ||
         (n >= 14000 && n <= 19999);
}

// The system variables a user block may not write, with what they hold (Fanuc custom macro B;
// the eleventh round wrote each of them): the tool offsets (#2001-#2999 on a lathe's and the
// older mills' numbering, #10001-#13999 the larger sets; a geometry or wear value off by any
// amount moves every later cut of that tool, and the control keeps it for the next job), the
// outputs to the machine's logic (#1100-#1199), and the settings that take feed hold, the feed
// override and single block away from the operator (#3003, #3004). nullptr: none of them.
const char* control_variable(int n) {
  if ((n >= 2000 && n <= 2999) || (n >= 10000 && n <= 13999))
    return "a tool offset (#2001-#2999, #10001-#13999): every later cut of that tool would be off by it, and "
           "the control keeps it for the next job";
  if (n >= 200000 && n <= 299999)
    return "a tool offset of a larger offset table (#200001-, a 30i's; UNVERIFIED range): every later cut of "
           "that tool would be off by it";
  if (n >= 1100 && n <= 1199) return "an output to the machine's own logic (#1100-#1199)";
  if (n == 3003 || n == 3004)
    return "a control setting that takes single block (#3003) or feed hold and the feed override (#3004) "
           "away from the operator";
  if (n == 3005) return "the control's settings (#3005: among them inch input and the mirror image)";
  return nullptr;
}

}  // namespace

std::vector<std::string> channel_writer::frame_words(std::string_view b) const {
  // The words as a control reads them (upper case, no comments or blanks): each from its
  // address to the next; a G or M code by its number (G00 is G0).
  bool glued = false;
  const std::string r = control_reading(b, m_.program, glued);
  std::vector<std::string> out;
  for (std::size_t i = 0; i < r.size();) {
    if (!ascii::is_upper(r[i])) {
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    while (j < r.size() && !ascii::is_upper(r[j]) && r[j] != ' ') ++j;
    std::string w = r.substr(i, j - i);
    if ((w[0] == 'G' || w[0] == 'M') && w.size() > 1) {
      double v = 0;
      const auto [end, ec] = std::from_chars(w.data() + 1, w.data() + w.size(), v, std::chars_format::fixed);
      if (ec == std::errc() && end == w.data() + w.size()) w = fmt::format("{}{:g}", w[0], v);
    }
    out.push_back(std::move(w));
    i = j;
  }
  return out;
}

std::string channel_writer::frame_words_lost(std::string_view block, std::string_view reply,
                                             bool& kept) const {
  kept = false;
  std::vector<std::string> more = frame_words(reply);
  for (const std::string& w : frame_words(block)) {
    auto at = std::find(more.begin(), more.end(), w);
    if (at == more.end() && w == "G28") at = std::find(more.begin(), more.end(), "G30");  // the shop's G30
    if (at == more.end()) return fmt::format("the word {}", w);
    more.erase(at);
  }
  kept = std::all_of(more.begin(), more.end(), [](const std::string& w) { return w[0] == 'M'; });
  return {};
}

std::string channel_writer::frame_waits(std::string_view b) const {
  for (const std::string& w : frame_words(b))
    if (wait_words_in(w) > 0) return w;
  return {};
}

// The first control character of `text` (a byte below 32 but a tab, or DEL): a carriage return
// or a line feed inside one block makes two lines to a reader, and what the control makes of
// the others is its own. npos: none.
std::size_t control_character(std::string_view text) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if ((c < 32 && c != '\t') || c == 127) return i;
  }
  return std::string_view::npos;
}

bool channel_writer::text_is_one_line(std::string_view text, std::string_view who, int line) {
  const std::size_t at = control_character(text);
  if (at == std::string_view::npos) return true;
  error(line, fmt::format("{} has a control character (code {}) at its character {}: a carriage return or a "
                          "line feed in it would end the block there, for the control and for the check",
                          who, static_cast<int>(static_cast<unsigned char>(text[at])), at + 1));
  return false;
}

bool channel_writer::user_block_passes(const std::string& given, std::string_view own) {
  const program_format& f = m_.program;
  if (!block_fits(given)) return false;
  if (f.comment_close != '\n')
    for (std::size_t i = given.find(f.comment_open); i != std::string::npos;
         i = given.find(f.comment_open, i + 1))
      if ((i = given.find(f.comment_close, i + 1)) == std::string::npos) {
        error(line_,
              fmt::format("\"{}\" opens a comment it does not close: a control may read on into the next "
                          "block",
                          given));
        return false;
      }
  if (comment_inside_word(given, f) != std::string::npos) {
    error(line_,
          fmt::format("\"{}\" has a comment inside a word: a control that skips comments reads one word "
                      "across it",
                      given));
    return false;
  }
  // Read as the control reads it (issue 38, sixth and seventh attacks): a lower-case word is the
  // same word, comments and blanks are skipped (`IF[#1EQ0]THENG50X100.`), every letter is an
  // address. `flat` keeps the blanks for the blank check; `b` is the reading every other check
  // reads; messages quote the block as given.
  const std::string flat = without_comments(given, f);
  bool glued = false;
  const std::string b = control_reading(given, f, glued);
  if (glued) {
    error(line_,
          fmt::format("\"{}\" has a word glued to the letters before it (`PCLOSG20`, `XG20`): a control "
                      "reads the word, the post's checks of modes and waits may not; write a blank "
                      "between them",
                      given));
    return false;
  }
  if (print_statement(b)) return true;  // text to print: nothing moves
  bool not_a_position = false, incremental = false, sets_frame = false, local_frame = false,
       transforms = false;
  bool motion = false, data = false, length = false, absolute = false, parameters = false;
  bool reference = false, elsewhere = false;  // G28: X at its reference; G30, G53: X unknown
  double modal = -1;                          // a mode the post neither writes nor restores
  // The codes of the post's block that `b` replaces: its work offset (a header's G54), G49,
  // G10.9 are the post's, kept, not the user's doing.
  std::vector<double> post_codes;
  if (!own.empty()) {
    bool own_glued = false;
    each_g(control_reading(std::string(own), f, own_glued), f, [&](double g) { post_codes.push_back(g); });
  }
  each_g(b, f, [&](double g) {
    const bool posts = std::any_of(post_codes.begin(), post_codes.end(), [&](double p) { return is(g, p); });
    // After these an X is no position in the work frame: a dwell (G4 X1.5), data setting
    // (G10), machine coordinates (G53), a macro's arguments (G65, G66).
    data = data || is(g, 4) || is(g, 10) || is(g, 65) || is(g, 66);
    // G52 X0. cancels a local frame and moves nothing (the thirteenth round took its X for a
    // position, and the next increment counted from 0).
    not_a_position = not_a_position || data || is(g, 53) || is(g, 52);
    motion = motion || is(g, 0) || is(g, 1) || is(g, 2) || is(g, 3);
    incremental = incremental || (absolute_code_ && is(g, 91));
    absolute = absolute || (absolute_code_ && is(g, 90) && !incremental);
    reference = reference || is(g, 28);
    elsewhere = elsewhere || is(g, 30) || is(g, 53);
    // G10 L50 .. G11: parameters, among them the work offsets and the stroke limits.
    parameters = parameters || (!posts && is(g, 10) && has_word(b, 'L', {50, 52}));
    // The tool length offset: the post writes it with each tool and cancels it at home.
    length = length ||
             (!posts && (is(g, 43) || is(g, 43.1) || is(g, 43.4) || is(g, 43.5) || is(g, 44) || is(g, 49)));
    // G10 sets a work offset with L2 or L20 and the workpiece shift with P0 (with another P, or
    // L10-L13, a tool offset: a wear adjustment is a shop's own business); G52 X0. cancels a
    // local frame; G50.3 and G92.1 preset the work frame. G92 sets the frame where the safe
    // start writes G90 (G-code system B and C, mills); in Fanuc lathe system A it is the
    // threading cycle (its frame setting is G50).
    sets_frame =
        sets_frame || (!posts && (is(g, 50) || (is(g, 92) && absolute_code_) ||
                                  (is(g, 10) && (has_word(b, 'L', {2, 20}) || has_word(b, 'P', {0})))));
    local_frame = local_frame || (!posts && is(g, 52));
    transforms = transforms || (!posts && ((g >= 54 && g <= 59 && is(g, std::round(g))) || is(g, 54.1) ||
                                           is(g, 54.2) || is(g, 51) || is(g, 51.1) || is(g, 68) ||
                                           is(g, 68.1) || is(g, 68.2) || is(g, 50.3) || is(g, 92.1)));
    for (const double m : {7.1, 12.1, 112.0, 107.0, 41.0, 42.0, 66.0, 66.1, 51.2, 10.9, 16.0, 23.0, 93.0})
      if (is(g, m) && !posts) modal = m;
  });
  // G90 and G91 in one block: a control takes the last; the gate the worse, G91.
  if (incremental) absolute = false;
  // G91 given by an earlier user block holds until the post's G90 after the event.
  incremental = incremental || (user_incremental_ && !absolute);
  if (modal >= 0) {
    error(line_,
          fmt::format("\"{}\" turns on a mode the post neither writes nor turns off (polar or cylindrical "
                      "interpolation, polar coordinates, nose radius compensation, a modal macro call, "
                      "polygon turning, radius or diameter input, the stroke check off, inverse time feed: "
                      "G{}): every later block of the post would be read in it",
                      given, modal));
    return false;
  }
  if (parameters) {
    error(line_, fmt::format("\"{}\" writes parameters (G10 L50): a parameter may hold a work offset or the "
                             "travel limits; set them on the control, not from the program",
                             given));
    return false;
  }
  // A jump: the control would skip or repeat the post's blocks between it and its target.
  if (b.find(" goto ") != std::string::npos) {
    error(line_,
          fmt::format("\"{}\" jumps (GOTO): the control would skip or repeat the post's blocks between it "
                      "and its target",
                      given));
    return false;
  }
  if (length) {
    error(line_,
          fmt::format("\"{}\" sets or cancels the tool length offset (G43, G43.4, G44, G49): the post "
                      "writes each tool's offset itself, and every later Z of the post would be off by "
                      "a tool length",
                      given));
    return false;
  }
  if (data && motion) {
    error(line_,
          fmt::format("\"{}\" mixes a motion with a dwell, a data setting or a macro call: its axis words "
                      "cannot be held to the travel; write them in blocks of their own",
                      given));
    return false;
  }
  // Another work offset, a scaling or mirror image, a rotation: every later position moves.
  if (transforms) {
    error(line_,
          fmt::format(
              "\"{}\" selects another work offset, a mirror image, a scaling or a rotation "
              "(G54-G59, G54.1, G51, G51.1, G68, G50.3, G92.1): every later position of the post would be "
              "in another frame; the post writes the channel's frame itself",
              given));
    return false;
  }
  // First the blanks: a blank inside a word changes what every check below reads.
  for (std::size_t i = 0; i < flat.size(); ++i) {
    const char c = flat[i];
    // A blank inside a word: after an address, or between two digits of a number.
    if (c == ' ' && i > 0) {
      std::size_t k = i;
      while (k < flat.size() && flat[k] == ' ') ++k;
      const char before = flat[i - 1], after = k < flat.size() ? flat[k] : '\0';
      const bool address_before =
          ascii::is_upper(before) && (i < 2 || !ascii::is_letter(flat[i - 2])) && before != f.comment_open;
      const bool number_after = ascii::is_digit(after) || after == '.';
      if ((address_before && (number_after || after == '-' || after == '+' || after == '#')) ||
          ((ascii::is_digit(before) || before == '.' || before == '#') && number_after)) {
        const std::size_t from = flat.rfind(' ', i - 1) == std::string::npos ? 0 : flat.rfind(' ', i - 1) + 1;
        std::size_t to = k;
        while (to < flat.size() && flat[to] != ' ') ++to;
        error(line_, fmt::format("\"{}\" has a blank inside the word '{}': a control that skips blanks reads "
                                 "one word there",
                                 given, flat.substr(from, to - from)));
        return false;
      }
    }
  }
  const axis_def* x = ch_.axis('X');
  const bool u_is_x = x && !ch_.axis('U') && x_diameter_;  // a lathe's incremental X (G-code system A)
  // A write to a work offset's system variable moves every later position, as G10 L2 does.
  for (const macro_use& u : macro_uses(b)) {
    // An indirect write (#[5200+21]=, #[#1]=): its number is known only when the block runs, and
    // may be a work offset's.
    if (u.write && u.number < 0) {
      error(line_,
            fmt::format("\"{}\" writes a variable by an expression (#[...]=), known only when the block "
                        "runs: it may be a work offset's (#5000-#5999, #7000-#7999, #14000-#19999); "
                        "write its number",
                        given));
      return false;
    }
    if (u.write && work_offset_variable(u.number)) {
      error(line_,
            fmt::format("\"{}\" writes #{}, a system variable of the work offsets (#5000-#5999, "
                        "#7000-#7999, #14000-#19999): every later position of the post would be off by it",
                        given, u.number));
      return false;
    }
    if (u.write && control_variable(u.number)) {
      error(line_,
            fmt::format("\"{}\" writes #{}, {}: set it at the machine, not from a machine file's block",
                        given, u.number, control_variable(u.number)));
      return false;
    }
  }
  // A rotary axis word (a C axis, a trunnion's A) within its travel, as an X (the eleventh round
  // wrote `B500.` on a head of -30..210); no word of an indexing head at all: the post indexes
  // it for each tool, where the tool must point, and a turn between (`G0 G53 B90.`) left the
  // next turning cut at B90.
  for (std::size_t i = 0, depth = 0; i < b.size(); ++i) {
    if (b[i] == '[') ++depth;
    if (b[i] == ']' && depth > 0) --depth;
    if (depth > 0) continue;
    if (ch_.head_index.present() && b[i] == ch_.head_index.address) {
      error(line_,
            fmt::format("\"{}\" turns the indexing head ({}): the post indexes it for each tool, where "
                        "the tool must point, and the next cut would run at the angle this block leaves",
                        given, b[i]));
      return false;
    }
    if ((b[i] != 'A' && b[i] != 'B' && b[i] != 'C') || incremental) continue;
    const axis_def* r = ch_.axis(b[i]);
    if (!r || !r->min || !r->max) continue;
    double v = 0;
    const std::size_t from = i + 1 + (i + 1 < b.size() && b[i + 1] == '+' ? 1 : 0);
    const auto got = std::from_chars(b.data() + from, b.data() + b.size(), v, std::chars_format::fixed);
    if (got.ec != std::errc() || (v >= *r->min && v <= *r->max)) continue;
    error(line_, fmt::format("{} is outside channel {}'s {} travel {}..{} (channel.axis min/max)",
                             b.substr(i, static_cast<std::size_t>(got.ptr - b.data()) - i), ch_.number, b[i],
                             *r->min, *r->max));
    return false;
  }
  // A speed clamp (the G codes of a spindle's clamp block with an S): no higher than the CL's
  // MAXRPM in force or the spindle's limit (the eleventh round raised the Integrex's to
  // `G92 S9999 R1` before a face to X0 under G96, where the comparison with the CL is off).
  bool clamp_block = false;  // the block is a spindle's clamp (its S a limit, not a speed)
  for (const spindle_def& sp : m_.spindles) {
    if (sp.clamp.empty()) continue;
    std::vector<double> want, have;
    each_g(sp.clamp, f, [&](double g) { want.push_back(g); });
    each_g(b, f, [&](double g) { have.push_back(g); });
    const bool clamp = !want.empty() && std::all_of(want.begin(), want.end(), [&](double g) {
      return std::any_of(have.begin(), have.end(), [&](double h) { return is(g, h); });
    });
    clamp_block = clamp_block || clamp;
    const std::size_t at = b.find('S');
    const std::size_t digits =
        at == std::string::npos ? at : at + 1 + (at + 1 < b.size() && b[at + 1] == '+');
    double v = 0;
    if (!clamp || at == std::string::npos ||
        std::from_chars(b.data() + digits, b.data() + b.size(), v, std::chars_format::fixed).ec !=
            std::errc())
      continue;
    double limit = sp.max_rpm > 0 ? sp.max_rpm : 0;
    if (cl_clamp_ > 0 && (limit <= 0 || cl_clamp_ < limit)) limit = cl_clamp_;
    if (limit <= 0 || v <= limit) continue;
    const std::string above =
        limit == cl_clamp_
            ? fmt::format("the CL's MAXRPM of {:g}", limit)
            : fmt::format("the {} spindle's limit of {:g} rpm ([[spindle]] max_rpm)", sp.name, limit);
    error(line_, fmt::format("\"{}\" clamps the spindle at {:g} rpm, above {}: under constant surface speed "
                             "the spindle would run up to it near the centre",
                             given, v, above));
    return false;
  }
  if (last_x_.known) user_x_ = last_x_.value;
  const std::optional<double> from_x = user_x_;
  const std::size_t then_at = b.find(" then ");
  bool x_named = false;  // the block has an X word (or a lathe's U)
  int bracket = 0;       // inside [...] a letter is an operator (XOR) or an expression's, no word
  for (std::size_t i = 0; i < b.size(); ++i) {
    const char c = b[i];  // the reading has no comments (unclosed ones are refused above)
    if (c == '[') ++bracket;
    if (c == ']' && bracket > 0) --bracket;
    const bool word_start = bracket == 0 && ascii::is_upper(c);  // keywords are in lower case
    if (((word_start && c == 'O') || c == ':') && i + 1 < b.size() && ascii::is_digit(b[i + 1])) {
      error(line_, fmt::format("\"{}\" holds a program number: a control that loads the file starts another "
                               "program there, and this one loses the blocks after it",
                               given));
      return false;
    }
    if (!word_start) continue;
    // A G or M code given by a variable or an expression (G#1, G[10], M#1, M[100]), or with a
    // sign (G+55, read as G55 by some controls): the post cannot say what it does (a work offset,
    // inches, a wait).
    if ((c == 'G' || c == 'M') && i + 1 < b.size() &&
        (b[i + 1] == '#' || b[i + 1] == '[' || b[i + 1] == '+' || b[i + 1] == '-')) {
      error(line_,
            fmt::format("\"{}\" gives a {} code by a variable, an expression or with a sign: the post cannot "
                        "say what it does (a frame, a unit, a wait); write the code",
                        given, c));
      return false;
    }
    // A G code or a wait under IF [..] THEN: whether the control runs it is known only then (a
    // unit, a frame, a wait the other channels may wait for in vain).
    if (then_at != std::string::npos && i > then_at && (c == 'G' || c == m_.waits.address)) {
      long long code = -1;
      if (c == m_.waits.address && i + 1 < b.size() && ascii::is_digit(b[i + 1])) {
        code = 0;
        for (std::size_t j = i + 1; j < b.size() && ascii::is_digit(b[j]) && code < 1000000000; ++j)
          code = code * 10 + (b[j] - '0');
      }
      if (c == 'G' || is_wait_word(m_.waits, c, code)) {
        error(line_,
              fmt::format("\"{}\" gives a {} under IF [..] THEN: whether the control runs it is known only "
                          "when the block runs; write it unconditionally, or not at all",
                          given, c == 'G' ? "G code" : "wait"));
        return false;
      }
    }
    // An axis name list (Mazak `G17 XC`): no value after the letter.
    const char next = i + 1 < b.size() ? b[i + 1] : '\0';
    // A sequence number without its number (`NG55`): what the control makes of the letters
    // after it is not the post's to guess.
    if (c == 'N' && !ascii::is_digit(next)) {
      error(line_, fmt::format("\"{}\" has an N without its number: write N and digits, or no N", given));
      return false;
    }
    const bool has_value =
        ascii::is_digit(next) || next == '-' || next == '+' || next == '.' || next == '#' || next == '[';
    if (!has_value) continue;
    double frame_value = 1;
    if (local_frame)
      std::from_chars(b.data() + i + (next == '+' ? 2 : 1), b.data() + b.size(), frame_value,
                      std::chars_format::fixed);
    if ((sets_frame || (local_frame && frame_value != 0)) && is_axis_letter(c)) {
      error(line_,
            fmt::format("\"{}\" sets or shifts the coordinate system (G50 or G92 with an axis word, G10 "
                        "L2/L20, G52 with a shift): every later position of the post would be off by it",
                        given));
      return false;
    }
    // A rotary axis's number without its point is read in the least increment too (`C120` is
    // 0.12 degrees where decimal-point programming is off: attack 47).
    if ((c == 'A' || c == 'B' || c == 'C') && ch_.axis(c) && !not_a_position && m_.program.trailing_point &&
        next != '#' && next != '[') {
      std::size_t j = i + 1;
      if (j < b.size() && (b[j] == '-' || b[j] == '+')) ++j;
      while (j < b.size() && (ascii::is_digit(b[j]) || b[j] == '.')) ++j;
      const std::string_view word(b.data() + i, j - i);
      if (word.find('.') == std::string_view::npos &&
          word.find_first_not_of("0-+", 1) != std::string_view::npos) {
        error(line_,
              fmt::format("{} in \"{}\" has no decimal point: a control without decimal-point programming "
                          "reads it in its least increment (0.001 degree); write {}.",
                          word, given, word));
        return false;
      }
    }
    const bool is_x = c == 'X', is_u = c == 'U' && u_is_x;
    x_named = x_named || is_x || is_u;
    if (!x || !x->min || !x->max || not_a_position || (!is_x && !is_u)) continue;  // G10 P U: an offset
    std::size_t j = i + 1;
    if (j < b.size() && b[j] == '+') ++j;  // X+9000. is X9000.
    double v = 0;
    const auto r = std::from_chars(b.data() + j, b.data() + b.size(), v, std::chars_format::fixed);
    if (r.ec != std::errc()) {
      std::size_t e = i + 1;
      for (int depth = 0; e < b.size() && b[e] != ' ' && (depth > 0 || !ascii::is_upper(b[e])); ++e)
        depth += b[e] == '[' ? 1 : b[e] == ']' ? -1 : 0;
      error(line_, fmt::format("{} in \"{}\": an {} the post cannot hold to channel {}'s X travel {}..{} (a "
                               "variable or an expression); write the number",
                               b.substr(i, e - i), given, c, ch_.number, *x->min, *x->max));
      return false;
    }
    const std::string_view word(b.data() + i, static_cast<std::size_t>(r.ptr - (b.data() + i)));
    // A number without its point is read in the least increment where decimal-point programming
    // is off (the Fanuc default): X460 is 0.46 mm there, 460 mm elsewhere.
    if (v != 0 && word.find('.') == std::string_view::npos) {
      error(line_,
            fmt::format("{} in \"{}\" has no decimal point: a control without decimal-point programming "
                        "reads it in its least increment; write {}.",
                        word, given, word));
      return false;
    }
    if ((is_u || incremental) && !from_x && v != 0) {
      // Where X is not known (after the post's home return, or a G30 or G53 it cannot follow) an
      // increment is bounded by nothing (`G30 U0.` then `U460.`, the twelfth round; `U460.` right
      // after the post's `G28 U0.`, the thirteenth).
      error(line_,
            fmt::format("{} in \"{}\" is an increment of X where the post does not know where X is (after "
                        "a home return, G30 or G53); write an absolute X",
                        word, given));
      return false;
    }
    if (is_u || incremental) {
      // An increment: from the X written last (by the post, or by the event's user blocks before
      // this one: a G code there makes the post write every axis again, not forget where X is).
      // With none known only an increment of 0 comes here (above).
      const bool in = !from_x || (*from_x + v >= *x->min && *from_x + v <= *x->max);
      if (from_x) user_x_ = *from_x + v;
      if (!in) {
        error(line_,
              fmt::format("{} (incremental) takes X outside channel {}'s X travel {}..{} (channel.axis "
                          "min/max)",
                          word, ch_.number, *x->min, *x->max));
        return false;
      }
    } else if (v < *x->min || v > *x->max) {
      error(line_, fmt::format("{} is outside channel {}'s X travel {}..{} (channel.axis min/max)", word,
                               ch_.number, *x->min, *x->max));
      return false;
    } else {
      user_x_ = v;
    }
  }
  // A channel with a kinematic chain is not compared with the CL (its writer holds every point
  // to the forward transform instead, docs/emulator.md): nothing would see a user block set a
  // spindle's speed or direction there (the thirteenth round turned the Integrex's main spindle
  // backwards at 4000 rpm under a turning cut).
  if (m_.chain(ch_.number) && !clamp_block) {
    bool speed = false;
    each_g(b, f, [&](double g) { speed = speed || is(g, 96) || is(g, 97); });
    for (std::size_t i = 0, depth = 0; i + 1 < b.size() && !speed; ++i) {
      if (b[i] == '[') ++depth;
      if (b[i] == ']' && depth > 0) --depth;
      if (depth > 0) continue;
      if (b[i] == 'S' && (ascii::is_digit(b[i + 1]) || b[i + 1] == '+' || b[i + 1] == '.' || b[i + 1] == '#'))
        speed = true;
      if (b[i] != 'M' || !ascii::is_digit(b[i + 1])) continue;
      long long v = 0;
      for (std::size_t j = i + 1; j < b.size() && ascii::is_digit(b[j]) && v < 1000000000; ++j)
        v = v * 10 + (b[j] - '0');
      for (const spindle_def& sp : m_.spindles) speed = speed || v == sp.cw || v == sp.ccw;
    }
    if (speed) {
      error(line_,
            fmt::format("\"{}\" sets a spindle's speed or direction on channel {}, whose program is not "
                        "compared with the CL (a kinematic chain): the post writes the spindle from the "
                        "CL's SPINDL there",
                        given, ch_.number));
      return false;
    }
  }
  // G40 while the CL's cutter compensation is on: the rest of the contour would run on the
  // tool's centre, with a cancel move that gouges the wall (the twelfth round, mid-contour).
  bool cancels = false;
  each_g(b, f, [&](double g) { cancels = cancels || is(g, 40); });
  if (cancels && comp_cl_on_) {
    error(line_,
          fmt::format("\"{}\" cancels the cutter compensation (G40) while the CL's CUTCOM is on: the rest "
                      "of the contour would run on the tool's centre",
                      given));
    return false;
  }
  // The machine's own codes for what the post does itself: a chuck opened (from another path
  // while this one's spindle turns, or under synchronisation with nothing holding the part: the
  // twelfth round), a C axis or an indexing head clamped or unclamped.
  for (const auto& [code, what] : reserved_m_codes()) {
    for (std::size_t i = 0, depth = 0; i < b.size(); ++i) {
      if (b[i] == '[') ++depth;
      if (b[i] == ']' && depth > 0) --depth;
      if (depth > 0 || b[i] != 'M') continue;
      long long v = 0;
      std::size_t j = i + 1;
      for (; j < b.size() && ascii::is_digit(b[j]) && v < 1000000000; ++j) v = v * 10 + (b[j] - '0');
      if (j == i + 1 || v != code) continue;
      error(line_, fmt::format("\"{}\" gives M{}, the machine's {}: the post gives it itself where the part "
                               "and the spindles allow it",
                               given, code, what));
      return false;
    }
  }
  // Last, the whitelist: a form none of the checks above names is refused too.
  std::string axis_letters;
  for (const axis_def& a : ch_.axes) axis_letters += a.address;
  if (std::string why = user_block_form_error(
          b, given,
          {incremental, increment_letters(), x_diameter_ && !absolute_code_, axis_letters, &post_codes});
      !why.empty()) {
    error(line_, why);
    return false;
  }
  if (absolute)
    user_incremental_ = false;
  else if (incremental)
    user_incremental_ = true;
  // After a reference return X is at its reference, taken as the top of its travel (where a
  // lathe's turret retracts to); after G30 or G53 it is not known.
  // Only when the block names X (`G28 U0.`): `G28 W0.` leaves X where it is.
  if (reference && x_named && x && x->max)
    user_x_ = *x->max;
  else if ((reference || elsewhere) && x_named)
    user_x_.reset();
  return true;
}

std::vector<std::pair<long long, std::string>> channel_writer::reserved_m_codes() const {
  std::vector<std::pair<long long, std::string>> out;
  const auto add = [&out](const std::string& block, std::string what) {
    for (std::size_t i = 0; i + 1 < block.size(); ++i) {
      if (block[i] != 'M' || !ascii::is_digit(block[i + 1]) || (i > 0 && ascii::is_letter(block[i - 1])))
        continue;
      long long v = 0;
      for (std::size_t j = i + 1; j < block.size() && ascii::is_digit(block[j]) && v < 1000000000; ++j)
        v = v * 10 + (block[j] - '0');
      out.emplace_back(v, what);
    }
  };
  for (const spindle_def& s : m_.spindles) {
    add(s.chuck_open, fmt::format("chuck open of the {} spindle", s.name));
    add(s.c_axis.clamp, fmt::format("C axis clamp of the {} spindle", s.name));
    add(s.c_axis.unclamp, fmt::format("C axis unclamp of the {} spindle", s.name));
  }
  add(ch_.head_index.unclamp, "indexing head unclamp");
  add(ch_.head_index.clamp, "indexing head clamp");
  return out;
}

std::string channel_writer::increment_letters() const {
  std::string out;  // a lathe's increments in G-code system A (U for X, W for Z, H for C)
  if (x_diameter_ && !absolute_code_)
    for (const char l : {'U', 'V', 'W', 'H'})
      if (!ch_.axis(l)) out += l;
  return out;
}

bool channel_writer::insert_passes(const std::string& text, int line) {
  if (!text_is_one_line(text, "INSERT text", line)) return false;
  // An end of the program in the body (`M30`, `/M30`, `M99`), or a comment no ')' closes: the
  // checker's reading would stop there, the control too or not (block delete), and nothing
  // after it would be checked (attack 67 H1: a reserved variable written after `/M30`).
  // As written and as a control that skips blanks reads it (attack 68 H2: `M 30`, `M 9 9`).
  const program_format& p = m_.program;
  bool glued = false;
  const std::string reading = control_reading(text, m_.program, glued);
  for (const std::string_view form : {std::string_view(text), std::string_view(reading)})
    if (const std::string fault = code_text_fault(form, p.comment_open, p.comment_close, code_use::line);
        !fault.empty()) {
      error(line, fmt::format("INSERT \"{}\": {}", text, fault));
      return false;
    }
  const std::string increments = increment_letters();
  const std::string why = insert_return_error(reading, text, {false, increments, false, {}});
  if (why.empty()) return true;
  error(line, "INSERT " + why);
  return false;
}

}  // namespace twinpost
