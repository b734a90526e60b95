#include "analysis/cl_compare.hpp"
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>

#include <cstdint>
#include <cstdlib>
#include <utility>
#include <variant>
#include <vector>

#include "analysis/cl_compare_arc.hpp"
#include "analysis/cl_compare_axis.hpp"
#include "analysis/cl_compare_turn.hpp"
#include "analysis/modal_state.hpp"
#include "analysis/nc_codes.hpp"
#include "analysis/program_units.hpp"
#include "analysis/rotary_sweep.hpp"
#include "analysis/spindle_state.hpp"
#include "kinematics/vec3_ops.hpp"
#include "machines/macro_variables.hpp"
#include "nc/nc_words.hpp"
#include "parser/cam_tool.hpp"
#include "parser/cycle_words.hpp"
#include "support/ascii.hpp"

namespace twinpost {

namespace {

constexpr double tip_tolerance = 0.002;   // mm (issue 37)
constexpr double axis_tolerance = 0.001;  // degrees, the tool axis (issue 37)
constexpr double feed_tolerance = 0.005;  // of the CL's feed (issue 37)
constexpr double turn_chord =
    0.01;  // mm a fed C turn may leave the CL's line (the chains' chordal tolerance)

// A G code as ten times its number: G12.1 is 121, G99 is 990.
int g10(double number) { return static_cast<int>(std::lround(number * 10)); }

// How far point `p` lies from the segment `from`-`to` (the held blocks of a CL straight move).
double off_segment(const vec3& from, const vec3& to, const vec3& p) {
  const vec3 d{to.x - from.x, to.y - from.y, to.z - from.z};
  const double dd = d.x * d.x + d.y * d.y + d.z * d.z;
  const double t =
      dd > 0 ? std::clamp(((p.x - from.x) * d.x + (p.y - from.y) * d.y + (p.z - from.z) * d.z) / dd, 0.0, 1.0)
             : 0.0;
  return kin::distance(p, vec3{from.x + t * d.x, from.y + t * d.y, from.z + t * d.z});
}

// Where one axis is, as the program has left it.
struct axis_state {
  enum class kind : unsigned char {
    unknown,  // not followed (a cycle, a coordinate setting, an expression): not compared
    known,    // at `value`, in the program's frame and units
    away      // at its reference point (G28/G30) or in machine coordinates (G53)
  } k = kind::unknown;
  double value = 0;
  int line = 0;          // the line that sent it away
  const char* why = "";  // "G28", "G53"
};

}  // namespace

struct alignas(64) cl_comparison::impl {
  impl(const machine& m, const channel_def& ch, diagnostic_sink& d, std::string file,
       const channel_spindles* reading_spindles, const channel_modes* reading_modes)
      : m(m), ch(ch), diags(d), cl_file(std::move(file)), own_spindles(m, ch.number), own_modes(m),
        codes(m, ch) {
    if (reading_spindles) spindles_given = reading_spindles;
    if (reading_modes) modes_given = reading_modes;
    const axis_def* x = ch.axis('X');
    x_div = (x && !x->diameter) ? 1.0 : 2.0;  // the writer's rule: X is a diameter unless said
    if (x && x->mirror) x_div = -x_div;
    lathe = !x || x->diameter;

    has_y = ch.axis('Y') != nullptr;
    u_incremental = lathe && !ch.axis('U');
    w_incremental = lathe && !ch.axis('W');
    v_incremental = lathe && has_y && !ch.axis('V');        // G-code system A: V is Y's increment
    g90_modes = gcode_system_of(m, ch) != gcode_system::a;  // analysis/nc_codes
    system_c = units_of(m).system_c;                        // G70/G71 the units, G20/G21 cycles

    if (const spindle_def* s = m.spindle(ch.spindle)) work = static_cast<int>(s - m.spindles.data());
    for (const spindle_def& s : m.spindles) {
      offsets.push_back(split_nc_words(s.work_offset));
      bool is_live = false;
      for (const channel_def& c : m.channels) is_live = is_live || c.live_spindle == s.name;
      live.push_back(is_live);
    }
    gms_only = own_spindles.needs_gms();
    if (ch.head_index.present()) {
      head_address = ch.head_index.address;
      head_dir = head_turn::of(ch.head_index);
      head_offset = !ch.head_index.offset_turning.empty() || !ch.head_index.offset_live.empty();
      for (const std::string* code : {&ch.head_index.offset_turning, &ch.head_index.offset_live})
        if (!code->empty()) {
          (code == &ch.head_index.offset_turning ? head_turning : head_live) =
              static_cast<int>(head_codes.size());
          head_codes.push_back(split_nc_words(*code));
        }
      // A tilted tool's tool-tip control (the chain's G43.4 H#3020) is the head's too: its
      // records are a G68.2 frame's, passed over.
      if (const kinematic_chain* k = m.chain(ch.number); k && !k->tool_tip_on.empty())
        head_codes.push_back(split_nc_words(k->tool_tip_on));
    }
    // The dwell's time word: the letter before `{seconds}` or `{ms}` in the machine's template.
    // (`{seconds:.3f}` too: the field's name, as the writer finds it.)
    for (const auto& [field, scale] : {std::pair{std::string_view("{seconds"), 1.0}, {"{ms", 0.001}})
      if (const std::size_t at = m.codes.dwell.find(field);
          at != std::string::npos && at > 0 && ascii::is_letter(m.codes.dwell[at - 1]))
        dwell_address = ascii::upper(m.codes.dwell[at - 1]), dwell_scale = scale;
    const cycle_rules& cy = m.cycles;
    for (const std::string* code :
         {&cy.drill_code, &cy.dwell_code, &cy.peck_code, &cy.chip_break_code, &cy.tap_code, &cy.tap_left_code,
          &cy.side_drill_code, &cy.side_dwell_code, &cy.side_peck_code, &cy.side_tap_code}) {
      const bool side = code == &cy.side_drill_code || code == &cy.side_dwell_code ||
                        code == &cy.side_peck_code || code == &cy.side_tap_code;
      for (const nc_word& w : split_nc_words(*code))
        if (w.address == 'G' && w.numeric && g10(w.number) >= 730 && g10(w.number) <= 890)
          (side ? side_g : hole_g).push_back(g10(w.number));
    }
    // A mill/turn head's chain writes its tilted tools under tool-tip control (the Integrex's
    // G43.4 H#3020 with B and C): followed there (attack 63 H1: its records were passed over).
    if (const kinematic_chain* k = m.chain(ch.number);
        k && !k->rotaries.empty() && (!ch.head_index.present() || !k->tool_tip_on.empty()))
      chain_def = k;
    whole_chain = chain_def && !ch.head_index.present();
    if (whole_chain)
      for (const rotary_axis_def& r : chain_def->rotaries) chain_letters |= nc_letter(r.address);
    // A chain's C is one of its rotary axes, not the part turned under X and Y.
    has_c = ch.axis('C') != nullptr && !whole_chain;
    if (has_c)
      for (const spindle_def& s : m.spindles) {
        for (const std::string& b : s.c_axis.on) c_on_codes.push_back(split_nc_words(b));
        for (const std::string& b : s.c_axis.off) c_off_codes.push_back(split_nc_words(b));
      }
    for (auto* list : {&c_on_codes, &c_off_codes})
      for (auto& c : *list)
        for (nc_word& w : c) {
          w.value = {};  // numbers only: the text they were split from is gone
          c_letters |= nc_letter(w.address);
        }
    read_tool_call(ch.tool_call);
    if (chain_def) chain.emplace(m, *chain_def, ch.number, tool_m6 ? 6 : -1, true);
    // The coolant codes, each kind's on and off: flood is codes.coolant_on (each block of it
    // turns it on) and coolant_off, the others their [on, off] pairs.
    for (const std::string& b : m.codes.coolant_on) coolant_codes.push_back({split_nc_words(b), 1});
    coolant_codes.push_back({split_nc_words(m.codes.coolant_off), 0});
    int kind = 2;
    for (const auto* pair : {&m.codes.coolant_mist, &m.codes.coolant_through, &m.codes.coolant_air}) {
      if (pair->size() == 2) {
        coolant_codes.push_back({split_nc_words((*pair)[0]), kind});
        coolant_codes.push_back({split_nc_words((*pair)[1]), 0});
      }
      ++kind;
    }
    for (auto& c : coolant_codes) {
      for (nc_word& w : c.words) w.value = {};  // numbers only: the text they were split from is gone
      for (const nc_word& w : c.words) coolant_letters |= nc_letter(w.address);
    }

    needs_length = tool_m6 && !lathe;
    if (ch.length_offset.find("H{offset") != std::string::npos) h_from = 1;
    if (ch.length_offset.find("H{tool") != std::string::npos) h_from = 0;
    // A chain writes its length or tool-tip code with H and the CL's offset (LOADTL/n,adj, else
    // the tool): attack 63 H2, an INSERT `G43 H5` ran the joints solved for tool 1 on H5.
    if (whole_chain && !offset_code(*chain_def).empty()) h_from = 1;
    units(m.program.output_units == output_unit::inch);

    for (const auto& o : offsets)
      for (const nc_word& w : o) gms_only = gms_only && (w.address == 'G' || w.address == 'M');
  }

  const machine& m;
  const channel_def& ch;
  diagnostic_sink& diags;
  std::string cl_file;
  // The spindles and the modal G state (analysis/spindle_state, analysis/modal_state): the
  // reading's, with each block applied before it comes here (post's self-check), else kept here.
  channel_spindles own_spindles;
  modal_states own_modes;
  const channel_spindles* spindles_given = nullptr;
  const channel_modes* modes_given = nullptr;
  const channel_spindles& spindles_now() const { return spindles_given ? *spindles_given : own_spindles; }

  // The machine file's reading of the words.
  double x_div = 2;  // program X / part-frame x: 2 for a diameter, negative on a mirrored turret
  bool lathe = true, inch = false, has_y = false, u_incremental = false, w_incremental = false,
       v_incremental = false;
  bool g90_modes = false;  // G90/G91 are the absolute and incremental modes (not lathe cycles)
  double out_mm = 1, axis_half = 0.0005, increment = 0.001;
  double feed_half[2] = {0.05, 0.00005};  // half the feed's last digit, per minute and per revolution, in mm
  nc_codes codes;                         // the channel's G codes (the feed modes), analysis/nc_codes
  std::vector<std::vector<nc_word>> offsets;  // each spindle's work offset, split
  std::vector<bool> live;                     // each spindle: some channel's live spindle
  bool gms_only = true;                       // every code that selects a spindle is a G, M or S word

  // The tool call's T word: T = tool x 10^tool_digits + what follows (the offset's digits or
  // literal ones: T{tool:02}{offset:02}, M6 T{tool:02}00); -1: not read (a template that
  // does not say how many digits follow). `tool_m6`: the call changes the tool with M6, a T
  // alone only preselects it.
  int tool_digits = -1;
  bool tool_m6 = false;
  bool offset_in_call = false, offset_in_offset_call = false;  // {offset} after {tool}

  // The coolant's codes and what each turns on (0: off; 1 flood, 2 mist, 3 through, 4 air).
  struct coolant_code {
    std::vector<nc_word> words;
    int kind = 0;
  };
  std::vector<coolant_code> coolant_codes;
  std::uint32_t coolant_letters = 0;
  int nc_coolant = -1, cl_coolant = -1;  // -1: not given yet
  int cl_coolant_line = 0;
  std::string coolant_text;

