#pragma once
// A machine definition: everything twinpost knows about one machine and its control.
// Loaded from TOML (machines/machine_loader.hpp); the built-in ones live in
// machines/builtin/*.toml. Plain data: no behaviour beyond small look-ups.
#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "machines/kinematic_chain.hpp"
#include "machines/machine_events.hpp"
#include "machines/machine_timing.hpp"
#include "machines/millturn_rules.hpp"
#include "machines/word_format.hpp"

namespace twinpost {

/// How a wait names its partners when three or more channels exist.
enum class partner_style {
  none,          ///< 2-channel controls: plain `M100` in both channels
  path_numbers,  ///< Fanuc `M100 P12`, `P123` (digits of the channel numbers, ascending)
  binary,        ///< Fanuc with parameter 8103#1: P = sum of 2^(channel-1)
  /// Citizen/Mitsubishi `!2L1`: the digits of the other channels, the wait's own channel
  /// left out (`!23L5`, also written `!2!3L5`); only with wait_syntax::bang.
  others,
};

/// How a wait is written.
enum class wait_syntax {
  m_code,  ///< a code word `<address><code>` with an optional partner list (M100 P12, M950)
  bang,    ///< `<marker><partners><address><number>`: Citizen/Mitsubishi `!2L1`
};

/// Rules for wait codes (Fanuc waiting M-codes, Mazak M950-M997, ...).
struct wait_rules {
  wait_syntax syntax = wait_syntax::m_code;
  char marker = '!';          ///< bang: the character that opens a wait and each partner
  char address = 'M';         ///< the address letter of the wait code (bang: of the number)
  int first = 0;              ///< lowest code of the range
  int last = 0;               ///< highest code of the range
  int step = 1;               ///< distance between allocated codes
  std::vector<int> excluded;  ///< codes inside the range that mean something else
  bool reuse = false;         ///< when the range is used up, start again at `first`
  partner_style partners = partner_style::none;
  char partner_address = 'P';  ///< address of the partner list
  /// A wait without a partner list meets every channel (Star style: `M200` is `M200 P123`);
  /// false: with three or more channels every wait names its partners (Fanuc PS0161).
  bool partners_optional = false;
  /// A code outside the range that is a wait of fixed channels, written in each of them and
  /// with no partner list (Star style: M82/M83 spindle synchronisation in channels 1 and 2).
  struct fixed_wait {
    int code = 0;
    std::vector<int> channels;  ///< ascending, at least two
  };
  std::vector<fixed_wait> fixed;
  /// True when `code` lies in the range, on the step grid, and is not excluded: a code the
  /// post may allocate.
  bool is_wait_code(int code) const;
  /// The fixed wait with this code, or nullptr.
  const fixed_wait* fixed_wait_of(int code) const;
  /// A wait of either kind: the checker's question.
  bool is_any_wait(int code) const { return is_wait_code(code) || fixed_wait_of(code); }
};

/// A spindle of the machine (main, sub, live tool).
struct spindle_def {
  std::string name;               ///< "main", "sub", "live"
  int cw = 3, ccw = 4, stop = 5;  ///< M-codes
  std::optional<int> select;      ///< M-code that selects this spindle (Mazak M901/M902)
  std::string clamp;              ///< max-speed clamp block, e.g. "G50 S{max}" or "G92 S{max} R1"
  double max_rpm = 0;             ///< machine limit; 0 = none
  /// The work offset of a workpiece spindle ("G54", "G55"), written when a channel starts
  /// working on this spindle; empty: none.
  std::string work_offset;
  /// CAM writes this spindle's work with Z+ away from its chuck, against the machine's Z
  /// (a sub spindle facing the main one): Z and Y are written reversed, G2/G3 swapped in
  /// G17/G18, J and K negated (a half turn about X, as the Fusion Integrex and Doosan posts do).
  bool reverse_z = false;
  /// Each channel that may command this spindle has its own (a turret's live-tool drive: the
  /// same codes in every path, a motor per turret): never shared between channels, however
  /// many list it in channel.spindles. Default false: a spindle two channels may command is
  /// one spindle they share (the workpiece spindles).
  bool per_channel = false;
  /// The spindle held as a C axis for live-tool work (machines/millturn_rules.hpp).
  c_axis_codes c_axis;
  /// The blocks that open and close this spindle's chuck ("M206", "M207"); empty: unknown to
  /// the post. The control emulator (analysis/control_emulator) refuses an opening while the
  /// spindle turns unsynchronised and a start with the chuck open.
  std::string chuck_open;
  std::string chuck_close;
};

/// An axis of a channel.
struct axis_def {
  char address = 'X';
  bool diameter = false;  ///< X programmed as a diameter (lathe)
  bool mirror = false;    ///< sign inverted against the CL (a lower turret)
  /// Travel limits in the units the axis is programmed in, if known. The post holds every X
  /// word to them (a lathe's X is measured from the spindle centre in the program and on the
  /// machine); Y and Z are machine coordinates against work coordinates, not checked yet.
  std::optional<double> min, max;
};

/// A channel (Fanuc path, Mazak head, Citizen system): one program stream.
struct channel_def {
  int number = 1;                       ///< 1-based channel number
  std::vector<int> heads;               ///< CL HEAD numbers served by this channel (HEAD/1 -> 1)
  std::vector<std::string> head_names;  ///< CL head words served (MAIN, SIDE)
  /// Tool call format, e.g. "T{tool:02}{offset:02}" or "T{tool} M6"; the file's channel
  /// `kind` (turret or mill_head) only chooses its default.
  std::string tool_call;
  /// A block after the tool call that applies the tool's offset ({tool}, {offset}): a Fanuc
  /// lathe-system B head changes the tool with M6 T0700, then takes its offset with T0707 (the
  /// Fusion Doosan Mill/Turn post). Empty: the tool call does it all.
  std::string offset_call;
  /// A mill head's tool length offset ({tool}, {offset}): words written in the first move after
  /// each tool call (`G43 H{offset}`: the Fusion Fanuc mill posts' `G43 Z.. H..` with the first
  /// move of a section). Only on a channel without a kinematic chain or an indexing head (those
  /// write their own). Empty: none, and the comparison with the CL holds the program to it.
  std::string length_offset;
  /// The blocks that take this channel's tool home ([[channel]] home: a head with a Y axis homes
  /// it with X); empty: the machine's codes.home. Read through machine::home().
  std::vector<std::string> home;
  std::string spindle = "main";  ///< the spindle this channel works on at start
  /// The channel's tool-driving spindle (a mill head's milling spindle): milling tools, and
  /// drills off the centre line, turn it; empty: the channel has none.
  std::string live_spindle;
  /// The spindles this channel may command (names of [[spindle]]s); a block of the channel
  /// that commands another is an error (analysis/shared_resources). Default: its `spindle`,
  /// its `live_spindle` and every spindle that is no channel's live_spindle.
  std::vector<std::string> spindles;
  /// The spindle in force stops before a tool change and turns again before the next move
  /// (a mill head's tool changer: the Fusion Integrex post stops it before every T.. M6).
  /// Default: true for kind mill_head, false for a turret.
  bool tool_change_stops_spindle = false;
  /// Whether a tool call may cancel the offset (T0300): false, the default, stops the post at
  /// such a call (the tip would run at the turret's reference point); true for a control
  /// whose tool table applies the geometry by tool number.
  bool offset_zero = false;
  std::vector<axis_def> axes;   ///< at least X and Z
  std::string file_suffix;      ///< for split layout, e.g. "_1" or ".P-2"
  channel_timing timing;        ///< [timing] merged with [timing.channel.N] (machine_timing.hpp)
  head_index_rules head_index;  ///< [channel.head_index]: an indexing B head (millturn_rules.hpp)
  /// The axis with this address, or nullptr.
  const axis_def* axis(char address) const;
};

/// How the channels' programs are laid out in files.
enum class layout_kind { split, merged_appended, merged_sections };

/// The units of the program's words: millimetres (G21) or inches (G20).
enum class output_unit { mm, inch };
/// The frame the program is written in when the CL's frame is turned (NX MSYS): the CL's own
/// (its MCS, where the machinist sets the work offset) or the absolute frame MSYS maps to.
enum class cl_frame { mcs, absolute };

/// Which blocks get an N number (when program.sequence_start > 0).
enum class sequence_mode { all, tool_change };

/// Output program format: numbers, blocks, comments, program frame.
struct program_format {
  std::string extension = ".nc";     ///< output file extension
  std::string file_name = "{name}";  ///< base name; {name} = sanitized PARTNO, {program} = number
  int program_number = 1000;         ///< O-number used when the job gives none
  std::string program_line = "O{program:04} ({name})";  ///< first block of a program
  std::vector<std::string> header;                      ///< blocks after the program line
  std::vector<std::string> footer;                      ///< blocks before the end code
  std::string end_code = "M30";                         ///< last block of each channel's program
  bool percent_lines = true;                            ///< '%' at the start and end of a file
  std::string section_marker;                           ///< merged layouts: "G109 L{channel}" or "${channel}"
  int sequence_start = 0;                               ///< 0 = no N numbers
  int sequence_step = 10;
  /// All blocks (header and footer too; not '%', the program line, comments or section
  /// markers), or only the tool calls: the restart points.
  sequence_mode sequence_numbers = sequence_mode::all;
  char comment_open = '(';
  char comment_close = ')';
  int comment_max = 0;  ///< longest comment text; 0 = unlimited
  /// Macro variables the setup owns (#500: the transfer's grip position): a program block that
  /// writes one is an error. The variables the [transfer] blocks read are reserved as well
  /// (machines/macro_variables.hpp).
  std::vector<int> reserved_variables;
  /// Lengths and feeds in millimetres or inches (a US shop programs in inch); the header
  /// must say the same (G21 / G20: checked at load).
  output_unit output_units = output_unit::mm;
  /// NX MSYS: the points as the CL gives them, in its MCS (the default: NX's posts write
  /// mom_mcs_goto), or turned into the absolute frame (docs/records.md, "Frames").
  cl_frame frame = cl_frame::mcs;
  int decimals_metric = 3;  ///< decimals of linear axes in mm output
  int decimals_inch = 4;    ///< decimals of linear axes in inch output
  /// Decimals of linear axis words in the output units.
  int axis_decimals() const { return output_units == output_unit::inch ? decimals_inch : decimals_metric; }
  bool trailing_point = true;  ///< "X10." for whole numbers (false: "X10")
  bool arcs_ijk = true;        ///< G2/G3 with I/K (false: R)
};

/// The control's codes for lathe output.
struct control_codes {
  std::string css = "G96";
  std::string rpm = "G97";
  std::string feed_per_rev = "G99";
  std::string feed_per_min = "G98";
  /// The blocks that take the tool home, in order: X (away from the part) first, then Z, as
  /// public Fanuc lathe posts do (`G28 U0.` then `G28 W0.`, docs/machines.md). Written before
  /// every tool change and for GOHOME.
  std::vector<std::string> home = {"G28 U0.", "G28 W0."};
  std::string dwell = "G4 U{seconds}";  ///< dwell block
  std::string program_stop = "M0";      ///< CL STOP
  std::string optional_stop = "M1";     ///< CL OPSTOP
  std::vector<std::string> coolant_on = {"M8"};
  std::string coolant_off = "M9";
  /// The other kinds of coolant, each [on, off] (the off code differs by kind: Mazak turns
  /// through-tool coolant off with M163, not M9); empty: the machine has none, and a CL that
  /// asks for it stops the post.
  std::vector<std::string> coolant_mist, coolant_through, coolant_air;
  /// Whether G41/G42 may start on a rapid move. Fanuc accepts G41/G42 with G0 or G1; the Mazak
  /// control starts tool nose radius compensation only with a feed move.
  bool cutcom_on_rapid = true;
  /// Where the D register of G41/G42 comes from: "" (none: a lathe's T word carries the nose
  /// radius), "tool" (the tool number), "cutcom" (the CUTCOM record's register, required) or
  /// "table" (the tool's [[tool]] diameter_offset). A CUTCOM register, when the CL gives one,
  /// is written under "tool" and "table" too.
  std::string cutcom_offset;
  /// Balance cutting (HEAD/BOTH): written in both channels right after the wait that opens
  /// the section and right before the wait that closes it (Fanuc G68/G69, Mazak M562/M563).
  /// Empty: the machine has none and the two heads simply cut together.
  std::string balance_on;
  std::string balance_off;
  /// Spindle synchronisation on and off (Mazak M511/M513): while on, the main and the sub turn
  /// together, and a chuck may open on a part the other spindle holds. Empty: none known.
  std::string spindle_sync_on;
  std::string spindle_sync_off;
};

/// A tool of the machine's tool table: what kind of tool a number calls, for CL data that
/// gives no TLDATA. Which spindle turns follows from the kind (docs/machines.md).
struct tool_def {
  int number = 0;    ///< the tool number of the CL tool call
  int channel = 0;   ///< the channel whose tool it is; 0: every channel
  std::string kind;  ///< "turn", "drill" or "mill"
  /// The CAM's name of the tool (NX `TOOL PATH/op,TOOL,name`, CATIA `TPRINT/name`): a job that
  /// moves before any tool call starts with this tool when the CAM names it (docs/machines.md).
  std::string name{};
  /// The gauge length (spindle nose to tip, mm) as measured on the machine: the tool length
  /// of multi-axis output (docs/machines.md, "Multi-axis output").
  std::optional<double> length{};
  /// The cutting diameter (mm): a surface speed (SPINDL/SMM, SFM) of a milling or drilling
  /// tool becomes rpm = 1000 v / (pi D) from it when the CL gives no TLDATA diameter.
  std::optional<double> diameter{};
  /// The D register of its cutter radius compensation (codes.cutcom_offset = "table").
  std::optional<int> diameter_offset{};
  /// False: the tool cuts with no spindle turning (a burnishing roller, a scribe, a probe
  /// moved at feed): a feed move with no spindle started is no error for it.
  bool spindle = true;
  /// The speed the tool cuts at when the CL gives no SPINDL between its call and its first
  /// move (NX writes its speeds into its own post, not the CLSF): rpm, or a surface speed
  /// (m/min, G96 on a lathe's turning tool, rpm from the diameter for a rotating one).
  std::optional<double> rpm{};
  std::optional<double> surface_speed{};
  bool ccw = false;  ///< direction = "ccw" (M4); "cw" (M3) by default
};

/// The part transfer from the main to the sub spindle (CL TRANSFER/GRIP, TRANSFER/RELEASE):
/// every channel retracts (codes.home), all wait, `channel` writes the blocks, all wait.
struct transfer_def {
  int channel = 0;                   ///< the channel that writes the blocks; 0: no transfer
  std::vector<std::string> grip;     ///< sync on, sub spindle advance, sub chuck close
  std::vector<std::string> release;  ///< main chuck open, sub spindle return, sync off
  /// The release after a part-off between GRIP and RELEASE (a pick-off from bar stock): the sub
  /// takes the part away and the main chuck stays closed on the bar. Empty with
  /// `has_release_after_cutoff` false: a release after a part-off stops the post.
  std::vector<std::string> release_after_cutoff;
  bool has_release_after_cutoff = false;
};

/// Limits the post holds the CL data to.
struct motion_limits {
  double max_feed = 0;  ///< highest feed per minute in mm/min; 0 = none
  /// The most blocks a second the control reads while it keeps the feed; 0 = no limit known.
  double blocks_per_second = 0;
};

/// [cycles]: the drilling and tapping cycles the control runs itself, with their codes
/// (docs/machines.md, "[cycles]"). Plain moves (the expanded form) are the fallback.
struct cycle_rules {
  std::string drill = "expanded";  ///< "canned" | "expanded"
  std::string tap = "none";        ///< "rigid" | "floating" | "expanded" | "none" (a tap is an error)
  std::string plane;            ///< written before a canned cycle, the header's plane after (G17); "": none
  std::string drill_code;       ///< one feed to depth (G81; Fanuc lathe: G83 without Q)
  std::string dwell_code;       ///< the same with a dwell P (ms) at the bottom (G82); "": expanded
  std::string peck_code;        ///< pecks of Q with a full retract (G83); "": expanded
  std::string chip_break_code;  ///< pecks of Q with a short retract (G73); "": expanded
  std::string tap_code;         ///< right-hand tapping (G84, G84.2)
  std::string tap_left_code;    ///< left-hand tapping (G84.3); "": a left-hand tap is refused
  std::string rigid_code;       ///< before a rigid tap, with the speed (M29 S..); "": none
  std::string cancel = "G80";
  std::string return_initial;   ///< the return to the initial level, in the cycle block (G98); "": none
  bool r_from_initial = false;  ///< R is the distance from the initial level (Fanuc lathe), else a Z
  bool q_increments = false;    ///< Q in least increments without a point (Q5000 = 5 mm)
  std::string sync_feed;        ///< expanded tapping's synchronised feed (G32); "": none
  /// Cross (radial) holes drilled along X with the lathe's side cycles, C positioned and
  /// clamped first (milling.cross_holes = "side_cycle"; Fanuc system A: G87 drill, G88 tap).
  std::string side_drill_code, side_dwell_code, side_peck_code, side_tap_code;
  /// Threading (CYCLE/THREAD, THREAD/TURN): "g76" (Fanuc two-block, P/Q in the least
  /// increment), "g276" (Mazak EIA two-block, P/Q in mm), "g92" (Fanuc box per pass),
  /// "g292" (Mazak EIA box per pass), "g32" (each pass as G0/G32 moves); "": a thread is
  /// an error at its record.
  std::string thread;
  /// Radial grooving (CYCLE/GROOVE): "g75" (Fanuc two-block) or "expanded" (G0/G1 plunges);
  /// "": a groove is an error at its record.
  std::string groove;

