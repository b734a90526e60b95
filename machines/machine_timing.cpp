// The [timing] table of a machine definition (docs/machines.md, "[timing]"): rapid rates per
// axis, tool-change, wait-code and M-code times, machine-wide and per channel.
#include <fmt/format.h>

#include "machines/machine.hpp"
#include "machines/toml_reader.hpp"

namespace twinpost::detail {

namespace {

void read_seconds(const table_reader& r, std::string_view key, double& out) {
  if (r.read(key, out) && out < 0)
    r.fail(*r.find(key), fmt::format("{} must be >= 0 seconds, not {}", r.key_path(key), out));
}

// rapid = { X = 30000, Z = 36000 }: one rate per axis address, each > 0. Rates of `into`
// for the same axis are replaced. `allowed` tells whether an axis may be named here.
template <class Allowed>
void read_rapid(const table_reader& r, std::vector<std::pair<char, double>>& into, Allowed allowed) {
  const toml::node* n = r.find("rapid");
  if (!n) return;
  const toml::table* t = n->as_table();
  if (!t)
    r.fail(*n, fmt::format("{} must be a table of rates per axis, e.g. {{ X = 30000, Z = 30000 }}",
                           r.key_path("rapid")));
  for (auto&& [key, value] : *t) {
    const std::string_view name = key.str();
    const std::string path = fmt::format("{}.{}", r.key_path("rapid"), name);
    if (name.size() != 1 || name[0] < 'A' || name[0] > 'Z')
      r.fail(value, fmt::format("{}: an axis is one upper-case letter", path));
    const std::optional<double> rate = value.template value<double>();
    if (!rate || !(value.is_integer() || value.is_floating_point()))
      r.fail(value, fmt::format("{} must be a number (the axis's unit per minute)", path));
    if (!(*rate > 0)) r.fail(value, fmt::format("{} must be > 0, not {}", path, *rate));
    if (const std::string why = allowed(name[0]); !why.empty())
      r.fail(value, fmt::format("{}: {}", path, why));
    bool replaced = false;
    for (auto& [a, v] : into)
      if (a == name[0]) v = *rate, replaced = true;
    if (!replaced) into.emplace_back(name[0], *rate);
  }
}

void read_figures(const table_reader& r, channel_timing& t) {
  read_seconds(r, "tool_change", t.tool_change);
  read_seconds(r, "wait", t.wait);
  read_seconds(r, "m_code", t.m_code);
}

}  // namespace

void read_timing(const table_reader& root, machine& m) {
  const toml::table* t = root.sub_table("timing");
  if (!t) return;
  table_reader r(*t, "timing", root.source(), {"rapid", "tool_change", "wait", "m_code", "channel"});
  channel_timing common;
  common.given = true;
  read_rapid(r, common.rapid, [&](char a) -> std::string {
    for (const channel_def& c : m.channels)
      if (c.axis(a)) return "";
    return fmt::format("no channel of this machine has axis {}", a);
  });
  read_figures(r, common);
  for (channel_def& c : m.channels) c.timing = common;

  if (const toml::table* per = r.sub_table("channel")) {
    for (auto&& [key, value] : *per) {
      const std::string_view name = key.str();
      channel_def* ch = nullptr;
      for (channel_def& c : m.channels)
        if (std::to_string(c.number) == name) ch = &c;
      if (!ch) r.fail(value, fmt::format("timing.channel.{}: this machine has no channel {}", name, name));
      const toml::table* ct = value.as_table();
      if (!ct) r.fail(value, fmt::format("timing.channel.{} must be a table", name));
      table_reader cr(*ct, fmt::format("timing.channel.{}", name), root.source(),
                      {"rapid", "tool_change", "wait", "m_code"});
      read_rapid(cr, ch->timing.rapid, [&](char a) -> std::string {
        return ch->axis(a) ? "" : fmt::format("channel {} has no axis {}", ch->number, a);
      });
      read_figures(cr, ch->timing);
    }
  }
  // Every axis of every channel moves at a known rate, or no rapid could be timed.
  for (const channel_def& c : m.channels)
    for (const axis_def& a : c.axes)
      if (!c.timing.rapid_of(a.address))
        r.fail_here(
            fmt::format("timing: no rapid rate for axis {} of channel {} (timing.rapid.{} or "
                        "timing.channel.{}.rapid.{})",
                        a.address, c.number, a.address, c.number, a.address));
}

}  // namespace twinpost::detail
