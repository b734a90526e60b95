#pragma once
// The timeline as text (the summary `twinpost timeline` and `post` print), as JSON
// (`twinpost timeline --json`) and as one self-contained HTML page (analysis/timeline_page.cpp).
#include <string>
#include <string_view>

#include "analysis/cycle_time.hpp"

namespace twinpost {

/// The summary: the cycle time, each channel's working and idle time, the blocks not timed,
/// the balance advice. Each line starts with `indent`.
std::string format_timeline_text(const timeline& t, std::string_view indent = "");

/// The same data for tools, with the kept blocks when there are any.
std::string format_timeline_json(const timeline& t);

/// The balance advice, one sentence per idle: "channel 2 idles 41.30 s at M951
/// (PART_2.nc:14) waiting for channel 1".
std::string advice_text(const idle_note& n);

/// One HTML file, nothing fetched: a lane per channel, operations coloured by tool, waits
/// linked across lanes, idle in grey, the critical path, totals; `title` heads it.
std::string timeline_page(const timeline& t, std::string_view title);

}  // namespace twinpost
