#include "analysis/rotary_sweep.hpp"
#include "analysis/modal_state.hpp"

#include "analysis/nc_codes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "kinematics/forward.hpp"
#include "kinematics/inverse.hpp"

namespace twinpost {

namespace {

// mm a rapid's tip may pass below the work's top: the sag of a link between two tool axes at the
// same height, every axis moving linearly (about R·Δθ²/8: 0.06 mm for 2° at 400 mm, 0.5 mm at
// 5.7°), is no swing into the work.
constexpr double sag_allowed = 0.5;

// mm: how far above its end a feed down may have started cutting (a plunge from the CAM's feed
// plane; an approach at feed from the clearance is taken from this far above its end).
constexpr double plunge_above = 10;

// mm: how far above the work a feed down starts at least (a CAM's feed plane: the Autodesk
// Fusion default "feed height" is 5 mm over the stock's top, NX's engage distance 3 mm;
// UNVERIFIED for every CAM): a plunge cuts from no higher than this below its start.
constexpr double feed_plane_above = 2;

// With the tool's length not known, a finding must hold for every tool from the gauge point (0)
// up to `long_tool` mm, tried every `length_step` mm (a joints program's words depend on the
// length they were computed for, and the tip's height at each tool axis with it).
constexpr double long_tool = 300, length_step = 50;

// A height linear in the tool's length L (every transform of the tip is affine in it):
// at0 + L per_mm.
struct height {
  double at0 = 0, per_mm = 0;
  double at(double l) const { return at0 + l * per_mm; }
};

int g100(double g) { return static_cast<int>(std::lround(g * 100)); }

// The G number of a machine code ("G43.4" -> 4340); -1 when it has none.
int code_g(const std::string& code) {
  for (const nc_word& w : split_nc_words(code))
    if (w.address == 'G' && w.numeric) return g100(w.number);
  return -1;
}

// The M number of a machine code with no G word ("M128" -> 12800); -1 otherwise.
int code_m(const std::string& code) {
  int m = -1;
  for (const nc_word& w : split_nc_words(code)) {
    if (w.address == 'G') return -1;
    if (w.address == 'M' && w.numeric && m < 0) m = g100(w.number);
  }
  return m;
}

struct axis_value {
  enum class kind : unsigned char { unknown, known, away } k = kind::unknown;
  double value = 0;  // mm, or degrees
};

bool known(const axis_value& a) { return a.k == axis_value::kind::known; }

}  // namespace

struct rotary_sweep::impl {
  impl(const machine& m, const kinematic_chain& c, int channel, int change_m, bool follow_only)
      : m(m), chain(c), plan(c), channel(channel), change_m(change_m), follow_only(follow_only),
        codes(m, m.channels[static_cast<std::size_t>(channel - 1)]) {
    for (std::size_t i = 0; i < 3 && i < c.linear.size(); ++i) linear_address[i] = c.linear[i];
    for (std::size_t i = 0; i < c.rotaries.size() && i < 2; ++i) rotary_address[i] = c.rotaries[i].address;
    tcp_g = code_g(c.tool_tip_on);
    off_g = code_g(c.tool_tip_off);
    // Tool-tip control as an M code (Heidenhain's M128/M129 in ISO programs; attack 63 L7).
    tcp_m = code_m(c.tool_tip_on);
    off_m = code_m(c.tool_tip_off);
    length_g = code_g(c.length_on);
    plane_g = code_g(c.plane);
    index_g = code_g(c.plane_index);
    plane_off_g = code_g(c.plane_off);
    units(m.program.output_units == output_unit::inch);  // the program's unit until G20 or G21
    new_tool(-1);
    // With only heads the tip's height is Z's and the heads' alone: X and Y need not be known.
    heads_only = plan.table_count == 0;
    axis_of.fill(-1);
    for (int i = 0; i < 3; ++i)
      if (linear_address[static_cast<std::size_t>(i)] >= 'A' &&
          linear_address[static_cast<std::size_t>(i)] <= 'Z')
        axis_of[static_cast<std::size_t>(linear_address[static_cast<std::size_t>(i)] - 'A')] =
            static_cast<signed char>(i);
    for (int i = 0; i < plan.rotary_count; ++i)
      if (rotary_address[static_cast<std::size_t>(i)] >= 'A' &&
          rotary_address[static_cast<std::size_t>(i)] <= 'Z')
        axis_of[static_cast<std::size_t>(rotary_address[static_cast<std::size_t>(i)] - 'A')] =
            static_cast<signed char>(3 + i);
    for (const rotary_axis_def& r : c.rotaries)
      reach += std::sqrt(r.point.x * r.point.x + r.point.y * r.point.y + r.point.z * r.point.z);
  }

  const machine& m;
  const kinematic_chain& chain;
  kin::chain_plan plan;
  int channel;
  int change_m;      // the M code of the tool change (M6); -1: a T word changes the tool
  bool follow_only;  // the comparison's follower: no swing, no work's top
  nc_codes codes;    // what its G codes make of a block's axis words
  bool heads_only = true;
  std::array<char, 3> linear_address{'X', 'Y', 'Z'};
  std::array<char, 2> rotary_address{0, 0};
  std::array<signed char, 26> axis_of{};  // by letter: 0-2 a linear axis, 3-4 a rotary one, -1 none
  int tcp_g = -1, off_g = -1, length_g = -1, plane_g = -1, index_g = -1, plane_off_g = -1;
  int tcp_m = -1, off_m = -1;
  double increment = 0.001;  // what a word without a decimal point counts, program units
  double mm = 1;             // mm per program unit (G20: 25.4)