  // The program as read so far: the block's words, split here (own_words) or by the
  // self-check's reader (its split, not copied), while the block is read.
  std::vector<nc_word> own_words;
  const std::vector<nc_word>* block_words = &own_words;
  const std::vector<nc_word> no_words;
  long t_pending = -1, t_active = -1;  // the tool a T word named, and the one in the spindle
  std::string t_text;                  // the T word that called it
  int lines = 0;
  axis_state x, y, z;
  bool absolute = true;
  int plane = 0;       // G17, G18, G19; 0 unknown
  int motion = -1;     // modal G0..G3, 32 for threading; -1 unknown
  bool cycle = false;  // a canned or lathe cycle
  bool polar = false, cylinder = false, frame = false, polar_coords = false, inverse_time = false;
  // Polar interpolation (G12.1, G112) followed: it began with C known at 0, so its X and C are
  // the part's x and y on the face; `polar_c` is that C (in the Y axis's units). The tool is on
  // the line through the spindle's axis only where the Y axis stands at 0: the control turns the
  // part and moves X for the programmed point, and a Y left elsewhere shifts every move of the
  // mode across that line.
  bool polar_follow = false;
  axis_state polar_c;
  bool rotary = false;  // a rotary-axis word since the last tool call
  // An indexing head ([channel.head_index], the B head of a mill/turn): its angle word turns
  // the tool, and the tip stays the program's X Y Z once the head's length offset is given
  // again (`G43 P1 H#3020` on the Integrex; none on a head whose T word's offset holds it).
  char head_address = 0;
  bool head_offset = false;  // the head has offset codes: after an index, the tip waits for G43
  bool head_due = false;     // indexed, its offset not given since
  // The head's offset codes split (their words' text is the machine file's), and the block
  // that left another offset in force than theirs (G49, G44, G43 H5); "" while theirs is.
  std::vector<std::vector<nc_word>> head_codes;
  std::string head_wrong;
  std::string head_wrong_why;             // why head_wrong's code is the other spindle's
  int head_turning = -1, head_live = -1;  // their places in head_codes
  int head_used = -1;                     // the head code in force (note_head_offset), its block:
  std::string head_used_text;
  bool said_head = false;
  // Where the head points the tool: its angle as the program left it (degrees; none where not
  // known: before its first index, after a tool change, which may turn it at the changer, or a
  // reference return) and the block that set it.
  head_turn head_dir;
  std::optional<double> head_deg;
  // A channel with a kinematic chain (but a mill/turn's indexing head): its linear and rotary
  // words, length offset, tool-tip control and tilted planes followed as the control reads
  // them (analysis/rotary_sweep), the tip and the tool axis through the forward transform.
  const kinematic_chain* chain_def = nullptr;
  std::optional<rotary_sweep> chain;
  bool whole_chain = false;  // every move the chain's (else a mill/turn head's, under tool-tip control)
  std::uint32_t chain_letters = 0;  // a whole chain's rotary addresses
  enum class mid_kind { feed, rapid, arc, away };
  struct chain_block {
    std::optional<vec3> tip, sag;  // where it ends, and halfway along it (feed blocks)
    int line = 0;
    std::string text;
    mid_kind kind = mid_kind::feed;
    bool text_later = false;  // `text` is move_text's once the next block comes
    bool unknown = false;     // (plains) an axis word of its own is a variable or an expression
  };
  std::vector<chain_block> mids;  // a chain's feed blocks since the last motion record (n_mids of them)
  // A channel without a chain (a lathe's, a 3-axis mill's): its moving blocks since the last
  // motion record, where each ends (the part frame, mm; none where an axis is not known), held
  // at a feed record to the CL's straight move (plain_blocks; the thirty-sixth note's open item:
  // an [events] block `X20.` between a rapid and a feed record moved the feed's start).
  std::vector<chain_block> plains;
  std::size_t n_plains = 0;
  chain_block plain_next;      // the last block that moved, not in `plains` yet
  bool plains_over = false;    // more blocks than `plains` holds since the last motion record
  bool plain_pending = false;  // plain_next goes into plains at the next line (settle_plain_block)
  bool said_plain = false;
  std::size_t n_mids = 0;
  bool mid_staged = false;  // mids[n_mids] is a block whose tip is not worked out yet
  bool said_mid = false;
  bool fixture = false;         // a rotary fixture offset (G54.2 Pn) in force
  std::string unfollowed_text;  // the first frame of a chain's program not followed, and its line
  int unfollowed_line = 0;
  bool said_frame = false;
  std::optional<double> cl_length, cl_length_next;  // the CL's TLDATA length (mm), now and for the next call
  bool cl_after_call = false;                       // a TLDATA now describes the tool just called
  std::string head_text;
  int head_line = 0;
  bool said_axis = false;
  // The C axis of a channel that has one: the part turned under X and Y (the writer's frame:
  // the program's X, Y are the part's turned by -C about Z).
  bool has_c = false;
  bool c_known = true;  // C at 0 until the spindle becomes a C axis
  double c_deg = 0;
  std::vector<std::vector<nc_word>> c_on_codes, c_off_codes;
  std::uint32_t c_letters = 0;  // the letters of those codes
  // Canned hole cycles: the G codes of the machine's [cycles] drilling and tapping codes (G81,
  // G83, G84 ...), along Z, and of its side cycles (G87, G88), along X.
  std::vector<int> hole_g, side_g;
  int hole_cycle = 0;  // the hole cycle in force: 1 along Z, 2 a side cycle; 0 none
  // The last hole a cycle block drilled since the last record: where the block's words put the
  // axes (the axis along the drill is the hole's bottom).
  struct nc_hole {
    bool valid = false, side = false;
    axis_state x, y, z;
    std::string text;
  } hole;
  bool said_hole = false;
  // A hole the program drilled with moves (a cycle the machine writes expanded, pecks): the
  // record's feed blocks that went deepest each way along Z while a CL cycle is on.
  struct fed_point {
    bool valid = false;
    axis_state x, y, z;
    std::string text;
  } fed_low, fed_high;
  bool length_on = false;       // a tool length offset in force (G43, G43.4, G43.5, G44)
  bool needs_length = false;    // a mill head's channel: Z is the gauge line without one
  bool foreign_offset = false;  // a work offset no spindle names (G56): another part frame
  bool shifted = false;         // offsets written (G10, #5221=), a coordinate setting: not known
  std::string shift_text;       // the block that set it, and its line in the program
  int shift_line = 0;
  bool said_shift = false;
  bool mirrored = false;         // under G51 or G51.1 (part of `frame`)
  bool rapid_in_record = false;  // a block of this record moved in rapid
  std::string rapid_text;
  int per_rev = -1;  // feed mode: 1 per revolution, 0 per minute, -1 unknown
  double f = -1;     // the F in force (program units)
  int h_from = -1;   // the length offset's H is the CL's offset (1) or tool (0); -1 unknown
  long h_word = -1;  // a mill's last H word (its length offset's register); -1 none read
  std::string h_text;
  bool system_c = false;  // G-code system C: G70/G71 are the units, G20/G21 cycles
  long t_offset = -1;     // the offset the last T word gave (its digits after the tool's); -1 unknown
  std::string s_expression, f_expression;  // S or F in force given as an expression (S[900*3])
  std::string skip_text;                   // a block under block delete since the last record
  std::string f_text;
  int work = -1;       // the workpiece spindle: its Z may run against the CL's
  bool moved = false;  // a move since the last record
  // The last block that moved: a view of the reader's line (kept by keep_texts before the
  // reader's bytes go) or a copy. A copy per block was a sixth of the comparison's reading.
  std::string move_copy;
  std::string_view move_view;         // not empty: the text, not copied yet
  std::array<axis_state, 3> hole_at;  // the block's X Y Z in a hole cycle (read_line)
  std::array<axis_state, 2> turned;   // x and y turned by C or polar interpolation (compare)
  // The last block that moved.
  const std::string& move_text() {
    if (!move_view.empty()) move_copy.assign(move_view), move_view = {};
    return move_copy;
  }
  void note_moved(std::string_view text) {
    if (text.empty()) move_copy.clear();
    move_view = text;
  }
  int move_line = 0;

  // The CL as read so far.
  int cl_tool = -1, cl_tool_line = 0;   // LOADTL / TURRET
  std::optional<double> cl_tool_table;  // cl_tool's length in the machine's [[tool]] table
  int cl_offset = -1;                   // its offset (LOADTL/n,adj; the tool's number when none)
  double cl_lead = -1;                  // THREAD/TURN's lead in mm while it is on; -1 off
  double cl_clamp = 0;                  // SPINDL/...,MAXRPM under CSS; 0 none
  int cl_spin_index = -1;               // the spindle SPINDL names (MAIN, SUB, LIVE); -1 none
  // The CL's spindle: -1 not given, 0 off, 1 turning; its speed in rpm or (css) m/min.
  int cl_spin = -1;
  bool cl_css = false;
  double cl_speed = 0;
  rotation cl_dir = rotation::none;
  int cl_spin_line = 0;
  double cl_mm = 1;
  double cl_feed = -1;  // mm/min or mm/rev; -1 none
  bool cl_per_rev = false;
  bool cl_cycle = false;
  cycle_event cl_cycle_record;  // the CL cycle in force: its FEDTO or DEPTH gives each hole's bottom
  bool cl_drilling = false;     // it drills along the tool (DRILL, DEEP, DEEP2, TAP), not a lathe cycle
  long compared = 0, passed = 0;
  // Each kind of finding is reported once per channel (the first is the one to fix; a
  // systematic error would otherwise repeat at every record of a long job).
  unsigned version = 0, fine_version = ~0u;  // changes seen; the state of the last right cut
  long reported = 0;                         // findings so far
  bool said_length = false, said_arc = false, said_coolant = false, said_skip = false,
       said_expression = false;
  bool said_offset = false, said_clamp = false;
  bool coolant_fine = false;  // the coolant held to the CL's since either last changed
  bool spindle_fine = false;  // the spindle held to the CL's since either last changed
  bool said_tip = false, said_rapid = false, said_feed = false, said_tool = false, said_spindle = false;
  // The last dwell written since the last record (a DELAY's own comes last: a wait's event
  // blocks before it are written at its record, attack 71 F1): its seconds, and whether a
  // control may count it in revolutions (written under feed per revolution, or with no feed
  // mode set: a control may keep the last program's G95, attack 71 F3).
  char dwell_address = 0;  // the machine's dwell template's time word (U in `G4 U{seconds}`)
  double dwell_scale = 1;  // its seconds per unit (0.001 for `P{ms}`)
  double dwelt = 0;        // seconds
  int dwells = 0;
  int dwell_mode = 0;  // its feed mode: 1 per revolution, 0 per minute, -1 not known
  std::string dwell_text;
  bool said_dwell = false;
  // The CAM's name of the tool an operation was made for (NX `TOOL PATH/..,TOOL,name`, CATIA
  // `TPRINT/name`), and the name in force when the program's tool was first held to it: an
  // operation for another tool, cut with no tool call between, is cut with the wrong tool (the
  // issue's item 6: post --tool 1 on an NX file of two operations).
  std::string cl_cam_name, cl_cam_record, named_cam;
  int cl_cam_line = 0, named_cam_line = 0;
  long named_tool = -1;                    // the program's tool named_cam belongs to
  unsigned cam_names = 0, cam_judged = 0;  // the CL's names read, and up to which one judged
  bool said_cam = false;
  // The record's blocks that turned C with the tip off the axis (the first `n_turns`), and the
  // CL's last motion point (part frame, mm; not known from a tool change to the next record).
  std::vector<c_turn_block> turns;
  std::size_t n_turns = 0;
  vec3 cl_prev;
  bool cl_prev_known = false, said_turn = false;

  void read_tool_call(const std::string& t) {
    const std::size_t at = t.find("T{tool");
    if (at == std::string::npos) return;
    const std::size_t close = t.find('}', at);
    if (close == std::string::npos) return;
    std::size_t i = close + 1;
    int digits = 0;
    while (i < t.size() && t[i] >= '0' && t[i] <= '9') ++digits, ++i;
    if (digits == 0 && t.compare(i, 8, "{offset:") == 0) {
      const std::size_t end = t.find('}', i);
      const std::string spec = t.substr(i + 8, end == std::string::npos ? 0 : end - i - 8);
      if (spec.size() < 2 || spec[0] != '0') return;  // no fixed width: the digits are not known
      digits = std::atoi(spec.c_str() + 1);
      i = end + 1;
    } else if (t.compare(i, 1, "{") == 0) {
      return;
    }
    tool_digits = digits;
    offset_in_call = t.find("{offset") != std::string::npos;
    offset_in_offset_call = ch.offset_call.find("{offset") != std::string::npos;
    for (const nc_word& w : split_nc_words(t))
      if (w.address == 'M' && w.numeric && w.number == 6) tool_m6 = true;
  }

  void send_away(axis_state& a, const char* why) {
    a.k = axis_state::kind::away;
    a.line = lines;
    a.why = why;
  }

  void set_axis(axis_state& a, const nc_word& w, bool incremental) {
    if (!w.numeric) {
      a.k = axis_state::kind::unknown;  // X#500: known when the block runs
      return;
    }
    // Without a decimal point the control counts least increments (`X44` is 0.044 mm).
    const double v = w.point ? w.number : w.number * increment;
    if (!incremental) {
      a.k = axis_state::kind::known;
      a.value = v;
    } else if (a.k == axis_state::kind::known) {
      a.value += v;
    }
  }

  bool offset_of(const std::vector<nc_word>& code) const {
    if (code.empty()) return false;
    const std::vector<nc_word>& words = *block_words;
    for (const nc_word& c : code) {
      bool found = false;
      for (const nc_word& w : words)
        if (w.address == c.address && w.numeric == c.numeric && w.number == c.number) found = true;
      if (!found) return false;
    }
    return true;
  }

  // A G43 on an indexing head's channel: the head's own offset (one of its codes, every word
  // as the machine file writes it: `G43 P1 H#3020`), or another register (`G43 P1 H5`).
  void note_head_offset(std::string_view text) {
    const std::vector<nc_word>& words = *block_words;
    head_wrong_why.clear();
    for (std::size_t i = 0; i < head_codes.size(); ++i) {
      const std::vector<nc_word>& code = head_codes[i];
      bool all = true;
      for (const nc_word& c : code) {
        bool found = false;
        for (const nc_word& w : words)
          found = found || (w.address == c.address && w.numeric == c.numeric &&
                            (c.numeric ? w.number == c.number : w.value == c.value));
        all = all && found;
      }
      // ... and the block's P and H are the code's own (`G43 P2 H#3020` is neither code).
      for (const nc_word& w : words) {
        if (w.address != 'P' && w.address != 'H') continue;
        bool in_code = false;
        for (const nc_word& c : code)
          in_code = in_code || (w.address == c.address && w.numeric == c.numeric &&
                                (c.numeric ? w.number == c.number : w.value == c.value));
        all = all && in_code;
      }
      if (!all) continue;
      head_used = static_cast<int>(i);  // (which one the tool wants, at its cut: head_spindle_wrong)
      head_used_text.assign(text);
      return head_wrong.clear();
    }
    head_wrong.assign(text), head_wrong_why.clear();
  }

  // The head's angle after a block that changed the tool or has the head's word: a tool change
  // forgets it (the changer may turn the head); the word sets it, absolute under G90 or G53,
  // added under G91, not known in a reference return (the word is the intermediate point's) or
  // as an expression. Without a decimal point it counts least increments, as C does.
  void note_head(const nc_word* w, bool home, bool machine, std::string_view text) {
    if (!w) return head_deg.reset();
    const bool incremental = !machine && !absolute;
    if (!w->numeric || home || (incremental && !head_deg)) return head_deg.reset();
    const double v = w->point ? w->number : w->number * (m.program.trailing_point ? 0.001 : 1.0);
    head_deg = incremental ? *head_deg + v : v;
    head_text.assign(text);
    head_line = lines;
  }

  // The tool's axis against the CL's, for a tool the live spindle turns: a turning tool's CL
  // gives no axis the head is indexed by, and a drill on the centre line stands still while
  // the part turns (both at the head's turning angle). Once a channel.
  void compare_axis(const event& e, const std::optional<vec3>& cl_axis, bool in_polar) {
    if (said_axis || !cl_axis || !head_deg || !head_dir.known()) return;
    const int sp = spindles_now().current();
    if (sp < 0 || !live[static_cast<std::size_t>(sp)]) return;
    const vec3 a = head_dir.machine_axis(*head_deg);
    if (in_polar && std::abs(a.x) > 1e-9) return;  // C is a coordinate there: only an axial tool is known
    const vec3 have = part_axis(a, x_div < 0 ? -1.0 : 1.0, z_sign(), in_polar ? 0.0 : c_turn());
    if (const std::optional<std::string> why = axis_fault(have, *cl_axis, axis_tolerance, "head points")) {
      said_axis = true;
      error(e, fmt::format("{}: the head was indexed by `{}` at line {} of the program", *why, head_text,
                           head_line));
    }
  }

