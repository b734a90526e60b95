#pragma once
// Stable renderings of events for `twinpost parse`: one line of text, or one JSON object.
#include <string>

#include "parser/events.hpp"

namespace twinpost {

/// `LINE<TAB>kind key=value ...`, e.g. "13\tgoto x=7.43 y=5.85 z=3.775 rapid".
std::string event_to_text(const event& e);

/// One JSON object on one line, e.g. {"line":13,"event":"goto","x":7.43,...}.
std::string event_to_json(const event& e);

/// A number in its shortest exact form, with -0 printed as 0.
std::string format_number(double v);

}  // namespace twinpost
