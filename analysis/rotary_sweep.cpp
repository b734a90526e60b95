#include "analysis/rotary_sweep.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <numbers>

#include "kinematics/forward.hpp"
#include "kinematics/inverse.hpp"

namespace twinpost {

namespace {

constexpr double level_tolerance = 0.01;  // mm: the chains' chordal tolerance

int g100(double g) { return static_cast<int>(std::lround(g * 100)); }

// The G number of a machine code ("G43.4" -> 4340); -1 when it has none.
int code_g(const std::string& code) {
  for (const nc_word& w : split_nc_words(code))
    if (w.address == 'G' && w.numeric) return g100(w.number);
  return -1;
}

struct axis_value {
  enum class kind : unsigned char { unknown, known, away } k = kind::unknown;
  double value = 0;  // mm, or degrees
};

}  // namespace

struct rotary_sweep::impl {
  impl(const machine& m, const kinematic_chain& c, int channel) : m(m), chain(c), plan(c), channel(channel) {
    for (std::size_t i = 0; i < 3 && i < c.linear.size(); ++i) linear_address[i] = c.linear[i];
    for (std::size_t i = 0; i < c.rotaries.size() && i < 2; ++i) rotary_address[i] = c.rotaries[i].address;
    tcp_g = code_g(c.tool_tip_on);
    off_g = code_g(c.tool_tip_off);
    length_g = code_g(c.length_on);
    plane_g = code_g(c.plane);
    index_g = code_g(c.plane_index);
    plane_off_g = code_g(c.plane_off);
    increment = m.program.trailing_point ? 0.001 : 1.0;
    for (int i = 0; i < plan.rotary_count; ++i) rot[i] = {axis_value::kind::known, 0};
  }

  const machine& m;
  const kinematic_chain& chain;
  kin::chain_plan plan;
  int channel;
  std::array<char, 3> linear_address{'X', 'Y', 'Z'};
  std::array<char, 2> rotary_address{0, 0};
  int tcp_g = -1, off_g = -1, length_g = -1, plane_g = -1, index_g = -1, plane_off_g = -1;
  double increment = 0.001;  // what a word without a decimal point counts
  double mm = 1;             // mm per program unit (G20: 25.4)

  std::array<axis_value, 3> lin{};
  std::array<axis_value, 2> rot{};
  bool absolute = true;
  int motion = -1;
  bool tcp = false, length = false, frame = false, cycle = false;
  // A tilted working plane (G68.2): its origin and Euler angles, its Z in the part frame, the
  // tip's place in its coordinates, and whether an axis moved in it before G53.1.
  bool plane = false, frame_moved = false;
  vec3 origin{};
  std::array<double, 3> euler{};
  vec3 frame_axis{0, 0, 1};
  std::array<axis_value, 3> flin{};

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

  // The tip in the part frame where the program has put it; none where that is not known.
  std::optional<vec3> tip_now() const {
    if (!frame) return all_known(lin, rot) ? std::optional(tip(values(lin), values(rot))) : std::nullopt;
    if (!plane || !length || tcp || !all_known(flin, rot)) return std::nullopt;
    return to_part({flin[0].value, flin[1].value, flin[2].value}, true);
  }

  // G69: the plane's moves leave the tip where its coordinates said; the linear axes are then
  // where that tip is with the rotary axes as they stand (the length offset along Z again).
  void leave_frame() {
    const std::optional<vec3> t = frame ? tip_now() : std::nullopt;
    if (frame) {
      if (t) {
        kin::joint_values angles;
        angles.rotary = values(rot);
        const kin::joint_values j = kin::positions(chain, *t, angles, tool_length);
        lin = {axis_value{axis_value::kind::known, j.linear.x},
               axis_value{axis_value::kind::known, j.linear.y},
               axis_value{axis_value::kind::known, j.linear.z}};
      } else {
        for (axis_value& a : lin)
          if (a.k == axis_value::kind::known) a.k = axis_value::kind::unknown;
      }
    }
    frame = plane = false;
  }
  int tool = -1;
  double tool_length = 0;
  bool length_known = false;
  // The last safe height (after()).
  bool has_safe = false;
  double safe = 0;
  bool cut_since = false;  // a cut since the tool call
  bool said = false;

