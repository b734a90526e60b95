// The [[channel]] tables of a machine definition and their [[channel.axis]] tables.
#include <algorithm>
#include <utility>

#include <fmt/format.h>

#include "machines/machine.hpp"
#include "machines/toml_reader.hpp"
#include "support/ascii.hpp"

namespace twinpost::detail {

namespace {

constexpr std::size_t max_channels = 64;

// One channel as read, with the table it came from for later messages.
struct read_channel {
  channel_def def;
  const table_reader* reader;
};

axis_def read_axis(const table_reader& r) {
  axis_def a;
  r.require("address");
  r.read_char("address", a.address, true);
  r.read("diameter", a.diameter);
  r.read("mirror", a.mirror);
  r.read("min", a.min);
  r.read("max", a.max);
  if (a.min && a.max && *a.min > *a.max)
    r.fail(*r.find("min"),
           fmt::format("channel.axis.min ({}) must be <= channel.axis.max ({})", *a.min, *a.max));
  return a;
}

void read_axes(const table_reader& r, channel_def& c) {
  for (const toml::table* t : r.tables("axis")) {
    table_reader ar(*t, "channel.axis", r.source(), {"address", "diameter", "mirror", "min", "max"});
    axis_def a = read_axis(ar);
    if (c.axis(a.address))
      ar.fail(*ar.find("address"), fmt::format("channel {} has axis {} twice", c.number, a.address));
    c.axes.push_back(a);
  }
  for (char required : {'X', 'Z'})
    if (!c.axis(required))
      r.fail_here(fmt::format("channel {} has no axis {} (X and Z are required)", c.number, required));
}

channel_def read_channel_table(const table_reader& r, const machine& m) {
  channel_def c;
  r.require("number");
  r.read("number", c.number);
  if (r.read("heads", c.heads)) {
    const toml::array& nodes = *r.find("heads")->as_array();
    for (std::size_t i = 0; i < c.heads.size(); ++i)
      if (c.heads[i] < 1)
        r.fail(*nodes.get(i), fmt::format("channel.heads must hold numbers >= 1, not {}", c.heads[i]));
  }
  if (r.read("head_names", c.head_names)) {
    const toml::array& nodes = *r.find("head_names")->as_array();
    for (std::size_t i = 0; i < c.head_names.size(); ++i)
      if (c.head_names[i].empty()) r.fail(*nodes.get(i), "channel.head_names must not hold an empty name");
  }
  std::string kind = "turret";
  if (r.read("kind", kind) && kind != "turret" && kind != "mill_head")
    r.fail(*r.find("kind"), fmt::format("channel.kind must be turret or mill_head, not '{}'", kind));
  // A lathe turret calls tool and offset together (T0505); a mill head changes tools (M6).
  if (!r.read_template("tool_call", c.tool_call, template_uses::tool_call))
    c.tool_call = kind == "turret" ? "T{tool:02}{offset:02}" : "T{tool:02} M6";
  r.read_template("offset_call", c.offset_call, template_uses::tool_call);
  r.read_template("length_offset", c.length_offset, template_uses::tool_call);
  c.tool_change_stops_spindle = kind == "mill_head";
  r.read("tool_change_stops_spindle", c.tool_change_stops_spindle);
  r.read("offset_zero", c.offset_zero);
  const bool spindle_given = r.read("spindle", c.spindle);
  if (!m.spindles.empty() && !m.spindle(c.spindle)) {
    const std::string message = fmt::format("channel.spindle '{}' names no [[spindle]]", c.spindle);
    if (spindle_given) r.fail(*r.find("spindle"), message);
    r.fail_here(message);
  }
  if (r.read("live_spindle", c.live_spindle) && !m.spindle(c.live_spindle))
    r.fail(*r.find("live_spindle"),
           fmt::format("channel.live_spindle '{}' names no [[spindle]]", c.live_spindle));
  if (r.read("spindles", c.spindles)) {
    // Names of [[spindle]]s, each once, and at least the ones the channel works with.
    const toml::array& nodes = *r.find("spindles")->as_array();
    for (std::size_t i = 0; i < c.spindles.size(); ++i) {
      if (!m.spindle(c.spindles[i]))
        r.fail(*nodes.get(i), fmt::format("channel.spindles: '{}' names no [[spindle]]", c.spindles[i]));
      for (std::size_t j = 0; j < i; ++j)
        if (c.spindles[j] == c.spindles[i])
          r.fail(*nodes.get(i), fmt::format("channel.spindles names '{}' twice", c.spindles[i]));
    }
    for (const std::string* own : {&c.spindle, &c.live_spindle})
      if (!own->empty() && m.spindle(*own) &&
          std::find(c.spindles.begin(), c.spindles.end(), *own) == c.spindles.end())
        r.fail(*r.find("spindles"),
               fmt::format("channel.spindles must name the channel's own spindle '{}' (channel.{})", *own,
                           own == &c.spindle ? "spindle" : "live_spindle"));
  }
  if (r.read("home", c.home) && c.home.empty())
    r.fail(*r.find("home"), "channel.home must name at least one block");
  if (r.read("file_suffix", c.file_suffix) && c.file_suffix.find_first_of("/\\") != std::string::npos)
    r.fail(*r.find("file_suffix"), "channel.file_suffix must not contain a path separator");
  read_axes(r, c);
  read_head_index(r, c);
  return c;
}

// Checks in file order, so the message points at the second of two clashing channels.
void check_numbers_and_heads(const std::vector<read_channel>& all) {
  const int n = static_cast<int>(all.size());
  for (std::size_t i = 0; i < all.size(); ++i) {
    const channel_def& c = all[i].def;
    const table_reader& r = *all[i].reader;
    if (c.number < 1 || c.number > n)
      r.fail(*r.find("number"),
             fmt::format("channel number {} is outside 1..{} (the number of channels)", c.number, n));
    for (std::size_t j = 0; j < i; ++j) {
      const channel_def& earlier = all[j].def;
      if (earlier.number == c.number)
        r.fail(*r.find("number"), fmt::format("duplicate channel number {}", c.number));
      for (std::size_t h = 0; h < c.heads.size(); ++h)
        if (std::find(earlier.heads.begin(), earlier.heads.end(), c.heads[h]) != earlier.heads.end())
          r.fail(*r.find("heads")->as_array()->get(h), fmt::format("head {} is served by channels {} and {}",
                                                                   c.heads[h], earlier.number, c.number));
      for (std::size_t h = 0; h < c.head_names.size(); ++h)
        for (const std::string& word : earlier.head_names)  // matched without case, as heads are
          if (ascii::iequals(word, c.head_names[h]))
            r.fail(*r.find("head_names")->as_array()->get(h),
                   fmt::format("head {} is served by channels {} and {}", c.head_names[h], earlier.number,
                               c.number));
    }
  }
}

}  // namespace

void read_channels(const table_reader& root, machine& m) {
  const std::vector<const toml::table*> tables = root.tables("channel");
  if (tables.empty()) root.fail_here("at least one [[channel]] is required");
  // The checker and binary partner lists hold a set of channels in 64 bits.
  if (tables.size() > max_channels)
    root.fail(*tables[max_channels], fmt::format("[[channel]] {} of {}: a machine has at most {} channels",
                                                 max_channels + 1, tables.size(), max_channels));
  // Readers are kept alive for the checks across channels, which report at their nodes.
  std::vector<table_reader> readers;
  readers.reserve(tables.size());
  std::vector<read_channel> all;
  for (const toml::table* t : tables) {
    readers.emplace_back(*t, "channel", root.source(),
                         std::initializer_list<std::string_view>{
                             "number", "heads", "head_names", "kind", "tool_call", "offset_call",
                             "length_offset", "spindle", "file_suffix", "axis", "tool_change_stops_spindle",
                             "live_spindle", "offset_zero", "spindles", "head_index", "home"});
    all.push_back({read_channel_table(readers.back(), m), &readers.back()});
  }
  check_numbers_and_heads(all);
  m.channels.clear();
  for (read_channel& c : all) m.channels.push_back(std::move(c.def));
  std::sort(m.channels.begin(), m.channels.end(),
            [](const channel_def& a, const channel_def& b) { return a.number < b.number; });
}

}  // namespace twinpost::detail