  // The axes where the program's blocks left them; the rotary axes not known until a word
  // gives them (a program may start with the heads where the last one left them).
  std::array<axis_value, 3> lin{};
  std::array<axis_value, 2> rot{};
  // Where the last block started (the comparison's follower: where_along).
  std::array<axis_value, 3> lin_from{};
  std::array<axis_value, 2> rot_from{};
  bool absolute = true;
  int motion = 0;  // a Fanuc control starts in G00
  bool tcp = false, length = false, frame = false, cycle = false;
  bool vector = false;              // tool-tip control with the tool axis as I J K (G43.5)
  std::array<axis_value, 3> ijk{};  // its I J K, as the last blocks gave them
  // A tilted working plane (G68.2): its origin and Euler angles, its Z in the part frame, and
  // the tip's place in its coordinates.
  bool plane = false;
  bool xy_turned = false;  // under a G68 rotation about Z: X and Y words are turned coordinates
  vec3 origin{};
  std::array<double, 3> euler{};
  vec3 frame_axis{0, 0, 1};
  std::array<axis_value, 3> flin{};
  int pending_tool = -1;  // a T word waiting for the tool change code
  // A drilling cycle: the level G98 returns to (Z before the cycle), G99's R plane, and which.
  axis_value initial{}, r_plane{};
  bool return_to_r = false;
  // The tool lengths followed: the tool's own, or 0 to long_tool where it is not known.
  std::vector<double> lengths;
  bool length_known = false;
  // Where G69 left the linear axes depends on the length (the plane's tip put back with the
  // heads as they stand): per mm of it; an absolute word of the axis ends it.
  std::array<double, 3> shift{};
  // The heads' part of the transform at `offset_at` (tip_height()), at L = 0 and per mm of L.
  mutable bool offset_cached = false;
  mutable std::array<double, 2> offset_at{};
  mutable vec3 offset0{}, offset_per_mm{};
  // The work's top as far as the program has cut: the highest tip of any feed block, where it
  // starts and where it ends, since the program began; per length followed.
  bool has_top = false;
  std::vector<double> top;
  // The other work offsets' tops (by G code x 100; G54.1 Pn as 100000 + n), and the one in force.
  struct part_top {
    int offset = 0;
    bool has = false;
    std::vector<double> top;
  };
  std::vector<part_top> other_parts;
  int offset_in_force = 0;

  void use_offset(int id) {
    if (id == offset_in_force) return;
    other_parts.push_back({offset_in_force, has_top, top});
    has_top = false;
    top.assign(lengths.size(), 0.0);
    for (auto p = other_parts.begin(); p != other_parts.end(); ++p)
      if (p->offset == id) {
        has_top = p->has && p->top.size() == lengths.size();
        if (has_top) top = p->top;
        other_parts.erase(p);
        break;
      }
    offset_in_force = id;
    bounded = false;
  }
  // The level the last rapid or feed retract left the tip at: feeds there link, not cut.
  bool has_ceiling = false;
  height ceiling;
  // under_top(): the last exact feed height, its Z word, the heads' turn since (radians), and
  // where the last feed block ended; `reach`: the heads' points' distances from the gauge point.
  bool bounded = false;
  double ref_z = 0, travel = 0, last_z = 0, reach = 0;
  height ref_height;
  std::array<double, 2> last_r{};
  bool said = false;

  void units(bool inch) {
    mm = inch ? 25.4 : 1.0;
    increment = m.program.trailing_point ? (inch ? 0.0001 : 0.001) : 1.0;
  }

  double word_value(const nc_word& w) const { return (w.point ? w.number : w.number * increment) * mm; }

  // A vector (or a point, `point`) of the plane in the part frame: Rz(I)·Rx(J)·Rz(K).
  vec3 to_part(vec3 v, bool point) const {
    const auto turn_z = [](vec3 p, double a) {
      return vec3{std::cos(a) * p.x - std::sin(a) * p.y, std::sin(a) * p.x + std::cos(a) * p.y, p.z};
    };
    v = turn_z(v, euler[2]);
    v = {v.x, std::cos(euler[1]) * v.y - std::sin(euler[1]) * v.z,
         std::sin(euler[1]) * v.y + std::cos(euler[1]) * v.z};
    v = turn_z(v, euler[0]);
    return point ? kin::operator+(v, origin) : v;
  }

  // Whether the tip's height is known with the axes at `l`, `r`: Z and the rotary axes (X and Y
  // too where a table turns the part).
  bool height_known(const std::array<axis_value, 3>& l, const std::array<axis_value, 2>& r) const {
    for (int i = 0; i < plan.rotary_count; ++i)
      if (!known(r[static_cast<std::size_t>(i)])) return false;
    if (!known(l[2])) return false;
    return heads_only || (known(l[0]) && known(l[1]));
  }