  /// The keys of the blocks above and their fields (the loader reads them, the overlap check
  /// holds them to the wait range).
  using code_field = std::pair<std::string_view, std::string cycle_rules::*>;
  static constexpr std::array<code_field, 15> code_keys{{
      {"plane", &cycle_rules::plane},
      {"drill_code", &cycle_rules::drill_code},
      {"dwell_code", &cycle_rules::dwell_code},
      {"peck_code", &cycle_rules::peck_code},
      {"chip_break_code", &cycle_rules::chip_break_code},
      {"tap_code", &cycle_rules::tap_code},
      {"tap_left_code", &cycle_rules::tap_left_code},
      {"rigid_code", &cycle_rules::rigid_code},
      {"cancel", &cycle_rules::cancel},
      {"return_initial", &cycle_rules::return_initial},
      {"sync_feed", &cycle_rules::sync_feed},
      {"side_drill_code", &cycle_rules::side_drill_code},
      {"side_dwell_code", &cycle_rules::side_dwell_code},
      {"side_peck_code", &cycle_rules::side_peck_code},
      {"side_tap_code", &cycle_rules::side_tap_code},
  }};
};

/// A box in the XZ plane of a spindle: radius (mm from the spindle axis, signed: the side of
/// channel 1's turret is +) and Z (the program's Z of that spindle).
struct xz_box {
  double r0 = 0, r1 = 0, z0 = 0, z1 = 0;
};

/// [[interference.channel]]: what moves with a channel's tool tip (docs/interference.md).
struct interference_channel {
  int channel = 0;
  /// +1: the tool works on the + side of the spindle axis at a positive X (an upper turret);
  /// -1: a mirrored (lower) turret, whose X is programmed positive on the other side.
  int side = 1;
  /// The tool and the turret or head body, each as a box relative to the tool tip on the
  /// turret's own side (r: away from the spindle axis towards the turret; z: along Z).
  std::vector<xz_box> boxes;
};

/// [[interference.zone]]: a static zone of a spindle (chuck and jaws, tailstock), in the
/// program's coordinates of that spindle, r symmetric about the axis (|r| <= r1, from r0).
struct interference_zone {
  std::string spindle;
  xz_box box;
};

/// [interference]: the geometry for the turret interference rule (analysis/interference).
/// No channels: the rule is off.
struct interference_rules {
  double clearance = 5;  ///< the least distance between two envelopes (mm)
  std::vector<interference_channel> channels;
  std::vector<interference_zone> zones;
  /// The entry of channel `c`, or nullptr.
  const interference_channel* channel(int c) const {
    for (const interference_channel& e : channels)
      if (e.channel == c) return &e;
    return nullptr;
  }
};

/// One machine and its control.
struct machine {
  std::string name;  ///< "integrex-i200st"
  std::string description;
  std::string control;  ///< "mazak-smoothx", "fanuc-0i-td", ...
  std::string source;   ///< file the definition came from (for messages)
  /// A definition for `twinpost check` (and its readers) only: its waits and sections are
  /// what the checker needs; the rest is not verified for posting, so `post` refuses it.
  bool check_only = false;
  std::vector<channel_def> channels;  ///< ordered by number
  std::vector<spindle_def> spindles;
  wait_rules waits;
  layout_kind layout = layout_kind::split;
  program_format program;
  word_formats formats;  ///< digits per address ([format]; defaults per control)
  control_codes codes;
  motion_limits limits;
  cycle_rules cycles;
  transfer_def transfer;
  std::vector<tool_def> tools;  ///< the tool table ([[tool]]); may be empty
  /// [[kinematics]]: the chains of the channels that have one (docs/kinematics.md).
  std::vector<kinematic_chain> kinematics;
  /// [milling]: live-tool work on a channel with a C axis (machines/millturn_rules.hpp).
  milling_rules milling;
  /// [interference]: envelopes and static zones (docs/interference.md).
  interference_rules interference;
  /// [events]: the user's blocks at the post's events and for records it does not know.
  event_templates events;

