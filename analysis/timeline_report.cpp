#include "analysis/timeline_report.hpp"

#include <fmt/format.h>

#include "support/json.hpp"

namespace twinpost {

namespace {

std::string seconds(double s) { return fmt::format("{:.3f} s", s); }
std::string place(const nc_place& p) { return fmt::format("{}:{}", p.file, p.line); }
std::string num(double v) { return fmt::format("{:.3f}", v); }

}  // namespace

int conflict_channel(const timeline& t, const diagnostic& d) {
  for (const channel_times& c : t.channels)
    if (c.file == d.file) return c.channel;
  return 0;
}

std::string advice_text(const idle_note& n) {
  std::string s =
      fmt::format("channel {} idles {} at {} ({})", n.channel, seconds(n.seconds), n.code, place(n.where));
  if (n.waited_for > 0) s += fmt::format(" waiting for channel {}", n.waited_for);
  return s;
}

std::string format_timeline_text(const timeline& t, std::string_view indent) {
  // Blocks not timed count 0: the cycle time is then a lower bound, and says so.
  std::string out = fmt::format("{}cycle time {}{} (channel {} ends last)\n", indent,
                                t.untimed > 0 ? "at least " : "", seconds(t.cycle), t.last_channel);
  for (const channel_times& c : t.channels)
    out += fmt::format("{}  channel {}: {} working + {} idle at {} wait{} = {}\n", indent, c.channel,
                       seconds(c.busy), seconds(c.idle), c.waits.size(), c.waits.size() == 1 ? "" : "s",
                       seconds(c.end));
  if (t.untimed > 0) {
    std::string kinds;
    for (const untimed_group& g : t.untimed_kinds)
      kinds +=
          fmt::format("{}{} ({}, first at {})", kinds.empty() ? "" : "; ", g.why, g.count, place(g.first));
    out += fmt::format("{}  {} block{} not timed: {}\n", indent, t.untimed, t.untimed == 1 ? "" : "s", kinds);
  }
  if (t.advice.empty()) {
    out += fmt::format("{}  balance: no channel idles at a wait\n", indent);
  } else {
    std::string s;
    for (const idle_note& n : t.advice) s += (s.empty() ? "" : "; ") + advice_text(n);
    out += fmt::format("{}  balance: {}\n", indent, s);
  }
  for (const diagnostic& d : t.conflicts)  // the interference rule's (only where it found some)
    if (d.level == severity::error)
      out += fmt::format("{}  turrets may meet: {}:{}: {}\n", indent, d.file, d.line, d.message);
  return out;
}

void write_timeline_json(const timeline& t, const std::function<void(std::string_view)>& out,
                         const timed_block_source& blocks) {
  // Written in pieces of about 64 KB: the blocks of a long program never sit in memory.
  std::string o;
  auto flush = [&](bool always) {
    if (always || o.size() >= (1u << 16)) {
      out(o);
      o.clear();
    }
  };
  o = "{\"machine\":" + json_quote(t.machine);
  o += fmt::format(",\"cycle\":{},\"at_least\":{},\"last_channel\":{},\"untimed\":{},\"channels\":[",
                   num(t.cycle), t.untimed > 0 ? "true" : "false", t.last_channel, t.untimed);
  for (std::size_t i = 0; i < t.channels.size(); ++i) {
    const channel_times& c = t.channels[i];
    o += i ? "," : "";
    o += fmt::format(
        "{{\"channel\":{},\"file\":{},\"busy\":{},\"idle\":{},\"end\":{},\"blocks\":{},\"untimed\":{}",
        c.channel, json_quote(c.file), num(c.busy), num(c.idle), num(c.end), c.blocks, c.untimed);
    o += ",\"operations\":[";
    for (std::size_t k = 0; k < c.operations.size(); ++k) {
      const tool_operation& op = c.operations[k];
      o += fmt::format(
          "{}{{\"tool\":{},\"start\":{},\"seconds\":{},\"blocks\":{},\"segment\":{},\"line\":{},"
          "\"text\":{},\"critical\":{}}}",
          k ? "," : "", json_quote(op.tool), num(op.start), num(op.seconds), op.blocks, op.segment,
          op.first_line, json_quote(op.first_text), op.critical ? "true" : "false");
      flush(false);
    }
    o += "],\"waits\":[";
    for (std::size_t k = 0; k < c.waits.size(); ++k) {
      const wait_stop& w = c.waits[k];
      o += fmt::format(
          "{}{{\"code\":{},\"line\":{},\"arrive\":{},\"release\":{},\"idle\":{},\"waiting_for\":{}}}",
          k ? "," : "", json_quote(w.code), w.where.line, num(w.arrive), num(w.release), num(w.idle()),
          w.waited_for);
      flush(false);
    }
    o += "]";
    bool first = true;
    auto block = [&](const timed_block& b) {
      o += first ? ",\"blocks\":[" : ",";
      first = false;
      o += fmt::format("{{\"line\":{},\"start\":{},\"seconds\":{},\"text\":{}", b.line, num(b.start),
                       num(b.seconds), json_quote(b.text));
      if (!b.untimed.empty()) o += ",\"untimed\":" + json_quote(b.untimed);
      if (b.wait) o += ",\"wait\":true";
      o += "}";
      flush(false);
    };
    if (blocks)
      blocks(c.channel, block);
    else
      for (const timed_block& b : c.kept) block(b);
    if (!first) o += "]";
    o += "}";
  }
  o += "],\"critical\":[";
  for (std::size_t k = 0; k < t.critical.size(); ++k)
    o += fmt::format("{}{{\"channel\":{},\"start\":{},\"end\":{}}}", k ? "," : "", t.critical[k].channel,
                     num(t.critical[k].start), num(t.critical[k].end));
  o += "],\"not_timed\":[";
  for (std::size_t k = 0; k < t.untimed_kinds.size(); ++k) {
    const untimed_group& g = t.untimed_kinds[k];
    o += fmt::format("{}{{\"why\":{},\"count\":{},\"file\":{},\"line\":{}}}", k ? "," : "", json_quote(g.why),
                     g.count, json_quote(g.first.file), g.first.line);
  }
  o += "],\"advice\":[";
  for (std::size_t k = 0; k < t.advice.size(); ++k) {
    const idle_note& n = t.advice[k];
    o += fmt::format(
        "{}{{\"channel\":{},\"idle\":{},\"code\":{},\"file\":{},\"line\":{},\"waiting_for\":{},"
        "\"text\":{}}}",
        k ? "," : "", n.channel, num(n.seconds), json_quote(n.code), json_quote(n.where.file), n.where.line,
        n.waited_for, json_quote(advice_text(n)));
  }
  o += "]";
  // The interference rule's findings, only where there are some (the data of a sound job is
  // unchanged): each with its channel (by its file) and its place in time when it was kept.
  if (!t.conflicts.empty()) {
    o += ",\"conflicts\":[";
    for (std::size_t k = 0; k < t.conflicts.size(); ++k) {
      const diagnostic& d = t.conflicts[k];
      o += fmt::format("{}{{\"channel\":{},\"severity\":{},\"file\":{},\"line\":{},\"message\":{}}}",
                       k ? "," : "", conflict_channel(t, d),
                       json_quote(d.level == severity::error ? "error" : "note"), json_quote(d.file), d.line,
                       json_quote(d.message));
    }
    o += "]";
  }
  o += "}\n";
  flush(true);
}

std::string format_timeline_json(const timeline& t) {
  std::string all;
  write_timeline_json(t, [&](std::string_view piece) { all += piece; });
  return all;
}

}  // namespace twinpost