  // The tip's height in the part frame with the axes at `l` (mm; an unknown X or Y as 0: only
  // the height is read) and `r` (degrees), as a function of the tool's length.
  height tip_height(const std::array<axis_value, 3>& l, const std::array<double, 2>& r) const {
    const vec3 at{known(l[0]) ? l[0].value : 0.0, known(l[1]) ? l[1].value : 0.0, l[2].value};
    // Without the length offset the linear axes carry the gauge point, one tool length above
    // where the tip would be at home.
    const double lift = length ? 0.0 : chain.tool_direction.z;
    if (heads_only) {
      // The linear words are the tip's place with the heads at 0: the heads' part of the
      // transform is added to them (kin::head_offset), found again only when they turn.
      if (!offset_cached || r != offset_at) {
        kin::joint_values j;
        j.rotary = r;
        const kin::joint_turns turns(plan, j);
        offset0 = kin::head_offset(plan, turns, 0);
        offset_per_mm = kin::operator-(kin::head_offset(plan, turns, 1), offset0);
        offset_at = r;
        offset_cached = true;
      }
      return {at.z + offset0.z, offset_per_mm.z - lift + shift[2]};
    }
    kin::joint_values j;
    j.linear = at;
    j.rotary = r;
    const double z0 = kin::forward(plan, j, 0).tip.z;
    j.linear = {at.x - chain.tool_direction.x * (length ? 0.0 : 1.0) + shift[0],
                at.y - chain.tool_direction.y * (length ? 0.0 : 1.0) + shift[1], at.z - lift + shift[2]};
    return {z0, kin::forward(plan, j, 1).tip.z - z0};
  }

  // The rotations at `j`'s rotary values: the last ones kept (most records of a program turn
  // nothing, or a little: their sines are not computed again).
  mutable std::array<double, 2> turns_at{std::nan(""), std::nan("")};
  mutable std::array<kin::turn, 2> turns_kept{};
  kin::joint_turns turns_of(const kin::joint_values& j) const {
    if (j.rotary != turns_at) {
      turns_kept = kin::joint_turns(plan, j).t;
      turns_at = j.rotary;
    }
    return kin::joint_turns(turns_kept);
  }

  // Where the program has put the tip and which way the tool points, for a tool `l` mm long.
  std::optional<rotary_sweep::pose> where(double l) const {
    if (cycle) return std::nullopt;
    if (vector) {
      // X Y Z the tip, I J K the tool's axis, both in the part frame.
      if (frame) return std::nullopt;
      for (const auto* a : {&lin, &ijk})
        for (const axis_value& v : *a)
          if (!known(v)) return std::nullopt;
      return rotary_sweep::pose{{lin[0].value, lin[1].value, lin[2].value},
                                {ijk[0].value, ijk[1].value, ijk[2].value}};
    }
    kin::joint_values j;
    for (int i = 0; i < plan.rotary_count; ++i) {
      if (!known(rot[static_cast<std::size_t>(i)])) return std::nullopt;
      j.rotary[static_cast<std::size_t>(i)] = rot[static_cast<std::size_t>(i)].value;
    }
    const kin::joint_turns turns = turns_of(j);
    const std::array<axis_value, 3>& at = frame ? flin : lin;
    for (const axis_value& a : at)
      if (!known(a)) return std::nullopt;
    const vec3 p{at[0].value, at[1].value, at[2].value};
    // In a tilted plane its coordinates are the tip's, the length along its Z; under tool-tip
    // control the words are the tip in the part frame.
    if (frame) {
      if (!plane || !length || tcp) return std::nullopt;
      return rotary_sweep::pose{to_part(p, true), kin::tool_axis(plan, turns)};
    }
    if (tcp) return rotary_sweep::pose{p, kin::tool_axis(plan, turns)};
    return joints_pose(p, j, turns, l);
  }

  // The tip and axis of a tool `l` long with the linear words at `p` and the rotary axes at
  // `j` (turned `turns`), neither tool-tip control nor a tilted plane in force.
  std::optional<rotary_sweep::pose> joints_pose(const vec3& p, kin::joint_values j,
                                                const kin::joint_turns& turns, double l) const {
    if (chain.output == multiaxis_output::pivot) {
      // The words are the pivot for the programmed length (machines/kinematic_chain.hpp
      // pivot_shift); a length offset making up another tool's length is not followed.
      if (length) return std::nullopt;
      const vec3 s = pivot_shift(chain);
      j.linear = {p.x - s.x, p.y - s.y, p.z - s.z};
      const kin::tool_pose t = kin::forward(plan, j, chain.programmed_length, turns);
      return rotary_sweep::pose{t.tip, t.axis};
    }
    if (!length) return std::nullopt;  // the gauge point: the comparison says so
    j.linear = {p.x + l * shift[0], p.y + l * shift[1], p.z + l * shift[2]};
    const kin::tool_pose t = kin::forward(plan, j, l, turns);
    return rotary_sweep::pose{t.tip, t.axis};
  }

  // The tip a fraction `t` along the last block, every axis moving linearly from where it
  // started (a control's interpolation of the joints); none under tool-tip control, I J K or a
  // tilted plane, in a cycle, where an end is not known, or when the block turned no rotary
  // axis (its tip then runs straight).
  std::optional<rotary_sweep::pose> along(double l, double t) const {
    if (cycle || vector || frame || tcp) return std::nullopt;
    kin::joint_values j;
    bool turned = false;
    for (int i = 0; i < plan.rotary_count; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (!known(rot[k]) || !known(rot_from[k])) return std::nullopt;
      turned = turned || rot[k].value != rot_from[k].value;
      // A `shortest` axis reads its value modulo 360 and turns the shorter way.
      double turn = rot[k].value - rot_from[k].value;
      if (chain.rotaries[k].rollover == rotary_rollover::shortest) turn = std::remainder(turn, 360.0);
      j.rotary[k] = rot_from[k].value + t * turn;
    }
    if (!turned) return std::nullopt;
    double p[3];
    for (std::size_t i = 0; i < 3; ++i) {
      if (!known(lin[i]) || !known(lin_from[i])) return std::nullopt;
      p[i] = lin_from[i].value + t * (lin[i].value - lin_from[i].value);
    }
    return joints_pose({p[0], p[1], p[2]}, j, kin::joint_turns(plan, j), l);
  }

