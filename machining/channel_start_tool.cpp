// A job that moves before any tool call (an NX operation file, one of many operations CATIA or
// Creo wrote under one LOADTL): which tool is in the spindle, and the program started as after
// its call. Kinds for tools the CL leaves without one (post --tool-kind).
#include "machining/channel_writer.hpp"
#include "parser/cam_tool.hpp"
#include <fmt/format.h>

namespace twinpost {

void channel_writer::start_with(std::optional<int> tool, std::string_view kind) {
  start_tool_ = tool;
  default_kind_ = kind == "mill"    ? tool_kind::mill
                  : kind == "drill" ? tool_kind::drill
                  : kind == "turn"  ? tool_kind::turn
                                    : tool_kind::unknown;
}

void channel_writer::note_cam_tool(const text_event& t, int line) {
  const std::string_view name = cam_tool_name(t);
  if (name.empty()) return;
  cam_tool_ = name;
  cam_tool_line_ = line;
  cam_tool_record_ = t.major;
  cam_tool_due_ = true;
}

bool channel_writer::start_tool(int line) {
  // The CAM's name first: it says which tool this operation was made for; post --tool says
  // what the spindle holds when the CL names no tool the machine knows. Either way the call is
  // written, as a tool call record would be: the program does not lean on what the last one
  // left in the spindle, and the length offset, spindle and coolant follow as after any call.
  // An operation whose CAM name maps to another tool than the one in force, with no call of
  // its own (NX writes LOAD/TOOL at a change; a file without it would cut with the last
  // tool): its tool is called, as at the start.
  const bool named_due = cam_tool_due_;
  cam_tool_due_ = false;
  tool_event t;
  const tool_def* named = cam_tool_.empty() ? nullptr : m_.tool_named(ch_.number, cam_tool_);
  if (named && named_due && named->number != tool_) {
    t.source = tool_source::cam_name;
    t.tool = named->number;
    line = cam_tool_line_;
  } else if (tool_ >= 0 && named_due && !named && !tool_cam_name_.empty() && tool_cam_name_ != cam_tool_) {
    // An operation for another tool than the one in the spindle, with no call of its own and a
    // name the machine does not know (post --tool 1 on an NX file of two operations): the drill
    // would be cut with the end mill.
    error(line,
          fmt::format("{} at line {} names the tool '{}', but the spindle holds tool {}, taken for '{}' "
                      "(line {}), and no tool call comes between: give the operation its LOAD/TOOL, or "
                      "the tool under its [[tool]] in machine '{}' (name = \"{}\")",
                      cam_tool_record_, cam_tool_line_, cam_tool_, tool_, tool_cam_name_, tool_cam_line_,
                      m_.name, cam_tool_));
    tool_cam_name_ = cam_tool_;  // said once per change of name
    return true;
  } else if (tool_ >= 0) {
    return true;
  } else if (start_tool_) {
    t.source = tool_source::option;
    t.tool = *start_tool_;
  } else {
    return false;
  }
  call_tool(t, line);
  return tool_ >= 0;
}

void channel_writer::no_tool(int line) {
  // The turret's tool and offset would be whatever the last program left: a move with no tool
  // call (HEAD/BOTH's second channel, a job that starts moving before LOADTL) is refused, once:
  // the post has failed, and every later move would only say it again.
  if (no_tool_said_) return;
  no_tool_said_ = true;
  const std::string option = ch_.number == 1 ? "post --tool N" : fmt::format("post --tool {}:N", ch_.number);
  const std::string name =
      cam_tool_.empty()
          ? std::string(
                "the CAM's name of the tool under its [[tool]] in the machine file (name = ..., as NX "
                "TOOL PATH or CATIA TPRINT gives it)")
          : fmt::format(
                "the CAM's name of the tool under its [[tool]] in machine '{}' (name = \"{}\", as {} at "
                "line {} names it)",
                m_.name, cam_tool_, cam_tool_record_, cam_tool_line_);
  error(line,
        fmt::format("a move with no tool called in this channel: give LOADTL or TURRET before the first "
                    "move, {}, or the tool in the spindle with {}",
                    name, option));
}

}  // namespace twinpost
