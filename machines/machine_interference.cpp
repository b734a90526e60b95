// [interference] of a machine definition: the envelopes of what moves with each channel's tool
// and the static zones of the spindles, read for the turret interference rule
// (analysis/interference.hpp, docs/interference.md).
#include <fmt/format.h>

#include "machines/machine.hpp"
#include "machines/toml_reader.hpp"

namespace twinpost::detail {

namespace {

// A box written [r0, r1, z0, z1]: four numbers, each pair in order.
xz_box read_box(const table_reader& r, const toml::node& n) {
  const toml::array* a = n.as_array();
  double v[4] = {};
  if (!a || a->size() != 4) r.fail(n, "a box is [r0, r1, z0, z1]: four numbers (mm)");
  for (std::size_t i = 0; i < 4; ++i) {
    const toml::node* e = a->get(i);
    if (const auto d = e->value<double>())
      v[i] = *d;
    else
      r.fail(*e, "a box is [r0, r1, z0, z1]: four numbers (mm)");
  }
  if (!(v[0] <= v[1]) || !(v[2] <= v[3])) r.fail(n, "a box needs r0 <= r1 and z0 <= z1");
  return {v[0], v[1], v[2], v[3]};
}

}  // namespace

void read_interference(const table_reader& root, machine& m) {
  const toml::table* t = root.sub_table("interference");
  if (!t) return;
  table_reader r(*t, "interference", root.source(), {"clearance", "channel", "zone"});
  interference_rules& out = m.interference;
  if (r.read("clearance", out.clearance) && !(out.clearance >= 0))
    r.fail(*r.find("clearance"), fmt::format("interference.clearance must be >= 0, not {}", out.clearance));
  for (const toml::table* ct : r.tables("channel")) {
    table_reader c(*ct, "interference.channel", root.source(), {"channel", "side", "boxes"});
    interference_channel e;
    c.require("channel");
    c.read("channel", e.channel);
    if (e.channel < 1 || e.channel > static_cast<int>(m.channels.size()))
      c.fail(*c.find("channel"), fmt::format("interference.channel.channel {} names no channel (the machine "
                                             "has {})",
                                             e.channel, m.channels.size()));
    if (out.channel(e.channel))
      c.fail(*c.find("channel"), fmt::format("channel {} is given two envelopes", e.channel));
    if (c.read("side", e.side) && e.side != 1 && e.side != -1)
      c.fail(*c.find("side"), fmt::format("interference.channel.side must be 1 or -1, not {}", e.side));
    c.require("boxes");
    const toml::array* boxes = c.find("boxes")->as_array();
    if (!boxes || boxes->empty()) c.fail(*c.find("boxes"), "interference.channel.boxes is a list of boxes");
    for (const toml::node& b : *boxes) e.boxes.push_back(read_box(c, b));
    out.channels.push_back(std::move(e));
  }
  for (const toml::table* zt : r.tables("zone")) {
    table_reader z(*zt, "interference.zone", root.source(), {"spindle", "box"});
    interference_zone e;
    z.require("spindle");
    z.read("spindle", e.spindle);
    if (!m.spindle(e.spindle))
      z.fail(*z.find("spindle"),
             fmt::format("interference.zone.spindle '{}' names no [[spindle]]", e.spindle));
    z.require("box");
    e.box = read_box(z, *z.find("box"));
    out.zones.push_back(std::move(e));
  }
}

}  // namespace twinpost::detail