  // The tip's height where the program has put it; none where that is not known.
  std::optional<height> height_now() const {
    if (!frame) return height_known(lin, rot) ? std::optional(tip_height(lin, values(rot))) : std::nullopt;
    return plane_height(flin);
  }

  // The tip's height at the plane's coordinates `f`: the point itself, whatever the length.
  std::optional<height> plane_height(const std::array<axis_value, 3>& f) const {
    if (!frame || !plane || !length || tcp) return std::nullopt;
    for (const axis_value& a : f)
      if (!known(a)) return std::nullopt;
    return height{to_part({f[0].value, f[1].value, f[2].value}, true).z, 0};
  }

  static std::array<double, 2> values(const std::array<axis_value, 2>& r) { return {r[0].value, r[1].value}; }

  // G69: the plane's moves leave the tip where its coordinates said; the linear axes are then
  // where that tip is with the rotary axes as they stand (the length offset along Z again).
  void leave_frame() {
    if (frame) {
      bool all = plane && length && !tcp;
      for (const axis_value& a : flin) all = all && known(a);
      for (int i = 0; i < plan.rotary_count; ++i) all = all && known(rot[static_cast<std::size_t>(i)]);
      if (all) {
        kin::joint_values angles;
        angles.rotary = values(rot);
        const vec3 t = to_part({flin[0].value, flin[1].value, flin[2].value}, true);
        const kin::joint_values j = kin::positions(chain, t, angles, 0);
        lin = {axis_value{axis_value::kind::known, j.linear.x},
               axis_value{axis_value::kind::known, j.linear.y},
               axis_value{axis_value::kind::known, j.linear.z}};
        const kin::joint_values j1 = kin::positions(chain, t, angles, 1);
        shift = {j1.linear.x - j.linear.x, j1.linear.y - j.linear.y, j1.linear.z - j.linear.z};
      } else {
        for (axis_value& a : lin)
          if (a.k == axis_value::kind::known) a.k = axis_value::kind::unknown;
      }
    }
    frame = plane = false;
  }

  void new_tool(int t) {
    bounded = false;
    // A control whose tool call gives the length offset (joints output with no length_on: a
    // Sinumerik's T1 D1 M6) has it in force from the call.
    if (chain.length_on.empty() && chain.output == multiaxis_output::joints && t >= 0) length = true;
    const std::optional<double> l = t >= 0 ? m.tool_length(channel, t) : std::nullopt;
    length_known = l.has_value();
    lengths.clear();
    if (l)
      lengths.push_back(*l);
    else
      for (double x = 0; x <= long_tool + 1e-9; x += length_step) lengths.push_back(x);
    // The work's top stays (the work is the same) for every length of the new tool: where the
    // last tool's length was not known either, the lowest it may have been.
    std::vector<double> old = std::move(top);
    top.assign(lengths.size(), old.empty() ? 0.0 : *std::min_element(old.begin(), old.end()));
  }

  // One word of a linear axis (`linear`: in the program's unit, a word without a decimal point
  // in its least increments) or of a rotary one (degrees, 0.001 without a point): where it
  // leaves the axis.
  void set(axis_value& a, const nc_word& w, bool incremental, bool linear) const {
    const double v = linear ? (w.point ? w.number : w.number * increment) * mm
                            : (w.point || !m.program.trailing_point ? w.number : w.number * 0.001);
    if (!w.numeric) {
      a.k = axis_value::kind::unknown;  // B#100: known only when the block runs
    } else if (!incremental) {
      a = {axis_value::kind::known, v};
    } else if (known(a)) {
      a.value += v;
    } else {
      a.k = axis_value::kind::unknown;  // an increment from home or from anywhere unknown
    }
  }

  // The comparison's follower on a block of axis words and F alone (most of a 5-axis
  // program's): the axes, as block() sets them; false for any other block.
  bool plain_block(const std::vector<nc_word>& words) {
    if (cycle) return false;
    for (const nc_word& w : words)
      if (w.address != 'F' &&
          (w.address < 'A' || w.address > 'Z' || axis_of[static_cast<std::size_t>(w.address - 'A')] < 0))
        return false;
    const bool incremental = !absolute;
    for (const nc_word& w : words) {
      if (w.address == 'F') continue;
      const int a = axis_of[static_cast<std::size_t>(w.address - 'A')];
      if (a >= 3) {
        set(rot[static_cast<std::size_t>(a - 3)], w, incremental, false);
        continue;
      }
      const auto li = static_cast<std::size_t>(a);
      if (frame) {
        if (!plane)
          flin[li].k = axis_value::kind::unknown;
        else
          set(flin[li], w, incremental, true);
        lin[li].k = axis_value::kind::unknown;
        continue;
      }
      set(lin[li], w, incremental, true);
      if (xy_turned && li < 2) lin[li].k = axis_value::kind::unknown;
      if (!incremental) shift[li] = 0;
    }
    return true;
  }

