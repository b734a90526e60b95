#include "parser/event_text.hpp"

#include <charconv>
#include <cmath>
#include <fmt/format.h>

#include "support/json.hpp"

namespace twinpost {

namespace {

// An event as a name and a list of fields; both renderings are made from this one list.
struct field {
  enum class type { number, text, flag, numbers } t;
  std::string key;
  double number = 0;
  std::string text;
  std::vector<double> numbers;
};

struct fields {
  std::string name;
  std::vector<field> f;
  void num(std::string k, double v) { f.push_back({field::type::number, std::move(k), v, {}, {}}); }
  void str(std::string k, std::string v) {
    f.push_back({field::type::text, std::move(k), 0, std::move(v), {}});
  }
  void flag(std::string k, bool on) {
    if (on) f.push_back({field::type::flag, std::move(k), 0, {}, {}});
  }
  void nums(std::string k, std::vector<double> v) {
    f.push_back({field::type::numbers, std::move(k), 0, {}, std::move(v)});
  }
  void xyz(const vec3& p, const char* x = "x", const char* y = "y", const char* z = "z") {
    num(x, p.x), num(y, p.y), num(z, p.z);
  }
};

const char* motion_name(motion_kind k) {
  switch (k) {
    case motion_kind::from: return "from";
    case motion_kind::go_to: return "goto";
    case motion_kind::delta: return "godlta";
    case motion_kind::home: return "gohome";
  }
  return "goto";
}

struct describe {
  fields& out;
  void operator()(const motion_event& e) {
    out.name = motion_name(e.kind);
    out.xyz(e.pos);
    if (e.axis) out.xyz(*e.axis, "i", "j", "k");
    out.flag("rapid", e.rapid);
    out.flag("continued", e.continued);
  }
  void operator()(const arc_event& e) {
    out.name = "arc";
    out.xyz(e.end);
    out.xyz(e.center, "cx", "cy", "cz");
    out.xyz(e.normal, "i", "j", "k");
    out.num("r", e.radius);
    out.str("dir", e.ccw ? "ccw" : "cw");
    if (e.turns > 0) out.num("turns", e.turns);
    out.flag("continued", e.continued);
  }
  void operator()(const tool_event& e) {
    static const char* src[] = {"LOADTL", "LOAD/TOOL", "SELECT/TOOL", "TURRET"};
    out.name = e.preselect ? "tool-select" : "tool";
    out.num("tool", e.tool);
    if (e.offset) out.num("offset", *e.offset);
    out.str("from", src[static_cast<int>(e.source)]);
  }
  void operator()(const tool_data_event& e) {
    out.name = "tool-data";
    out.str("from", e.major);
    if (!e.words.empty()) out.str("words", fmt::format("{}", fmt::join(e.words, ",")));
    out.nums("values", e.values);
  }
  void operator()(const spindle_event& e) {
    static const char* modes[] = {"rpm", "sfm", "smm", "off", "on", "orient", "lock"};
    out.name = "spindle";
    out.str("mode", modes[static_cast<int>(e.mode)]);
    if (e.mode != spindle_mode::off && e.mode != spindle_mode::on && e.mode != spindle_mode::lock)
      out.num("speed", e.speed);
    if (e.dir != rotation::none) out.str("dir", e.dir == rotation::cw ? "cw" : "ccw");
    if (e.max_rpm) out.num("maxrpm", *e.max_rpm);
    if (e.range) out.num("range", *e.range);
    if (!e.spindle.empty()) out.str("spindle", e.spindle);
  }
  void operator()(const feed_event& e) {
    static const char* modes[] = {"per-minute", "per-rev", "inverse-time"};
    out.name = "feed";
    out.str("mode", modes[static_cast<int>(e.mode)]);
    out.num("value", e.value);
    out.str("units", e.units == unit_system::mm ? "mm" : "inch");
  }
  void operator()(const coolant_event& e) {
    out.name = "coolant";
    out.str("mode", e.mode);
    if (!e.level.empty()) out.str("level", e.level);
  }
  void operator()(const cutcom_event& e) {
    out.name = "cutcom";
    out.str("side", e.side);
    if (e.reg) out.num("register", *e.reg);
    if (!e.plane.empty()) out.str("plane", e.plane);
  }
  void operator()(const cycle_event& e) {
    out.name = "cycle";
    out.str("type", e.type);
    for (const auto& [k, v] : e.params) out.num(k, v);
    if (!e.words.empty()) out.str("words", fmt::format("{}", fmt::join(e.words, ",")));
    if (!e.positional.empty()) out.nums("values", e.positional);
  }
  void operator()(const thread_event& e) {
    out.name = "thread";
    out.str("mode", e.on ? "TURN" : "OFF");
    if (e.on) {
      out.num("lead", e.lead);
      out.num("starts", e.starts);
    }
  }
  void operator()(const delay_event& e) {
    out.name = "delay";
    out.num(e.revolutions ? "revolutions" : "seconds", e.value);
  }
  void operator()(const stop_event& e) {
    out.name = "stop";
    out.str("kind", e.optional ? "optional" : "program");
  }
  void operator()(const transfer_event& e) {
    out.name = "transfer";
    static const char* steps[] = {"grip", "release", "retract", "blocks", "on_sub"};
    out.str("step", steps[static_cast<int>(e.step)]);
  }
  void operator()(const aux_event& e) {
    out.name = e.prefun ? "prefun" : "auxfun";
    out.num("code", e.code);
    if (!e.extra.empty()) out.nums("values", e.extra);
  }
  void operator()(const text_event& e) {
    out.name = "text";
    out.str("major", e.major);
    out.str("text", e.text);
  }
  void operator()(const units_event& e) {
    out.name = "units";
    out.str("units", e.units == unit_system::mm ? "mm" : "inch");
  }
  void operator()(const machin_event& e) {
    out.name = "machin";
    out.str("name", e.name);
    if (!e.args.empty()) out.str("args", fmt::format("{}", fmt::join(e.args, ",")));
  }
  void operator()(const multax_event& e) {
    out.name = "multax";
    out.str("state", e.on ? "on" : "off");
  }
  void operator()(const coordsys_event& e) {
    out.name = "coordsys";
    out.str("from", e.source);
    out.nums("values", e.values);
  }
  void operator()(const head_event& e) {
    out.name = "head";
    static const char* words[] = {"", "MAIN", "SIDE", "BOTH"};
    if (e.which == head_select::number)
      out.num("head", e.number);
    else
      out.str("head", words[static_cast<int>(e.which)]);
  }
  void operator()(const channel_event& e) {
    out.name = "channel";
    out.num("channel", e.channel);
  }
  void operator()(const sync_event& e) {
    static const char* src[] = {"catia", "icam", "manus"};
    out.name = "sync";
    out.str("from", src[static_cast<int>(e.source)]);
    // "next": an ICAM marker left out, numbered per channel by the router, not here.
    if (e.index)
      out.num("index", *e.index);
    else
      out.str("index", "next");
    if (!e.channels.empty()) out.nums("channels", std::vector<double>(e.channels.begin(), e.channels.end()));
    if (e.master) out.num("master", *e.master);
  }
  void operator()(const tool_axis_event& e) {
    out.name = "tool-axis";
    out.xyz(e.axis, "i", "j", "k");
  }
  void operator()(const comment_event& e) {
    static const char* kinds[] = {"comment", "header", "data-comment", "ude"};
    out.name = kinds[static_cast<int>(e.kind)];
    out.str("text", e.text);
  }
  void operator()(const end_event& e) {
    out.name = "end";
    out.str("word", e.word);
  }
  void operator()(const passthrough_event& e) {
    out.name = "passthrough";
    out.str("major", e.major);
    out.str("args", e.text);
    out.flag("unknown", !e.known);
  }
};

fields describe_event(const event& e) {
  fields f;
  std::visit(describe{f}, e.data);
  return f;
}

// Text values are quoted (JSON-style) only when they hold a blank, a quote, a control or
// non-ASCII byte, or nothing: the text form stays one line of plain ASCII.
std::string text_value(const std::string& s) {
  bool plain = !s.empty();
  for (unsigned char c : s)
    if (c <= ' ' || c == '"' || c >= 0x7f) plain = false;
  return plain ? s : json_quote(s);
}

}  // namespace

// A number for JSON: JSON has no inf or nan (a GODLTA or a computed radius can overflow).
static std::string json_number(double v) { return std::isfinite(v) ? format_number(v) : "null"; }

// Numbers joined with ','.
static std::string number_list(const std::vector<double>& v, bool json = false) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i) s += ',';
    s += json ? json_number(v[i]) : format_number(v[i]);
  }
  return s;
}

