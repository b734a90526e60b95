// The record policy: one table of every major word twinpost knows, what a post does with it
// (posted, ignored on purpose, refused) and why, with the handler that does it. docs/records.md
// lists it (ctest `records.doc` holds the two equal); `twinpost parse --records` prints it.
#include <array>
#include <cstdint>

#include "parser/detail/lexical.hpp"
#include "parser/event_builder.hpp"

namespace twinpost {

namespace {
constexpr char upper_ascii(char c) { return c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c; }

// `pattern` (leading minor words, `...` for any more arguments) against the record's arguments.
// An empty pattern is the word's catch-all row: it matches any arguments.
bool args_match(std::string_view pattern, const cl_record& r) {
  if (pattern.empty()) return true;
  std::size_t i = 0;
  while (!pattern.empty()) {
    const std::size_t comma = pattern.find(',');
    const std::string_view w = pattern.substr(0, comma);
    pattern = comma == std::string_view::npos ? std::string_view() : pattern.substr(comma + 1);
    if (w == "...") return true;
    if (i >= r.args.size() || r.args[i].kind != arg_kind::word || !word_is(r.args[i].word, w)) return false;
    ++i;
  }
  return i == r.args.size();
}
}  // namespace

struct event_builder::rule_index {
  std::span<const rule_row> rows;
  std::span<const record_rule> rules;
  // first[c]..first[c + 1]: the rows whose word starts with letter 'A' + c.
  std::array<unsigned char, 27> first;
};

// The lookup runs once per record: the table is sorted by word and cut into one run per
// first letter, so a lookup is an index and a few length compares (GOTO: two), with no
// allocation and no indirect call beyond the handler itself.
const event_builder::rule_index& event_builder::rules() {
  using b = event_builder;
  using h = statement_handler;
  constexpr auto posted = [](std::string_view w, h f, std::string_view how, std::string_view args = {}) {
    return rule_row{{w, args, record_use::posted, how}, f};
  };
  constexpr auto ignored = [](std::string_view w, std::string_view why, h f = &b::on_ignored,
                              std::string_view args = {}) {
    return rule_row{{w, args, record_use::ignored, why}, f};
  };
  constexpr auto refused = [](std::string_view w, std::string_view why) {
    return rule_row{{w, {}, record_use::refused, why}, &b::on_refused};
  };
  // Notes say how a record is posted, or why it is safe to pass over, or why a post cannot
  // carry it out. Rows of one word for given minor words come first, its catch-all last.
  static constexpr rule_row table[] = {
      posted("AUXFUN", &b::on_aux<false>, "`Mn` in a block of its own"),
      ignored("BOX",
              "the bounding box of the tool path, for the CAM's display and stock checks; it moves "
              "nothing"),
      refused("CALSUB",
              "it calls a subprogram defined by DEFSUB or kept on the control; twinpost posts no "
              "subprogram call yet, and without the body the state after the call is unknown"),
      posted("CHANNEL", &b::on_channel, "selects the channel (turret) the records after it go to"),
      posted("CHANNL", &b::on_channel, "as CHANNEL (ICAM)"),
      posted("CIRCLE", &b::circle,
             "with the GOTO after it: a G2/G3 arc with I and K, its sense as the dialect gives it; NX's "
             "TIMES,n: n full turns, one block each, a helix when the GOTO lies at another depth; a GOTO "
             "elsewhere on the circle (a helical entry) adds the part turn on to it, one block more, the "
             "depth spread over the whole sweep at one pitch (whole turns: the shallower of the two "
             "readings of TIMES). An end within one unit of the written words of the start is the start "
             "(its words written as the start's); an arc shorter than that writes no block, one whose "
             "radius is under it is an error. R arcs take the radius the points lie on. A GOTO whose "
             "distance from the centre "
             "(in the circle's plane) differs from the start's by more than 0.01 mm is an error: no circle "
             "about that centre goes through both"),
      refused("CLAMP",
              "it clamps or unclamps an axis with the machine's own codes, which no machine file "
              "names yet; a dropped clamp or unclamp changes what the axis can do"),
      refused("CNTRL", "a control point of a NURBS spline (NX): as NURBS"),
      posted("COOLNT", &b::on_coolnt, "the machine's coolant on and off codes (M8, M9)"),
      refused("COUPLE",
              "it couples axes or spindles (ICAM's lathe vocabulary); its exact meaning is not "
              "verified, and posting nothing for it could leave out a coupled motion"),
      ignored("CSI_SET_EXTENSION_LENGTH",
              "SolidWorks CAM's tool extension, for its simulation; the control uses its own tool offsets"),
      ignored("CSI_SET_FLUTE_LENGTH",
              "SolidWorks CAM's flute length, for its simulation; the control uses its own tool offsets"),
      ignored("CSYS",
              "the frame the CAM gives the points in (SolidWorks CAM; Creo's `$$-> CSYS`); the points are "
              "posted as given, in the work offset of the machine file. SolidWorks writes TRNTYP/WORLD: a "
              "turned CSYS names the operation's tool axis (its Z) with the points in the world frame, and "
              "each move must be under that axis; a CSYS that is not rigid or is moved from the origin stops "
              "the post",
              &b::on_coordsys),
      posted("CUTCOM", &b::on_cutcom,
             "G41/G42/G40 on the next move (left and right swap on a mirrored turret and on the Z-reversed "
             "sub spindle, as G2/G3 do), with the D register codes.cutcom_offset says"),
      ignored("CUTCOM_GEOMETRY_TYPE",
              "Creo's note of which point of the tool the path follows (OUTPUT_ON_CENTER); the points are "
              "posted as they are"),
      ignored("CUTTER",
              "the tool's geometry, for the CAM's simulation; the control uses its own tool offsets",
              &b::on_tool_data),
      posted("CYCLE", &b::on_cycle,
             "DRILL, DEEP, DEEP2 and TAP along Z (on a lathe on the spindle centre line, or with a live tool "
             "and C; on a machining centre anywhere, and along the Z of a tilted working plane, G68.2, on a "
             "machine with one): the machine's canned cycle ([cycles]: Fanuc lathe "
             "G83/M29 G84, Fanuc mill G81-G83/G73/M29 G84/G74, Mazak G81-G83/G73/G84.2 with G98) or plain "
             "moves (a tap on G32 "
             "with the spindle reversed at the bottom); THREAD and GROOVE as [cycles] say (G76/G276, "
             "G92/G292 or G32 passes; G75 or G0/G1 plunges); the words read as the dialect defines them "
             "(SolidWorks FEDTO is a depth; NX's DRILL,DEEP is DEEP; a hole as a tool's first move is "
             "approached on its retract plane). Positional values (CATIA's DRILL,d,f), any other cycle, a "
             "word the post does not carry out, or a "
             "cycle the machine file names no form for stops the post at the record"),
      refused("DEFSUB",
              "it starts a subprogram definition; twinpost posts no subprograms yet, and posting "
              "the body where it is defined would run it there"),
      posted("DELAY", &b::on_delay, "a dwell, from the machine's dwell template (G4)"),
      ignored("DMIS",
              "DMIS/ON and OFF bracket inspection statements for a measuring machine (Creo); they "
              "move no axis of the lathe"),
      posted("END", &b::on_end,
             "the end of the job: each program ends with the machine's footer (a job without an end is "
             "warned as cut off)"),
      posted("END-OF-PATH", &b::on_end, "NX's end of a tool path: as END"),
      refused("ENDSUB", "it ends a subprogram definition: as DEFSUB"),
      ignored("FEATNO", "Creo's NC-sequence number, a label for the CAM; it changes nothing on the machine"),
      posted("FEDRAT", &b::on_fedrat,
             "the F word with G98/G99 (per minute, per revolution) as the machine has them"),
      posted("FINI", &b::on_end, "the end of the part program: as END"),
      posted("FROM", &b::on_motion<motion_kind::from>,
             "the start position: no block, the first move starts there"),
      posted("GODLTA", &b::on_motion<motion_kind::delta>,
             "a G0/G1 move by the distances given (one value: along the tool axis)"),
      posted("GOHOME", &b::on_motion<motion_kind::home>, "the machine's home block (G28 U0 W0)"),
      posted("GOTO", &b::on_motion<motion_kind::go_to>,
             "a G0/G1 move; X as the machine's diameter or radius, mirrored on a lower turret"),
      posted("HEAD", &b::on_head,
             "selects the head (channel) of the records after it; HEAD/BOTH cuts with two turrets at once "
             "between waits"),
      posted("INSERT", &b::on_insert,
             "a raw NC block, written as it stands (APT: a line put straight onto the tape); in the "
             "SolidWorks dialect a comment, since SolidWorks CAM writes information text with INSERT "
             "(`INSERT/Stock Size X144. ...`)"),
      ignored("INTOL",
              "the inside tolerance the CAM used to cut curves into moves; the moves in the file "
              "already meet it"),
      refused("KNOT", "the knot vector of a NURBS spline (NX): as NURBS"),
      ignored("LINTOL", "the tolerance of multi-axis moves between points; the CAM has already applied it"),
      posted("LOAD", &b::on_load_tool, "a tool call, from the machine's tool template (T0101)", "TOOL,..."),
      refused("LOAD",
              "LOAD of anything but TOOL has no meaning twinpost knows; it may load what the "
              "program needs"),
      posted("LOADTL", &b::on_tool<tool_source::loadtl>, "a tool call, from the machine's tool template"),
      refused("LOCAL_ORIGIN",
              "it shifts the origin of the later points (CATIA turning); twinpost does not "
              "post a work-offset shift yet"),
      ignored("MACHIN",
              "names the CAM's postprocessor and machine; twinpost posts for the machine it is given",
              &b::on_machin),
      ignored("MFGNO", "Creo's manufacturing model name, a label; it changes nothing on the machine"),
      ignored("MODE", "says the job turns, which a lathe channel does anyway", &b::on_ignored, "LATHE"),
      ignored("MODE", "says the job turns (as MODE/LATHE), which a lathe channel does anyway", &b::on_ignored,
              "TURN"),
      refused("MODE",
              "any other MODE changes how later records are read or cut (MODE/INCR: incremental "
              "points; MODE/MILL: milling); twinpost posts absolute turning moves only"),
      ignored("MOVE_ATTRIB",
              "SolidWorks CAM tags the moves after it as lead-in, lead-out or link, for its "
              "display; the moves themselves follow as GOTO records"),
      ignored("MSYS",
              "NX's machine coordinate system: the points stay measured from its origin (the work offset), "
              "and on a mill its rotation (MCS to absolute) turns every later point and tool axis before the "
              "kinematics; a frame that is not rigid, a turned MCS on a lathe channel and a drilling cycle "
              "under a turned MCS stop the post",
              &b::on_coordsys),
      ignored(
          "MULTAX",
          "says GOTO points carry a tool axis (i,j,k); the reader takes 3 or 6 numbers either way. On a "
          "channel with a kinematic chain ([[kinematics]]) a tilted axis turns the rotary axes; elsewhere a "
          "move whose tool axis is not along Z is an error",
          &b::on_multax),
      refused("NURBS",
              "a spline move (NX: NURBS/, then KNOT/ and CNTRL/x,y,z records); no public definition of "
              "the record was found (its order, the knots it leaves out, whether the point before it is "
              "the first control point), and a spline read by a guess is a path the CAM never made, so it "
              "is not cut into moves"),
      ignored("OPFEATEND",
              "the end of a SolidWorks CAM operation; the next OPFEATSTART comment names the next one",
              &b::on_text<text_kind::op_end>),
      posted("OPFEATSTART", &b::on_text<text_kind::op_start>,
             "a comment naming the SolidWorks CAM operation"),
      refused("OPSKIP",
              "it makes the blocks after it optional (block skip, `/`); twinpost writes no skip "
              "marks yet, and without them those blocks would always run"),
      posted("OPSTOP", &b::on_stop, "the optional stop (M1), then the spindle and coolant blocks again"),
      refused("ORIGIN", "it shifts the later points; twinpost does not post a work-offset shift yet"),
      ignored("OUTTOL", "the outside tolerance the CAM used to cut curves into moves: as INTOL"),
      ignored("PAINT", "colour and speed of the CAM's display; it moves nothing"),
      posted("PARTNO", &b::on_text<text_kind::partno>,
             "the first PARTNO names the programs and their files (the {name} of the machine's templates)"),
      refused("PITCH",
              "ICAM: threads per CL unit (or a lead per turn, MULTRD starts) for the THREAD and COUPLE "
              "records after it; twinpost reads the lead from THREAD/TURN itself, and dropping PITCH "
              "would cut those with a lead it never saw"),
      posted("PPRINT", &b::on_text<text_kind::pprint>,
             "a comment block, cut to the machine's comment length"),
      posted("PREFUN", &b::on_aux<true>, "`Gn` in a block of its own"),
      posted("RAPID", &b::on_rapid,
             "the next move is a rapid (G0); with a kinematic chain the rotary axes move in the same block, "
             "not cut into sub-moves"),
      ignored("REMARK",
              "a note for the reader of the CL source (APT); PPRINT is the record for a comment in "
              "the program",
              &b::on_text<text_kind::other>),
      ignored("REWIND",
              "rewinds a punched tape (CATIA ends with REWIND/0); a program file has nothing to "
              "rewind"),
      refused("ROTABL",
              "SolidWorks CAM writes ROTABL/angle,AAXIS (BAXIS, CAXIS),TABLE,CCLW around each operation and "
              "undoes it in reverse order at its end; its files read as a turn in radians of the frame the "
              "points after it are in, but no public definition confirms that (ICAM's ROTABL/a positions the "
              "axis at a degrees), so the turn is not guessed: later moves could cut at the wrong angle"),
      refused("ROTHED",
              "it turns a rotary head to an angle of its own; twinpost turns the heads from the tool axis "
              "of GOTO and TLAXIS, and a head angle given apart from it could contradict it"),
      ignored("SELCTL",
              "preselects the next tool of a magazine; a turret indexes at the tool call (LOADTL, TURRET), "
              "so nothing is written",
              &b::on_tool<tool_source::select_tool>),
      ignored("SELECT", "preselects the next tool: as SELCTL, a turret needs nothing written for it",
              &b::on_load_tool, "TOOL,..."),
      refused("SELECT", "SELECT of anything but TOOL has no meaning twinpost knows"),
      ignored("SET", "absolute coordinates (Makino), which the post writes anyway", &b::on_ignored,
              "MODE,ABSOL"),
      refused("SET",
              "any other SET changes how later records are read (SET/MODE,INCR: incremental points); the "
              "post reads absolute points only"),
      refused("SETSTART",
              "Creo writes it as the comment `$$-> SETSTART` (repeating FROM), which stays a "
              "comment; as a record of its own its meaning is not verified"),
      posted("SPINDL", &b::on_spindl,
             "the S word with M3/M4/M5 and G96/G97 (with the speed limit), on the spindle it names"),
      posted("STOP", &b::on_stop, "the program stop (M0), then the spindle and coolant blocks again"),
      refused("SWITCH",
              "CATIA's SWITCH/n means what the shop's PP table says; twinpost does not know "
              "that table"),
      posted("SYNC", &b::on_sync, "a wait of the channels it names (CATIA): one wait code for all of them"),
      posted("SYNCTR", &b::on_synctr, "a wait (ICAM), numbered per channel when it gives no marker"),
      posted("THREAD", &b::on_thread,
             "THREAD/TURN,LEAD,l (or PITCH,p, STARTS,n): the feed moves after it are spindle-synchronised "
             "passes (G32 F<lead>) until THREAD/OFF, on a machine whose `[cycles]` name a thread form; "
             "any other THREAD, or one on a machine without, stops the post"),
      ignored("TITLES", "headings for the CL listing (APT); nothing for the control",
              &b::on_text<text_kind::other>),
      posted("TLAXIS", &b::on_tlaxis,
             "the tool axis of later moves and drilling cycles: no block; on a channel with a kinematic "
             "chain the next GOTO turns the rotary axes to it; a drilling cycle or an arc with the rotary "
             "axes off 0 outside a tilted working plane (G68.2, where the machine has one), or a move on a "
             "channel without a chain, under an axis not along Z is an error"),
      posted(
          "TLDATA", &b::on_tool_data,
          "the tool's kind (NX: TLDATA/MILL, DRILL, TURN) chooses the spindle on a channel with a live "
          "spindle (milling and off-centre drilling: the live one); no block. TLDATA/MILL's diameter turns "
          "a surface speed into rpm; the rest of the geometry is for the CAM's simulation (and the length "
          "for multi-axis output)"),
      posted("TOOL PATH", &b::on_text<text_kind::toolpath>,
             "a comment naming the NX operation and its tool; the name finds the tool in [[tool]] (name) for "
             "a job that moves before any tool call"),
      ignored("TOOLNO",
              "CATIA's tool number and kind, repeated by the LOADTL that calls the tool, which is "
              "posted"),
      posted("TPRINT", &b::on_text<text_kind::tprint>,
             "a comment block, as PPRINT; CATIA's tool name, found in [[tool]] (name) for a job that moves "
             "before any tool call"),
      posted("TRANSFER", &b::on_transfer,
             "the part transfer to the sub spindle (twinpost's record, from an NX UDE or a CAM's "
             "user command): GRIP (sync, sub advance, chuck close) and RELEASE (main chuck open, sub "
             "return), every channel home and waiting, the blocks from the machine's [transfer]"),
      ignored("TRNTYP",
              "SolidWorks CAM's transformation type (TRNTYP/WORLD,0,0,0: points in the world "
              "frame); the points are posted as given"),
      posted("TURRET", &b::on_tool<tool_source::turret>,
             "a tool call with its offset (TURRET/1,21: T0121), from the machine's tool template"),
      posted("UNIT", &b::on_units, "as UNITS (SolidWorks CAM)"),
      posted("UNITS", &b::on_units, "the units later values are read in (MM or INCHES)"),
  };
  constexpr std::size_t n = std::size(table);
  static_assert(n < 256, "the first-letter index holds row numbers below 256");
  static constexpr std::array<record_rule, n> rules_only = [] {
    std::array<record_rule, n> r{};
    for (std::size_t i = 0; i < n; ++i) r[i] = table[i].rule;
    return r;
  }();
  static constexpr std::array<unsigned char, 27> first = [] {
    for (std::size_t i = 0; i < n; ++i) {
      const bool last_of_word = i + 1 == n || table[i + 1].rule.word != table[i].rule.word;
      if (i + 1 < n && table[i + 1].rule.word < table[i].rule.word)
        throw "the record table must be sorted by word";
      if (last_of_word != table[i].rule.args.empty())
        throw "a word's rows for given minor words come first, its catch-all row last";
    }
    for (std::string_view w : parser_detail::text_majors) {
      bool found = false;
      for (const rule_row& r : table) found = found || r.rule.word == w;
      if (!found) throw "every word of a text record needs a row";
    }
    std::array<unsigned char, 27> f{};
    std::size_t i = 0;
    for (int c = 0; c < 26; ++c) {
      f[c] = static_cast<unsigned char>(i);
      while (i < n && table[i].rule.word[0] == 'A' + c) ++i;
    }
    if (i != n) throw "every word of the record table must start with a letter A-Z";
    f[26] = static_cast<unsigned char>(n);
    return f;
  }();
  static constexpr rule_index index{table, rules_only, first};
  return index;
}

event_builder::statement_handler event_builder::handler_of(std::string_view major) {
  if (major.empty()) return &event_builder::other;
  const char c = upper_ascii(major[0]);
  if (c < 'A' || c > 'Z') return &event_builder::other;
  const rule_index& x = rules();
  for (std::size_t i = x.first[c - 'A'], end = x.first[c - 'A' + 1]; i < end; ++i)
    if (word_is(major, x.rows[i].rule.word))
      return x.rows[i].rule.args.empty() ? x.rows[i].handler : &event_builder::by_args;
  return &event_builder::other;
}

const event_builder::rule_row* event_builder::rule_of(const cl_record& r) {
  if (r.major.empty()) return nullptr;
  const char c = upper_ascii(r.major[0]);
  if (c < 'A' || c > 'Z') return nullptr;
  const rule_index& x = rules();
  for (std::size_t i = x.first[c - 'A'], end = x.first[c - 'A' + 1]; i < end; ++i)
    if (word_is(r.major, x.rows[i].rule.word) && args_match(x.rows[i].rule.args, r)) return &x.rows[i];
  return nullptr;
}

std::span<const record_rule> record_rules() { return event_builder::rules().rules; }

}  // namespace twinpost
