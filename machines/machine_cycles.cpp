// The [cycles] table of a machine definition: which drilling, tapping, threading and grooving
// cycles the control runs itself, and their codes (docs/machines.md, "[cycles]").
#include <algorithm>
#include <array>

#include <fmt/format.h>

#include "machines/machine.hpp"
#include "machines/toml_reader.hpp"

namespace twinpost::detail {

// Reads `key` into `out` and fails at it unless it is one of `allowed`.
void read_choice(const table_reader& r, std::string_view key, std::string& out,
                 std::initializer_list<std::string_view> allowed) {
  if (!r.read(key, out)) return;
  if (std::find(allowed.begin(), allowed.end(), out) != allowed.end()) return;
  std::string list;
  for (std::string_view a : allowed) list += fmt::format("{}\"{}\"", list.empty() ? "" : ", ", a);
  r.fail(*r.find(key), fmt::format("{} must be one of {}, not \"{}\"", r.key_path(key), list, out));
}

void read_cycles(const table_reader& root, cycle_rules& c) {
  const toml::table* t = root.sub_table("cycles");
  if (!t) return;
  table_reader r(*t, "cycles", root.source(), {"drill",           "tap",
                                               "plane",           "drill_code",
                                               "dwell_code",      "peck_code",
                                               "chip_break_code", "tap_code",
                                               "tap_left_code",   "rigid_code",
                                               "cancel",          "return_initial",
                                               "r_from_initial",  "q_increments",
                                               "sync_feed",       "thread",
                                               "groove",          "side_drill_code",
                                               "side_dwell_code", "side_peck_code",
                                               "side_tap_code"});
  read_choice(r, "drill", c.drill, {"canned", "expanded"});
  read_choice(r, "tap", c.tap, {"rigid", "floating", "expanded", "none"});
  read_choice(r, "thread", c.thread, {"g76", "g276", "g92", "g292", "g32"});
  read_choice(r, "groove", c.groove, {"g75", "expanded"});
  for (const auto& [key, field] : cycle_rules::code_keys) r.read_fixed(key, c.*field);
  r.read("r_from_initial", c.r_from_initial);
  r.read("q_increments", c.q_increments);
  // A kind that needs codes the file does not give would fail at the first hole: say so here.
  auto need = [&](std::string_view kind_key, std::string_view code_key, const std::string& code) {
    if (code.empty())
      r.fail(*r.find(kind_key), fmt::format("{} = \"{}\" needs cycles.{}", r.key_path(kind_key),
                                            kind_key == "drill" ? c.drill : c.tap, code_key));
  };
  if (c.drill == "canned") need("drill", "drill_code", c.drill_code);
  if (c.tap == "rigid" || c.tap == "floating") need("tap", "tap_code", c.tap_code);
  if (c.tap == "expanded") need("tap", "sync_feed", c.sync_feed);
  if ((c.drill == "canned" || c.tap == "rigid" || c.tap == "floating") && c.cancel.empty())
    r.fail_here("[cycles] with canned cycles needs cycles.cancel (G80)");
}

}  // namespace twinpost::detail