  bool known(const axis_value& a) const { return a.k == axis_value::kind::known; }

  double word_value(const nc_word& w) const { return w.point ? w.number : w.number * increment; }

  // The tip in the part frame with the axes at `l` (mm) and `r` (degrees).
  vec3 tip(const std::array<double, 3>& l, const std::array<double, 2>& r) const {
    kin::joint_values j;
    j.linear = {l[0], l[1], l[2]};
    // Without the length offset the linear axes carry the gauge point, one tool length above
    // where the tip would be at home.
    if (!length) j.linear = kin::operator-(j.linear, kin::operator*(tool_length, chain.tool_direction));
    j.rotary = r;
    return kin::forward(plan, j, tool_length).tip;
  }

  bool all_known(const std::array<axis_value, 3>& l, const std::array<axis_value, 2>& r) const {
    for (const axis_value& a : l)
      if (!known(a)) return false;
    for (int i = 0; i < plan.rotary_count; ++i)
      if (!known(r[static_cast<std::size_t>(i)])) return false;
    return true;
  }

  static std::array<double, 3> values(const std::array<axis_value, 3>& l) {
    return {l[0].value, l[1].value, l[2].value};
  }
  static std::array<double, 2> values(const std::array<axis_value, 2>& r) { return {r[0].value, r[1].value}; }

  void new_tool(int t) {
    tool = t;
    has_safe = false;
    cut_since = false;
    const std::optional<double> l = m.tool_length(channel, t);
    tool_length = l.value_or(0);
    length_known = l.has_value();
  }

