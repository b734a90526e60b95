#pragma once
// The worst case of Lua's pattern matcher for one call, worked out before the call: the
// matcher is one C function the instruction count never interrupts, and a pattern such as
// ".-.-.-.-b" backtracks without end on a long subject (docs/scripting.md, "What a script
// cannot do").
#include <string_view>

namespace twinpost::scripting {

/// An upper estimate of the steps of string.find/match/gmatch/gsub with `pattern` over
/// `subject`: the start positions tried (1 when anchored with '^') times, for every item
/// repeated with '*', '+' or '-', one more than the longest run of subject bytes the item
/// matches, times 2 for each '?', times the subject's length when the pattern holds %b or a
/// back reference. A malformed pattern counts up to the item Lua stops at (the matcher
/// backtracks through the items before it until it gets there, if it ever does).
double pattern_steps(std::string_view subject, std::string_view pattern);

}  // namespace twinpost::scripting