std::string format_number(double v) {
  if (v == 0) v = 0;  // -0 -> 0
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string event_to_text(const event& e) {
  fields f = describe_event(e);
  std::string out = fmt::format("{}\t{}", e.line, f.name);
  for (const field& x : f.f) {
    switch (x.t) {
      case field::type::number: out += fmt::format(" {}={}", x.key, format_number(x.number)); break;
      case field::type::text: out += fmt::format(" {}={}", x.key, text_value(x.text)); break;
      case field::type::flag: out += fmt::format(" {}", x.key); break;
      case field::type::numbers: {
        out += fmt::format(" {}={}", x.key, number_list(x.numbers));
        break;
      }
    }
  }
  return out;
}

std::string event_to_json(const event& e) {
  fields f = describe_event(e);
  std::string out = fmt::format("{{\"line\":{},\"event\":{}", e.line, json_quote(f.name));
  for (const field& x : f.f) {
    out += fmt::format(",{}:", json_quote(x.key));
    switch (x.t) {
      case field::type::number: out += json_number(x.number); break;
      case field::type::text: out += json_quote(x.text); break;
      case field::type::flag: out += "true"; break;
      case field::type::numbers: {
        out += fmt::format("[{}]", number_list(x.numbers, true));
        break;
      }
    }
  }
  return out + "}";
}

}  // namespace twinpost
