#pragma once
// The worst case of Lua's pattern matcher for one call, worked out before the call: the
// matcher is one C function the instruction count never interrupts, and a pattern such as
// ".-.-.-.-b" backtracks without end on a long subject (docs/scripting.md, "What a script
// cannot do").
#include <cstddef>
#include <string_view>
#include <vector>

namespace twinpost::scripting {

/// A pattern's items as the matcher walks them (Lua 5.4 manual §6.4.1).
struct pattern_shape {
  bool anchored = false;                   ///< '^' first, where it anchors (not in gmatch)
  std::vector<std::string_view> repeated;  ///< items repeated with '*', '+' or '-'
  std::size_t singles = 0;                 ///< items matched once (a literal byte, a class, a set)
  int optional = 0;                        ///< items with '?'
  bool linear = false;                     ///< %b or a back reference: a scan of the subject per try
  std::size_t longest_set = 0;             ///< bytes of the longest `[...]` (the matcher walks it per byte)
};

/// The items of `pattern`. A malformed pattern keeps the items up to the one Lua stops at (the
/// matcher backtracks through the items before it until it gets there, if it ever does).
/// `anchor_works` is false for gmatch, where a leading '^' is a literal byte.
pattern_shape pattern_items(std::string_view pattern, bool anchor_works = true);

/// The bytes pattern_steps() reads to find the runs of the repeated items: one scan of the
/// subject per repeated item, or 0 when the bound without them is small enough.
double pattern_scan_bytes(const pattern_shape& shape, std::size_t subject_bytes);

/// An upper estimate of the steps of string.find/match/gmatch/gsub: the start positions tried
/// (1 when anchored) times one more than the items (a literal pattern compares each of them
/// at every start), times, for every repeated item, one more than the longest run of subject
/// bytes it matches, times 2 for each '?', times the subject's length with %b or a back
/// reference. Stops early, with a figure above `cap`, once the product passes `cap`.
double pattern_steps(const pattern_shape& shape, std::string_view subject, double cap);

}  // namespace twinpost::scripting
