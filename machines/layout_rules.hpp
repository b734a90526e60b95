#pragma once
// The one place that decides whether a machine's programs can be laid out in files one way
// (machine.layout, or `twinpost post --layout`). The loader, the CLI's override and the post
// driver all ask it, so the rule and its message cannot drift apart.
#include <string>
#include <string_view>

#include "machines/machine.hpp"

namespace twinpost {

/// Why `layout` cannot be used for machine `m`, as a message without a place; "" when it can.
/// merged_appended writes `program.section_marker` before each channel, so it needs one;
/// merged_sections writes `$n` whatever the marker; split needs nothing of the machine.
std::string layout_problem(const machine& m, layout_kind layout);

}  // namespace twinpost
