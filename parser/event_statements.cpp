// event_builder: statements (MAJOR/args) and motion.
#include <cmath>
#include <fmt/format.h>

#include "parser/detail/word_events.hpp"
#include "parser/event_builder.hpp"
#include "parser/event_text.hpp"

namespace twinpost {

using detail::numbers_of;
using detail::upper;

namespace {

bool known_passthrough(std::string_view m);
bool ignorable_in_post(const cl_record& r);

double planar_radius(vec3 p, vec3 c, vec3 n) {
  double dx = p.x - c.x, dy = p.y - c.y, dz = p.z - c.z;
  double nl = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  double a = nl > 0 ? (dx * n.x + dy * n.y + dz * n.z) / nl : 0;
  double r2 = dx * dx + dy * dy + dz * dz - a * a;
  return r2 > 0 ? std::sqrt(r2) : 0;
}

std::size_t where(const cl_record& r) { return r.args.empty() ? r.major_offset : r.args.front().offset; }

}  // namespace

void event_builder::statement(const cl_record& r, int line, event_queue& out, build_issues& issues) {
  std::string_view m = r.major;
  end_of_motion_record();
  if (word_is(m, "GOTO")) return motion(r, motion_kind::go_to, line, out, issues);
  if (word_is(m, "FROM")) return motion(r, motion_kind::from, line, out, issues);
  if (word_is(m, "GODLTA")) return motion(r, motion_kind::delta, line, out, issues);
  if (word_is(m, "GOHOME")) return motion(r, motion_kind::home, line, out, issues);
  if (word_is(m, "RAPID")) {
    rapid_ = true;
    return;
  }
  if (word_is(m, "CIRCLE")) return circle(r, line, issues);
  if (word_is(m, "SPINDL")) return out.push_back({line, detail::read_spindl(r, issues)});
  if (word_is(m, "FEDRAT")) return out.push_back({line, detail::read_fedrat(r, units_, issues)});
  if (word_is(m, "COOLNT")) return out.push_back({line, detail::read_coolnt(r, issues)});
  if (word_is(m, "CUTCOM")) return out.push_back({line, detail::read_cutcom(r, issues)});
  if (word_is(m, "CYCLE")) return out.push_back({line, detail::read_cycle(r)});
  auto push = [&](auto opt) {
    if (opt) out.push_back({line, std::move(*opt)});
  };
  if (word_is(m, "DELAY")) return push(detail::read_delay(r, issues));
  if (word_is(m, "AUXFUN")) return push(detail::read_aux(r, false, issues));
  if (word_is(m, "PREFUN")) return push(detail::read_aux(r, true, issues));
  if (word_is(m, "LOADTL")) return push(detail::read_tool(r, tool_source::loadtl, issues));
  if (word_is(m, "TURRET")) return push(detail::read_tool(r, tool_source::turret, issues));
  if (word_is(m, "LOAD") || word_is(m, "SELECT") || word_is(m, "SELCTL")) {
    bool tool_word = !r.args.empty() && r.args[0].kind == arg_kind::word && word_is(r.args[0].word, "TOOL");
    if (tool_word || word_is(m, "SELCTL")) {
      tool_source s = word_is(m, "LOAD") ? tool_source::load_tool : tool_source::select_tool;
      return push(detail::read_tool(r, s, issues));
    }
  }
  if (word_is(m, "TLDATA") || word_is(m, "CUTTER")) {
    tool_data_event t;
    t.major = upper(m);
    for (const cl_arg& a : r.args) {
      if (a.kind == arg_kind::word) t.words.push_back(upper(a.word));
      if (a.kind == arg_kind::number) t.values.push_back(a.number);
    }
    return out.push_back({line, std::move(t)});
  }
  if (word_is(m, "UNITS") || word_is(m, "UNIT")) {
    if (!r.args.empty() && r.args[0].kind == arg_kind::word) {
      std::string_view w = r.args[0].word;
      if (word_is(w, "MM")) units_ = unit_system::mm;
      else if (word_is(w, "INCHES") || word_is(w, "INCH")) units_ = unit_system::inch;
      else return issues.push_back({severity::error, r.args[0].offset, fmt::format("unknown units '{}'", w)});
      return out.push_back({line, units_event{units_}});
    }
    return issues.push_back({severity::error, where(r), "UNITS needs MM or INCHES"});
  }
  if (word_is(m, "MACHIN")) {
    machin_event e;
    for (std::size_t i = 0; i < r.args.size(); ++i) {
      const cl_arg& a = r.args[i];
      std::string s = a.kind == arg_kind::word ? std::string(a.word)
                      : a.kind == arg_kind::number ? format_number(a.number) : std::string();
      if (i == 0) e.name = std::move(s);
      else e.args.push_back(std::move(s));
    }
    return out.push_back({line, std::move(e)});
  }
  if (word_is(m, "MULTAX")) {
    bool on = r.args.empty() || r.args[0].kind != arg_kind::word || !word_is(r.args[0].word, "OFF");
    return out.push_back({line, multax_event{on}});
  }
  if (word_is(m, "MSYS") || word_is(m, "CSYS"))
    return out.push_back({line, coordsys_event{upper(m), numbers_of(r)}});
  if (word_is(m, "TLAXIS")) {
    std::vector<double> n = numbers_of(r);
    if (n.size() != 3) return issues.push_back({severity::error, where(r), "TLAXIS takes 3 numbers"});
    axis_ = vec3{n[0], n[1], n[2]};
    return out.push_back({line, tool_axis_event{*axis_}});
  }
  if (word_is(m, "HEAD")) return push(detail::read_head(r, issues));
  if (word_is(m, "CHANNEL") || word_is(m, "CHANNL")) return push(detail::read_channel(r, issues));
  if (word_is(m, "SYNC")) return push(detail::read_sync(r, issues));
  if (word_is(m, "SYNCTR")) return push(detail::read_synctr(r, issues));
  if (word_is(m, "STOP") || word_is(m, "OPSTOP")) return out.push_back({line, stop_event{word_is(m, "OPSTOP")}});
  if (word_is(m, "FINI") || word_is(m, "END") || word_is(m, "END-OF-PATH"))
    return out.push_back({line, end_event{upper(m)}});
  bool known = known_passthrough(m);
  if (!known && posting_) {
    // Nothing silent in a post: a record twinpost cannot carry out stops it.
    issues.push_back({severity::error, r.major_offset,
                      fmt::format("unknown major word '{}': twinpost cannot post this record", upper(m))});
    return;
  }
  if (known && posting_ && !ignorable_in_post(r)) {
    // Known, but a post cannot do what it asks (STOP, THREAD, NURBS, ORIGIN, ...): dropping
    // it would write a program that differs from the CL without a word.
    issues.push_back({severity::error, r.major_offset,
                      fmt::format("{} is not supported by the post: twinpost cannot carry out this record", upper(m))});
    return;
  }
  if (!known)
    issues.push_back({severity::warning, r.major_offset,
                      fmt::format("unknown major word '{}' (a post stops here with an error)", upper(m))});
  out.push_back({line, passthrough_event{upper(m), detail::args_text(r), known}});
}

void event_builder::motion(const cl_record& r, motion_kind kind, int line, event_queue& out,
                           build_issues& issues) {
  const std::vector<double>& n = numbers(r);
  bool words = n.size() != r.args.size();
  if (kind == motion_kind::home && r.args.empty()) {
    point({pos_.x, pos_.y, pos_.z}, false, kind, line, out);
    return;
  }
  if (kind == motion_kind::delta && n.size() == 1 && !words) {
    // GODLTA/d: along the tool axis.
    vec3 a = axis_.value_or(vec3{0, 0, 1});
    point({a.x * n[0], a.y * n[0], a.z * n[0]}, false, kind, line, out);
    return;
  }
  if ((n.size() != 3 && n.size() != 6) || words) {
    const char* name = kind == motion_kind::go_to ? "GOTO" : kind == motion_kind::from ? "FROM"
                       : kind == motion_kind::delta ? "GODLTA" : "GOHOME";
    issues.push_back({severity::error, where(r),
                      fmt::format("{} takes 3 or 6 numbers (x,y,z[,i,j,k]), found {} argument{}", name,
                                  r.args.size(), r.args.size() == 1 ? "" : "s")});
    end_of_motion_record();
    return;
  }
  if (kind == motion_kind::go_to) {
    in_goto_ = true;
    rapid_record_ = rapid_;
    rapid_ = false;
  }
  point(n, false, kind, line, out);
}

void event_builder::point(const std::vector<double>& n, bool continued, motion_kind kind, int line,
                          event_queue& out) {
  vec3 p{n[0], n[1], n[2]};
  if (kind == motion_kind::delta) p = {pos_.x + p.x, pos_.y + p.y, pos_.z + p.z};
  if (n.size() == 6) axis_ = vec3{n[3], n[4], n[5]};  // modal: NX repeats it only on change
  if (kind == motion_kind::go_to && circle_) {
    arc_event a;
    a.start = pos_;
    a.end = p;
    a.center = circle_->center;
    a.normal = circle_->normal;
    a.radius = circle_->radius.value_or(planar_radius(pos_, a.center, a.normal));
    a.ccw = circle_->ccw.value_or(circle_is_ccw(dialect_));
    a.continued = continued;
    a.turns = circle_->turns;
    circle_used_ = true;
    pos_ = p;
    out.push_back({line, a});
    return;
  }
  // Built in place in the queue: the event is read from where it was written.
  motion_event& e = out.next_motion(line);  // every field set below
  e.kind = kind;
  e.pos = p;
  e.axis = axis_;
  e.rapid = kind == motion_kind::go_to ? rapid_record_ : false;
  e.continued = continued;
  if (kind != motion_kind::go_to && rapid_) {
    e.rapid = true;
    rapid_ = false;
  }
  pos_ = p;
}

void event_builder::circle(const cl_record& r, int line, build_issues& issues) {
  std::vector<double> n;
  pending_circle c;
  c.line = line;
  c.column = column_;
  for (std::size_t i = 0; i < r.args.size(); ++i) {
    const cl_arg& a = r.args[i];
    if (a.kind == arg_kind::number) n.push_back(a.number);
    if (a.kind != arg_kind::word) continue;
    if (word_is(a.word, "CLOCKWISE") || word_is(a.word, "CLW")) c.ccw = false;
    else if (word_is(a.word, "COUNTERCLOCKWISE") || word_is(a.word, "CCLW")) c.ccw = true;
    else if (word_is(a.word, "TIMES")) {
      // NX: CIRCLE/...,TIMES,n: the GOTO after it goes n full turns round the circle.
      const bool count = i + 1 < r.args.size() && r.args[i + 1].kind == arg_kind::number;
      const double t = count ? r.args[i + 1].number : 0;
      if (!count || t != std::floor(t) || t < 1 || t > max_circle_turns) {
        issues.push_back({severity::error, count ? r.args[i + 1].offset : a.offset,
                          count ? fmt::format("CIRCLE TIMES {} is not a whole number of turns from 1 to {}",
                                              format_number(t), max_circle_turns)
                                : std::string("CIRCLE TIMES needs a number of turns")});
        return;
      }
      c.turns = static_cast<int>(t);
      ++i;
    } else issues.push_back({severity::warning, a.offset, fmt::format("word '{}' ignored in CIRCLE", a.word)});
  }
  // 4: xc,yc,zc,r   6: xc,yc,zc,i,j,k (SolidWorks, no radius)   7: + r (Creo)   11: NX
  if (n.size() != 4 && n.size() != 6 && n.size() != 7 && n.size() != 11) {
    issues.push_back({severity::error, where(r),
                      fmt::format("CIRCLE takes 4, 6, 7 or 11 numbers, found {}", n.size())});
    return;
  }
  c.center = {n[0], n[1], n[2]};
  if (n.size() == 4) c.radius = n[3];
  if (n.size() >= 6) c.normal = {n[3], n[4], n[5]};
  if (n.size() >= 7) c.radius = n[6];
  circle_ = c;
  circle_used_ = false;
}

namespace {
// Records that only inform (display, tolerances, feature and tool labels): a post may pass
// over them, since the program does the same with or without them.
bool ignorable_in_post(const cl_record& r) {
  static constexpr std::string_view words[] = {
      "PAINT", "BOX", "MOVE_ATTRIB", "TRNTYP", "TOOLNO", "CSI_SET_FLUTE_LENGTH",
      "CSI_SET_EXTENSION_LENGTH", "INTOL", "OUTTOL", "LINTOL", "FEATNO", "MFGNO",
      "CUTCOM_GEOMETRY_TYPE", "REWIND", "DMIS"};
  for (std::string_view w : words)
    if (word_is(r.major, w)) return true;
  // SET/MODE,ABSOL (Makino) says what twinpost does anyway: absolute coordinates.
  return word_is(r.major, "SET") && r.args.size() == 2 && r.args[0].kind == arg_kind::word &&
         word_is(r.args[0].word, "MODE") && r.args[1].kind == arg_kind::word && word_is(r.args[1].word, "ABSOL");
}

bool known_passthrough(std::string_view m) {
  static constexpr std::string_view words[] = {
      "PAINT", "BOX", "MOVE_ATTRIB", "TRNTYP", "SET", "REWIND", "TOOLNO", "SWITCH",
      "LOCAL_ORIGIN", "ROTABL", "NURBS", "KNOT", "CNTRL", "CSI_SET_FLUTE_LENGTH",
      "CSI_SET_EXTENSION_LENGTH", "MODE", "COUPLE", "CLAMP", "THREAD",
      "ORIGIN", "INTOL", "OUTTOL", "LINTOL", "CALSUB", "DEFSUB", "ENDSUB", "DMIS", "FEATNO",
      "MFGNO", "SETSTART", "CUTCOM_GEOMETRY_TYPE", "OPSKIP", "PITCH"};
  for (std::string_view w : words)
    if (word_is(m, w)) return true;
  return false;
}
}  // namespace

}  // namespace twinpost