  std::optional<std::pair<int, std::string>> block(const std::vector<nc_word>& words,
                                                   const channel_modes& md) {
    // The motion, G90/G91, the unit and the return level: the modal state's (only a G word
    // changes them).
    if (md.now.any) {
      if (md.motion >= 0) motion = md.motion;
      absolute = !md.incremental;
      if (mm != (md.inch ? 25.4 : 1.0)) units(md.inch);
      return_to_r = md.return_to_r;
    }
    if (follow_only) lin_from = lin, rot_from = rot;
    if (follow_only && plain_block(words)) [[likely]]
      return std::nullopt;
    bool home = false, machine_block = false, not_a_move = false, index = false, plane_block = false;
    bool change = false, incremental = !absolute;
    int rotary_column = 0, t_word = -1;
    for (const nc_word& w : words) {
      if (w.address == 'T' && w.numeric && w.number >= 0 && w.number < 1e9)
        t_word = static_cast<int>(w.number);
      if (w.address == 'M' && w.numeric && w.number == change_m) change = true;
      if (w.address == 'M' && w.numeric && (tcp_m >= 0 || off_m >= 0)) [[unlikely]] {
        if (g100(w.number) == tcp_m) tcp = length = true, vector = chain.output == multiaxis_output::vector;
        if (g100(w.number) == off_m) tcp = vector = length = false;
      }
      if (w.address != 'G' || !w.numeric) continue;
      const int g = g100(w.number);
      if (g == 0 || g == 100 || g == 200 || g == 300) cycle = false;  // (the motion: the modal state's)
      if (g == 2800 || g == 3000) home = true;
      if (g == 5300) machine_block = true;
      if (g == 8000) cycle = false;
      if (g == 7300 || (g >= 8100 && g <= 8900)) {
        if (!cycle) initial = lin[2];  // the initial level G98 returns to
        cycle = true;
      }
      // A dwell, data or coordinate setting, macro call, scaling (analysis/nc_codes): no move.
      if (codes.role(w.number) == axis_words::none) not_a_move = true;
      // Tool-tip control: the chain's code, and Fanuc's two (G43.4, G43.5 with the tool axis).
      // (The chain's own code writes I J K where its output is `vector`, whatever the code.)
      if (g == tcp_g || g == 4340 || g == 4350)
        tcp = length = true, vector = g == 4350 || (g == tcp_g && chain.output == multiaxis_output::vector);
      if (g == length_g && g != tcp_g) tcp = vector = false, length = true;
      if (g == off_g || g == 4900) tcp = vector = length = false;
      if (g == plane_g) {
        // G68.2 X Y Z I J K: the plane's origin and Fanuc's Z-X-Z Euler angles (with a P word
        // the I J K mean something else: the plane is not followed).
        frame = plane_block = true;
        plane = true;
        origin = {};
        euler = {};
        for (const nc_word& a : words) {
          if (a.address == 'P') plane = false;
          if (!a.numeric) continue;
          if (a.address == 'I' || a.address == 'J' || a.address == 'K')
            euler[static_cast<std::size_t>(a.address - 'I')] = a.number * std::numbers::pi / 180;
          for (int i = 0; i < 3; ++i)
            if (a.address == linear_address[static_cast<std::size_t>(i)])
              (i == 0 ? origin.x : i == 1 ? origin.y : origin.z) = word_value(a);
        }
        frame_axis = to_part({0, 0, 1}, false);
        for (axis_value& a : flin) a.k = axis_value::kind::unknown;
      } else if (g == 6830 || g == 6840) {
        // Fanuc's tilted planes by the tool axis (G68.3) and by increments (G68.4): a frame
        // whose moves are not followed (attack 63 H3: their X Y Z were read as a move).
        frame = true;
        plane = false;
        not_a_move = true;
        for (axis_value& a : flin) a.k = axis_value::kind::unknown;
      } else if (g == 6800) {
        // G68 X Y R in the XY plane turns X and Y about Z: heights stay Z's (attack 62 M2). About
        // another axis (I, J) it is a frame whose moves are not followed.
        bool about_z = true;
        for (const nc_word& a : words)
          if ((a.address == 'I' || a.address == 'J') && (!a.numeric || a.number != 0)) about_z = false;
        if (about_z) {
          xy_turned = true;
        } else {
          frame = true;
          plane = false;
        }
        not_a_move = true;
      }
      if (g == 6900) xy_turned = false;
      if ((g >= 5400 && g <= 5900 && g % 100 == 0) || g == 5410) {
        // Each work offset is a part of its own, with a top of its own (attack 62 FP6: a second
        // part in G55 with another Z zero was held to the first's top).
        int id = g;
        if (g == 5410)
          for (const nc_word& a : words)
            if (a.address == 'P' && a.numeric) id = 100000 + static_cast<int>(a.number);
        use_offset(id);
      }
      if (g == index_g) index = true;
      if (g == plane_off_g) leave_frame();
    }
    // The tool: a T word with the change code (or alone where the tool call has none), or the
    // change code after a T that preselected it.
    if (t_word >= 0) pending_tool = t_word;
    // The tool change takes Z to its tool-change position, above the work (a machining
    // centre's M6 macro: attack 62 FP5).
    if (change && change_m >= 0 && known(lin[2])) lin[2].k = axis_value::kind::away;
    if ((change || change_m < 0) && pending_tool >= 0) {
      new_tool(pending_tool);
      pending_tool = -1;
    }
    const std::array<axis_value, 3> lin0 = lin, flin0 = flin;
    const std::array<axis_value, 2> rot0 = rot;
    bool turned = false, table = false;
    std::array<bool, 3> homes{};
    std::array<bool, 2> rotary_homes{};
    for (const nc_word& w : words) {
      if (w.address < 'A' || w.address > 'Z') continue;
      const int a_index = axis_of[static_cast<std::size_t>(w.address - 'A')];
      if (vector && !plane_block && motion <= 1 && w.address >= 'I' && w.address <= 'K') [[unlikely]] {
        // Tool-tip control with the tool axis (G43.5): I J K the axis in the part frame, modal
        // (an arc's are its centre's).
        axis_value& v = ijk[static_cast<std::size_t>(w.address - 'I')];
        v = w.numeric ? axis_value{axis_value::kind::known, w.number} : axis_value{};
        continue;
      }
      if (a_index < 0 || plane_block) continue;  // G68.2's X Y Z: the plane's origin
      const int li = a_index < 3 ? a_index : -1, ri = a_index >= 3 ? a_index - 3 : -1;
      if (li >= 0 && frame) {
        // The plane's coordinates: the tip's place in it, once its length offset is along its Z.
        axis_value& f = flin[static_cast<std::size_t>(li)];
        if (home || machine_block || not_a_move || !plane || cycle)
          f.k = axis_value::kind::unknown;
        else
          set(f, w, incremental, true);
        lin[static_cast<std::size_t>(li)].k =
            home || machine_block ? axis_value::kind::away : axis_value::kind::unknown;
        continue;
      }
      if (not_a_move) {
        if (li >= 0) lin[static_cast<std::size_t>(li)].k = axis_value::kind::unknown;
        continue;
      }
      if (li >= 0) {
        axis_value& a = lin[static_cast<std::size_t>(li)];
        if (machine_block) {
          // G53: machine coordinates. Z at or above its machine zero (the top of its travel on a
          // Fanuc mill) is the tool at home; anywhere else, not known in the part frame.
          const bool up = li == 2 && w.numeric && w.number >= 0;
          a.k = up ? axis_value::kind::away : axis_value::kind::unknown;
          continue;
        }
        // A G28/G30 block moves to its intermediate point first (the words, as a G0 would read
        // them), then home.
        set(a, w, incremental, true);
        if (xy_turned && li < 2) a.k = axis_value::kind::unknown;
        if (!incremental) shift[static_cast<std::size_t>(li)] = 0;
        if (home) homes[static_cast<std::size_t>(li)] = true;
        if (cycle) a.k = axis_value::kind::unknown;  // a cycle's R and bottom
        continue;
      }
      axis_value& a = rot[static_cast<std::size_t>(ri)];
      set(a, w, incremental && !machine_block, false);
      if (home) rotary_homes[static_cast<std::size_t>(ri)] = true;
      if (!rotary_column) rotary_column = w.column;
      const bool moved = !known(rot0[static_cast<std::size_t>(ri)]) || !known(a) ||
                         std::abs(a.value - rot0[static_cast<std::size_t>(ri)].value) > 1e-9;
      turned = turned || moved;
      if (moved && chain.rotaries[static_cast<std::size_t>(ri)].kind == rotary_kind::table) table = true;
    }
    if (index && !tcp) {
      // G53.1 turns the rotary axes to the plane's Z, the solution nearest where they stand.
      kin::joint_values previous;
      previous.rotary = values(rot0);
      kin::ik_result r;
      r.error = kin::ik_error::unreachable;
      if (plane)
        r = kin::inverse(plan, kin::tool_pose{{0, 0, 0}, frame_axis}, 0, previous, kin::ik_need::angles);
      for (int i = 0; i < plan.rotary_count; ++i) {
        const auto u = static_cast<std::size_t>(i);
        if (!r.ok()) {
          rot[u].k = axis_value::kind::unknown;
          continue;
        }
        if (chain.rotaries[u].kind == rotary_kind::table &&
            (!known(rot0[u]) || std::abs(r.joints.rotary[u] - rot0[u].value) > 1e-9))
          table = true;
        rot[u] = {axis_value::kind::known, r.joints.rotary[u]};
      }
      turned = true;
    }
    std::optional<std::pair<int, std::string>> finding;
    const bool rapid = motion == 0 || home || machine_block || index;
    if (follow_only) [[likely]] {
      // The comparison's follower: where the axes are, not the swings or the work's top.
      for (int i = 0; i < 3; ++i)
        if (homes[static_cast<std::size_t>(i)]) lin[static_cast<std::size_t>(i)].k = axis_value::kind::away;
      for (std::size_t i = 0; i < 2; ++i)
        if (rotary_homes[i]) rot[i] = {axis_value::kind::known, 0};
      if (cycle && !frame && absolute) cycle_end(words);
      return finding;
    }
    // A table turns the part, not the tool: the tip keeps its distance from the table's axis,
    // and whether the part reaches it is the part's size, which the program does not say.
    if (turned && rapid && !tcp && !table && !said && !frame)
      finding = swing(lin0, rot0, index, rotary_column);
    if (index && frame && !tcp && turned && !table && !said)
      finding = swing(lin0, rot0, index, rotary_column);
    for (int i = 0; i < 3; ++i)
      if (homes[static_cast<std::size_t>(i)]) lin[static_cast<std::size_t>(i)].k = axis_value::kind::away;
    // G28 B..: from its intermediate point the head turns on to its reference point (0), with
    // the linear axes the block names at home and the others where they stand (attack 62 M1:
    // `G91 G28 B0.` at the clearance was never followed, and B kept its old angle).
    if (rotary_homes[0] || rotary_homes[1]) {
      const std::array<axis_value, 3> l_mid = lin;
      const std::array<axis_value, 2> r_mid = rot;
      bool moved = false;
      for (std::size_t i = 0; i < 2; ++i)
        if (rotary_homes[i]) {
          moved = moved || !known(rot[i]) || rot[i].value != 0;
          rot[i] = {axis_value::kind::known, 0};
        }
      if (moved && !finding && !tcp && !table && !said && !frame)
        finding = swing(l_mid, r_mid, false, rotary_column);
    }
    if (rapid) {
      // A rapid's end: the level later feeds at or above it link at (a retract, not a cut).
      if (const std::optional<height> h = height_now()) ceiling = *h, has_ceiling = true;
    } else if (!cycle) {
      feed_top(lin0, rot0, flin0);
    }
    if (cycle && !frame && absolute) cycle_top(words);
    return finding;
  }