  // A frame a chain's comparison does not follow: its records are passed over, said once.
  void note_unfollowed(std::string_view text) {
    if (!unfollowed_text.empty()) return;
    unfollowed_text.assign(text);
    unfollowed_line = lines;
  }
  void said_unfollowed(const event& e) {
    if (unfollowed_text.empty() || std::exchange(said_frame, true)) return;
    say(e, severity::warning,
        fmt::format(
            "the records under `{}` (line {} of its program) are not held to the CL: the comparison does "
            "not follow that frame",
            unfollowed_text, unfollowed_line));
  }

  // At a cut: the head's turning offset for a tool that turns with the part's spindle or stands
  // while the part turns (a centre drill), the live one for a tool the live spindle turns (the
  // issue's item 10; the Fusion "Mazak Integrex i" post, rev. 44083, writes `G43 P1` for turning
  // and axial centre drilling). Judged where the tool cuts, not at the offset's block: a SPINDL
  // may come after the approach that gave the offset (attack 69 H1).
  bool head_spindle_wrong(const event& e) {
    const int sp = spindles_now().current();
    if (head_used < 0 || head_turning < 0 || head_live < 0 || sp < 0 || !head_wrong.empty() ||
        ch.head_index.offset_turning == ch.head_index.offset_live)
      return head_offset_wrong(e);
    const int want = live[static_cast<std::size_t>(sp)] ? head_live : head_turning;
    if (want == head_used) return false;
    head_wrong = head_used_text;
    head_wrong_why = fmt::format(
        "the head's offset for a {} tool, and the tool cuts with the {} spindle, whose "
        "offset code is `{}`",
        want == head_live ? "turning or stationary" : "live", m.spindles[static_cast<std::size_t>(sp)].name,
        want == head_live ? ch.head_index.offset_live : ch.head_index.offset_turning);
    return head_offset_wrong(e);
  }

  // The head's offset is another than its codes give: X Y Z are not the tip (once per channel).
  bool head_offset_wrong(const event& e) {
    if (head_wrong.empty()) return false;
    if (!std::exchange(said_head, true)) {
      if (!head_wrong_why.empty())  // (review 37 item 10: `G43 P1` is the Integrex's turning offset)
        error(
            e,
            fmt::format(
                "the head's tool length offset is not the tool's: `{}` gives {}: X Y Z are not the tool tip",
                head_wrong, head_wrong_why));
      else
        error(e, fmt::format(
                     "the head's tool length offset is not the machine's here: `{}` left {} in force where "
                     "the head's offset codes give {}: X Y Z are not the tool tip",
                     head_wrong, head_wrong.find("G43") != std::string::npos ? "another offset" : "none",
                     head_code_text()));
    }
    ++passed;
    return true;
  }

  std::string head_code_text() const {
    std::string out;
    for (const std::string* code : {&ch.head_index.offset_turning, &ch.head_index.offset_live})
      if (!code->empty()) out += fmt::format("{}`{}`", out.empty() ? "" : " or ", *code);
    return out;
  }

  // `text`, split here (the writer's thread: post on one core), or split already into
  // `split` with `letters` (the self-check's reading: nc_block), as line `at` of the program.
  void line(std::string_view text, const std::vector<nc_word>* split = nullptr,
            std::uint32_t split_letters = 0, int at = 0) {
    const bool was = shifted, was_mirrored = mirrored;
    std::uint32_t letters = 0;
    if (split) {
      block_words = split;  // views into `text`, as a split of our own
      letters = split_letters;
      lines = at;
    } else {
      letters = split_nc_words(text, own_words);
      block_words = &own_words;
      ++lines;
    }
    read_line(text, letters);
    block_words = &own_words;       // (the reader's words are its until its next block)
    if (!split) (void)move_text();  // (a line of the writer's: copied at once)
    if ((shifted && !was) || (mirrored && !was_mirrored && !shifted)) {
      shift_text.assign(text);
      shift_line = lines;
    }
  }

  void read_line(std::string_view text, const std::uint32_t letters) {
    const std::vector<nc_word>& words = *block_words;
    // A block under block delete (`/G0 X44. Z2.`) runs or not as the operator's switch says (a
    // wait or another M code under it is the checker's).
    constexpr std::uint32_t skip_letters = nc_letter('X') | nc_letter('Y') | nc_letter('Z') | nc_letter('U') |
                                           nc_letter('V') | nc_letter('W') | nc_letter('G') | nc_letter('F') |
                                           nc_letter('S') | nc_letter('T');
    std::size_t at = 0;
    while (at < text.size() && (text[at] == ' ' || text[at] == '\t')) ++at;
    if (at < text.size() && text[at] == '/' && skip_text.empty() && (letters & skip_letters) != 0)
      skip_text.assign(text);
    if (letters & nc_variable_bit)
      for (const macro_use& u : macro_uses(text))
        if (u.write && (u.number < 0 || (u.number >= 2500 && u.number <= 2806) ||
                        (u.number >= 5201 && u.number <= 5335) || (u.number >= 7001 && u.number <= 7999) ||
                        (u.number >= 14001 && u.number <= 14999)))
          shifted = true;  // a work offset written through its variable (#5223=-5.)
    if (words.empty()) return;
    // The unit, G90/G91, the plane and the feed mode: the modal state's, this block applied
    // (only a G word changes them).
    if (!modes_given) own_modes.block(ch.number, words, letters);
    if (const channel_modes& md = modes_given ? *modes_given : own_modes.channel(ch.number); md.now.any)
      take_modes(md);
    // (Its swings are the emulator's to report, in check and in post's self-check.)
    if (mid_staged) settle_chain_block();     // before this block moves the follower on
    if (plain_pending) settle_plain_block();  // (before this line moves the axes on)
    if (chain) chain->block(words, modes_given ? *modes_given : own_modes.channel(ch.number));
    // Any word but an axis's (a G, M, S, T, F ...) may change what a cut is held to.
    constexpr std::uint32_t axis_letters = nc_letter('X') | nc_letter('Y') | nc_letter('Z') | nc_letter('U') |
                                           nc_letter('V') | nc_letter('W') | nc_letter('I') | nc_letter('J') |
                                           nc_letter('K') | nc_letter('R') | nc_letter('N');
    // (A chain's rotary words are axis words too.)
    if (letters & ~(axis_letters | chain_letters)) ++version;
    constexpr std::uint32_t gms = nc_letter('G') | nc_letter('M') | nc_letter('S');
    if (!gms_only || (letters & gms)) {
      if (!spindles_given) own_spindles.apply(words);
      spindle_fine = false;
      // The workpiece spindle: its work offset (G55 for the sub) or its select code; a live
      // spindle's select code does not move the part.
      for (std::size_t i = 0; i < m.spindles.size(); ++i) {
        const spindle_def& s = m.spindles[i];
        if (offset_of(offsets[i])) work = static_cast<int>(i);
        if (s.select && !live[i])
          for (const nc_word& w : words)
            if (w.address == 'M' && w.numeric && w.number == *s.select) work = static_cast<int>(i);
      }
    }
    if (letters & coolant_letters)
      for (const coolant_code& c : coolant_codes)
        if (offset_of(c.words)) {
          nc_coolant = c.kind;
          coolant_text.assign(text);
          coolant_fine = false;
        }
    if (letters & c_letters) {
      // The spindle held as a C axis: where C stands is not known until a C word (or its
      // reference return) says; back to a turning spindle, the part frame is the program's.
      for (const auto& c : c_on_codes)
        if (offset_of(c)) c_known = false;
      for (const auto& c : c_off_codes)
        if (offset_of(c)) c_known = true, c_deg = 0;
    }
    const double c_before = c_deg;
    const bool c_known_before = c_known;
    bool not_a_move = false, home = false, machine = false, setting = false, m6 = false, tool_call = false,
         dwell = false;
    const nc_word* head_word = nullptr;
    const char* home_why = "";
    // Most lines are moves with axis words and an F: only the F is read before the axes. A whole
    // chain's rotary words are such a line's too (the chain follows them; no C of the part,
    // no head index, no rotary left unfollowed on its channel: the loop below passes them by).
    const bool plain = (letters & ~(axis_letters | nc_letter('F') | chain_letters)) == 0;
    if (plain)
      for (const nc_word& w : words)
        if (w.address == 'F') take_feed(w);
    if (plain && !cycle && motion != 2 && motion != 3) [[likely]]
      return read_plain_move(text, letters);
    for (const nc_word& w : plain ? no_words : words) {
      if (w.address == 'T') {
        // The control applies the new tool's offsets with its next move: the program's
        // coordinates stay those of the tip.
        rotary = false;
        if (tool_digits >= 0 && w.numeric && w.number >= 0) {
          const long scale = std::lround(std::pow(10.0, tool_digits));
          const long t = static_cast<long>(w.number);
          // The offset: the digits after the tool's, where the call writes them ({offset}), or
          // a T alone where the channel's offset call does (M6 T0700, then T0707).
          const bool change = !tool_m6 || has_word(words, 'M', 6);
          if (change) {
            t_pending = t / scale;
            t_offset = offset_in_call ? t % scale : -1;
          } else if (offset_in_offset_call) {
            t_offset = t % scale;
          } else {
            t_pending = t / scale;  // a preselection: the tool changes at M6
          }
          t_text.assign("T").append(w.value);
          if (!tool_m6) t_active = t_pending, tool_call = true;
        } else {
          t_pending = t_active = t_offset = -1;  // T#1, or a template the tool is not read from
        }
        continue;
      }
      if (w.address == 'M' && w.numeric && w.number == 6 && tool_m6) {
        m6 = true;  // the block's T, wherever it stands in the block, is the tool changed to
        continue;
      }
      if (w.address == 'S') {
        // An expression's speed is known only when the block runs.
        if (w.numeric)
          s_expression.clear();
        else
          s_expression.assign("S").append(w.value);
        continue;
      }
      if (w.address == 'H' && needs_length) {
        h_word = w.numeric ? static_cast<long>(w.number) : -1;
        h_text.assign("H").append(w.value);
        continue;
      }
      if (w.address == 'F') {
        take_feed(w);
        continue;
      }
      if (w.address == head_address) {
        // A head index `G0 G53 B90.`: the tool turned; its tip is X Y Z again once the head's
        // length offset is given (the writer's first move after the index).
        head_due = head_offset;
        head_word = &w;
        continue;
      }
      if (w.address == 'C' && has_c) {
        // A C position turns the part under X and Y. In a G28 block C goes to its reference
        // point (the word is the intermediate point's); after G30, G27, G29 or G53, and in polar
        // or cylindrical interpolation (C no angle of the part frame), where it stands is not
        // known. Without a decimal point the word counts least increments (`C120` is 0.12
        // degrees where decimal-point programming is off), as X, Y and Z do.
        if (polar && polar_follow) {
          // In polar interpolation C is the face's second coordinate (the block's G90/G91 as
          // for any axis word); where the C axis stands after the mode is not known.
          set_axis(polar_c, w, has_word(words, 'G', 91) || (!has_word(words, 'G', 90) && !absolute));
          c_known = false;
        } else if (has_word(words, 'G', 28)) {
          c_deg = 0, c_known = true;
        } else if (!w.numeric || polar || cylinder || has_word(words, 'G', 7.1) ||
                   has_word(words, 'G', 107) || has_word(words, 'G', 30) || has_word(words, 'G', 27) ||
                   has_word(words, 'G', 29) || has_word(words, 'G', 53) || has_word(words, 'G', 50) ||
                   has_word(words, 'G', 92) || has_word(words, 'G', 52)) {
          // (G50, G92, G52 with C set C's origin: a coordinate setting, the records after it
          // passed over.)
          c_known = false;
        } else {
          const double v = w.point ? w.number : w.number * (m.program.trailing_point ? 0.001 : 1.0);
          // The block's G90/G91 holds for its C wherever it stands in the block.
          const bool block_absolute = has_word(words, 'G', 91)                ? false
                                      : g90_modes && has_word(words, 'G', 90) ? true
                                                                              : absolute;
          if (block_absolute)
            c_deg = v, c_known = true;
          else
            c_deg += v;
        }
        continue;
      }
      if (w.address == 'H' && has_c && !needs_length) {
        // Fanuc's incremental C (G-code system A; `G28 H0.` its reference return), or the
        // head's offset register (G43 H#3020: the head's length offset, below).
        // On a head whose offset codes name an H register, an H is the offset's (G49 H0, G43.4
        // H5, a bare H5 in G43 mode: attack 48), held to the head's codes.
        if (has_word(words, 'G', 28))
          c_deg = 0, c_known = true;
        else if (head_offset && !has_word(words, 'G', 43) && !has_word(words, 'G', 43.4) &&
                 !has_word(words, 'G', 43.5) && !has_word(words, 'G', 44) && !has_word(words, 'G', 49))
          head_wrong.assign(text), head_wrong_why.clear();
        else if (!head_offset && !has_word(words, 'G', 43) && !has_word(words, 'G', 44))
          c_known = false;
        continue;
      }
      if (w.address == 'A' || w.address == 'B' || w.address == 'C') {
        // An A or B that is no indexing head's, a C of a channel without one: the tip then
        // depends on rotary axes this comparison does not follow (a chain's are: `chain`).
        if (!(w.address == 'C' && cylinder) && !whole_chain) rotary = true;
        continue;
      }
      if (w.address != 'G' || !w.numeric) continue;
      const int g = g10(w.number);
      if (g >= 730 && g <= 890) {
        if (std::find(side_g.begin(), side_g.end(), g) != side_g.end())
          hole_cycle = 2;
        else if (std::find(hole_g.begin(), hole_g.end(), g) != hole_g.end())
          hole_cycle = 1;
      } else if (g == 0 || g == 10 || g == 20 || g == 30 || g == 800) {
        hole_cycle = 0;
      }
      switch (g) {
        case 0:
        case 10:
        case 20:
        case 30: cycle = false; break;  // (the motion: the modal state's)
        case 320:
        case 330:
        case 340: cycle = false; break;
        case 800: cycle = false; break;
        case 700:
        case 710:
          // G-code system C: G70 inch, G71 metric (the modal state's; its lathe cycles are
          // G72-G78).
          if (!system_c) cycle = true;
          break;
        case 770:
        case 780:
          if (system_c) cycle = true;
          break;
        case 720:
        case 730:
        case 740:
        case 750:
        case 760:
        case 810:
        case 820:
        case 830:
        case 840:
        case 842:
        case 843:
        case 850:
        case 860:
        case 870:
        case 880:
        case 890: cycle = true; break;
        case 900:
          // (G90 and G91 in systems B and C, and on a mill: the modal state's.)
          if (!g90_modes) cycle = true;  // a lathe's G90 (G-code system A): the turning cycle
          break;
        case 200:
        case 210:
          if (system_c) cycle = true;  // system C's G20, G21: the OD and threading cycles (else units)
          break;
        case 430:
          head_due = false;
          length_on = true;
          if (head_offset) note_head_offset(text);
          break;
        case 434:
        case 435:
          length_on = true;
          if (head_offset) note_head_offset(text);
          break;
        case 440:  // G44 subtracts the offset: never the tip
        case 490:
          length_on = false;
          if (head_offset) head_wrong.assign(text), head_wrong_why.clear();
          break;
        case 540:
        case 550:
        case 560:
        case 570:
        case 580:
        case 590:
        case 541: {
          bool named = false, any = false;
          for (const auto& o : offsets) named = named || offset_of(o), any = any || !o.empty();
          foreign_offset = any && !named;  // G56 where the spindles name G54 and G55: another part frame
          break;
        }
        case 920:
        case 940:
          if (!g90_modes)
            cycle = true;
          else if (g == 920)
            setting = true, shifted = shifted || any_axis(words);
          break;
        case 121:
        case 1120:
          polar = true;
          polar_follow = has_c && c_known && std::abs(c_turn()) < 1e-6;
          polar_c = axis_state{};
          break;
        case 131:
        case 1130: polar = polar_follow = false; break;
        case 71:
        case 1070: {
          cylinder = false;
          for (const nc_word& c : words)
            if (c.address == 'C' && c.numeric && c.number != 0) cylinder = true;
          not_a_move = true;
          break;
        }
        case 511:
        case 510:
          mirrored = true;  // the post writes neither: a user's mirror image or scaling
          [[fallthrough]];
        case 680:
        case 681:
        case 682:
        case 683:
        case 684: {
          // A chain's tilted plane is followed (`chain`), but for the forms the post never
          // writes: G68.2 with P (another angle convention), G68.3, G68.4, G68 (attack 63 H3:
          // passed over without a word, or G68.3's X Y Z read as a move).
          const bool followed = g == 682 && whole_chain && !has_address(words, 'P');
          frame = frame || !followed;
          if (!followed && whole_chain) note_unfollowed(text);
          not_a_move = true;
          break;
        }
        case 542:
          // A rotary fixture offset (G54.2 Pn; P0 ends it): the part frame turns with the table.
          fixture = false;
          for (const nc_word& p : words)
            if (p.address == 'P' && (!p.numeric || p.number != 0)) fixture = true;
          if (fixture && whole_chain) note_unfollowed(text);
          break;
        case 690:
        case 501:
          // The axes a frame's blocks set are its coordinates, not the part's.
          if (frame) x.k = y.k = z.k = axis_state::kind::unknown;
          frame = mirrored = false;
          break;
        case 160: polar_coords = true; break;
        case 150: polar_coords = false; break;
        case 280:
        case 300:
          home = true;
          home_why = g == 280 ? "G28" : "G30";
          break;
        case 530: machine = true; break;
        case 500:
        case 520:
          setting = true;
          shifted = shifted || any_axis(words);  // a coordinate setting or a local frame
          break;
        case 100:
          // Offset data written (G10 L2 P1 Z-5., a workpiece shift G10 P0 Z..): the part frame
          // is no longer the setup's.
          shifted = true;
          not_a_move = true;
          break;
        case 109:
          // Mazak radius input (G10.9 X0) and diameter input (G10.9 X1) of X.
          for (const nc_word& c : words)
            if (c.address == 'X' && c.numeric && lathe)
              x_div = std::copysign(c.number == 0 ? 1.0 : 2.0, x_div);
          not_a_move = true;
          break;
        case 270:
        case 290:
          // A reference point check or a return from it: the named axes rapid to the point,
          // then where the control leaves them (G29 moves on from the reference point).
          home = true;
          home_why = g == 270 ? "G27" : "G29";
          break;
        case 40:
          dwell = true;
          not_a_move = true;
          break;
        case 650:
        case 661: not_a_move = true; break;
        default: break;
      }
    }
    if (dwell && dwell_address) [[unlikely]]
      note_dwell(words, text);
    if (m6) t_active = t_pending;
    if (m6 || tool_call || head_word) [[unlikely]]
      note_head(head_word, home, machine, text);
    // The axis words (an arc's centre is measured from where the block starts).
    const double start[3] = {x.value, y.value, z.value};
    const bool start_known = x.k == axis_state::kind::known && z.k == axis_state::kind::known &&
                             (!has_y || y.k == axis_state::kind::known || plane == 18);
    bool any = false;
    if (hole_cycle) hole_at = {x, y, z};  // where a hole cycle's block puts the axes
    bool repeats = false;                 // a cycle block's repeat count (K or L) above 1
    if (cycle)
      for (const nc_word& w : words)
        if ((w.address == 'K' || w.address == 'L') && (!w.numeric || w.number > 1)) repeats = true;
    for (const nc_word& w : words) {
      bool incremental = !absolute;
      axis_state* const a = axis_of(w, incremental);
      if (!a) continue;
      any = true;
      if (not_a_move) continue;
      if (home)
        send_away(*a, home_why);
      else if (machine)
        send_away(*a, "G53");
      else if (setting || cycle) {
        if (hole_cycle && !setting) set_axis(hole_at[a == &x ? 0 : a == &y ? 1 : 2], w, incremental);
        // A hole cycle leaves the axes across its drill at the hole (G81 X20. Y8.: Y stays at 8
        // after G80), unless it repeats (K, L: the holes step on); the axis along the drill
        // ends at the R or initial level.
        const bool across = hole_cycle == 1 ? a != &z : hole_cycle == 2 ? a != &x : false;
        if (across && !setting && !repeats)
          set_axis(*a, w, incremental);
        else
          a->k = axis_state::kind::unknown;
      } else
        set_axis(*a, w, incremental);
    }
    if (has_c && c_known && c_known_before && c_deg != c_before && !polar && !cylinder && !frame && !rotary &&
        !cycle && !not_a_move && !home && !machine && !setting && (motion == 0 || motion == 1)) [[unlikely]]
      note_turn(start, start_known, c_before, text);
    if (any && hole_cycle && cycle && !not_a_move && !home && !machine && !setting) {
      hole.valid = true;
      hole.side = hole_cycle == 2;
      hole.x = hole_at[0], hole.y = hole_at[1], hole.z = hole_at[2];
      hole.text.assign(text);
    }
    // A reference return, check or machine-coordinate block moves its axes at rapid: inside a
    // feed move that is a rapid through the cut (G28 Z-30. passes its intermediate point).
    if (any && !not_a_move && (home || machine) && !rapid_in_record) {
      rapid_in_record = true;
      rapid_text.assign(text);
    }
    if (any && !not_a_move && !home && !machine && !setting) {
      note_move(text);
      if ((motion == 2 || motion == 3) && !cycle) note_arc(start, start_known);
    }
    stage_block(text, letters, any, not_a_move, home || machine, setting);
  }

