#pragma once
// Typed CL events: what the records mean, with each dialect's conventions already applied
// (argument order, CIRCLE direction, modal tool axis, one-shot RAPID, units). This is what
// channels/ consumes. Plain data, no behaviour.
#include <array>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "parser/dialect.hpp"
#include "support/vec3.hpp"

namespace twinpost {

enum class motion_kind : unsigned char { from, go_to, delta, home };

/// A straight move (or the FROM start point). `pos` is the absolute end point.
struct motion_event {
  motion_kind kind = motion_kind::go_to;
  vec3 pos;
  std::optional<vec3> axis;  ///< tool axis (i,j,k), given or modal
  bool rapid = false;        ///< RAPID applied to this move (one-shot)
  bool continued = false;    ///< a coordinate-only line of a multi-point GOTO
};

/// A circular move: CIRCLE data plus the end point that followed it.
struct arc_event {
  vec3 start, end, center;
  vec3 normal{0, 0, 1};  ///< circle axis as written in the CL
  double radius = 0;     ///< as written, or computed from the start point
  bool ccw = true;       ///< counter-clockwise about `normal` (dialect convention applied)
  bool continued = false;
  bool turns_axis = false;  ///< its GOTO gives a tool axis other than the one in force
  int turns = 0;  ///< NX `CIRCLE/...,TIMES,n`: n full turns, then the arc on to the end if it is elsewhere on
                  ///< the circle; 0: an arc
};

/// The most full turns one CIRCLE/...,TIMES,n may ask for: a helical entry makes a few (attack
/// 45: 200 records of TIMES,9999 wrote a 42 MB program).
inline constexpr int max_circle_turns = 100;

/// `cam_name` and `option` are no CL record: the post's own call of the tool a job moves with
/// before any tool call, named by the CAM in the machine's [[tool]] table or given by
/// `post --tool` (machining/channel_start_tool.cpp).
enum class tool_source : unsigned char { loadtl, load_tool, select_tool, turret, cam_name, option };

/// A tool call, or a tool preselection (SELECT/TOOL).
struct tool_event {
  tool_source source = tool_source::loadtl;
  int tool = 0;
  std::optional<int> offset;  ///< length/offset register (LOADTL/n,adj, ADJUST, TURRET offset)
  bool preselect = false;
};

/// Tool geometry (TLDATA, CUTTER, `$$-> CUTTER`): kept as written.
struct tool_data_event {
  std::string major;
  std::vector<std::string> words;
  std::vector<double> values;
};

enum class spindle_mode : unsigned char { rpm, sfm, smm, off, on, orient, lock };
enum class rotation : unsigned char { none, cw, ccw };

struct spindle_event {
  spindle_mode mode = spindle_mode::rpm;
  double speed = 0;
  rotation dir = rotation::none;
  std::optional<double> max_rpm;
  std::optional<int> range;
  std::string spindle;  ///< "main", "sub", "live" when named; empty = the channel's own
};

enum class feed_mode : unsigned char { per_minute, per_rev, inverse_time };
enum class unit_system : unsigned char { mm, inch };

struct feed_event {
  feed_mode mode = feed_mode::per_minute;
  double value = 0;
  unit_system units = unit_system::mm;
};

struct coolant_event {
  std::string mode;   ///< ON OFF FLOOD MIST TAP THRU AIR (upper case)
  std::string level;  ///< LOW MEDIUM HIGH, or empty
};

struct cutcom_event {
  std::string side;  ///< LEFT RIGHT OFF ON
  std::optional<int> reg;
  std::string plane;  ///< XYPLAN ... when given
};

/// CYCLE records in both forms: keyword pairs (DEPTH,3.5) and positional numbers.
struct cycle_event {
  std::string type;  ///< DRILL DEEP ... or OFF, ON, INIT
  std::vector<std::pair<std::string, double>> params;
  std::vector<std::string> words;  ///< words without a value (G98, AUTO, units)
  std::vector<double> positional;
  cycle_word_meaning meaning;  ///< what the words mean in the job's dialect
};

/// THREAD/TURN (modal threading passes) or THREAD/OFF. While on, every feed move of the
/// channel is a spindle-synchronised threading pass with this lead (docs/records.md).
struct thread_event {
  bool on = true;
  double lead = 0;  ///< distance per spindle turn, in CL units (PITCH times STARTS)
  int starts = 1;   ///< number of thread starts (STARTS, MULTRD)
};

/// STOP (program stop) or OPSTOP (optional stop).
struct stop_event {
  bool optional = false;
};

/// A part transfer from the main to the sub spindle (TRANSFER/GRIP, TRANSFER/RELEASE): the
/// router frames it with waits of every channel (channels/router), the writers retract and the
/// machine's transfer channel writes its blocks (machine::transfer).
struct transfer_event {
  enum class phase : unsigned char {
    grip,     ///< the CL record: sync on, sub spindle advance, sub chuck close
    release,  ///< the CL record: main chuck open, sub spindle return; the part is then on the sub
    retract,  ///< (router to every channel) coolant off and home before the first wait
    blocks,   ///< (router to the transfer channel) the machine's blocks of the grip or release
    on_sub,   ///< (router to every channel, after a release) the channel now works on the sub
  };
  phase step = phase::grip;
  bool release = false;  ///< for retract and blocks: whether it is the release
  /// For the release's blocks: the CL line of a feed move to or past the centre line between
  /// the GRIP and the RELEASE (a part-off: the bar stays clamped); 0: none.
  int cutoff_line = 0;
};

struct delay_event {
  double value = 0;
  bool revolutions = false;
};

struct aux_event {
  bool prefun = false;  ///< PREFUN (G) rather than AUXFUN (M)
  int code = 0;
  std::vector<double> extra;
};

enum class text_kind : unsigned char { partno, pprint, insert, tprint, op_start, op_end, toolpath, other };

struct text_event {
  text_kind kind = text_kind::pprint;
  std::string major;
  std::string text;
};

struct units_event {
  unit_system units = unit_system::mm;
};

struct machin_event {
  std::string name;
  std::vector<std::string> args;
};

struct multax_event {
  bool on = true;
};

/// A coordinate system: NX MSYS, CSYS, Creo `$$-> CSYS`, CATIA `$$*CATIA0` matrix.
struct coordsys_event {
  std::string source;
  std::vector<double> values;  ///< as written (9 or 12)
};

enum class head_select : unsigned char { number, main, side, both };

struct head_event {
  head_select which = head_select::number;
  int number = 0;
};

struct channel_event {
  int channel = 1;
};

enum class sync_source : unsigned char { catia, icam, manus };

/// An explicit synchronisation mark.
struct sync_event {
  sync_source source = sync_source::catia;
  /// Sync number / marker; unset for an ICAM `SYNCTR/NEXT` without a marker: each channel
  /// counts its own, which only the router knows (channels/router), so the parser leaves it.
  std::optional<int> index;
  std::vector<int> channels;  ///< partners as written; empty = all channels
  std::optional<int> master;
};

struct tool_axis_event {
  vec3 axis;
};

enum class comment_kind : unsigned char { plain, header, data, ude };

struct comment_event {
  comment_kind kind = comment_kind::plain;
  std::string text;
};

struct end_event {
  std::string word;  ///< FINI, END, END-OF-PATH
};

/// A record twinpost does not interpret; `known` says whether the word is recognised.
struct passthrough_event {
  std::string major;
  std::string text;  ///< the arguments as written
  bool known = false;
  /// A word the machine file turns into blocks ([[events.record]], cl_reader_options::user_records).
  bool user = false;
};

using event_data = std::variant<motion_event, arc_event, tool_event, tool_data_event, spindle_event,
                                feed_event, coolant_event, cutcom_event, cycle_event, thread_event,
                                delay_event, stop_event, aux_event, text_event, transfer_event, units_event,
                                machin_event, multax_event, coordsys_event, head_event, channel_event,
                                sync_event, tool_axis_event, comment_event, end_event, passthrough_event>;

/// One event with the physical line of the record it came from.
struct event {
  int line = 0;
  event_data data;
  int column = 0;  ///< column of the record's major word (or first number) in `line`; 0: none
};

}  // namespace twinpost