  // A feed block: the work reaches as high as where it starts and ends.
  void feed_top(const std::array<axis_value, 3>& l0, const std::array<axis_value, 2>& r0,
                const std::array<axis_value, 3>& f0) {
    // (A feed that cannot reach the top is passed over, a retract's ceiling with it: only a feed
    // above the top could have been taken for a cut by a ceiling missed there, and a feed that
    // ends above the top is never passed over.)
    if (!frame && heads_only && height_known(l0, r0) && height_known(lin, rot) && under_top(l0, r0)) return;
    const std::optional<height> end = height_now();
    std::optional<height> start = frame ? plane_height(f0) : std::nullopt;
    if (!frame && height_known(l0, r0)) start = tip_height(l0, values(r0));
    if (!end && !start) return;
    const height e = end.value_or(start.value_or(height{})), b = start.value_or(e);
    // What a feed says of the work (attack 62 FP1: a feed at the clearance made the clearance
    // the work's top): a feed up (a retract at feed) cuts at its start, and its end is the level
    // later feeds link at; a feed at or above that level, or at the last rapid's, links; a feed
    // down cuts from at most `plunge_above` over its end (an approach at feed from the clearance
    // starts far above the work) and `feed_plane_above` under its start (a plunge starts from
    // the CAM's feed plane, a few mm over the work: attack 62 FP4, a link at that height).
    const bool up = e.at(lengths[0]) > b.at(lengths[0]) + sag_allowed;
    bool any = false;
    for (std::size_t k = 0; k < lengths.size(); ++k) {
      const double eu = e.at(lengths[k]), bu = b.at(lengths[k]);
      double h = 0;
      if (up)
        h = bu;
      else if (has_ceiling && eu >= ceiling.at(lengths[k]) - sag_allowed)
        continue;
      else
        h = std::max(eu, std::min(bu - feed_plane_above, eu + plunge_above));
      if (!has_top || h > top[k]) top[k] = h;
      any = true;
    }
    if (up) ceiling = e, has_ceiling = true;
    if (!any) return;
    has_top = true;
    // The end's exact height: the reference later feed blocks are bounded from.
    bounded = false;
    if (!frame && heads_only && end) {
      bounded = true;
      ref_z = lin[2].value;
      ref_height = *end;
      travel = 0;
      last_z = lin[2].value;
      last_r = values(rot);
    }
  }