  // The axis state word `w` sets (X, Y, Z; U, V, W where they are increments: `incremental`
  // then true), or none.
  axis_state* axis_of(const nc_word& w, bool& incremental) {
    switch (w.address) {
      case 'X': return &x;
      case 'Y': return &y;
      case 'Z': return &z;
      case 'U': return u_incremental ? (incremental = true, &x) : nullptr;
      case 'W': return w_incremental ? (incremental = true, &z) : nullptr;
      case 'V': return v_incremental ? (incremental = true, &y) : nullptr;
      default: return nullptr;
    }
  }

  // A block of axis words (an F among them) and nothing else, out of a cycle, not an arc:
  // read_line's way for it with every other word's flag at rest (most blocks of a program).
  void read_plain_move(std::string_view text, std::uint32_t letters) {
    bool any = false;
    for (const nc_word& w : *block_words) {
      bool incremental = !absolute;
      if (axis_state* const a = axis_of(w, incremental)) {
        any = true;
        set_axis(*a, w, incremental);
      }
    }
    if (any) note_move(text);
    stage_block(text, letters, any, false, false, false);
  }

  // A block that moved an axis of the part frame (no home, no machine coordinates, no
  // setting): the last that moved, and a feed in a CL cycle or a rapid as they go.
  void note_move(std::string_view text) {
    moved = true;
    note_moved(text);
    move_line = lines;
    if (cl_cycle && cl_drilling && motion == 1 && !cycle) [[unlikely]]
      note_fed(text);
    // A rapid with X or Z still at its reference point or machine position (the Y set to the
    // centre line at the tool-change position before polar interpolation) is far from the
    // part: no rapid through the cut.
    if (motion == 0 && !cycle && !rapid_in_record && x.k != axis_state::kind::away &&
        z.k != axis_state::kind::away) {
      rapid_in_record = true;
      rapid_text.assign(text);
    }
  }

  // The block staged as a chain's or a plain channel's block between two records. `away`: a
  // return to the reference point or to machine coordinates.
  void stage_block(std::string_view text, std::uint32_t letters, bool any, bool not_a_move, bool away,
                   bool setting) {
    // A chain's feed block between two records: where it puts the tip, held at the next record
    // to the CL's straight move (attack 63 M4: an `on_block` block dipped 20 mm mid-move).
    // A rapid, an arc or a return to the reference point or to machine coordinates there is
    // no part of a straight feed move at all (attack 66 M3, M4: an INSERT's G0 plunge, a G2
    // circle, a G53 G1 posted).
    // (Under tool-tip control a rapid of rotary words alone turns the tool about its tip: the
    // writer's turn at the pole, `G0 C90.`, moves no tip; review 67 M1.)
    constexpr std::uint32_t xyz = nc_letter('X') | nc_letter('Y') | nc_letter('Z');
    if (chain && motion >= 0 && motion <= 3 && !cycle && !not_a_move && !setting &&
        (letters & (xyz | chain_letters)) != 0 && (whole_chain || chain->tool_tip_on()) &&
        !(motion == 0 && !away && (letters & xyz) == 0 && chain->tool_tip_on())) [[unlikely]]
      stage_chain_block(text, away          ? mid_kind::away
                              : motion == 0 ? mid_kind::rapid
                              : motion >= 2 ? mid_kind::arc
                                            : mid_kind::feed);
    if (!chain && any && !not_a_move && !setting && !cycle && !said_plain)
      stage_plain_block(text, away                         ? mid_kind::away
                              : motion == 0                ? mid_kind::rapid
                              : motion == 2 || motion == 3 ? mid_kind::arc
                                                           : mid_kind::feed);  // (G32: a straight cut)
  }

  // A block of a channel without a chain that moved since the last motion record. Most are the
  // record's own block, held by the record's comparison: it waits as `plain_next`, and what it is
  // and where it ends goes into `plains` only when another line comes before the record
  // (settle_plain_block), the state still where it left it. A move of more than 4096 blocks is
  // refused at its record.
  void stage_plain_block(std::string_view text, mid_kind kind) {
    plain_next.line = lines;
    plain_next.kind = kind;
    // A block that moved is move_text until the next line.
    plain_next.text_later = move_line == lines;
    if (!plain_next.text_later) plain_next.text.assign(text);
    plain_pending = true;
  }

  // The waiting block, with its text and where it ends when every axis of the part frame is known
  // and plain (no C turned, polar or cylindrical interpolation, frame or shift; the record's own
  // comparison passes those over).
  void settle_plain_block() {
    plain_pending = false;
    if (n_plains == 4096) {  // (bounded memory: a move past it is refused at its record)
      plains_over = true;
      return;
    }
    if (n_plains == plains.size()) plains.emplace_back();
    chain_block& b = plains[n_plains++];
    b.line = plain_next.line;
    b.kind = plain_next.kind;
    b.text = plain_next.text_later ? move_text() : plain_next.text;
    b.tip.reset();
    b.unknown = false;
    const auto known = [](const axis_state& a) { return a.k == axis_state::kind::known; };
    // A feed to an axis word given by a variable (`G1 X#100 Z-15.`): where it ends is known only
    // when the block runs (attack 68 M5). Read again from its text: rare.
    if (b.kind == mid_kind::feed && (!known(x) || !known(z) || (has_y && !known(y))))
      for (const nc_word& w : split_nc_words(std::string_view(b.text)))
        if (w.expression && std::string_view("XYZUVW").find(w.address) != std::string_view::npos)
          b.unknown = true;
    if (b.kind == mid_kind::away || polar || cylinder || frame || polar_coords || rotary || shifted ||
        foreign_offset || head_due || !c_known || c_deg != 0 || !known(x) || !known(z) ||
        (has_y && !known(y)))
      return;
    const double zs = z_sign();
    b.tip = vec3{part(x, x_div), has_y ? part(y, zs) : 0.0, part(z, zs)};
  }

