#pragma once
// [events] of a machine file: blocks a user adds before or after the post's own at each event
// (program start and end, tool change, spindle, coolant, wait, cycle, transfer, operation
// start, section), and [[events.record]] entries that turn a CL record the post does not know into
// blocks (docs/customising.md). Plain data: machines/machine_events.cpp reads it, the channel
// writer (machining/channel_events.cpp) writes it.
#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "machines/name_template.hpp"

namespace twinpost {

/// The events a machine file may add blocks to.
enum class event_point : unsigned char {
  program_start,  ///< after the header's blocks, before the channel's first block (`after` only)
  program_end,    ///< before the channel's closing blocks and footer (`before` only)
  tool_change,    ///< around the whole tool change (spindle stop, coolant off, home, call)
  spindle_start,  ///< around a SPINDL that turns a spindle
  spindle_stop,   ///< around SPINDL/OFF
  coolant_on,     ///< around COOLNT/ON (any kind)
  coolant_off,    ///< around COOLNT/OFF
  wait,           ///< around each wait block
  cycle,          ///< around each CYCLE that starts (drill, tap, thread, groove ...)
  transfer,       ///< around the transfer channel's grip or release blocks
  operation,      ///< around the comment of an operation start (TOOL PATH, operation PPRINT)
  section,        ///< one tool, workpiece spindle and tool axis: before its first move, after its last
};
inline constexpr std::size_t event_point_count = 12;

/// The TOML key of each event_point, in its order.
inline constexpr std::array<std::string_view, event_point_count> event_point_keys{
    "program_start", "program_end", "tool_change", "spindle_start", "spindle_stop", "coolant_on",
    "coolant_off",   "wait",        "cycle",       "transfer",      "operation",    "section"};

/// The placeholders the blocks of each event are given (name_template.hpp), in the order of
/// event_point_keys.
namespace event_uses {
using p = placeholder;
// {x} {y} {z}: the position at the event (channel_events.cpp), everywhere but at the program's
// start (no move yet); {name}: the CAM's name of the tool (tool_change), of the operation
// (operation, section).
inline constexpr std::array<placeholder_set, event_point_count> of{{
    {p::channel},                    // program_start
    {p::channel, p::x, p::y, p::z},  // program_end
    {p::tool, p::offset, p::channel, p::text, p::name, p::x, p::y,
     p::z},                                                       // tool_change: {text} [[tool]] name
    {p::rpm, p::channel, p::x, p::y, p::z},                       // spindle_start
    {p::channel, p::x, p::y, p::z},                               // spindle_stop
    {p::channel, p::x, p::y, p::z},                               // coolant_on
    {p::channel, p::x, p::y, p::z},                               // coolant_off
    {p::code, p::channel, p::x, p::y, p::z},                      // wait: {code} the wait code
    {p::channel, p::text, p::x, p::y, p::z},                      // cycle: {text} its type (DRILL, TAP ...)
    {p::channel, p::x, p::y, p::z},                               // transfer
    {p::channel, p::text, p::name, p::x, p::y, p::z},             // operation: {text} the record's text
    {p::tool, p::offset, p::channel, p::name, p::x, p::y, p::z},  // section
}};
/// [[events.record]] blocks: {text} the record's arguments as written.
inline constexpr placeholder_set record{p::channel, p::text, p::x, p::y, p::z};
}  // namespace event_uses

/// The blocks of one event.
struct event_blocks {
  std::vector<std::string> before, after;
};

/// One [[events.record]]: a CL record the post does not know, and the blocks it becomes.
struct record_event {
  std::string major;               ///< upper case (PARTS_CATCHER)
  std::vector<std::string> words;  ///< the first arguments it must have (upper case); empty: any
  std::vector<std::string> blocks;
  int line = 0, column = 0;  ///< where `major` is in the machine file (for messages about it)
};

/// [events]; empty when the file has none (then the post writes what it wrote without it).
struct event_templates {
  std::array<event_blocks, event_point_count> at;
  std::vector<record_event> records;
  /// [events] script: the Lua script's file name as the machine file writes it
  /// ("catcher.lua"), empty when none; `script_path` the file beside the machine file
  /// (docs/scripting.md).
  std::string script, script_path;
  /// [events] script_records: CL majors (upper case) the script's on_record takes over, even
  /// ones the post knows.
  std::vector<std::string> script_records;
  /// [events] script_instructions, script_seconds: the script's budgets for the whole job,
  /// raised from scripting::script_limits' defaults; 0 when the file does not say.
  double script_instructions = 0, script_seconds = 0;

  const event_blocks& operator[](event_point p) const { return at[static_cast<std::size_t>(p)]; }
  bool empty() const {
    for (const event_blocks& b : at)
      if (!b.before.empty() || !b.after.empty()) return false;
    return records.empty() && script.empty();
  }
  /// The entry for a record with major word `major` (upper case) and arguments `args` (as
  /// written): the first whose words are the first arguments (ASCII case ignored); nullptr if none.
  const record_event* record_for(std::string_view major, std::string_view args) const;
  /// Whether some entry names `major` (upper case).
  bool names_record(std::string_view major) const;
};

}  // namespace twinpost