  // A drilling cycle's block: its R plane (a Z under G90 on a mill) is where each hole's feed
  // starts, at the hole's X and Y: the work reaches that high.
  // A hole drilled: the tool ends at the initial level (G98) or the R plane (G99).
  void cycle_end(const std::vector<nc_word>& words) {
    bool moves = false;
    for (const nc_word& w : words)
      moves = moves || (w.address >= 'A' && w.address <= 'Z' &&
                        axis_of[static_cast<std::size_t>(w.address - 'A')] >= 0);
    for (const nc_word& w : words)
      if (w.address == 'R' && w.numeric) r_plane = {axis_value::kind::known, word_value(w)};
    if (moves) lin[2] = return_to_r ? r_plane : initial;
  }

  void cycle_top(const std::vector<nc_word>& words) {
    cycle_end(words);
    for (const nc_word& w : words) {
      if (w.address != 'R' || !w.numeric) continue;
      std::array<axis_value, 3> l = lin;
      l[2] = {axis_value::kind::known, word_value(w)};
      if (!height_known(l, rot)) return;
      const height h = tip_height(l, values(rot));
      for (std::size_t k = 0; k < lengths.size(); ++k)
        if (!has_top || h.at(lengths[k]) > top[k]) top[k] = h.at(lengths[k]);
      has_top = true;
      bounded = false;
      return;
    }
  }

  // Whether a feed block that continues the last one (it starts where that one ended) cannot
  // raise the work's top: its height is bounded by the last exact one, the Z words since, and
  // how far the heads have turned since (the tip moves at most its distance from their axes per
  // radian), without the trigonometry of an exact height at every block of a joints program.
  bool under_top(const std::array<axis_value, 3>& l0, const std::array<axis_value, 2>& r0) {
    if (!bounded || !has_top || l0[2].value != last_z || values(r0) != last_r) return false;
    const auto r = values(rot);
    for (int i = 0; i < plan.rotary_count; ++i)
      travel += std::abs(r[i] - r0[i].value) * std::numbers::pi / 180;
    last_z = lin[2].value;
    last_r = r;
    const double rise = std::max(l0[2].value, lin[2].value) - ref_z;
    for (std::size_t k = 0; k < lengths.size(); ++k)
      if (ref_height.at(lengths[k]) + rise + (reach + plan.head_count * lengths[k]) * travel > top[k])
        return false;
    return true;
  }