  // At a feed record of a channel without a chain: its blocks since the last motion record but
  // the last (whose end is the record's point, held by compare) against the CL's straight move
  // from the record before to `to` (mm), within `tol`; once a channel. A feed block must end on
  // that move; a rapid anywhere but at its start (where the tool stands: a move back there is
  // the CL's own), an arc or a return to the reference point or machine coordinates is no part
  // of a straight feed move.
  void hold_plain_blocks(const event& e, const vec3& to, double tol) {
    // The last block that moved is the record's own, whether a line after it (an M8) has put it
    // into plains or not.
    const std::size_t held = plain_pending ? n_plains : n_plains > 0 ? n_plains - 1 : 0;
    if (held == 0 || !cl_prev_known || said_plain) return;
    if (plains_over) {  // (attack 68 H3: a first version held 64 blocks and let the 65th through)
      said_plain = true;
      return error(e,
                   fmt::format("the program writes more than {} blocks inside the CL's straight feed move "
                               "to this record's point: they are not held to it; give the move as CL records",
                               plains.size()));
    }
    const vec3 from = cl_prev;
    const auto off_line = [&](const vec3& p) { return off_segment(from, to, p); };
    const auto move = [&] {
      return fmt::format("the CL's straight feed move from ({:.3f}, {:.3f}, {:.3f}) to this record's point",
                         from.x, from.y, from.z);
    };
    for (std::size_t i = 0; i < held; ++i) {
      const chain_block& b = plains[i];
      if (b.kind == mid_kind::rapid && b.tip && kin::distance(*b.tip, from) <= tol) continue;
      if (b.kind != mid_kind::feed) {
        // (A rapid among this record's own blocks is said as such: compare_rest.)
        if (b.kind != mid_kind::arc && rapid_in_record) continue;
        said_plain = true;
        error(e, fmt::format(
                     "the program's block `{}` (line {} of its program) is {} inside {}{}", b.text, b.line,
                     b.kind == mid_kind::rapid ? "a rapid"
                     : b.kind == mid_kind::arc ? "an arc"
                                               : "a return to the reference point or to machine coordinates",
                     move(),
                     b.kind == mid_kind::rapid && b.tip
                         ? fmt::format(", to ({:.3f}, {:.3f}, {:.3f}): the feed then starts there", b.tip->x,
                                       b.tip->y, b.tip->z)
                         : std::string()));
        return;
      }
      if (b.unknown) {
        said_plain = true;
        return error(e,
                     fmt::format("the program's block `{}` (line {} of its program) moves the tool inside {} "
                                 "to an axis word given by a variable or an expression: where it cuts is "
                                 "known only when the block runs",
                                 b.text, b.line, move()));
      }
      if (!b.tip) continue;
      if (const double off = off_line(*b.tip); off > tol) {
        said_plain = true;
        error(e, fmt::format(
                     "the program's block `{}` (line {} of its program) takes the tool tip {:.3f} mm off "
                     "{}, to ({:.3f}, {:.3f}, {:.3f}) (the part frame, mm)",
                     b.text, b.line, off, move(), b.tip->x, b.tip->y, b.tip->z));
        return;
      }
    }
  }

  // A chain's block between two records, staged: where its tip goes is worked out when the next
  // block comes (the follower still where this one left it), not for the last before a record,
  // whose end is the record's point (compare_chain). A move of more blocks is held at its first
  // 4096.
  void stage_chain_block(std::string_view text, mid_kind kind) {
    if (said_mid || n_mids == 4096) return;
    if (n_mids == mids.size()) mids.emplace_back();
    chain_block& b = mids[n_mids];
    b.line = lines;
    // A feed block that moved X, Y or Z is move_text until the next block: its text is taken
    // from there when that one comes (the last before a record is never copied; its findings
    // quote move_text).
    b.text_later = kind == mid_kind::feed && move_line == lines;
    if (!b.text_later) b.text.assign(text);
    b.kind = kind;
    b.tip.reset();
    b.sag.reset();
    mid_staged = true;
  }

  // The staged block's tip (the part frame, mm) and where it is halfway along the block, when
  // its words say it without the tool's length or with the length known. A rapid, an arc or a
  // return is said as it is.
  void settle_chain_block() {
    mid_staged = false;
    chain_block& b = mids[n_mids];
    if (b.text_later) b.text = move_text();
    if (b.kind != mid_kind::feed) {
      ++n_mids;
      return;
    }
    if (needs_length && (!chain->length_on() || h_word == 0) && chain_def->output != multiaxis_output::pivot)
      return;  // (the record says so)
    const std::optional<double> length = chain_length();
    const std::optional<rotary_sweep::pose> at = chain->where(length.value_or(0));
    if (!at) return;
    if (!length)
      if (const std::optional<rotary_sweep::pose> longer = chain->where(100);
          !longer || kin::distance(longer->tip, at->tip) > tip_tolerance / 10)
        return;
    b.tip = at->tip;
    b.sag = chain_sag(length);
    ++n_mids;
  }

  // Where the last block's tip is halfway along it as the control interpolates the joints (the
  // most a short block's tip path sags from the straight line between its ends); none where it
  // runs straight or is not known (attack 66 M2: one block from a move's first sub-move to its
  // end, both ends on the CL's line, sagged 3.18 mm below the floor halfway).
  std::optional<vec3> chain_sag(const std::optional<double>& length) const {
    if (!length && chain_def->output != multiaxis_output::pivot) return std::nullopt;
    const std::optional<rotary_sweep::pose> mid = chain->where_along(length.value_or(0), 0.5);
    return mid ? std::optional(mid->tip) : std::nullopt;
  }

  // A chain's blocks since the last record against the CL's straight move from the record before
  // to `to`, within `tol`: once a channel. `last`: halfway along the block that ends at the
  // record.
  // `straight`: a GOTO's move (else a CIRCLE's: only a rapid or a return among its blocks is
  // said, its arc blocks are the arc's comparison's).
  void hold_chain_blocks(const event& e, const vec3& to, double tol, const std::optional<vec3>& last,
                         const std::string& last_text, int last_line, bool straight) {
    const vec3 from = cl_prev;
    const auto off_line = [&](const vec3& p) { return off_segment(from, to, p); };
    // (Formatted for a finding only: at every record it was a third of the comparison's time.)
    const auto move = [&] {
      return fmt::format("the CL's straight move from ({:.3f}, {:.3f}, {:.3f}) to this record's point",
                         from.x, from.y, from.z);
    };
    // Halfway along a block the joints' interpolation may leave the line by the chain's
    // chordal tolerance, as the writer cuts its moves (kin::linearise).
    const double sag_tol = tol + chain_def->chordal_tolerance;
    const auto sagged = [&](const std::string& text, int line, const vec3& p) {
      said_mid = true;
      error(e,
            fmt::format(
                "halfway along the program's block `{}` (line {} of its program) the tool tip is {:.3f} mm "
                "off {}, at ({:.3f}, {:.3f}, {:.3f}), as the control moves the joints (the part frame, "
                "mm; the forward transform of its words)",
                text, line, off_line(p), move(), p.x, p.y, p.z));
    };
    for (std::size_t i = 0; i < n_mids; ++i) {
      const chain_block& b = mids[i];
      if (!straight && (b.kind == mid_kind::feed || b.kind == mid_kind::arc)) continue;
      if (b.kind != mid_kind::feed) {
        // (A rapid among this record's own blocks is said as such: compare_rest.)
        if (b.kind != mid_kind::arc && rapid_in_record) continue;
        said_mid = true;
        error(e, fmt::format(
                     "the program's block `{}` (line {} of its program) is {} inside {}", b.text, b.line,
                     b.kind == mid_kind::rapid ? "a rapid"
                     : b.kind == mid_kind::arc ? "an arc"
                                               : "a return to the reference point or to machine coordinates",
                     move()));
        return;
      }
      if (!b.tip) continue;
      if (const double off = off_line(*b.tip); off > tol) {
        said_mid = true;
        error(e,
              fmt::format(
                  "the program's block `{}` (line {} of its program) takes the tool tip {:.3f} mm off "
                  "{}, to ({:.3f}, {:.3f}, {:.3f}) (the part frame, mm; the forward transform of its words)",
                  b.text, b.line, off, move(), b.tip->x, b.tip->y, b.tip->z));
        return;
      }
      if (b.sag && off_line(*b.sag) > sag_tol) return sagged(b.text, b.line, *b.sag);
    }
    if (straight && last && off_line(*last) > sag_tol) sagged(last_text, last_line, *last);
  }

  // A block that turned C (G0 or G1): the part turns under the tool, whose tip runs round the
  // part's axis. Under G0 inside a CL feed move that is a rapid through the cut (review 55: a
  // `G0 C..` with no X, Y or Z word was no move at all to the comparison).
  void note_turn(const double* start, bool start_known, double c0, std::string_view text) {
    const auto known = [](const axis_state& a) { return a.k == axis_state::kind::known; };
    if (!start_known || !known(x) || !known(z) || (has_y && !known(y))) return;
    const double zs = z_sign();
    const vec3 from{start[0] * out_mm / x_div, has_y ? start[1] * out_mm * zs : 0.0, start[2] * out_mm * zs};
    const vec3 to{part(x, x_div), has_y ? part(y, zs) : 0.0, part(z, zs)};
    const double tol = std::max(tip_tolerance, axis_half * 3.001);
    if (std::hypot(from.x, from.y) <= tol && std::hypot(to.x, to.y) <= tol) return;  // on the axis
    if (n_turns == turns.size()) turns.emplace_back();
    c_turn_block& b = turns[n_turns++];
    b.start = from, b.end = to, b.c0 = c0, b.c1 = c_deg, b.rapid = motion == 0;
    b.text.assign(text);
    moved = true;
    note_moved(text);
    move_line = lines;
    if (b.rapid && !rapid_in_record) {
      rapid_in_record = true;
      rapid_text.assign(text);
    }
  }

  // The record's C turns against the CL's move to `pos` (docs/emulator.md).
  void compare_turns(const event& e, const vec3& pos, const std::optional<vec3>& axis, bool feed) {
    if (n_turns == 0 || said_turn) return;
    const vec3 to{pos.x * cl_mm, pos.y * cl_mm, pos.z * cl_mm};
    const double tol = std::max(tip_tolerance, axis_half * 3.001);
    const std::string fault =
        c_turn_fault(std::span(turns.data(), n_turns), cl_prev_known ? &cl_prev : nullptr, to,
                     axis.value_or(vec3{0, 0, 1}), feed, std::max(turn_chord, tol), tol);
    if (fault.empty()) return;
    said_turn = true;
    error(e, fault);
  }

  // A feed block while a CL cycle is on: the deepest each way along Z so far in the record.
  void note_fed(std::string_view text) {
    if (z.k != axis_state::kind::known) return;
    for (fed_point* f : {&fed_low, &fed_high}) {
      const bool further = !f->valid || (f == &fed_low ? z.value < f->z.value : z.value > f->z.value);
      if (!further) continue;
      f->valid = true;
      f->x = x, f->y = y, f->z = z;
      f->text.assign(text);
    }
  }

  // The record's arc blocks so far (the first `n_arcs`; the rest kept for their strings'
  // room): their sense, centre and ends in the part frame.
  std::vector<nc_arc_block> arcs;
  std::size_t n_arcs = 0;

  // (A block that moved in G2 or G3, no cycle.)
  void note_arc(const double* start, bool start_known) {
    const std::vector<nc_word>& words = *block_words;
    if (n_arcs == arcs.size()) arcs.emplace_back();
    nc_arc_block& arc = arcs[n_arcs++];
    arc.r = 0;
    arc.ccw = motion == 3;
    arc.plane = plane;
    arc.text = move_text();
    double off[3] = {0, 0, 0};
    bool given = false;
    for (const nc_word& w : words) {
      const int i = w.address == 'I'   ? 0
                    : w.address == 'J' ? 1
                    : w.address == 'K' ? 2
                    : w.address == 'R' ? 3
                                       : -1;
      if (i < 0) continue;
      if (!w.numeric) return void(arc.plane = 0);  // I#100: not known until it runs
      const double v = w.point ? w.number : w.number * increment;
      if (i == 3) {
        arc.r = v;
      } else {
        off[i] = v;
        given = true;
      }
    }
    // I is a radius along the program's X even where X is a diameter: the centre in the part
    // frame is the start plus the offsets, each turned as its axis is.
    const double zs = z_sign();
    const double sx = x_div < 0 ? -1.0 : 1.0;
    const auto known = [](const axis_state& a) { return a.k == axis_state::kind::known; };
    arc.centre_known = given && start_known;
    arc.ends_known = start_known && known(x) && known(z) && (!has_y || known(y) || plane == 18);
    arc.start = {start[0] * out_mm / x_div, start[1] * out_mm * zs, start[2] * out_mm * zs};
    arc.end = {part(x, x_div), has_y ? part(y, zs) : 0.0, part(z, zs)};
    if (!has_y) arc.start.y = 0;
    arc.centre = {arc.start.x + off[0] * out_mm * sx, arc.start.y + off[1] * out_mm * zs,
                  arc.start.z + off[2] * out_mm * zs};
  }

  double z_sign() const {
    return work >= 0 && m.spindles[static_cast<std::size_t>(work)].reverse_z ? -1.0 : 1.0;
  }

  // The part-frame coordinate of program axis `a` (`div`: program value per part-frame mm).
  double part(const axis_state& a, double div) const { return a.value * out_mm / div; }

  // Once a channel: the records from `e` on are passed over, the part frame being the
  // program's own (attack 50 F3: a G52 Z-5. or G51.1 Z0. from INSERT silenced the comparison
  // without a word). Said as a warning: the program is written, not verified from here.
  void said_passed_shift(const event& e) {
    if (said_shift) return;
    said_shift = true;
    say(e, severity::warning,
        shifted
            ? fmt::format("this record and the channel's later ones are not held to the CL: the program sets "
                          "the part frame itself at line {} of its program (`{}`)",
                          shift_line, shift_text)
            : fmt::format("the records under a mirror image or a scaling are not held to the CL, from this "
                          "one on: the program sets it at line {} of its program (`{}`)",
                          shift_line, shift_text));
  }

  // A finding at the CL record `e`, as "channel n: ...".
  void say(const event& e, severity level, std::string_view message) {
    diagnostic d;
    d.level = level;
    d.file = cl_file;
    d.line = e.line;
    d.column = e.column;
    d.message = fmt::format("channel {}: {}", ch.number, message);
    diags.report(std::move(d));
  }

  void error(const event& e, std::string message) {
    ++reported;
    say(e, severity::error, message);
  }