  /// The channel that serves CL head `head`, or nullptr.
  const channel_def* channel_for_head(int head) const;
  /// The channel that serves CL head word `word` (MAIN, SIDE), or nullptr.
  const channel_def* channel_for_head(std::string_view word) const;
  /// The program number a PARTNO gives: `name` when it is all digits and fits the O format
  /// (1..9999 on a four-digit control; O0000 is no program), else nullopt.
  std::optional<int> program_number_of(std::string_view name) const;
  /// The kind ("turn", "drill", "mill") the tool table gives tool `number` of channel
  /// `channel`, or "" when it has no entry.
  std::string_view tool_kind(int channel, int number) const;
  /// The tool table's gauge length of tool `number` of channel `channel`, if it gives one.
  std::optional<double> tool_length(int channel, int number) const;
  /// The tool table's entry of tool `number` of channel `channel` (one of that channel before
  /// one of every channel), or nullptr.
  const tool_def* tool(int channel, int number) const;
  /// The tool table's entry named `name` (ASCII case ignored) for channel `channel` (one of that
  /// channel before one for every channel); null if none.
  const tool_def* tool_named(int channel, std::string_view name) const;
  /// The kinematic chain of channel `channel`, or nullptr.
  const kinematic_chain* chain(int channel) const;
  /// The home blocks of `channel`: its own ([[channel]] home), else codes.home.
  const std::vector<std::string>& home(int channel) const;
  /// The spindle named `name`, or nullptr.
  const spindle_def* spindle(std::string_view name) const;
  /// Whether channel `channel` may command spindle `index` (into `spindles`).
  bool may_command(int channel, int index) const;
  /// Whether spindle `index` is shared: not per_channel, and two or more channels may command it.
  bool shared_spindle(int index) const;
};

}  // namespace twinpost
