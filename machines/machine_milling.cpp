// Mill/turn data of a machine definition (machines/millturn_rules.hpp): [milling], a spindle's
// c_* keys and a channel's [channel.head_index] (docs/machines.md, "Mill/turn").
#include <algorithm>

#include <fmt/format.h>

#include "machines/machine.hpp"
#include "machines/toml_reader.hpp"

namespace twinpost::detail {

namespace {

void read_one_of(const table_reader& r, std::string_view key, std::string& out,
                 std::initializer_list<std::string_view> allowed) {
  if (!r.read(key, out)) return;
  if (std::find(allowed.begin(), allowed.end(), out) != allowed.end()) return;
  std::string list;
  for (std::string_view a : allowed) list += fmt::format("{}\"{}\"", list.empty() ? "" : " or ", a);
  r.fail(*r.find(key), fmt::format("{} must be {}, not \"{}\"", r.key_path(key), list, out));
}

}  // namespace

void read_c_axis(const table_reader& r, c_axis_codes& c) {
  r.read_fixed("c_on", c.on);
  r.read_fixed("c_off", c.off);
  r.read_fixed("c_clamp", c.clamp);
  r.read_fixed("c_unclamp", c.unclamp);
  if (c.on.empty() != c.off.empty())
    r.fail(*r.find(c.on.empty() ? "c_off" : "c_on"),
           "spindle.c_on and spindle.c_off go together: a spindle held as a C axis must be let go again");
  if (c.clamp.empty() != c.unclamp.empty())
    r.fail(*r.find(c.clamp.empty() ? "c_unclamp" : "c_clamp"),
           "spindle.c_clamp and spindle.c_unclamp go together");
}

void read_head_index(const table_reader& channel, channel_def& c) {
  const toml::table* t = channel.sub_table("head_index");
  if (!t) return;
  table_reader r(
      *t, "channel.head_index", channel.source(),
      {"address", "unclamp", "move", "clamp", "turning", "axial", "radial", "offset_turning", "offset_live"});
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
  if (!c.axis(h.address))
    r.fail(*r.find(r.find("address") ? "address" : "move"),
           fmt::format("channel {} has no axis {} to index (channel.axis)", c.number, h.address));
  const axis_def& a = *c.axis(h.address);
  for (const char* key : {"turning", "axial", "radial"}) {
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
                  "face_milling", "face_holes", "radial_frame_on", "radial_frame_off"});
  milling_rules& g = m.milling;
  g.given = true;
  r.read_fixed("radius_input", g.radius_input);
  r.read_fixed("diameter_input", g.diameter_input);
  if (g.radius_input.empty() != g.diameter_input.empty())
    r.fail(*r.find(g.radius_input.empty() ? "diameter_input" : "radius_input"),
           "milling.radius_input and milling.diameter_input go together");
  r.read_fixed("polar_on", g.polar_on);
  r.read_fixed("polar_off", g.polar_off);
  if (g.polar_on.empty() != g.polar_off.empty())
    r.fail(*r.find(g.polar_on.empty() ? "polar_off" : "polar_on"),
           "milling.polar_on and milling.polar_off go together");
  if (r.read("polar_rapid_feed", g.polar_rapid_feed) && !(g.polar_rapid_feed > 0))
    r.fail(*r.find("polar_rapid_feed"), "milling.polar_rapid_feed must be a feed above 0 (mm/min)");
  read_one_of(r, "face_milling", g.face_milling, {"y_axis", "polar"});
  read_one_of(r, "face_holes", g.face_holes, {"y_axis", "c_axis"});
  r.read_fixed("radial_frame_on", g.radial_frame_on);
  r.read_fixed("radial_frame_off", g.radial_frame_off);
  if (g.radial_frame_on.empty() != g.radial_frame_off.empty())
    r.fail(*r.find(g.radial_frame_on.empty() ? "radial_frame_off" : "radial_frame_on"),
           "milling.radial_frame_on and milling.radial_frame_off go together");
  if (g.face_milling == "polar" && g.polar_on.empty())
    r.fail(*r.find("face_milling"), "milling.face_milling = \"polar\" needs milling.polar_on and polar_off");
}

}  // namespace twinpost::detail