  // The tip's path through a rapid that turns a head, against the work's top.
  std::optional<std::pair<int, std::string>> swing(const std::array<axis_value, 3>& l0,
                                                   const std::array<axis_value, 2>& r0, bool index,
                                                   int column) {
    if (!has_top) return std::nullopt;
    // With Z at home (its reference point, or G53 at the top of its travel) the tool is clear.
    if (l0[2].k == axis_value::kind::away || lin[2].k == axis_value::kind::away) return std::nullopt;
    if (!height_known(l0, r0) || !height_known(lin, rot)) return std::nullopt;
    const auto ra = values(r0), rb = values(rot);
    double most = 0;
    for (int i = 0; i < plan.rotary_count; ++i) most = std::max(most, std::abs(rb[i] - ra[i]));
    const int n = std::clamp(static_cast<int>(std::ceil(most * 4)), 4, 720);  // a quarter degree
    // The tip below the work's top, carried there by the turn itself: below where the linear
    // words alone would put it with the heads held (a rapid down to a level the program names
    // is the program's own: the unwind at a clearance whose words stay put), or below both of
    // the tip's own heights at the rapid's ends (the tilt from a point to the same point tilted,
    // whose words drop to pay for the tilt: review 61). For every length followed.
    const std::size_t ks = lengths.size();
    std::vector<double> low(ks), drop(ks);
    std::vector<char> found(ks, 0);
    const height h0 = tip_height(l0, ra), h1 = tip_height(lin, rb);
    for (int k = 0; k <= n; ++k) {
      const double t = static_cast<double>(k) / n;
      std::array<axis_value, 3> l = l0;
      for (int i = 0; i < 3; ++i)
        if (known(l0[i]) && known(lin[i])) l[i].value = l0[i].value + (lin[i].value - l0[i].value) * t;
      std::array<double, 2> r{};
      for (int i = 0; i < 2; ++i) r[i] = ra[i] + (rb[i] - ra[i]) * t;
      const height z = tip_height(l, r), held = tip_height(l, ra);
      for (std::size_t u = 0; u < ks; ++u) {
        const double zu = z.at(lengths[u]);
        if (zu >= top[u] - sag_allowed || (found[u] && zu >= low[u])) continue;
        const double ends = std::min(h0.at(lengths[u]), h1.at(lengths[u]));
        const double below = std::max(held.at(lengths[u]), ends) - zu;
        if (below <= sag_allowed) continue;
        low[u] = zu, drop[u] = below, found[u] = 1;
      }
    }
    for (char f : found)
      if (!f) return std::nullopt;
    said = true;
    std::string turn;
    for (int i = 0; i < plan.rotary_count; ++i)
      if (std::abs(rb[i] - ra[i]) > 1e-9)
        turn += fmt::format("{}{} {} to {}", turn.empty() ? "" : ", ",
                            rotary_address[static_cast<std::size_t>(i)], kin::number_text(ra[i]),
                            kin::number_text(rb[i]));
    return std::pair{
        column ? column : 1,
        fmt::format(
            "{} turns the rotary axes ({}) with tool-tip control off and the tool not at home: the "
            "tip swings down to z {:.3f} (the part frame, mm; {}), {:.3f} mm below where the linear "
            "words, or both its ends, put it, and below z {:.3f}, the highest the program "
            "has fed a tool from or to: the "
            "work reaches that high; retract Z to its reference point (G91 G28 Z0.) before the rotary "
            "axes turn",
            index ? chain.plane_index : std::string("the rapid"), turn, low[0],
            length_known ? fmt::format("a tool {:g} mm long", lengths[0])
                         : fmt::format("the gauge point's: the tool's length is not known, and every tool "
                                       "up to {:g} mm long swings below too",
                                       long_tool),
            drop[0], top[0])};
  }
};

rotary_sweep::rotary_sweep(const machine& m, const kinematic_chain& chain, int channel, int change_m,
                           bool follow_only)
    : p_(std::make_unique<impl>(m, chain, channel, change_m, follow_only)) {}
rotary_sweep::~rotary_sweep() = default;
rotary_sweep::rotary_sweep(rotary_sweep&&) noexcept = default;
rotary_sweep& rotary_sweep::operator=(rotary_sweep&&) noexcept = default;

std::optional<std::pair<int, std::string>> rotary_sweep::block(const std::vector<nc_word>& words,
                                                               const channel_modes& modes) {
  return p_->block(words, modes);
}

std::optional<rotary_sweep::pose> rotary_sweep::where(double length) const { return p_->where(length); }

std::optional<rotary_sweep::pose> rotary_sweep::where_along(double length, double t) const {
  return p_->along(length, t);
}

bool rotary_sweep::length_on() const { return p_->length; }

bool rotary_sweep::tool_tip_on() const { return p_->tcp; }

std::optional<vec3> rotary_sweep::axis_now() const {
  if (p_->vector) {
    for (const auto& v : p_->ijk)
      if (!known(v)) return std::nullopt;
    return vec3{p_->ijk[0].value, p_->ijk[1].value, p_->ijk[2].value};
  }
  kin::joint_values j;
  for (int i = 0; i < p_->plan.rotary_count; ++i) {
    const auto& r = p_->rot[static_cast<std::size_t>(i)];
    if (!known(r)) return std::nullopt;
    j.rotary[static_cast<std::size_t>(i)] = r.value;
  }
  return kin::tool_axis(p_->plan, p_->turns_of(j));
}

bool rotary_sweep::upright() const {
  if (p_->frame) return false;
  for (int i = 0; i < p_->plan.rotary_count; ++i) {
    const auto& r = p_->rot[static_cast<std::size_t>(i)];
    if (!known(r) || r.value != 0) return false;
  }
  return true;
}

}  // namespace twinpost