  std::optional<std::pair<int, std::string>> block(const std::vector<nc_word>& words) {
    bool home = false, machine_block = false, not_a_move = false, index = false, plane_block = false;
    int rotary_column = 0;
    for (const nc_word& w : words) {
      if (w.address == 'T' && w.numeric) {
        new_tool(static_cast<int>(w.number));
        continue;
      }
      if (w.address != 'G' || !w.numeric) continue;
      const int g = g100(w.number);
      if (g == 0 || g == 100 || g == 200 || g == 300) motion = g / 100, cycle = false;
      if (g == 9000) absolute = true;
      if (g == 9100) absolute = false;
      if (g == 2000) mm = 25.4;
      if (g == 2100) mm = 1;
      if (g == 2800 || g == 3000) home = true;
      if (g == 5300) machine_block = true;
      if (g == 8000) cycle = false;
      if (g == 7300 || (g >= 8100 && g <= 8900)) cycle = true;
      if (g == 400 || g == 1000 || g == 5000 || g == 5200 || g == 6500 || g == 9200) not_a_move = true;
      if (g == tcp_g) tcp = length = true;
      if (g == length_g) tcp = false, length = true;
      if (g == off_g) tcp = length = false;
      if (g == plane_g) {
        // G68.2 X Y Z I J K: the plane's origin and Fanuc's Z-X-Z Euler angles.
        frame = plane = plane_block = true;
        frame_moved = false;
        origin = {};
        euler = {};
        for (const nc_word& a : words) {
          if (!a.numeric) continue;
          if (a.address == 'I' || a.address == 'J' || a.address == 'K')
            euler[static_cast<std::size_t>(a.address - 'I')] = a.number * std::numbers::pi / 180;
          for (int i = 0; i < 3; ++i)
            if (a.address == linear_address[static_cast<std::size_t>(i)])
              (i == 0 ? origin.x : i == 1 ? origin.y : origin.z) = word_value(a) * mm;
        }
        frame_axis = to_part({0, 0, 1}, false);
        for (axis_value& a : flin) a.k = axis_value::kind::unknown;
      } else if (g == 6800) {
        frame = true;  // a rotation the plane's words give some other way: its moves not followed
        plane = false;
        not_a_move = true;
      }
      if (g == index_g) index = true;
      if (g == plane_off_g) leave_frame();
    }
    const std::array<axis_value, 3> lin0 = lin;
    const std::array<axis_value, 2> rot0 = rot;
    bool turned = false, table = false;
    for (const nc_word& w : words) {
      int li = -1, ri = -1;
      for (int i = 0; i < 3; ++i)
        if (w.address == linear_address[static_cast<std::size_t>(i)]) li = i;
      for (int i = 0; i < plan.rotary_count; ++i)
        if (w.address == rotary_address[static_cast<std::size_t>(i)]) ri = i;
      if ((li < 0 && ri < 0) || plane_block) continue;  // G68.2's X Y Z: the plane's origin
      if (frame && li >= 0 && !home && !machine_block && !not_a_move) {
        // The plane's coordinates: the tip's place in it, once its length offset is along its Z.
        axis_value& f = flin[static_cast<std::size_t>(li)];
        if (!w.numeric || !plane || cycle)
          f.k = axis_value::kind::unknown;
        else if (absolute)
          f = {axis_value::kind::known, word_value(w) * mm};
        else if (f.k == axis_value::kind::known)
          f.value += word_value(w) * mm;
        lin[static_cast<std::size_t>(li)].k = axis_value::kind::unknown;
        frame_moved = true;
        continue;
      }
      if (frame && li >= 0 && (home || machine_block))
        flin[static_cast<std::size_t>(li)].k = axis_value::kind::unknown;
      if (not_a_move) {
        if (li >= 0 && !home && !machine_block)
          lin[static_cast<std::size_t>(li)].k = axis_value::kind::unknown;
        continue;
      }
      axis_value& a = li >= 0 ? lin[static_cast<std::size_t>(li)] : rot[static_cast<std::size_t>(ri)];
      const double scale = li >= 0 ? mm : 1.0;
      if (!w.numeric) {
        a.k = axis_value::kind::unknown;
      } else if (li >= 0 && (home || machine_block)) {
        a.k = axis_value::kind::away;
      } else if (ri >= 0 && home) {
        a = {axis_value::kind::known, 0};  // the rotary's reference point
      } else if (li >= 0 && cycle) {
        a.k = axis_value::kind::unknown;  // a cycle's R and bottom
      } else if (absolute || machine_block) {
        a = {axis_value::kind::known, word_value(w) * scale};
      } else if (a.k == axis_value::kind::known) {
        a.value += word_value(w) * scale;
      }
      if (ri >= 0) {
        if (!rotary_column) rotary_column = w.column;
        const bool moved = !known(rot0[static_cast<std::size_t>(ri)]) || !known(a) ||
                           std::abs(a.value - rot0[static_cast<std::size_t>(ri)].value) > 1e-9;
        turned = turned || moved;
        if (moved && chain.rotaries[static_cast<std::size_t>(ri)].kind == rotary_kind::table) table = true;
      }
    }
    std::optional<std::pair<int, std::string>> finding;
    if (index && !tcp) {
      // G53.1 turns the rotary axes to the plane's Z, the solution nearest where they stand.
      if (!frame_moved && (all_known(lin0, rot0) || lin0[2].k == axis_value::kind::away)) {
        kin::joint_values previous;
        previous.rotary = values(rot0);
        const kin::ik_result r = kin::inverse(plan, kin::tool_pose{{0, 0, 0}, frame_axis}, tool_length,
                                              previous, kin::ik_need::angles);
        if (r.ok()) {
          for (int i = 0; i < plan.rotary_count; ++i) {
            const auto u = static_cast<std::size_t>(i);
            if (chain.rotaries[u].kind == rotary_kind::table &&
                std::abs(r.joints.rotary[u] - rot0[u].value) > 1e-9)
              table = true;
            rot[u] = {axis_value::kind::known, r.joints.rotary[u]};
          }
          turned = true;
          lin = lin0;
        } else {
          for (axis_value& a : rot) a.k = axis_value::kind::unknown;
        }
      } else {
        for (axis_value& a : rot) a.k = axis_value::kind::unknown;
      }
    }
    const bool rapid = motion == 0 || home || machine_block || index;
    // A table turns the part, not the tool: the tip keeps its distance from the table's axis,
    // and whether the part reaches it is the part's size, which the program does not say.
    if (turned && rapid && !tcp && !table && !said) finding = swing(lin0, rot0, index, rotary_column);
    after(rapid);
    return finding;
  }

