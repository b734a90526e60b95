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
#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "machines/macro_variables.hpp"
#include "machining/channel_writer.hpp"
#include "support/ascii.hpp"

namespace twinpost {

namespace {

// The G codes of block `b` outside comments, as numbers the way a control reads them: G92.0 is
// 92, G054.1 is 54.1.
template <class F>
void each_g(std::string_view b, const program_format& f, F&& on_g) {
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b[i] == f.comment_open) {
      if ((i = b.find(f.comment_close, i + 1)) == std::string_view::npos) return;
      continue;
    }
    if (b[i] != 'G' || (i > 0 && ascii::is_letter(b[i - 1]))) continue;
    double g = 0;
    const auto r = std::from_chars(b.data() + i + 1, b.data() + b.size(), g);
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
    if (b[i] != letter || (i > 0 && ascii::is_letter(b[i - 1]))) continue;
    std::size_t j = i + 1;
    if (b[j] == '+') ++j;
    if (j < b.size() && (b[j] == '#' || b[j] == '[')) return true;
    double v = 0;
    const auto r = std::from_chars(b.data() + j, b.data() + b.size(), v);
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
  for (const std::string_view k : {"POPEN", "PCLOS"})
    if (rest.starts_with(k)) return blank_after(k.size());
  for (const std::string_view k : {"DPRNT[", "BPRNT["}) {
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

// Block `b` as a control reads its words: letters in upper case outside comments (`g55` is G55;
// the checker reads lower case too, docs/checker.md).
std::string upper_outside_comments(std::string_view b, const program_format& f) {
  std::string out(b);
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (out[i] == f.comment_open) {
      if ((i = out.find(f.comment_close, i + 1)) == std::string::npos) break;
      continue;
    }
    out[i] = ascii::upper(out[i]);
  }
  return out;
}

// The first comment of `b` that stands inside a word (`G(C)55`, `X(C)9000.`, `M1(C)00`): a
// control that skips comments reads the word across it. npos: none.
std::size_t comment_inside_word(std::string_view b, const program_format& f) {
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b[i] != f.comment_open) continue;
    const std::size_t close = b.find(f.comment_close, i + 1);
    if (close == std::string_view::npos) return std::string_view::npos;
    const char before = i > 0 ? b[i - 1] : ' ';
    const char after = close + 1 < b.size() ? b[close + 1] : ' ';
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
bool work_offset_variable(int n) {
  return (n >= 5000 && n <= 5999) || (n >= 7000 && n <= 7999) || (n >= 14000 && n <= 19999);
}

}  // namespace

bool channel_writer::user_block_passes(const std::string& given) {
  const program_format& f = m_.program;
  // Read as the control reads it: a lower-case word is the same word (issue 38, sixth attack).
  const std::string b = upper_outside_comments(given, f);
  if (!block_fits(b)) return false;
  if (const std::size_t at = comment_inside_word(b, f); at != std::string::npos) {
    error(line_, fmt::format("\"{}\" has a comment inside a word ('{}'): a control that skips comments reads "
                             "one word across it",
                             given, b.substr(at == 0 ? 0 : at - 1, b.find(f.comment_close, at) - at + 3)));
    return false;
  }
  if (print_statement(b)) return true;  // text to print: nothing moves
  bool not_a_position = false, incremental = false, sets_frame = false, local_frame = false,
       transforms = false;
  bool motion = false, data = false;
  double modal = -1;  // a mode the post neither writes nor restores
  each_g(b, f, [&](double g) {
    // After these an X is no position in the work frame: a dwell (G4 X1.5), data setting
    // (G10), machine coordinates (G53), a macro's arguments (G65, G66).
    data = data || is(g, 4) || is(g, 10) || is(g, 65) || is(g, 66);
    not_a_position = not_a_position || data || is(g, 53);
    motion = motion || is(g, 0) || is(g, 1) || is(g, 2) || is(g, 3);
    incremental = incremental || (absolute_code_ && is(g, 91));
    // G10 sets a work offset with L2 or L20 and the workpiece shift with P0 (with another P, or
    // L10-L13, a tool offset: a wear adjustment is a shop's own business); G52 X0. cancels a
    // local frame; G50.3 and G92.1 preset the work frame. G92 sets the frame where the safe
    // start writes G90 (G-code system B and C, mills); in Fanuc lathe system A it is the
    // threading cycle (its frame setting is G50).
    sets_frame = sets_frame || is(g, 50) || (is(g, 92) && absolute_code_) ||
                 (is(g, 10) && (has_word(b, 'L', {2, 20}) || has_word(b, 'P', {0})));
    local_frame = local_frame || is(g, 52);
    transforms = transforms || (g >= 54 && g <= 59 && is(g, std::round(g))) || is(g, 54.1) || is(g, 51) ||
                 is(g, 51.1) || is(g, 68) || is(g, 68.1) || is(g, 68.2) || is(g, 50.3) || is(g, 92.1);
    for (const double m : {7.1, 12.1, 112.0, 107.0, 41.0, 42.0, 66.0, 66.1, 51.2, 10.9})
      if (is(g, m)) modal = m;
  });
  if (modal >= 0) {
    error(line_,
          fmt::format("\"{}\" turns on a mode the post neither writes nor turns off (polar or cylindrical "
                      "interpolation, nose radius compensation, a modal macro call, polygon turning, radius "
                      "or diameter input: G{}): every later block of the post would be read in it",
                      b, modal));
    return false;
  }
  if (data && motion) {
    error(line_,
          fmt::format("\"{}\" mixes a motion with a dwell, a data setting or a macro call: its axis words "
                      "cannot be held to the travel; write them in blocks of their own",
                      b));
    return false;
  }
  // Another work offset, a scaling or mirror image, a rotation: every later position moves.
  if (transforms) {
    error(line_,
          fmt::format(
              "\"{}\" selects another work offset, a mirror image, a scaling or a rotation "
              "(G54-G59, G54.1, G51, G51.1, G68, G50.3, G92.1): every later position of the post would be "
              "in another frame; the post writes the channel's frame itself",
              b));
    return false;
  }
  // First the blanks: a blank inside a word changes what every check below reads.
  for (std::size_t i = 0; i < b.size(); ++i) {
    const char c = b[i];
    if (c == f.comment_open) {
      if ((i = b.find(f.comment_close, i + 1)) == std::string::npos) break;
      continue;
    }
    // A blank inside a word: after an address, or between two digits of a number.
    if (c == ' ' && i > 0) {
      std::size_t k = i;
      while (k < b.size() && b[k] == ' ') ++k;
      const char before = b[i - 1], after = k < b.size() ? b[k] : '\0';
      const bool address_before =
          ascii::is_upper(before) && (i < 2 || !ascii::is_letter(b[i - 2])) && before != f.comment_open;
      const bool number_after = ascii::is_digit(after) || after == '.';
      if ((address_before && (number_after || after == '-' || after == '+' || after == '#')) ||
          ((ascii::is_digit(before) || before == '.' || before == '#') && number_after)) {
        const std::size_t from = b.rfind(' ', i - 1) == std::string::npos ? 0 : b.rfind(' ', i - 1) + 1;
        std::size_t to = k;
        while (to < b.size() && b[to] != ' ') ++to;
        error(line_, fmt::format("\"{}\" has a blank inside the word '{}': a control that skips blanks reads "
                                 "one word there",
                                 b, b.substr(from, to - from)));
        return false;
      }
    }
  }
  const axis_def* x = ch_.axis('X');
  const bool u_is_x = x && !ch_.axis('U') && x_diameter_;  // a lathe's incremental X (G-code system A)
  // A write to a work offset's system variable moves every later position, as G10 L2 does.
  for (const macro_use& u : macro_uses(b))
    if (u.write && work_offset_variable(u.number)) {
      error(line_,
            fmt::format("\"{}\" writes #{}, a system variable of the work offsets (#5000-#5999, "
                        "#7000-#7999, #14000-#19999): every later position of the post would be off by it",
                        b, u.number));
      return false;
    }
  int bracket = 0;  // inside [...] a letter is an operator (XOR) or an expression's, no word
  for (std::size_t i = 0; i < b.size(); ++i) {
    const char c = b[i];
    if (c == f.comment_open && f.comment_close != '\n') {
      if ((i = b.find(f.comment_close, i + 1)) == std::string::npos) {
        error(line_,
              fmt::format("\"{}\" opens a comment it does not close: a control may read on into the next "
                          "block",
                          b));
        return false;
      }
      continue;
    }
    if (c == '[') ++bracket;
    if (c == ']' && bracket > 0) --bracket;
    const bool word_start = bracket == 0 && ascii::is_upper(c) && (i == 0 || !ascii::is_letter(b[i - 1]));
    if (((word_start && c == 'O') || c == ':') && i + 1 < b.size() && ascii::is_digit(b[i + 1])) {
      error(line_, fmt::format("\"{}\" holds a program number: a control that loads the file starts another "
                               "program there, and this one loses the blocks after it",
                               b));
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
                        b, c));
      return false;
    }
    // An axis name list (Mazak `G17 XC`): no value after the letter.
    const char next = i + 1 < b.size() ? b[i + 1] : '\0';
    // A sequence number without its number (`NG55`): what the control makes of the letters
    // after it is not the post's to guess.
    if (c == 'N' && !ascii::is_digit(next)) {
      error(line_, fmt::format("\"{}\" has an N without its number: write N and digits, or no N", b));
      return false;
    }
    const bool has_value =
        ascii::is_digit(next) || next == '-' || next == '+' || next == '.' || next == '#' || next == '[';
    if (!has_value) continue;
    double frame_value = 1;
    if (local_frame) std::from_chars(b.data() + i + (next == '+' ? 2 : 1), b.data() + b.size(), frame_value);
    if ((sets_frame || (local_frame && frame_value != 0)) && is_axis_letter(c)) {
      error(line_,
            fmt::format("\"{}\" sets or shifts the coordinate system (G50 or G92 with an axis word, G10 "
                        "L2/L20, G52 with a shift): every later position of the post would be off by it",
                        b));
      return false;
    }
    const bool is_x = c == 'X', is_u = c == 'U' && u_is_x;
    if (!x || !x->min || !x->max || not_a_position || (!is_x && !is_u)) continue;  // G10 P U: an offset
    std::size_t j = i + 1;
    if (j < b.size() && b[j] == '+') ++j;  // X+9000. is X9000.
    double v = 0;
    const auto r = std::from_chars(b.data() + j, b.data() + b.size(), v);
    if (r.ec != std::errc()) {
      std::size_t e = i + 1;
      while (e < b.size() && b[e] != ' ') ++e;
      error(line_, fmt::format("{} in \"{}\": an {} the post cannot hold to channel {}'s X travel {}..{} (a "
                               "variable or an expression); write the number",
                               b.substr(i, e - i), b, c, ch_.number, *x->min, *x->max));
      return false;
    }
    const std::string_view word(b.data() + i, static_cast<std::size_t>(r.ptr - (b.data() + i)));
    if (is_u || incremental) {
      // An increment: from the X written last, or, with none known, no longer than the travel.
      const bool in = last_x_.known ? last_x_.value + v >= *x->min && last_x_.value + v <= *x->max
                                    : std::abs(v) <= *x->max - *x->min;
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
    }
  }
  return true;
}

}  // namespace twinpost
