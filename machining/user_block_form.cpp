// machining/user_block_form.hpp: the whitelist of a user block's forms.
#include "machining/user_block_form.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "support/ascii.hpp"

namespace twinpost {

namespace {

// The G codes a user block may give: those whose effect on the post's later blocks the post
// follows or undoes.
// - G0 and G1 motion (the post writes its own motion code again after a user block's G code);
//   not G2 and G3: an arc's path is not held to the travel (`G2 I-500.` is a full circle that
//   reaches X-980 on a mill of +-400, the twelfth round);
// - G4 dwell, G9 exact stop (one block), G61 and G64 (exact stop and cutting mode: how corners
//   are run, not where);
// - G17-G19 plane, G94/G95/G98/G99 feed mode, G90/G91 (put back after the event,
//   channel_user_modes), G20/G21 (the other unit is refused there);
// - G28 and G30 reference returns (below: through no intermediate point), G53 machine
//   coordinates;
// - G40 and G80 (cancels), G96/G97 (surface speed on or off; the S and the spindle the CL asks
//   for are compared at every cut), G50 and G92 (the gate refuses them with an axis word: a
//   speed clamp), G52 (only its cancel, X0.).
// Not G10 (data setting: work and tool offsets, parameters, tool life; the eleventh round wrote
// a geometry offset with `G10 P10001 X100. Z500.` and cleared the tool life data with G10 L3),
// and on a lathe in G-code system A not G90, G92 and G94: there they are the turning, threading
// and facing cycles, whose taper R takes X where the gate does not look (`G90 X50. Z-20.
// R-300.` starts at X-550.).
constexpr double known_g[] = {0,  1,  4,  9,  17, 18, 19, 20, 21, 28, 30, 40, 50, 52,
                              53, 61, 64, 80, 90, 91, 92, 94, 95, 96, 97, 98, 99};

// The arithmetic of an assignment (Fanuc custom macro B), as control_reading writes it: in lower
// case between blanks. The comparisons (EQ, NE, ...) belong to IF and WHILE.
constexpr std::string_view functions[] = {"sin", "cos", "tan", "asin",  "acos", "atan", "sqrt",
                                          "abs", "bin", "bcd", "round", "fix",  "fup",  "ln",
                                          "exp", "pow", "adp", "and",   "or",   "xor",  "mod"};

bool is_axis(char c) { return std::string_view("XYZUVWABC").find(c) != std::string_view::npos; }

std::string refusal(std::string_view given, std::string_view why) {
  return fmt::format("\"{}\" {}", given, why);
}

std::string assignment_error(std::string_view r, std::size_t i, std::string_view given) {
  // `#` and the variable's number, then `=`.
  std::size_t j = i + 1;
  while (j < r.size() && ascii::is_digit(r[j])) ++j;
  if (j == i + 1 || j >= r.size() || r[j] != '=')
    return refusal(given,
                   "uses a variable outside an assignment `#<number>=...` and outside a word's value: "
                   "the post reads neither; write the number");
  int depth = 0;
  for (std::size_t k = j + 1; k < r.size(); ++k) {
    const char c = r[k];
    if (c == '[') ++depth;
    if (c == ']' && --depth < 0) break;
    if (ascii::is_digit(c) || c == '#' || c == '.' || c == '+' || c == '-' || c == '*' || c == '/' ||
        c == '[' || c == ']' || c == ' ')
      continue;
    if (ascii::is_letter(c) && !ascii::is_upper(c)) {
      std::size_t e = k;
      while (e < r.size() && ascii::is_letter(r[e]) && !ascii::is_upper(r[e])) ++e;
      const std::string_view w = r.substr(k, e - k);
      if (std::find(std::begin(functions), std::end(functions), w) != std::end(functions)) {
        k = e - 1;
        continue;
      }
    }
    return refusal(given,
                   "has more than an assignment after its `=` (words, a comparison, a second "
                   "statement): the control reads all of it as one expression or stops with an alarm; "
                   "write the assignment in a block of its own");
  }
  if (depth != 0)
    return refusal(given, "has an assignment whose brackets do not pair: the control stops with an alarm");
  if (r.find_first_not_of(' ', j + 1) == std::string_view::npos)
    return refusal(given, "assigns nothing after its `=`: write the value");
  return {};
}

struct word {
  char letter;
  double value;
  bool number;            // a value was given (an axis letter of a name list has none)
  std::string_view text;  // as the control reads it
};

// G28 and G30 move every named axis to the intermediate point first, at rapid: a point other
// than where the tool is (`G28 X100.`, `G28 Z0.` under G90) is a move the post cannot follow.
std::string through_a_point(const std::vector<word>& words, std::string_view given, bool incremental,
                            const user_block_context& c) {
  for (const word& w : words) {
    if (!is_axis(w.letter) || !w.number) continue;
    const bool increment = incremental || c.increment_letters.find(w.letter) != std::string_view::npos;
    if (!increment || w.value != 0)
      return refusal(given,
                     fmt::format("returns to the reference position through the intermediate point "
                                 "{}: G28 and G30 go there first, at rapid, and the post cannot follow "
                                 "it; give no move on the way ({})",
                                 w.text, c.increment_letters.empty() ? "G91 G28 Z0." : "G28 U0. or G28 W0."));
  }
  return {};
}

}  // namespace

std::string user_block_form_error(std::string_view r, std::string_view given, const user_block_context& c) {
  std::size_t i = 0;
  const auto blanks = [&] {
    while (i < r.size() && r[i] == ' ') ++i;
  };
  blanks();
  if (i < r.size() && r[i] == '/') {  // block delete, with its switch's number on some controls
    ++i;
    if (i < r.size() && ascii::is_digit(r[i])) ++i;
  }
  blanks();
  if (i + 1 < r.size() && r[i] == 'N' && ascii::is_digit(r[i + 1])) {
    ++i;
    while (i < r.size() && ascii::is_digit(r[i])) ++i;
  }
  blanks();
  if (i < r.size() && r[i] == '#') return assignment_error(r, i, given);
  // A condition that sets a variable (`IF [#100 GT 10] THEN #3000=1`: a parts counter's alarm):
  // the condition in brackets, then an assignment the rules above hold.
  if (r.compare(i, 3, "if ") == 0) {
    std::size_t k = i + 3;
    while (k < r.size() && r[k] == ' ') ++k;
    const std::size_t then = r.find(" then ", k);
    if (k < r.size() && r[k] == '[' && then != std::string_view::npos) {
      std::size_t e = k;
      for (int depth = 0; e < then; ++e) {
        if (r[e] == '[') ++depth;
        if (r[e] == ']' && --depth == 0) break;
      }
      std::size_t q = then + 6;
      while (q < r.size() && r[q] == ' ') ++q;
      if (e < then && r.find_first_not_of(' ', e + 1) == then + 1 && q < r.size() && r[q] == '#')
        return assignment_error(r, q, given);
    }
  }
  std::vector<word> words;
  while (blanks(), i < r.size()) {
    const char a = r[i];
    if (ascii::is_letter(a) && !ascii::is_upper(a))  // control_reading's keywords are in lower case
      return refusal(given,
                     "is a macro statement (IF, WHILE, DO, END, GOTO): the post does not follow a "
                     "program's branches and loops; write the blocks it stands for");
    if (!ascii::is_upper(a) || a == 'O') {
      return refusal(given,
                     fmt::format("has '{}' where the post reads a word (an address and a number), an "
                                 "assignment (#1=...) or a print statement: a form the post cannot read "
                                 "is refused",
                                 r.substr(i, 1)));
    }
    const std::size_t at = i++;
    const std::size_t digits_from = i + (i < r.size() && (r[i] == '+' || r[i] == '-') ? 1 : 0);
    std::size_t e = digits_from;
    bool digit = false, point = false;
    for (; e < r.size(); ++e) {
      if (ascii::is_digit(r[e]))
        digit = true;
      else if (r[e] == '.' && !point)
        point = true;
      else
        break;
    }
    if (!digit) {
      const char next = digits_from < r.size() ? r[digits_from] : ' ';
      if (next == '#' || next == '[')
        return refusal(given, fmt::format("gives {} by a variable or an expression: the post cannot read "
                                          "the value; write the number",
                                          a));
      // An axis name list (Mazak `G17 XC`): axis letters side by side, with no value.
      const bool listed =
          is_axis(a) && e == i && ((i < r.size() && is_axis(r[i])) || (at > 0 && is_axis(r[at - 1])));
      if (!listed)
        return refusal(given, fmt::format("has the address {} without its number: write {} and a number, "
                                          "or leave it out",
                                          a, a));
      words.push_back({a, 0, false, r.substr(at, 1)});
      continue;
    }
    double v = 0;
    std::from_chars(r.data() + digits_from, r.data() + e, v, std::chars_format::fixed);
    if (digits_from > i && r[i] == '-') v = -v;
    words.push_back({a, v, true, r.substr(at, e - at)});
    i = e;
  }
  bool reference = false, machine = false, incremental = c.incremental;
  for (const word& w : words) {
    if (w.letter == 'G') {
      const auto same = [&](double g) { return std::abs(w.value - g) < 1e-9; };
      if (std::none_of(std::begin(known_g), std::end(known_g), same) &&
          !(c.post_codes && std::any_of(c.post_codes->begin(), c.post_codes->end(), same)))
        return refusal(
            given,
            fmt::format(
                "gives {}, a code the post does not follow in a user block: what it does to the "
                "post's later blocks is not known (a cycle stays on, a macro call or a skip moves "
                "where the post cannot see; G10 sets offsets, parameters or tool life data; an arc's path is "
                "not held to the travel). A user block may give G0, G1, G4, G9, G17-G21, G28, G30, G40, G50, "
                "G52 X0., G53, G61, G64, "
                "G80, G90-G92, G94-G99",
                w.text));
      const bool cycle =
          std::abs(w.value - 90) < 1e-9 || std::abs(w.value - 92) < 1e-9 || std::abs(w.value - 94) < 1e-9;
      if (c.lathe_cycles && cycle)
        return refusal(given, fmt::format("gives {}, on this lathe (G-code system A) a turning, threading or "
                                          "facing cycle: its passes and its taper (R) take the tool where "
                                          "the post does not follow it; let the CL cut them",
                                          w.text));
      reference = reference || std::abs(w.value - 28) < 1e-9 || std::abs(w.value - 30) < 1e-9;
      machine = machine || std::abs(w.value - 53) < 1e-9;
      incremental = incremental || std::abs(w.value - 91) < 1e-9;
    }
    // An M code is a whole number: `M100.` is an alarm on a Fanuc, and the post's counters of
    // waits, spindles and coolant would not read it as M100 while another control might.
    if (w.letter == 'M' && w.text.find('.') != std::string_view::npos)
      return refusal(given, fmt::format("gives {}, an M code with a decimal point: write the code as a whole "
                                        "number",
                                        w.text));
    // M2, M30: the program ends there, before the post's later blocks and the footer's returns
    // home (attack 51: an M30 emitted in the footer).
    if (w.letter == 'M' && (w.value == 2 || w.value == 30))
      return refusal(given, fmt::format("gives {}, the program's end: the blocks after it (the post's, the "
                                        "footer's returns home) would not run; the program ends with the "
                                        "machine's end code",
                                        w.text));
    if (w.letter == 'M' && (w.value == 98 || w.value == 99 || w.value == 198))
      return refusal(given,
                     fmt::format("calls a subprogram or returns from one ({}): what the subprogram moves "
                                 "and the waits in it are not the post's to read, and M99 in the main "
                                 "program starts it again",
                                 w.text));
  }
  for (const word& w : words) {
    // The tool length offset number (in G43 a new H changes the offset: every later Z is off by
    // the two tools' difference) and the cutter compensation's (a new D mid-contour): the post
    // writes each tool's. H is a lathe's incremental C where G-code system A makes it one.
    if ((w.letter == 'H' && c.increment_letters.find('H') == std::string_view::npos) || w.letter == 'D')
      return refusal(given, fmt::format("gives {}, a {} offset number: the post writes each tool's own, and "
                                        "every later cut would take this one",
                                        w.text, w.letter == 'H' ? "tool length" : "cutter compensation"));
    // An axis the channel does not have: on a Fanuc lathe A is the angle of direct drawing
    // dimension programming (`G1 A150. W-100.` moves X too), elsewhere an alarm at best.
    if (is_axis(w.letter) && w.number && c.axes.find(w.letter) == std::string_view::npos &&
        c.increment_letters.find(w.letter) == std::string_view::npos)
      return refusal(given, fmt::format("gives {}, a word of an axis this channel does not have: a Fanuc "
                                        "lathe reads A as the angle of a direct drawing move",
                                        w.text));
    // The custom macro interrupt (Fanuc's default M96/M97, parameters 6033/6034): a jump to a
    // subprogram on a signal, anywhere in the post's later blocks.
    if (w.letter == 'M' && (w.value == 96 || w.value == 97))
      return refusal(given, fmt::format("gives {}, the custom macro interrupt on a Fanuc (a jump to a "
                                        "subprogram on a signal): what it runs is not the post's to read",
                                        w.text));
    // G53 moves in machine coordinates; with an increment (G91, or a lathe's U, W) some controls
    // move by it (Mitsubishi M700, Mazak SmoothX's base), others ignore G53: unbounded either way.
    if (machine && is_axis(w.letter) && w.number &&
        (incremental || c.increment_letters.find(w.letter) != std::string_view::npos))
      return refusal(given, fmt::format("gives G53 with the increment {}: some controls move by it in "
                                        "machine coordinates, others ignore G53; write an absolute "
                                        "machine position",
                                        w.text));
  }
  // G28 or G30 with G53: two codes of one group in one block, and which the control takes is
  // its own (`G53 G28 X-9000.` passed the eleventh round unbounded).
  if (reference && machine)
    return refusal(given,
                   "gives G53 with G28 or G30: two codes of one group in one block; write them in blocks "
                   "of their own");
  if (reference) return through_a_point(words, given, incremental, c);
  return {};
}

std::string insert_return_error(std::string_view r, std::string_view given, const user_block_context& c) {
  // The words a control reads, loosely: an upper-case letter outside [...] and the number after
  // it; anything else (a macro statement, an expression) is the user's and not read here.
  std::vector<word> words;
  bool reference = false, machine = false, incremental = c.incremental, unread_axis = false;
  int depth = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (r[i] == '[') ++depth;
    if (r[i] == ']' && depth > 0) --depth;
    if (depth > 0 || !ascii::is_upper(r[i])) continue;
    const std::size_t at = i;
    std::size_t e = i + 1;
    if (e < r.size() && (r[e] == '+' || r[e] == '-')) ++e;
    const std::size_t from = e;
    while (e < r.size() && (ascii::is_digit(r[e]) || r[e] == '.')) ++e;
    if (e == from) {
      unread_axis = unread_axis || (is_axis(r[at]) && from < r.size() && (r[from] == '#' || r[from] == '['));
      continue;
    }
    double v = 0;
    std::from_chars(r.data() + from, r.data() + e, v, std::chars_format::fixed);
    if (r[at + 1] == '-') v = -v;
    words.push_back({r[at], v, true, r.substr(at, e - at)});
    i = e - 1;
    if (r[at] != 'G') continue;
    if (std::abs(v - 27) < 1e-9 || std::abs(v - 29) < 1e-9)
      return refusal(given, fmt::format("gives {}: it moves at rapid through the reference position or the "
                                        "last G28's intermediate point, a path the post cannot follow; write "
                                        "the moves, or G28 with no move on the way",
                                        words.back().text));
    reference = reference || std::abs(v - 28) < 1e-9 || std::abs(v - 30) < 1e-9;
    machine = machine || std::abs(v - 53) < 1e-9;
    incremental = incremental || std::abs(v - 91) < 1e-9;
  }
  if (!reference || machine) return {};
  if (unread_axis)
    return refusal(given,
                   "returns to the reference position through an intermediate point given by a variable "
                   "or an expression: G28 and G30 go there first, at rapid, and the post cannot follow it");
  return through_a_point(words, given, incremental, c);
}

}  // namespace twinpost