  // Returns false when the record is passed over.
  bool compare(const event& e, const vec3& pos, bool rapid, bool both,
               const std::optional<vec3>& cl_axis = std::nullopt) {
    // The head's offset first: a G49 H0 also makes C unknown, and would pass everything after.
    if (!head_due && (rapid ? head_offset_wrong(e) : head_spindle_wrong(e))) return false;
    if (whole_chain || (chain && chain->tool_tip_on())) return compare_chain(e, pos, rapid, both, cl_axis);
    const bool followed_polar = polar && polar_follow;
    if (both || cl_cycle || cycle || (polar && !polar_follow) || cylinder || frame || polar_coords ||
        rotary || foreign_offset || shifted || head_due || (!c_known && !followed_polar)) {
      if (shifted || mirrored) said_passed_shift(e);
      // An index not followed by the head's length offset leaves the tip unknown, not the tool's
      // axis (review 64: `G0 G53 B10.` between two drill moves posted a 10-degree plunge).
      if (head_due && !both && c_known && !polar && !cylinder && !frame && !rotary)
        compare_axis(e, cl_axis, false);
      ++passed;
      return false;
    }
    const double zs = z_sign();
    // Under a C angle the part's x, y are the program's turned by +C about Z (members: not
    // made for every record).
    axis_state& turned_x = turned[0];
    axis_state& turned_y = turned[1];
    const axis_state* xp = &this->x;
    const axis_state* yp = &this->y;
    bool with_y = has_y;  // y is compared: the channel has Y, or C turned x into it
    if (followed_polar) {
      // The programmed point (X, C) on the face, the tool where the control puts it: turned to
      // the point's angle at its distance from the axis, and off that line by where Y stands.
      if (x.k != axis_state::kind::known || polar_c.k != axis_state::kind::known ||
          (has_y && y.k != axis_state::kind::known)) {
        ++passed;
        return false;
      }
      const double px = part(x, x_div), py = part(polar_c, zs), y0 = has_y ? part(y, zs) : 0.0;
      const double r = std::hypot(px, py);
      const double ct = r > 0 ? px / r : 1.0, st = r > 0 ? py / r : 0.0;
      turned_x = x, turned_y = polar_c;
      turned_x.value = (px - y0 * st) * x_div / out_mm;
      turned_y.value = (py + y0 * ct) * zs / out_mm;
      xp = &turned_x, yp = &turned_y;
      with_y = true;
    } else if (c_deg != 0) {
      const auto at = part_xy(x, y);
      if (!at) {
        ++passed;
        return false;
      }
      turned_x = x, turned_y = y;
      turned_x.value = at->first * x_div / out_mm;
      turned_y.value = at->second * zs / out_mm;
      turned_y.k = axis_state::kind::known;
      xp = &turned_x, yp = &turned_y;
      with_y = true;
    }
    const axis_state& x = *xp;
    const axis_state& y = *yp;
    ++compared;
    // Three half units: a full circle ends on its start's words, which may stand a unit and a
    // half from the CL's end (within a unit of the start, channel_motion.cpp).
    const double tol = std::max(tip_tolerance, axis_half * 3.001);
    // Most records are right: the words are read for a message only when one is not.
    const auto fine = [&](const axis_state& a, double div, double want) {
      return a.k == axis_state::kind::unknown ||
             (a.k == axis_state::kind::known && std::abs(part(a, div) - want) <= tol);
    };
    const bool gauge = needs_length && (!length_on || h_word == 0) && z.k == axis_state::kind::known;
    if (!rapid && !gauge && std::holds_alternative<motion_event>(e.data)) [[unlikely]]
      if (n_plains > 0) hold_plain_blocks(e, {pos.x * cl_mm, pos.y * cl_mm, pos.z * cl_mm}, tol);  // (rare)
    if (fine(x, x_div, pos.x * cl_mm) && (!with_y || fine(y, zs, pos.y * cl_mm)) && !gauge &&
        fine(z, zs, pos.z * cl_mm)) {
      compare_axis(e, cl_axis, followed_polar);
      compare_rest(e, rapid);
      return true;
    }
    tip_fault(e, pos, x, y, with_y, gauge, zs, tol);
    compare_axis(e, cl_axis, followed_polar);
    compare_rest(e, rapid);
    return true;
  }

  // The record's tip is not where the program's axes `x` and `y` (turned by C or polar
  // interpolation; y compared when `with_y`) and Z put it, or Z is the gauge line: said once
  // (the rare way out of compare, kept apart so that the common one stays short).
  [[gnu::cold]] [[gnu::noinline]] void tip_fault(const event& e, const vec3& pos, const axis_state& x,
                                                 const axis_state& y, bool with_y, bool gauge, double zs,
                                                 double tol) {
    std::string off;
    double worst = 0;
    auto check = [&](char name, const axis_state& a, double div, double want) {
      if (a.k == axis_state::kind::away) {
        off += fmt::format("{}{} is where {} at line {} of the program left it, not at the CL's {:.3f}{}",
                           off.empty() ? "" : "; ", name, a.why, a.line, want,
                           absolute ? "" : " (G91 is in force: the axis words after it are increments)");
        worst = std::max(worst, 1.0);
        return;
      }
      if (a.k != axis_state::kind::known) return;
      const double have = part(a, div);
      const double d = std::abs(have - want);
      if (d <= tol) return;
      worst = std::max(worst, d);
      off += fmt::format("{}{} {:.3f} where the CL has {:.3f} ({:.3f} mm off)", off.empty() ? "" : "; ",
                         static_cast<char>(name + 'a' - 'A'), have, want, d);
    };
    check('X', x, x_div, pos.x * cl_mm);
    if (with_y) check('Y', y, zs, pos.y * cl_mm);
    if (gauge) {
      if (!said_length) {
        said_length = true;
        error(e,
              fmt::format("the program moves Z with no tool length offset in force (G43 H..): Z is then the "
                          "spindle's gauge line, one tool length below the CL's tip; give the channel a "
                          "length offset (channel.length_offset = \"G43 H{{offset:02}}\"){}",
                          moved ? fmt::format(", after the block `{}`", move_text()) : std::string()));
      }
    } else {
      check('Z', this->z, zs, pos.z * cl_mm);
    }
    if (!off.empty() && !std::exchange(said_tip, true))
      error(e,
            fmt::format("the program does not put the tool tip on this record's point (the part frame, mm): "
                        "{}{}",
                        off, moved ? fmt::format(", after the block `{}`", move_text()) : std::string()));
  }

  // The tool length the chain's words were written for: the [[tool]]'s and the CL's TLDATA, as
  // [[kinematics]] tool_length says which wins (machines/kinematic_chain.hpp chosen_length).
  std::optional<double> chain_length() const { return chosen_length(*chain_def, cl_tool_table, cl_length); }

  // A record of a channel with a kinematic chain: the tip and the tool axis where the program's
  // words put them through the forward transform, against the CL's point and axis.
  bool compare_chain(const event& e, const vec3& pos, bool rapid, bool both,
                     const std::optional<vec3>& cl_axis) {
    if (both || cl_cycle || cycle || polar || cylinder || frame || fixture || polar_coords ||
        foreign_offset || shifted) {
      if (shifted || mirrored) said_passed_shift(e);
      if ((frame || fixture) && !both) said_unfollowed(e);
      ++passed;
      return false;
    }
    if (needs_length && (!chain->length_on() || h_word == 0) &&
        chain_def->output != multiaxis_output::pivot) {
      ++compared;
      if (!std::exchange(said_length, true))
        error(e, fmt::format(
                     "the program moves with no tool length offset in force (G43 H.., the chain's "
                     "{}): X Y Z are then the spindle's gauge point, one tool length from the CL's tip{}",
                     offset_code(*chain_def),
                     moved ? fmt::format(", after the block `{}`", move_text()) : std::string()));
      compare_rest(e, rapid);
      return true;
    }
    // A tool of no known length: the tip only where the length does not move it (every head
    // that tilts the tool at 0, or tool-tip control); the axis in any case.
    const std::optional<double> length = chain_length();
    const std::optional<rotary_sweep::pose> at = chain->where(length.value_or(0));
    const double tol = std::max({tip_tolerance, chain_def->tolerance, axis_half * 3.001});
    const vec3 want{pos.x * cl_mm, pos.y * cl_mm, pos.z * cl_mm};
    if (!at) {
      // Not followed from here (a G53 left Z where the program does not say): the blocks before
      // are held all the same, a return to machine coordinates among them first.
      if (!rapid && cl_prev_known && !said_mid) hold_before(e, want, tol, std::nullopt);
      ++passed;
      return false;
    }
    ++compared;
    bool tip_known = true;
    if (!length)
      if (const std::optional<rotary_sweep::pose> longer = chain->where(100);
          !longer || kin::distance(longer->tip, at->tip) > tip_tolerance / 10)
        tip_known = false;
    if (tip_known && kin::distance(at->tip, want) > tol && !std::exchange(said_tip, true)) {
      std::string off;
      const double have_c[3] = {at->tip.x, at->tip.y, at->tip.z}, want_c[3] = {want.x, want.y, want.z};
      for (int i = 0; i < 3; ++i)
        if (std::abs(have_c[i] - want_c[i]) > tol)
          off += fmt::format("{}{} {:.3f} where the CL has {:.3f} ({:.3f} mm off)", off.empty() ? "" : "; ",
                             "xyz"[i], have_c[i], want_c[i], std::abs(have_c[i] - want_c[i]));
      if (off.empty()) off = fmt::format("{:.3f} mm from the CL's point", kin::distance(at->tip, want));
      error(e,
            fmt::format("the program does not put the tool tip on this record's point (the part frame, mm; "
                        "the forward transform of its words): {}{}",
                        off, moved ? fmt::format(", after the block `{}`", move_text()) : std::string()));
    }
    // (The blocks' own tips are held where they are known, whether or not the record's is.)
    if (!rapid && cl_prev_known && !said_mid) hold_before(e, want, tol, length);
    compare_chain_axis(e, at->axis, cl_axis);
    compare_rest(e, rapid);
    return true;
  }

  // The blocks since the last record against the CL's straight move to `want`; the last one, whose
  // end is the record's point (held by compare_chain), halfway along it when `length` says.
  void hold_before(const event& e, const vec3& want, double tol, const std::optional<double>& length) {
    const bool straight = std::holds_alternative<motion_event>(e.data);
    std::optional<vec3> last;
    const chain_block* last_block = mid_staged ? &mids[n_mids] : nullptr;
    if (last_block && last_block->kind == mid_kind::feed &&
        (length || chain_def->output == multiaxis_output::pivot))
      last = chain_sag(length);
    if (mid_staged && mids[n_mids].kind != mid_kind::feed) ++n_mids;  // said as it is
    mid_staged = false;
    if (n_mids > 0 || last)
      hold_chain_blocks(e, want, tol, last,
                        last_block ? (last_block->text_later ? move_text() : last_block->text) : move_text(),
                        last_block ? last_block->line : move_line, straight);
  }

  // A chain's tool axis `have` (from its rotary words) against the CL's: once a channel.
  void compare_chain_axis(const event& e, const vec3& have, const std::optional<vec3>& cl_axis) {
    if (!cl_axis || said_axis) return;
    const double tol = std::max(axis_tolerance, chain_def->angle_tolerance);
    const char* who =
        chain_def->output == multiaxis_output::vector ? "words I J K point" : "rotary axes point";
    if (const std::optional<std::string> why = axis_fault(have, *cl_axis, tol, who)) {
      said_axis = true;
      error(e, fmt::format("{}{}", *why,
                           moved ? fmt::format(", after the block `{}`", move_text()) : std::string()));
    }
  }

  // The C angle in force in (-180, 180] degrees (0 without one).
  double c_turn() const { return c_deg == 0 ? 0.0 : std::remainder(c_deg, 360.0); }

  // A point of the program (its X and Y axes) in the part frame, mm: the diameter, a mirror or
  // a reversed Z undone, then turned by the C angle; none when an axis it needs is not known.
  std::optional<std::pair<double, double>> part_xy(const axis_state& px, const axis_state& py) const {
    const double c = c_turn();
    if (px.k != axis_state::kind::known || (has_y && py.k != axis_state::kind::known)) return std::nullopt;
    const double a = part(px, x_div), b = has_y ? part(py, z_sign()) : 0.0;
    if (c == 0) return std::pair{a, b};
    const double t = c * std::numbers::pi / 180, ct = std::cos(t), st = std::sin(t);
    return std::pair{a * ct - b * st, a * st + b * ct};
  }

  // A CL cycle's hole (a GOTO between CYCLE/type and CYCLE/OFF) against the cycle block the
  // program drilled it with since the last record: along Z, its X and Y (turned by C) are the
  // hole's; a side cycle (along X) drills at the hole's Z, on the side C turned to it.
  void compare_hole(const event& e, const vec3& pos) {
    if (!head_due && head_spindle_wrong(e)) return;
    if (polar || cylinder || frame || polar_coords || rotary || foreign_offset || shifted || head_due ||
        !c_known || (whole_chain && !chain->upright())) {
      if (shifted || mirrored) said_passed_shift(e);
      ++passed;
      return;
    }
    if (!hole.valid) {
      if (cl_drilling) return compare_fed_hole(e, pos);
      ++passed;
      return;
    }
    const double tol = std::max(tip_tolerance, axis_half * 3.001);
    const double px = pos.x * cl_mm, py = pos.y * cl_mm, pz = pos.z * cl_mm;
    std::string off;
    if (!hole.side) {
      const auto at = part_xy(hole.x, hole.y);
      if (!at) {
        ++passed;
        return;
      }
      ++compared;
      const double d = std::hypot(at->first - px, at->second - py);
      if (d > tol)
        off = fmt::format("x {:.3f} y {:.3f} where the CL has x {:.3f} y {:.3f} ({:.3f} mm off)", at->first,
                          at->second, px, py, d);
      else
        off = depth_fault(e, pos, tol, hole.z, "its bottom");
    } else {
      if (hole.z.k != axis_state::kind::known || (has_y && hole.y.k != axis_state::kind::known)) {
        ++passed;
        return;
      }
      ++compared;
      // The CL's hole turned back by C: its y is the program's Y (0 on a lathe without Y).
      const double t = -c_turn() * std::numbers::pi / 180;
      const double y_turned = px * std::sin(t) + py * std::cos(t);
      // ... and on the tool's side of the axis (C 180 degrees round gives the same line: the
      // hole through the opposite wall).
      const double x_turned = px * std::cos(t) - py * std::sin(t);
      const bool other_side = std::abs(x_turned) > tol && (x_turned > 0) != (x_div > 0);
      const double zs = z_sign();
      const double z_have = part(hole.z, zs), y_have = has_y ? part(hole.y, zs) : 0.0;
      const double d = std::max(std::abs(z_have - pz), std::abs(y_have - y_turned));
      if (d > tol)
        off = fmt::format("z {:.3f} where the CL has {:.3f}, and {:.3f} mm across the drill's line at C{:g}",
                          z_have, pz, std::abs(y_have - y_turned), c_deg);
      else if (other_side)
        off = fmt::format(
            "at C{:g} the drill comes from the other side of the part than the CL's hole at x "
            "{:.3f} y {:.3f}",
            c_deg, px, py);
    }
    if (off.empty() || std::exchange(said_hole, true)) return;
    error(e, fmt::format("the program drills this record's hole elsewhere (the part frame, mm): {}, in the "
                         "block `{}`",
                         off, hole.text));
  }

