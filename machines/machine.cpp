#include "machines/machine.hpp"

#include <algorithm>
#include <charconv>

#include "support/ascii.hpp"

namespace twinpost {

bool wait_rules::is_wait_code(int code) const {
  if (code < first || code > last || step < 1) return false;
  if ((static_cast<long long>(code) - first) % step != 0) return false;  // first may be < 0 in code
  return std::find(excluded.begin(), excluded.end(), code) == excluded.end();
}

const wait_rules::fixed_wait* wait_rules::fixed_wait_of(int code) const {
  for (const fixed_wait& f : fixed)
    if (f.code == code) return &f;
  return nullptr;
}

const axis_def* channel_def::axis(char address) const {
  for (const axis_def& a : axes)
    if (a.address == address) return &a;
  return nullptr;
}

const channel_def* machine::channel_for_head(int head) const {
  for (const channel_def& c : channels)
    if (std::find(c.heads.begin(), c.heads.end(), head) != c.heads.end()) return &c;
  return nullptr;
}

const channel_def* machine::channel_for_head(std::string_view word) const {
  for (const channel_def& c : channels)
    for (const std::string& h : c.head_names)
      if (ascii::iequals(h, word)) return &c;  // dialects disagree on case: HEAD/MAIN, head/main
  return nullptr;
}

const tool_def* machine::tool(int channel, int number) const {
  const tool_def* any = nullptr;
  for (const tool_def& t : tools)
    if (t.number == number) {
      if (t.channel == channel) return &t;
      if (t.channel == 0) any = &t;
    }
  return any;
}

const tool_def* machine::tool_named(int channel, std::string_view name) const {
  const tool_def* any = nullptr;
  for (const tool_def& t : tools)
    if (!t.name.empty() && ascii::iequals(t.name, name)) {
      if (t.channel == channel) return &t;
      if (t.channel == 0 && !any) any = &t;
    }
  return any;
}

std::string_view machine::tool_kind(int channel, int number) const {
  const tool_def* t = tool(channel, number);
  return t ? std::string_view(t->kind) : std::string_view();
}

std::optional<double> machine::tool_length(int channel, int number) const {
  const tool_def* t = tool(channel, number);
  return t ? t->length : std::nullopt;
}

const std::vector<std::string>& machine::home(int channel) const {
  for (const channel_def& c : channels)
    if (c.number == channel && !c.home.empty()) return c.home;
  return codes.home;
}

const kinematic_chain* machine::chain(int channel) const {
  for (const kinematic_chain& c : kinematics)
    if (c.channel == channel) return &c;
  return nullptr;
}

const spindle_def* machine::spindle(std::string_view name) const {
  for (const spindle_def& s : spindles)
    if (s.name == name) return &s;
  return nullptr;
}

bool machine::may_command(int channel, int index) const {
  if (index < 0 || static_cast<std::size_t>(index) >= spindles.size()) return false;
  const std::string& name = spindles[static_cast<std::size_t>(index)].name;
  const channel_def* ch = nullptr;
  for (const channel_def& c : channels)
    if (c.number == channel) ch = &c;
  if (!ch) return false;
  if (!ch->spindles.empty())
    return std::find(ch->spindles.begin(), ch->spindles.end(), name) != ch->spindles.end();
  // The default: its own spindles, and every one that is no channel's live spindle.
  if (name == ch->spindle || name == ch->live_spindle) return true;
  return std::none_of(channels.begin(), channels.end(),
                      [&](const channel_def& c) { return c.live_spindle == name; });
}

bool machine::shared_spindle(int index) const {
  if (index < 0 || static_cast<std::size_t>(index) >= spindles.size()) return false;
  if (spindles[static_cast<std::size_t>(index)].per_channel) return false;
  int n = 0;
  for (const channel_def& c : channels) n += may_command(c.number, index) ? 1 : 0;
  return n >= 2;
}

std::optional<int> machine::program_number_of(std::string_view name) const {
  // Digits only (from_chars would take a sign), at most 9: they fit an int.
  if (name.empty() || name.size() > 9 || !std::all_of(name.begin(), name.end(), ascii::is_digit))
    return std::nullopt;
  int n = 0;
  std::from_chars(name.data(), name.data() + name.size(), n);
  if (n < 1 || n > formats['O'].max_count(0)) return std::nullopt;
  return n;
}

}  // namespace twinpost
