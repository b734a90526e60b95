// Mill/turn data of a machine definition (machines/millturn_rules.hpp): [milling], a spindle's
// c_* keys and a channel's [channel.head_index] (docs/machines.md, "Mill/turn").
#include <algorithm>

#include <fmt/format.h>

#include "machines/machine.hpp"
#include "machines/toml_reader.hpp"

namespace twinpost::detail {

namespace {

// Reads two keys that are given together or not at all (an on block without its off block
// would leave the machine in a mode); fails at the one given. `why` ends the message.
template <class T>
void read_pair(const table_reader& r, std::string_view on_key, T& on, std::string_view off_key, T& off,
               std::string_view why = "") {
  r.read_fixed(on_key, on);
  r.read_fixed(off_key, off);
  if (on.empty() == off.empty()) return;
  r.fail(*r.find(on.empty() ? off_key : on_key),
         fmt::format("{} and {} go together{}", r.key_path(on_key), r.key_path(off_key), why));
}

}  // namespace

void read_c_axis(const table_reader& r, c_axis_codes& c) {
  read_pair(r, "c_on", c.on, "c_off", c.off, ": a spindle held as a C axis must be let go again");
  read_pair(r, "c_clamp", c.clamp, "c_unclamp", c.unclamp);
}

namespace {
// The M-codes of a block (M35, M89; not M98.1, not inside a comment): what the control and the
// checker's reader take as M functions.
std::vector<int> m_codes(std::string_view block) {
  std::vector<int> out;
  bool comment = false;  // ended at its first ')', as a control ends it
  for (std::size_t i = 0; i < block.size(); ++i) {
    if (block[i] == '(') comment = true;
    if (block[i] == ')') comment = false;
    if (comment || block[i] != 'M') continue;
    std::size_t j = i + 1;
    int v = 0;
    while (j < block.size() && block[j] >= '0' && block[j] <= '9' && v < 100000)
      v = v * 10 + (block[j++] - '0');
    if (j > i + 1 && (j == block.size() || block[j] != '.')) out.push_back(v);
  }
  return out;
}
}  // namespace

void check_c_axis_codes(const table_reader& r, const c_axis_codes& c, const std::vector<spindle_def>& all) {
  auto check = [&](std::string_view key, const std::vector<std::string>& blocks) {
    for (const std::string& b : blocks)
      for (int code : m_codes(b))
        for (const spindle_def& s : all)
          for (const auto& [what, value] : {std::pair{"cw", std::optional<int>(s.cw)},
                                            {"ccw", std::optional<int>(s.ccw)},
                                            {"stop", std::optional<int>(s.stop)},
                                            {"select", s.select}})
            if (value && *value == code)
              r.fail(*r.find(key),
                     fmt::format("{} M{} is also the {} code of spindle '{}': a program could not tell the "
                                 "one from the other",
                                 r.key_path(key), code, what, s.name));
  };
  check("c_on", c.on);
  check("c_off", c.off);
  check("c_clamp", {c.clamp});
  check("c_unclamp", {c.unclamp});
}

void read_head_index(const table_reader& channel, channel_def& c) {
  const toml::table* t = channel.sub_table("head_index");
  if (!t) return;
  table_reader r(*t, "channel.head_index", channel.source(),
                 {"address", "unclamp", "move", "clamp", "turning", "axial", "radial", "turning_sub",
                  "axial_sub", "radial_sub", "offset_turning", "offset_live"});
  head_index_rules& h = c.head_index;
  r.read_char("address", h.address, true);
  r.require("move");
  r.read_fixed("move", h.move);
  r.read_fixed("unclamp", h.unclamp);
  r.read_fixed("clamp", h.clamp);
  r.read_fixed("offset_turning", h.offset_turning);
  r.read_fixed("offset_live", h.offset_live);
  r.read("turning", h.turning);
  r.read("axial", h.axial);
  r.read("radial", h.radial);
  r.read("turning_sub", h.turning_sub);
  r.read("axial_sub", h.axial_sub);
  r.read("radial_sub", h.radial_sub);
  if (!c.axis(h.address))
    r.fail(*r.find(r.find("address") ? "address" : "move"),
           fmt::format("channel {} has no axis {} to index (channel.axis)", c.number, h.address));
  const axis_def& a = *c.axis(h.address);
  for (const char* key : {"turning", "axial", "radial", "turning_sub", "axial_sub", "radial_sub"}) {
    std::optional<double> v;
    r.read(key, v);
    if (v && ((a.min && *v < *a.min) || (a.max && *v > *a.max)))
      r.fail(*r.find(key),
             fmt::format("channel.head_index.{} = {} is outside the travel of axis {}", key, *v, h.address));
  }
}

void read_milling(const table_reader& root, machine& m) {
  const toml::table* t = root.sub_table("milling");
  if (!t) return;
  table_reader r(*t, "milling", root.source(),
                 {"radius_input", "diameter_input", "polar_on", "polar_off", "polar_rapid_feed",
                  "face_milling", "face_holes", "cross_holes", "radial_frame_on", "radial_frame_off",
                  "cylindrical_on", "cylindrical_off"});
  milling_rules& g = m.milling;
  g.given = true;
  read_pair(r, "radius_input", g.radius_input, "diameter_input", g.diameter_input);
  read_pair(r, "polar_on", g.polar_on, "polar_off", g.polar_off);
  if (r.read("polar_rapid_feed", g.polar_rapid_feed) && !(g.polar_rapid_feed > 0))
    r.fail(*r.find("polar_rapid_feed"), "milling.polar_rapid_feed must be a feed above 0 (mm/min)");
  read_choice(r, "face_milling", g.face_milling, {"y_axis", "polar"});
  read_choice(r, "face_holes", g.face_holes, {"y_axis", "c_axis"});
  read_choice(r, "cross_holes", g.cross_holes, {"turned_frame", "side_cycle"});
  read_pair(r, "radial_frame_on", g.radial_frame_on, "radial_frame_off", g.radial_frame_off);
  if (g.cross_holes == "side_cycle" && m.cycles.side_drill_code.empty())
    r.fail(*r.find("cross_holes"),
           "milling.cross_holes = \"side_cycle\" needs cycles.side_drill_code (Fanuc G87): the holes are "
           "drilled with the lathe's side cycles");
  if (g.cross_holes == "side_cycle" && !g.radial_frame_on.empty())
    r.fail(*r.find("radial_frame_on"),
           "milling.radial_frame_on is the turned frame of cross_holes = \"turned_frame\"; with "
           "\"side_cycle\" the holes are drilled along X without it");
  // cylindrical_on is read as written: its {radius} or {diameter} is filled by the writer as an
  // NC number (40.), not by a format template.
  r.read("cylindrical_on", g.cylindrical_on);
  r.read_fixed("cylindrical_off", g.cylindrical_off);
  if (g.cylindrical_on.empty() != g.cylindrical_off.empty())
    r.fail(*r.find(g.cylindrical_on.empty() ? "cylindrical_off" : "cylindrical_on"),
           "milling.cylindrical_on and milling.cylindrical_off go together");
  if (!g.cylindrical_on.empty()) {
    // One block carries the cylinder's size; it is written inside the turned frame.
    int holes = 0;
    for (const std::string& b : g.cylindrical_on)
      for (std::size_t at = b.find('{'); at != std::string::npos; at = b.find('{', at + 1)) {
        const std::string_view rest = std::string_view(b).substr(at);
        if (!rest.starts_with("{radius}") && !rest.starts_with("{diameter}"))
          r.fail(*r.find("cylindrical_on"),
                 fmt::format("milling.cylindrical_on: unknown placeholder in \"{}\" (it takes {{radius}} or "
                             "{{diameter}})",
                             b));
        ++holes;
      }
    if (holes != 1)
      r.fail(*r.find("cylindrical_on"),
             "milling.cylindrical_on must hold the cylinder's size once: {radius} or {diameter}");
    if (g.radial_frame_on.empty() && g.cross_holes != "side_cycle")
      r.fail(*r.find("cylindrical_on"),
             "milling.cylindrical_on needs milling.radial_frame_on: cylindrical interpolation is written in "
             "the turned frame of cross holes");
  }
  if (g.face_milling == "polar" && g.polar_on.empty())
    r.fail(*r.find("face_milling"), "milling.face_milling = \"polar\" needs milling.polar_on and polar_off");
}

}  // namespace twinpost::detail