  // A hole drilled with moves: the feed block that went deepest into the part (towards -Z for a
  // tool looking down +Z) stands on the hole's x, y and at the CL's bottom. A record with no
  // feed block, or a tool off Z, is passed over.
  void compare_fed_hole(const event& e, const vec3& pos) {
    const std::optional<vec3>& axis = std::get<motion_event>(e.data).axis;
    const bool down = !(axis && axis->z < 0);
    const fed_point& f = down == (z_sign() > 0) ? fed_low : fed_high;
    if (!f.valid || (axis && std::abs(axis->z) < 0.9999)) {
      ++passed;
      return;
    }
    const auto at = part_xy(f.x, f.y);
    if (!at) {
      ++passed;
      return;
    }
    ++compared;
    const double tol = std::max(tip_tolerance, axis_half * 3.001);
    const double px = pos.x * cl_mm, py = pos.y * cl_mm;
    std::string off;
    if (const double d = std::hypot(at->first - px, at->second - py); d > tol)
      off = fmt::format(
          "its deepest feed at x {:.3f} y {:.3f} where the CL has x {:.3f} y {:.3f} ({:.3f} mm off)",
          at->first, at->second, px, py, d);
    else
      off = depth_fault(e, pos, tol, f.z, "its deepest feed");
    if (off.empty() || std::exchange(said_hole, true)) return;
    error(e, fmt::format("the program drills this record's hole elsewhere (the part frame, mm): {}, in the "
                         "block `{}`",
                         off, f.text));
  }

  // An axial hole's bottom: the cycle block's Z against the CL's, FEDTO or DEPTH from the GOTO
  // point along a tool axis on Z (a tool looking down +Z drills towards -Z). A tool off Z (a
  // cross hole in a turned frame) or a Z the block does not give is passed over. Empty: right.
  std::string depth_fault(const event& e, const vec3& pos, double tol, const axis_state& bottom_z,
                          std::string_view what) const {
    const std::optional<vec3>& axis = std::get<motion_event>(e.data).axis;
    if (bottom_z.k != axis_state::kind::known || (axis && std::abs(axis->z) < 0.9999)) return {};
    const double into = axis && axis->z < 0 ? 1.0 : -1.0;
    const std::optional<double> bottom = cycle_bottom(cl_cycle_record, pos.z, into);
    if (!bottom) return {};
    const double want = *bottom * cl_mm, have = part(bottom_z, z_sign());
    if (std::abs(have - want) <= tol) return {};
    return fmt::format("{} at z {:.3f} where the CL's bottom is z {:.3f} ({:.3f} mm {})", what, have, want,
                       std::abs(have - want), (have - want) * into > 0 ? "deeper" : "short of it");
  }

  // A CIRCLE record's arc blocks against its arc (analysis/cl_compare_arc): each block's sense
  // and centre (or R), its end on the circle, how far round they go and their pitch.
  void compare_arc(const event& e, const arc_event& a) {
    if (said_arc) return;
    arc_frame f;
    f.sx = x_div < 0 ? -1.0 : 1.0;
    f.zs = z_sign();
    f.out_mm = out_mm;
    f.cl_mm = cl_mm;
    f.tol = std::max(tip_tolerance, axis_half * 3.001);
    std::string fault = arc_blocks_fault(std::span(arcs.data(), n_arcs), a, f);
    if (fault.empty()) return;
    said_arc = true;
    error(e, std::move(fault));
  }

  // The tool, and at a cut the spindle, rapid against feed and the feed.
  void compare_rest(const event& e, bool rapid) {
    // A cut with nothing changed since the last cut found right (only axis words read, only
    // motion records) is right again: the tool, spindle, coolant and feed are the same.
    const bool cut = !rapid && moved;
    if (cut && version == fine_version && !rapid_in_record && skip_text.empty()) return;
    const long findings = reported;
    compare_tool(e);
    if (!skip_text.empty() && !said_skip) {
      said_skip = true;
      error(e, fmt::format("the program has a block under block delete before this record (`{}`): the "
                           "operator's switch decides whether it runs, so where the tool is here depends "
                           "on it; write it without the '/'",
                           skip_text));
    }
    if (rapid || !moved) return;
    compare_spindle(e);
    compare_coolant(e);
    for (const std::string* x : {&s_expression, &f_expression})
      if (!x->empty() && !said_expression) {
        said_expression = true;
        error(e, fmt::format("the program cuts here under {}, a value known only when the block runs: the "
                             "comparison with the CL cannot hold it to the CL's {}; write the number",
                             *x, x == &s_expression ? "spindle speed" : "feed"));
      }
    // A threading pass (G32): its F is the lead, which THREAD/TURN gives.
    if (motion == 32 && cl_lead > 0 && f > 0 && !said_feed &&
        std::abs(f * out_mm - cl_lead) > std::max(1e-4 * out_mm, cl_lead * 1e-4)) {
      said_feed = true;
      error(e, fmt::format("the CL threads with a lead of {:g} mm here, the program's G32 with {:g} mm ({})",
                           cl_lead, f * out_mm, f_text));
    }
    if (rapid_in_record)
      return said_rapid
                 ? void()
                 : (said_rapid = true,
                    error(e, fmt::format(
                                 "the CL asks for a feed move here, but the program moves in rapid: `{}`",
                                 rapid_text)));
    const bool feed_known = !(motion == 32 || inverse_time || per_rev < 0 || f < 0 || cl_feed < 0);
    if (feed_known) compare_feed(e);
    // The feed through the spindle's speed depends on X under CSS: not kept.
    if (cut && reported == findings && (!feed_known || (per_rev == 1) == cl_per_rev)) fine_version = version;
  }

  void compare_feed(const event& e) {
    if (said_feed) return;
    const bool nc_rev = per_rev == 1;
    // The slack: half the last digit the post writes a feed with (4 decimals per revolution, 1
    // per minute, one more in inches), not the digits a block happens to have: F1. for 0.5.
    const double f_mm = f * out_mm, half = feed_half[nc_rev ? 1 : 0];
    if (nc_rev == cl_per_rev) {
      if (std::abs(f_mm - cl_feed) <= std::max(feed_tolerance * cl_feed, half * 1.001)) return;
      return feed_error(e, f_mm, 0);
    }
    // The other mode: through the speed of the spindle the feed follows, at the tip's diameter.
    const double diameter = x.k == axis_state::kind::known ? std::abs(x.value * 2 / x_div) : 0;
    const double rpm = spindles_now().rpm(diameter, inch);
    if (rpm <= 0) return;  // a speed this channel did not give (another channel's): not followed
    const double have = nc_rev ? f_mm * rpm : f_mm / rpm;
    const double slack = nc_rev ? half * rpm : half / rpm;
    if (std::abs(have - cl_feed) <= std::max(feed_tolerance * cl_feed, slack * 1.001)) return;
    feed_error(e, have, rpm);
  }

  // `have`: the program's feed in the CL's unit; `rpm`: the speed it went through (0: none).
  void feed_error(const event& e, double have, double rpm) {
    said_feed = true;
    const char* nc_unit = per_rev == 1 ? "mm/rev" : "mm/min";
    const char* cl_unit = cl_per_rev ? "mm/rev" : "mm/min";
    const std::string mode =
        fmt::format("{} under {}", f_text, per_rev == 1 ? m.codes.feed_per_rev : m.codes.feed_per_min);
    if (rpm <= 0)
      return error(e, fmt::format("the CL feeds at {:g} {} here, the program at {:g} {} ({})", cl_feed,
                                  cl_unit, have, nc_unit, mode));
    error(e, fmt::format("the CL feeds at {:g} {} here, the program at {:g} {} ({} at {:g} rpm)", cl_feed,
                         cl_unit, have, cl_unit, mode, std::round(rpm)));
  }

  void cl_spindle(const spindle_event& d, int line) {
    spindle_fine = false;
    switch (d.mode) {
      case spindle_mode::off: cl_spin = 0; break;
      case spindle_mode::on:
        if (cl_spin < 0 && cl_speed <= 0) return;  // ON with no speed before: the writer's error
        cl_spin = 1;
        if (d.dir != rotation::none) cl_dir = d.dir;
        break;
      case spindle_mode::rpm:
      case spindle_mode::sfm:
      case spindle_mode::smm:
        cl_spin = 1;
        cl_css = d.mode != spindle_mode::rpm;
        // CSS in the program's unit: m/min with mm output, ft/min with inch output.
        cl_speed = d.mode == spindle_mode::rpm   ? d.speed
                   : d.mode == spindle_mode::sfm ? (inch ? d.speed : d.speed * 0.3048)
                   : inch                        ? d.speed / 0.3048
                                                 : d.speed;
        cl_dir = d.dir == rotation::none ? rotation::cw : d.dir;
        cl_clamp = d.max_rpm.value_or(0);
        cl_spin_index = -1;
        if (!d.spindle.empty()) {
          const spindle_def* named =
              m.spindle(d.spindle == "live" ? std::string_view(ch.live_spindle) : d.spindle);
          if (named) cl_spin_index = static_cast<int>(named - m.spindles.data());
        }
        break;
      default:
        cl_spin = -1;  // ORIENT, LOCK: not followed
        return;
    }
    cl_spin_line = line;
  }

  // A dwell block (`G4 U2.`, `G98 G4 U2.`): its seconds, and whether it is written under feed per
  // revolution, where a control may count it in spindle revolutions (Fanuc parameter 3405#1
  // DWL, "dwell per rotation in the feed per rotation mode"; issue 37, item 10).
  void note_dwell(const std::vector<nc_word>& words, std::string_view text) {
    ++dwells;
    dwelt = 0, dwell_text.assign(text), dwell_mode = per_rev;
    for (const nc_word& w : words)
      if (w.address == dwell_address && w.numeric) {
        // Seconds without a decimal point count least increments (`U2` is 0.002 s where
        // decimal-point programming is off), as an axis word does; milliseconds are whole.
        const bool seconds = dwell_scale == 1;
        dwelt +=
            (w.point || !seconds || !m.program.trailing_point ? w.number : w.number * 0.001) * dwell_scale;
      }
  }

  // The CL's DELAY of `seconds` against the dwells written for it.
  void compare_dwell(const event& e, double seconds) {
    if (said_dwell || !dwell_address) return;
    const double half = 0.0005;  // (a millisecond's half: the last digit written)
    std::string why;
    if (dwells == 0 && seconds < half) return;  // no time as written (P0): none is (the writer says so)
    if (dwells == 0)
      why = fmt::format("the CL dwells {:g} s here (DELAY), the program does not", seconds);
    else if (std::abs(dwelt - seconds) > half + 1e-9)
      why = fmt::format("the CL dwells {:g} s here (DELAY), the program {:g} s (`{}`)", seconds, dwelt,
                        dwell_text);
    else if (dwell_mode == 1)
      why = fmt::format(
          "the CL dwells {:g} s here (DELAY), the program under {} (`{}`): a control that counts "
          "a dwell in spindle revolutions under feed per revolution (Fanuc parameter 3405#1) "
          "waits {:g} revolutions{}",
          seconds, m.codes.feed_per_rev, dwell_text, dwelt,
          m.codes.feed_per_min.empty()
              ? "; the machine file gives no codes.feed_per_min to write the dwell under: give it (G98, G94)"
              : "");
    else if (dwell_mode < 0 && !m.codes.feed_per_rev.empty())
      why = fmt::format(
          "the CL dwells {:g} s here (DELAY), the program with no feed mode set (`{}`): a control "
          "that keeps {} from the last program and counts a dwell in spindle revolutions under "
          "it (Fanuc parameter 3405#1) waits {:g} revolutions; set {} first",
          seconds, dwell_text, m.codes.feed_per_rev, dwelt,
          m.codes.feed_per_min.empty() ? std::string("the feed mode") : m.codes.feed_per_min);
    if (why.empty()) return;
    said_dwell = true;
    error(e, why);
  }

  void compare_coolant(const event& e) {
    if (said_coolant || coolant_fine || cl_coolant < 0 || nc_coolant < 0) return;
    if (cl_coolant == nc_coolant) {
      coolant_fine = true;
      return;
    }
    said_coolant = true;
    static constexpr const char* kinds[] = {"off", "flood", "mist", "through the tool", "air"};
    error(e, fmt::format(
                 "the CL cuts with the coolant {} here (COOLNT at line {}), the program with it {} (`{}`)",
                 kinds[cl_coolant], cl_coolant_line, kinds[nc_coolant], coolant_text));
  }

  // The operation's CAM tool against the one the program's tool was first held to.
  [[gnu::noinline]] void compare_cam_tool(const event& e) {
    if (t_active < 0 || cl_cam_name.empty() || said_cam) return;
    cam_judged = cam_names;
    if (named_tool != t_active) {
      named_tool = t_active, named_cam = cl_cam_name, named_cam_line = cl_cam_line;
      return;
    }
    if (cl_cam_name == named_cam) return;
    // Two names the machine's tool table gives the same tool are one tool.
    if (const tool_def* t = m.tool_named(ch.number, cl_cam_name); t && t->number == t_active) return;
    said_cam = true;
    error(e,
          fmt::format("the CL's operation ({} at line {}) names the tool '{}', but the program has tool {} "
                      "({}) in the spindle here, held since the CL named '{}' (line {}), and calls no tool "
                      "between",
                      cl_cam_record, cl_cam_line, cl_cam_name, t_active, t_text, named_cam, named_cam_line));
  }