  // The tip's path through a rapid that turns a rotary axis, against the last safe height.
  std::optional<std::pair<int, std::string>> swing(const std::array<axis_value, 3>& l0,
                                                   const std::array<axis_value, 2>& r0, bool index,
                                                   int column) {
    if (l0[2].k == axis_value::kind::away || lin[2].k == axis_value::kind::away)
      return std::nullopt;  // at home
    if (!has_safe || !all_known(l0, r0) || !all_known(lin, rot)) return std::nullopt;
    const auto a = values(l0), b = values(lin);
    const auto ra = values(r0), rb = values(rot);
    double most = 0;
    for (int i = 0; i < plan.rotary_count; ++i) most = std::max(most, std::abs(rb[i] - ra[i]));
    const int n = std::clamp(static_cast<int>(std::ceil(most)), 1, 3600);
    double low = 0;
    bool first = true;
    for (int k = 0; k <= n; ++k) {
      const double t = static_cast<double>(k) / n;
      std::array<double, 3> l{};
      std::array<double, 2> r{};
      for (int i = 0; i < 3; ++i) l[i] = a[i] + (b[i] - a[i]) * t;
      for (int i = 0; i < 2; ++i) r[i] = ra[i] + (rb[i] - ra[i]) * t;
      const double z = tip(l, r).z;
      if (first || z < low) low = z;
      first = false;
    }
    if (low >= safe - level_tolerance) return std::nullopt;
    said = true;
    std::string turn;
    for (int i = 0; i < plan.rotary_count; ++i)
      if (std::abs(rb[i] - ra[i]) > 1e-9)
        turn += fmt::format("{}{} {:g} to {:g}", turn.empty() ? "" : ", ",
                            rotary_address[static_cast<std::size_t>(i)], ra[i], rb[i]);
    return std::pair{
        column ? column : 1,
        fmt::format(
            "{} turns the rotary axes ({}) with tool-tip control off and the tool not at home: the "
            "tip swings down to z {:.3f} (the part frame, mm; {}), below the last safe height z {:.3f} "
            "the program's first rapid put it at after {}; retract Z to its reference point (G91 G28 Z0.) "
            "before the rotary axes turn",
            index ? chain.plane_index : std::string("the rapid"), turn, low,
            length_known ? fmt::format("a tool {:g} mm long", tool_length)
                         : std::string("the gauge point's: the tool's length is not known"),
            safe, cut_since ? "the last cut" : "the tool call")};
  }

  // The last safe height after the block: where the first rapid after a cut (the retract), or
  // after the tool call the first rapid that puts the tip anywhere known (the approach from
  // home), puts the tip. Later rapids may go higher (a lift for the rotary axes to turn in) or
  // lower (the approach to the cut) without changing it.
  void after(bool rapid) {
    if (!rapid) {
      cut_since = true;
      has_safe = false;
      return;
    }
    if (has_safe || cycle) return;
    const std::optional<vec3> t = tip_now();
    if (!t) return;
    safe = t->z;
    has_safe = true;
  }
};

rotary_sweep::rotary_sweep(const machine& m, const kinematic_chain& chain, int channel)
    : p_(std::make_unique<impl>(m, chain, channel)) {}
rotary_sweep::~rotary_sweep() = default;
rotary_sweep::rotary_sweep(rotary_sweep&&) noexcept = default;
rotary_sweep& rotary_sweep::operator=(rotary_sweep&&) noexcept = default;

std::optional<std::pair<int, std::string>> rotary_sweep::block(const std::vector<nc_word>& words) {
  return p_->block(words);
}

}  // namespace twinpost
