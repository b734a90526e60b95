#pragma once
// What the CAM says of its tool outside the tool call: its name and its length. Each CAM
// writes them its own way (docs/records.md); these read the forms whose fields are known.
#include "parser/events.hpp"
#include <optional>
#include <string_view>
#include <variant>

namespace twinpost {

/// The tool length a TLDATA gives, in CL units, or nullopt where the record has none (or not
/// in a place known for certain). NX CLSF: `TLDATA/MILL,diameter,lower radius,length,...`
/// (5, 7 or 10 values) and `TLDATA/DRILL[,module],diameter,corner radius,length,point angle,
/// flute length`: the length is the third number of both.
std::optional<double> tldata_length(const tool_data_event& t);

/// Whether a TLDATA after `e` still describes the tool called before it: a TLDATA right after
/// a tool call, with only comments and texts between, describes that tool.
inline bool keeps_tool_call_open(const event& e) {
  return std::holds_alternative<text_event>(e.data) || std::holds_alternative<comment_event>(e.data) ||
         std::holds_alternative<passthrough_event>(e.data);
}

/// The cutting diameter a TLDATA/MILL or TLDATA/DRILL gives (its first number), in CL units.
std::optional<double> tldata_diameter(const tool_data_event& t);

/// The CAM's name of its tool in a text record, or empty: NX `TOOL PATH/op,TOOL,name` (the
/// field after the word TOOL), CATIA `TPRINT/name` (the whole text).
std::string_view cam_tool_name(const text_event& t);

}  // namespace twinpost