  void compare_tool(const event& e) {
    // (Nothing new since the last record, most of them: the test here, the judging out of line.)
    if (named_tool != t_active || cam_judged != cam_names) [[unlikely]]
      compare_cam_tool(e);
    if (cl_tool < 0 || t_active < 0) return;
    if (t_active != cl_tool) {
      if (said_tool) return;
      said_tool = true;
      return error(
          e, fmt::format("the CL cuts with tool {} here (the tool call at line {}), the program with tool {} "
                         "({}, read by the tool call {})",
                         cl_tool, cl_tool_line, t_active, t_text, ch.tool_call));
    }
    // A mill's length offset register against the CL's, as the channel's length_offset writes
    // it (G43 H{offset:02}: the CL's offset; H{tool}: its tool).
    if (length_on && h_word > 0 && !said_offset && h_from >= 0) {
      const long want = h_from == 1 ? cl_offset : cl_tool;
      if (want >= 0 && h_word != want) {
        said_offset = true;
        return error(e,
                     fmt::format("the CL cuts with tool {} on offset {} here (the tool call at line {}), the "
                                 "program with the length offset {} ({} {})",
                                 cl_tool, cl_offset, cl_tool_line, h_text,
                                 whole_chain ? "the chain's" : "channel.length_offset",
                                 whole_chain ? offset_code(*chain_def) + " H.." : ch.length_offset));
      }
    }
    // The offset the T word gave: 0 cancels the tool's geometry (the tip runs at the turret's
    // reference point) unless the machine's tool table applies it (channel.offset_zero).
    if (said_offset || t_offset < 0 || t_offset == cl_offset || (t_offset == 0 && ch.offset_zero)) return;
    said_offset = true;
    error(e, fmt::format(
                 "the CL cuts with tool {} on offset {} here (the tool call at line {}), the program on "
                 "offset {} ({}){}",
                 cl_tool, cl_offset, cl_tool_line, t_offset, t_text,
                 t_offset == 0 ? ": offset 0 cancels the tool's offset, and the tip runs where the turret's "
                                 "reference point is"
                               : ""));
  }

  // At a cut: the spindle the channel commanded last turns as the CL's SPINDL says.
  void compare_spindle(const event& e) {
    if (said_spindle || cl_spin != 1 || spindle_fine || !s_expression.empty()) return;
    // The spindle the CL names (SPINDL/...,MAIN), else the one the channel commanded last.
    const int sp = cl_spin_index >= 0 ? cl_spin_index : spindles_now().current();
    if (sp < 0) return;
    const spindle_setting& s = spindles_now().setting(sp);
    if (s.turn == spindle_turn::unknown || s.turn == spindle_turn::held) return;  // another channel's
    const spindle_def& def = m.spindles[static_cast<std::size_t>(sp)];
    const bool cw = cl_dir != rotation::ccw;
    std::string wrong;
    if (s.turn == spindle_turn::stopped) {
      wrong = "is stopped";
    } else if ((s.turn == spindle_turn::cw) != cw) {
      wrong = fmt::format("turns {} (M{})", cw ? "counter-clockwise" : "clockwise", cw ? def.ccw : def.cw);
    } else if (cl_css && s.mode == speed_mode::rpm) {
      spindle_fine = true;  // a surface speed the writer turned into a rotating tool's rpm (its diameter)
      return;
    } else if (!cl_css && s.mode == speed_mode::css) {
      wrong = fmt::format("turns under constant surface speed ({} S{:g})", m.codes.css, s.speed);
    } else if ((s.mode != speed_mode::unknown || (!cl_css && m.codes.rpm.empty() && m.codes.css.empty())) &&
               std::abs(s.speed - cl_speed) > std::max(0.5, cl_speed * 0.005)) {
      // (A machine without speed-mode codes turns at the S it was given: an rpm.)
      wrong = fmt::format("turns at S{:g}", s.speed);
    } else if (cl_css && s.mode == speed_mode::css && (cl_clamp > 0 || def.max_rpm > 0) &&
               (s.clamp <= 0 || s.clamp > (cl_clamp > 0 ? cl_clamp : def.max_rpm) + 0.5)) {
      // Under CSS the clamp holds the rpm near the centre: the CL's MAXRPM, else the spindle's.
      const double want = cl_clamp > 0 ? cl_clamp : def.max_rpm;
      wrong = s.clamp <= 0
                  ? fmt::format("has no clamp, where the CL holds it to {:g} rpm", want)
                  : fmt::format("is clamped at {:g} rpm, where the CL holds it to {:g}", s.clamp, want);
    } else {
      spindle_fine = true;
      return;
    }
    said_spindle = true;
    error(e,
          fmt::format("the CL cuts with the spindle turning {} at {:g} {} here (SPINDL at line {}), but the "
                      "program's {} spindle {}",
                      cw ? "clockwise" : "counter-clockwise", cl_speed,
                      cl_css ? (inch ? "ft/min" : "m/min") : "rpm", cl_spin_line, def.name, wrong));
  }

  void record(const event& e, bool both) {
    if (!std::holds_alternative<motion_event>(e.data) && !std::holds_alternative<arc_event>(e.data))
      ++version;
    // A TLDATA right after a tool call (comments between) describes that tool, else the next.
    const bool after_call = cl_after_call;
    cl_after_call = after_call && keeps_tool_call_open(e);
    std::visit(
        [&](const auto& d) {
          using T = std::decay_t<decltype(d)>;
          if constexpr (std::is_same_v<T, tool_event>) {
            if (!d.preselect) {
              cl_tool = d.tool, cl_tool_line = e.line, cl_offset = d.offset.value_or(d.tool);
              cl_tool_table = cl_tool >= 0 ? m.tool_length(ch.number, cl_tool) : std::nullopt;
              cl_prev_known = false;  // the tool goes home: its first move comes from there
              cl_length = std::exchange(cl_length_next, std::nullopt);
              cl_after_call = true;
              named_tool = -1;  // the CL's own call: its tool, whatever the operation's name
            }
          } else if constexpr (std::is_same_v<T, tool_data_event>) {
            cl_after_call = after_call;
            if (const std::optional<double> l = tldata_length(d))
              (after_call ? cl_length : cl_length_next) = *l * cl_mm;
          } else if constexpr (std::is_same_v<T, spindle_event>) {
            cl_spindle(d, e.line);
          } else if constexpr (std::is_same_v<T, thread_event>) {
            cl_lead = d.on ? d.lead * cl_mm : -1;
          } else if constexpr (std::is_same_v<T, coolant_event>) {
            const std::string& k = d.mode;
            cl_coolant = k == "OFF"                  ? 0
                         : k == "ON" || k == "FLOOD" ? 1
                         : k == "MIST"               ? 2
                         : k == "THRU"               ? 3
                         : k == "AIR"                ? 4
                                                     : -1;
            cl_coolant_line = e.line;
            coolant_fine = false;
          } else if constexpr (std::is_same_v<T, feed_event>) {
            cl_per_rev = d.mode == feed_mode::per_rev;
            cl_feed = d.mode == feed_mode::inverse_time
                          ? -1
                          : d.value * (d.units == unit_system::inch ? 25.4 : 1.0);
          } else if constexpr (std::is_same_v<T, cycle_event>) {
            // The writer starts a cycle at its type and ends it at OFF; ON and INIT change nothing.
            if (d.type == "OFF")
              cl_cycle = false;
            else if (d.type != "INIT" && d.type != "ON") {
              cl_cycle = true;
              cl_cycle_record = d;
              cl_drilling = d.type == "DRILL" || d.type == "DEEP" || d.type == "DEEP2" || d.type == "TAP";
            }
          } else if constexpr (std::is_same_v<T, units_event>) {
            units(d.units);
          } else if constexpr (std::is_same_v<T, delay_event>) {
            if (!d.revolutions) compare_dwell(e, d.value);
          } else if constexpr (std::is_same_v<T, text_event>) {
            if (const std::string_view name = cam_tool_name(d); !name.empty())
              cl_cam_name.assign(name), cl_cam_line = e.line, cl_cam_record = d.major, ++cam_names;
          } else if constexpr (std::is_same_v<T, motion_event>) {
            if (d.kind == motion_kind::go_to || d.kind == motion_kind::delta) {
              bool followed = true;
              if (cl_cycle && !both) {
                compare_hole(e, d.pos);
                // A chain drills along its tool axis: the rotary words' against the CL's.
                if (whole_chain)
                  if (const std::optional<vec3> a = chain->axis_now()) compare_chain_axis(e, *a, d.axis);
              } else
                followed = compare(e, d.pos, d.rapid, both, d.axis);
              // Between two holes the cycle moves at rapid.
              if (followed && !both && !turns_passed())
                compare_turns(e, d.pos, d.axis, !d.rapid && !cl_cycle);
              cl_prev = {d.pos.x * cl_mm, d.pos.y * cl_mm, d.pos.z * cl_mm};
              cl_prev_known = true;
            }
          } else if constexpr (std::is_same_v<T, arc_event>) {
            // (A chain's arc is held to the circle with its rotary axes at 0: X Y Z the tip.)
            if (compare(e, d.end, false, both) && !polar && (!whole_chain || chain->upright()))
              compare_arc(e, d);
            cl_prev = {d.end.x * cl_mm, d.end.y * cl_mm, d.end.z * cl_mm};
            cl_prev_known = true;
          }
        },
        e.data);
    moved = false;
    rapid_in_record = false;
    n_arcs = 0;
    dwells = 0;
    // The C turns of blocks between two motion records (INSERT text, an [events] block, a
    // tool's or a coolant's blocks) are held to the next one's move (attack 60 F3).
    if (std::holds_alternative<motion_event>(e.data) || std::holds_alternative<arc_event>(e.data))
      n_turns = 0, n_mids = 0, mid_staged = false, n_plains = 0, plain_pending = false, plains_over = false;
    hole.valid = false;
    fed_low.valid = fed_high.valid = false;
  }

  void units(unit_system u) { cl_mm = u == unit_system::inch ? 25.4 : 1.0; }

  // The part frame is not the setup's, or the tip depends on what is not followed.
  bool turns_passed() const {
    return frame || shifted || foreign_offset || head_due || rotary || polar || cylinder || polar_coords;
  }

  // The program's unit (G20: inch), its least increment (what an axis word without a decimal
  // point counts: `X44` is 0.044 mm where decimal-point programming is off, the Fanuc default)
  // and half of it in mm.
  // The modes a block's G words changed (analysis/modal_state): the motion (G0-G3, 32 for
  // threading), the unit (G20/G21, system C's G70/G71), G90/G91 (system A has no G91: an alarm),
  // the plane and the feed mode.
  void take_modes(const channel_modes& md) {
    motion = md.motion;
    if (md.inch != inch) units(md.inch);
    absolute = !md.incremental;
    plane = md.plane;
    if (md.feed == feed_kind::inverse_time) {
      inverse_time = true;
    } else if (md.feed != feed_kind::none) {
      per_rev = md.feed == feed_kind::per_rev ? 1 : 0;
      inverse_time = false;
    }
  }

  void units(bool in_inch) {
    // The control keeps where the axes are: their values are said again in the new unit.
    const double was = out_mm;
    inch = in_inch;
    out_mm = inch ? 25.4 : 1.0;
    for (axis_state* a : {&x, &y, &z}) a->value *= was / out_mm;
    const int decimals = inch ? m.program.decimals_inch : m.program.decimals_metric;
    axis_half = 0.5 * std::pow(10.0, -decimals) * out_mm;
    for (int rev = 0; rev < 2; ++rev)
      feed_half[rev] = 0.5 * std::pow(10.0, -((rev ? 4 : 1) + (inch ? 1 : 0))) * out_mm;
    // A machine file that writes whole numbers without their point (trailing_point = false)
    // is for a control that reads them as whole units (Fanuc parameter 3401#0 DPI = 1,
    // calculator-type input); elsewhere a number without a point counts the control's least
    // increment, 0.001 mm or 0.0001 inch (increment system IS-B), whatever the post's decimals.
    increment = !m.program.trailing_point ? 1.0 : inch ? 1e-4 : 1e-3;
  }

  void take_feed(const nc_word& w) {
    if (w.numeric) {
      f = w.number;
      f_text.assign("F").append(w.value);
      f_expression.clear();
    } else {
      f = -1;
      f_expression.assign("F").append(w.value);  // the feed is known only when the block runs
    }
  }

  static bool has_address(const std::vector<nc_word>& ws, char address) {
    for (const nc_word& w : ws)
      if (w.address == address) return true;
    return false;
  }

  static bool has_word(const std::vector<nc_word>& ws, char address, double number) {
    for (const nc_word& w : ws)
      if (w.address == address && w.numeric && w.number == number) return true;
    return false;
  }

  static bool any_axis(const std::vector<nc_word>& ws) {
    for (const nc_word& w : ws)
      if (w.address == 'X' || w.address == 'Y' || w.address == 'Z' || w.address == 'U' || w.address == 'W' ||
          w.address == 'A' || w.address == 'B' || w.address == 'C' || w.address == 'H')
        return true;
    return false;
  }
};

cl_comparison::cl_comparison(const machine& m, const channel_def& ch, diagnostic_sink& diags,
                             std::string cl_file)
    : m_(m), ch_(ch), diags_(diags), cl_file_(std::move(cl_file)) {}
cl_comparison::~cl_comparison() = default;
// (Out of line, so that each call's test stays a test: the construction inlined into every
// entry point cost them a frame each, 2 M instructions on the lathe job.)
[[gnu::noinline, gnu::cold]] void cl_comparison::make() {
  p_ = std::make_unique<impl>(m_, ch_, diags_, std::move(cl_file_), spindles_, modes_);
}
inline cl_comparison::impl& cl_comparison::made() {
  if (!p_) [[unlikely]]
    make();
  return *p_;
}
void cl_comparison::line(std::string_view text) { made().line(text); }
void cl_comparison::block(int line, std::string_view text, const std::vector<nc_word>& words,
                          std::uint32_t letters) {
  made().line(text, &words, letters, line);
}
void cl_comparison::keep_texts() { (void)made().move_text(); }
void cl_comparison::units(unit_system u) { made().units(u); }
void cl_comparison::record(const event& e, bool both) { made().record(e, both); }
long cl_comparison::compared() const { return p_ ? p_->compared : 0; }
long cl_comparison::passed_over() const { return p_ ? p_->passed : 0; }

}  // namespace twinpost
