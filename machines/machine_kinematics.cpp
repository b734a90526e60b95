// The [[kinematics]] tables of a machine definition: each channel's kinematic chain, with its
// [[kinematics.rotary]] axes (docs/kinematics.md, "The machine file").
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "machines/code_overlap.hpp"
#include "machines/machine.hpp"
#include "machines/toml_reader.hpp"
#include "support/ascii.hpp"

namespace twinpost::detail {

namespace {

double norm(const vec3& v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }

vec3 cross(const vec3& a, const vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// Reads `key` as an array of three numbers; `unit` asks for a direction, stored normalised.
bool read_vec3(const table_reader& r, std::string_view key, vec3& out, bool unit) {
  const toml::node* n = r.find(key);
  if (!n) return false;
  const toml::array* a = n->as_array();
  if (!a || a->size() != 3)
    r.fail(*n, fmt::format("{} must be an array of three numbers [x, y, z]", r.key_path(key)));
  double v[3];
  for (std::size_t i = 0; i < 3; ++i) {
    const toml::node& e = *a->get(i);
    if (const auto* f = e.as_floating_point())
      v[i] = f->get();
    else if (const auto* k = e.as_integer())
      v[i] = static_cast<double>(k->get());
    else
      r.fail(e, fmt::format("{} must hold only numbers, not {}", r.key_path(key), type_phrase(e.type())));
    if (!std::isfinite(v[i])) r.fail(e, fmt::format("{} must hold finite numbers", r.key_path(key)));
  }
  out = {v[0], v[1], v[2]};
  if (unit) {
    const double l = norm(out);
    if (l < 1e-9) r.fail(*n, fmt::format("{} must not be the zero vector", r.key_path(key)));
    out = {out.x / l, out.y / l, out.z / l};
  }
  return true;
}

template <class E, std::size_t N>
void read_name(const table_reader& r, std::string_view key, const std::pair<std::string_view, E> (&names)[N],
               E& out) {
  std::string text;
  if (!r.read(key, text)) return;
  std::string choices;
  for (std::size_t i = 0; i < N; ++i) {
    if (text == names[i].first) {
      out = names[i].second;
      return;
    }
    choices += i == 0 ? "" : (i + 1 == N ? " or " : ", ");
    choices += names[i].first;
  }
  r.fail(*r.find(key), fmt::format("{} must be {}, not '{}'", r.key_path(key), choices, text));
}

constexpr std::pair<std::string_view, rotary_kind> kind_names[] = {{"head", rotary_kind::head},
                                                                   {"table", rotary_kind::table}};
constexpr std::pair<std::string_view, rotary_rollover> rollover_names[] = {
    {"absolute", rotary_rollover::absolute}, {"shortest", rotary_rollover::shortest}};
constexpr std::pair<std::string_view, multiaxis_output> output_names[] = {
    {"joints", multiaxis_output::joints},
    {"tool_tip", multiaxis_output::tool_tip},
    {"vector", multiaxis_output::vector},
    {"pivot", multiaxis_output::pivot}};
constexpr std::pair<std::string_view, rotary_word_order> order_names[] = {
    {"address", rotary_word_order::address}, {"chain", rotary_word_order::chain}};
constexpr std::pair<std::string_view, multiaxis_moves> moves_names[] = {{"all", multiaxis_moves::all},
                                                                        {"tilted", multiaxis_moves::tilted}};
constexpr std::pair<std::string_view, length_source> length_names[] = {
    {"agree", length_source::agree}, {"table", length_source::table}, {"cl", length_source::cl}};
constexpr std::pair<std::string_view, preferred_sign> prefer_names[] = {
    {"none", preferred_sign::none},
    {"positive", preferred_sign::positive},
    {"negative", preferred_sign::negative}};

rotary_axis_def read_rotary(const table_reader& r, const kinematic_chain& c) {
  rotary_axis_def a;
  r.require("address");
  r.read_char("address", a.address, true);
  if (c.linear.find(a.address) != std::string::npos)
    r.fail(*r.find("address"),
           fmt::format("kinematics.rotary.address {} is a linear axis of the chain", a.address));
  for (const rotary_axis_def& earlier : c.rotaries)
    if (earlier.address == a.address)
      r.fail(*r.find("address"), fmt::format("channel {} has rotary axis {} twice", c.channel, a.address));
  r.require("kind");
  read_name(r, "kind", kind_names, a.kind);
  r.require("direction");
  read_vec3(r, "direction", a.direction, true);
  read_vec3(r, "point", a.point, false);
  r.read("min", a.min);
  r.read("max", a.max);
  bool continuous = false;
  r.read("continuous", continuous);
  if (continuous && (a.min || a.max))
    r.fail(*r.find("continuous"), "kinematics.rotary.continuous = true takes no min or max");
  if (!continuous && (!a.min || !a.max))
    r.fail_here(fmt::format("rotary axis {} needs min and max (degrees), or continuous = true", a.address));
  if (a.min && a.max && *a.min > *a.max)
    r.fail(*r.find("min"),
           fmt::format("kinematics.rotary.min ({}) must be <= kinematics.rotary.max ({})", *a.min, *a.max));
  read_name(r, "rollover", rollover_names, a.rollover);
  if (a.rollover == rotary_rollover::shortest && !continuous)
    r.fail(*r.find("rollover"), "kinematics.rotary.rollover = \"shortest\" needs continuous = true");
  read_name(r, "prefer", prefer_names, a.prefer);
  return a;
}

// The closed-form inverse needs each rotary axis to turn the tool: the axis that is nearer the
// tool (the inner one, docs/kinematics.md) must not lie along the tool, nor along the other.
void check_geometry(const table_reader& r, const toml::table& last, const kinematic_chain& c) {
  auto parallel = [](const vec3& a, const vec3& b) { return norm(cross(a, b)) < 1e-9; };
  if (c.rotaries.size() != 2) return;
  const rotary_axis_def& a = c.rotaries[0];
  const rotary_axis_def& b = c.rotaries[1];
  if (parallel(a.direction, b.direction))
    fail_at(
        r.source(), last.source(),
        fmt::format("rotary axes {} and {} are parallel: they cannot tilt the tool", a.address, b.address));
  // The inner rotation: the head nearer the tool, the primary table, or the head of a mixed chain.
  const rotary_axis_def& inner =
      a.kind == b.kind ? (a.kind == rotary_kind::head ? b : a) : (a.kind == rotary_kind::head ? a : b);
  if (parallel(inner.direction, c.tool_direction))
    fail_at(r.source(), last.source(),
            fmt::format("rotary axis {} lies along the tool: it cannot tilt it", inner.address));
}

// Pivot output: the pivot for a fixed tool length, on a chain whose every move it writes (the
// 3-axis writer and the tilted plane write the tip).
void check_pivot(const table_reader& r, kinematic_chain& c) {
  const bool pivot = c.output == multiaxis_output::pivot;
  if (!r.read("programmed_length", c.programmed_length)) {
    if (pivot)
      r.fail_here(
          "kinematics.output = \"pivot\" needs programmed_length (mm): the tool length the "
          "pivot points are written for");
    return;
  }
  if (!pivot)
    r.fail(*r.find("programmed_length"), "kinematics.programmed_length is read only with output = \"pivot\"");
  if (!(c.programmed_length >= 1 && c.programmed_length < 1e4))
    r.fail(*r.find("programmed_length"),
           fmt::format("kinematics.programmed_length must be >= 1 and < 10000 (mm), not {}",
                       c.programmed_length));
  if (std::none_of(c.rotaries.begin(), c.rotaries.end(),
                   [](const rotary_axis_def& a) { return a.kind == rotary_kind::head; }))
    r.fail(*r.find("output"),
           "kinematics.output = \"pivot\" needs a head: no pivot turns the tool (use "
           "\"joints\")");
  if (c.moves != multiaxis_moves::all)
    r.fail(*r.find("moves"),
           "kinematics.output = \"pivot\" needs moves = \"all\": the lathe's moves write "
           "the tip, not the pivot");
  if (!c.plane.empty())
    r.fail(*r.find("plane"),
           "kinematics.output = \"pivot\" takes no plane: a tilted working plane "
           "positions the tip, not the pivot");
  // The length code of pivot output makes up a tool's difference from the programmed length along
  // the tool; G43/G44 apply it along Z, which at A20 puts the tip sin 20 of it sideways, and
  // G43.4/G43.5 take X Y Z as the tip. Every G word of it, however written (G043, g43, G43.0).
  const std::string on = squeeze_blanks(c.length_on, '(', ')');
  for (std::size_t i = 0; i < on.size(); ++i) {
    if (on[i] == 'M' || on[i] == 'm')
      r.fail(*r.find("length_on"),
             fmt::format("kinematics.length_on = \"{}\" under pivot output holds an M code: "
                         "it must be the length code alone",
                         c.length_on));
    if (on[i] != 'G' && on[i] != 'g') continue;
    std::size_t e = i + 1;
    while (e < on.size() && (ascii::is_digit(on[e]) || on[e] == '.')) ++e;
    const std::string number = on.substr(i + 1, e - i - 1);
    const double g = number.empty() ? -1 : std::atof(number.c_str());
    if (g == 43 || g == 44 || g == 43.4 || g == 43.5 || g == 49)
      r.fail(
          *r.find("length_on"),
          fmt::format("kinematics.length_on = \"{}\" under pivot output: G{} {}, and a tilted tool needs the "
                      "length along the tool (Fanuc's G43.1, tool length compensation in the tool axis "
                      "direction), or none",
                      c.length_on, number,
                      g == 49              ? "cancels the length offset"
                      : g == 43 || g == 44 ? "applies the length along Z"
                                           : "takes X Y Z as the tip"));
  }
  // The pivot: where the heads' axes cross (one head: where its axis crosses the tool's), on the
  // tool's axis through the gauge point. Any point of an axis describes the same machine, so
  // the crossing, not a listed point, is what the control positions.
  struct line {
    vec3 p, d;
  };
  std::vector<line> lines;
  for (const rotary_axis_def& a : c.rotaries)
    if (a.kind == rotary_kind::head) lines.push_back({a.point, a.direction});
  if (lines.size() == 1) lines.push_back({{0, 0, 0}, c.tool_direction});
  const auto dot = [](const vec3& a, const vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; };
  const line &l1 = lines[0], &l2 = lines[1];
  const vec3 w{l1.p.x - l2.p.x, l1.p.y - l2.p.y, l1.p.z - l2.p.z};
  const double a = dot(l1.d, l1.d), b = dot(l1.d, l2.d), cc = dot(l2.d, l2.d), d = dot(l1.d, w),
               e = dot(l2.d, w);
  const double denom = a * cc - b * b;
  if (denom < 1e-12)
    r.fail(*r.find("output"),
           "kinematics.output = \"pivot\": the head's axis lies along the tool, so no pivot "
           "turns it (use \"joints\")");
  const double s = (b * e - cc * d) / denom, t = (a * e - b * d) / denom;
  const vec3 q1{l1.p.x + s * l1.d.x, l1.p.y + s * l1.d.y, l1.p.z + s * l1.d.z};
  const vec3 q2{l2.p.x + t * l2.d.x, l2.p.y + t * l2.d.y, l2.p.z + t * l2.d.z};
  const vec3 gap{q1.x - q2.x, q1.y - q2.y, q1.z - q2.z};
  const vec3& t0 = c.tool_direction;
  const double along = dot(q1, t0);
  const vec3 off{q1.x - along * t0.x, q1.y - along * t0.y, q1.z - along * t0.z};
  const double miss = std::sqrt(dot(gap, gap)), aside = std::sqrt(dot(off, off));
  if (miss > 1e-6 || aside > 1e-6)
    r.fail(*r.find("output"),
           fmt::format(
               "kinematics.output = \"pivot\" needs the heads' axes to cross on the tool's axis: {} ({:g} "
               "mm); the control positions that one point",
               miss > 1e-6 ? "they pass each other" : "they cross off it", miss > 1e-6 ? miss : aside));
  c.pivot_point = q1;
}

}  // namespace

void read_kinematics(const table_reader& root, machine& m) {
  for (const toml::table* t : root.tables("kinematics")) {
    table_reader r(*t, "kinematics", root.source(),
                   {"channel", "linear", "tool_direction", "tolerance", "angle_tolerance", "rotary", "output",
                    "tool_tip_on", "tool_tip_off", "length_on", "inverse_time", "chordal_tolerance", "plane",
                    "moves", "plane_index", "plane_off", "tool_length", "rotary_order", "programmed_length"});
    kinematic_chain c;
    r.require("channel");
    r.read("channel", c.channel);
    if (std::none_of(m.channels.begin(), m.channels.end(),
                     [&](const channel_def& d) { return d.number == c.channel; }))
      r.fail(*r.find("channel"), fmt::format("kinematics.channel {} names no channel", c.channel));
    for (const kinematic_chain& earlier : m.kinematics)
      if (earlier.channel == c.channel)
        r.fail(*r.find("channel"), fmt::format("channel {} has two [[kinematics]] tables", c.channel));
    if (r.read("linear", c.linear)) {
      const bool letters =
          std::all_of(c.linear.begin(), c.linear.end(), [](char x) { return ascii::is_upper(x); });
      if (c.linear.size() != 3 || !letters || c.linear[0] == c.linear[1] || c.linear[0] == c.linear[2] ||
          c.linear[1] == c.linear[2])
        r.fail(*r.find("linear"), fmt::format("kinematics.linear must be three different letters (\"XYZ\"), "
                                              "not \"{}\"",
                                              c.linear));
    }
    read_vec3(r, "tool_direction", c.tool_direction, true);
    read_name(r, "output", output_names, c.output);
    read_name(r, "moves", moves_names, c.moves);
    read_name(r, "tool_length", length_names, c.tool_length);
    read_name(r, "rotary_order", order_names, c.rotary_order);
    if (c.output == multiaxis_output::vector) c.tool_tip_on = "G43.5";
    // Pivot output gives the control the pivot itself: no length offset unless the machine names
    // one that makes up a tool's difference from the programmed length (docs/machines.md).
    if (c.output == multiaxis_output::pivot) c.length_on.clear();
    r.read("tool_tip_on", c.tool_tip_on);
    r.read("tool_tip_off", c.tool_tip_off);
    r.read("length_on", c.length_on);
    r.read("inverse_time", c.inverse_time);
    r.read("plane", c.plane);
    r.read("plane_index", c.plane_index);
    r.read("plane_off", c.plane_off);
    // Each code goes in front of the post's own words in a block: a comment character, a line
    // break or a tape mark in it would swallow the block's words or end the program there.
    for (const auto& [key, code] :
         {std::pair<std::string_view, const std::string*>{"tool_tip_on", &c.tool_tip_on},
          {"tool_tip_off", &c.tool_tip_off},
          {"length_on", &c.length_on},
          {"inverse_time", &c.inverse_time},
          {"plane", &c.plane},
          {"plane_index", &c.plane_index},
          {"plane_off", &c.plane_off}}) {
      const program_format& f = m.program;
      for (const char ch : *code)
        if (static_cast<unsigned char>(ch) < ' ' || static_cast<unsigned char>(ch) >= 0x7f || ch == '%' ||
            ch == '(' || ch == ')' || ch == ';' || ch == f.comment_open || ch == f.comment_close ||
            ch == '{' || ch == '}' || ch == '"' || ch == '\'' || ch == '\\')
          r.fail(*r.find(key), fmt::format("{} must hold codes only: '{}' would {}", r.key_path(key),
                                           ch == '%'                    ? "%"
                                           : std::string(1, ch) == "\n" ? "\\n"
                                                                        : std::string(1, ch),
                                           ch == '%' || ch < ' ' ? "end or break the block it begins"
                                           : std::string_view("{}\"'\\").find(ch) != std::string_view::npos
                                               ? "be written as it stands, no word of a block"
                                               : "make a comment of the block it begins"));
    }
    if (solves_joints(c) && c.inverse_time.empty())
      r.fail(*r.find("inverse_time"),
             "kinematics.inverse_time must name the inverse-time feed code (G93): joints "
             "and pivot output write F as 1/min on the moves that turn a rotary axis");
    for (std::string_view key : {"tolerance", "angle_tolerance", "chordal_tolerance"}) {
      double& v = key == "tolerance"         ? c.tolerance
                  : key == "angle_tolerance" ? c.angle_tolerance
                                             : c.chordal_tolerance;
      // Above 0, and no coarser than a check that still checks: 1 mm, 1 degree (attack 45:
      // tolerance = 1e308 switched the forward check off).
      if (r.read(key, v) && !(v > 0 && v <= 1))
        r.fail(*r.find(key), fmt::format("{} must be > 0 and at most 1 ({}), not {}", r.key_path(key),
                                         key == "angle_tolerance" ? "degree" : "mm", v));
    }
    const std::vector<const toml::table*> rotaries = r.tables("rotary");
    for (const toml::table* rt : rotaries) {
      table_reader ar(
          *rt, "kinematics.rotary", root.source(),
          {"address", "kind", "direction", "point", "min", "max", "continuous", "rollover", "prefer"});
      if (c.rotaries.size() == 2)
        ar.fail_here(
            fmt::format("channel {} has more than two rotary axes (the most twinpost solves)", c.channel));
      c.rotaries.push_back(read_rotary(ar, c));
    }
    if (!rotaries.empty()) check_geometry(r, *rotaries.back(), c);
    check_pivot(r, c);
    m.kinematics.push_back(std::move(c));
  }
}

}  // namespace twinpost::detail
