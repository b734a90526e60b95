#pragma once
// The timeline as text (the summary `twinpost timeline` and `post` print), as JSON
// (`twinpost timeline --json`) and as one self-contained HTML page (analysis/timeline_page.cpp).
#include <functional>
#include <string>
#include <string_view>

#include "analysis/cycle_time.hpp"

namespace twinpost {

/// The summary: the cycle time, each channel's working and idle time, the blocks not timed,
/// the balance advice. Each line starts with `indent`.
std::string format_timeline_text(const timeline& t, std::string_view indent = "");

/// Hands the timed blocks of one channel (its number) to a callback, one at a time
/// (for_each_timed_block).
using timed_block_source = std::function<void(int channel, const std::function<void(const timed_block&)>&)>;

/// The same data for tools, in pieces to `out`, with each channel's blocks: from `blocks` when
/// given (streamed: memory does not grow with them), else the kept ones when there are any.
void write_timeline_json(const timeline& t, const std::function<void(std::string_view)>& out,
                         const timed_block_source& blocks = {});
/// write_timeline_json into one string, with the kept blocks (the page's data).
std::string format_timeline_json(const timeline& t);

/// The balance advice, one sentence per idle: "channel 2 idles 41.30 s at M951
/// (PART_2.nc:14) waiting for channel 1".
std::string advice_text(const idle_note& n);

/// The channel whose program holds the place of `d` (a conflict of timeline::conflicts), by
/// its file; 0 when none.
int conflict_channel(const timeline& t, const diagnostic& d);

/// One HTML file, nothing fetched: a lane per channel, operations coloured by tool, waits
/// linked across lanes, idle in grey, the critical path, totals; `title` heads it.
std::string timeline_page(const timeline& t, std::string_view title);

}  // namespace twinpost
