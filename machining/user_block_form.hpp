#pragma once
// The last step of the gate every user block passes (machining/channel_user_gate.cpp): a
// whitelist of the forms the post reads. The gate's other checks refuse the forms the
// attacks on issue 38 found, one by one; this one accepts only what the post can follow and
// refuses the rest, so that a form nobody thought of yet is refused too (docs/customising.md,
// "the gate").
#include <string>
#include <string_view>
#include <vector>

namespace twinpost {

struct user_block_context {
  bool incremental = false;            ///< G91 in force for this block (given by it or before it)
  std::string_view increment_letters;  ///< addresses that are increments in any mode (a lathe's U, W, H)
  /// G90, G92 and G94 are a lathe's turning, threading and facing cycles (Fanuc G-code system A)
  bool lathe_cycles = false;
  std::string_view axes;  ///< the channel's axis letters ("XZCB"): a word of another is refused
  /// The G codes of the post's block this one replaces (on_block): the post's own, allowed.
  const std::vector<double>* post_codes = nullptr;
};

/// Empty when `reading` (the block as a control reads it: upper case, no comments or blanks,
/// macro keywords in lower case between blanks; channel_user_gate's control_reading) has one of
/// the forms the post reads; otherwise why not, quoting `given` (the block as written):
/// - `[/[digit]] [N<digits>]` then words, each an upper-case address (not O) and a number
///   (`[+-]digits[.digits]`, `[+-].digits`) or an axis letter of a name list (`G17 XC`), with
///   the G codes of the list the post follows and no subprogram call or return (M98, M99, M198);
///   G28 and G30 only through an intermediate point of no move (`G28 U0.`, `G91 G28 Z0.`);
/// - `[/] [N<digits>] #<number>=<expression>`: numbers, variables, `+ - * /`, brackets and
///   the arithmetic functions; nothing after it;
/// - nothing (a comment alone).
std::string user_block_form_error(std::string_view reading, std::string_view given,
                                  const user_block_context& c);

/// For INSERT text (the CAM user's NC, written as given): empty unless it returns to the
/// reference position along a path the post cannot follow: G27 or G29, or G28/G30 through an
/// intermediate point other than where the tool is (an increment of 0). `reading` as above.
std::string insert_return_error(std::string_view reading, std::string_view given,
                                const user_block_context& c);

}  // namespace twinpost
