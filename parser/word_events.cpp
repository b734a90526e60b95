#include "parser/detail/word_events.hpp"

#include "parser/detail/bad_number.hpp"

#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "parser/event_text.hpp"

namespace twinpost::detail {

namespace {

bool is_num(const cl_record& r, std::size_t i) {
  return i < r.args.size() && r.args[i].kind == arg_kind::number;
}
bool is_word(const cl_record& r, std::size_t i) {
  return i < r.args.size() && r.args[i].kind == arg_kind::word;
}

// Marks which arguments a reader has given a meaning, so that leftovers can be reported.
struct arg_use {
  const cl_record& r;
  std::vector<bool> used;
  explicit arg_use(const cl_record& rec) : r(rec), used(rec.args.size(), false) {}

  // The number right after word i, else the number right before it, if still free.
  std::optional<double> value_near(std::size_t i) {
    if (is_num(r, i + 1) && !used[i + 1]) return take(i + 1);
    if (i > 0 && is_num(r, i - 1) && !used[i - 1]) return take(i - 1);
    return std::nullopt;
  }
  std::optional<double> value_after(std::size_t i) {
    if (is_num(r, i + 1) && !used[i + 1]) return take(i + 1);
    return std::nullopt;
  }
  double take(std::size_t i) {
    used[i] = true;
    taken = i;
    return r.args[i].number;
  }
  std::size_t taken = 0;  // the argument taken last
  // The first free number, if any.
  std::optional<double> first_free_number() {
    for (std::size_t i = 0; i < r.args.size(); ++i)
      if (is_num(r, i) && !used[i]) return take(i);
    return std::nullopt;
  }
  void report_leftovers(std::string_view major, build_issues& issues) {
    for (std::size_t i = 0; i < r.args.size(); ++i) {
      if (used[i] || r.args[i].kind == arg_kind::empty) continue;
      const cl_arg& a = r.args[i];
      std::string what = a.kind == arg_kind::word ? fmt::format("word '{}'", a.word)
                                                  : fmt::format("number {}", format_number(a.number));
      issues.push_back({severity::warning, a.offset, fmt::format("{} ignored in {}", what, major)});
    }
  }
};

}  // namespace

bool report_bad_number(const cl_record& r, build_issues& issues) {
  for (const cl_arg& a : r.args) {
    if (a.kind != arg_kind::word) continue;
    if (auto message = bad_number_message(a.word)) {
      issues.push_back({severity::error, a.offset, std::move(*message)});
      return true;
    }
  }
  return false;
}

int as_int(double v) {
  constexpr double lo = std::numeric_limits<int>::min();
  constexpr double hi = std::numeric_limits<int>::max();
  if (!(v > lo)) return std::numeric_limits<int>::min();
  if (!(v < hi)) return std::numeric_limits<int>::max();
  return static_cast<int>(std::lround(v));
}

std::vector<double> numbers_of(const cl_record& r) {
  std::vector<double> v;
  for (const cl_arg& a : r.args)
    if (a.kind == arg_kind::number) v.push_back(a.number);
  return v;
}

std::string args_text(const cl_record& r) {
  std::string s;
  for (std::size_t i = 0; i < r.args.size(); ++i) {
    if (i) s += ',';
    const cl_arg& a = r.args[i];
    if (a.kind == arg_kind::number) s += format_number(a.number);  // never "-0"
    if (a.kind == arg_kind::word) s += a.word;
  }
  return s;
}

spindle_event read_spindl(const cl_record& r, build_issues& issues) {
  spindle_event e;
  arg_use use(r);
  for (std::size_t i = 0; i < r.args.size(); ++i) {  // words that own the number after them
    if (!is_word(r, i)) continue;
    std::string_view w = r.args[i].word;
    if (word_is(w, "MAXRPM"))
      use.used[i] = true, e.max_rpm = use.value_after(i);
    else if (word_is(w, "RANGE")) {
      use.used[i] = true;
      if (auto v = use.value_after(i)) e.range = as_int(*v);
    } else if (word_is(w, "ORIENT")) {
      use.used[i] = true;
      e.mode = spindle_mode::orient;
      if (auto v = use.value_after(i)) e.speed = *v;
    }
  }
  bool unit_given = false;
  for (std::size_t i = 0; i < r.args.size(); ++i) {
    if (!is_word(r, i) || use.used[i]) continue;
    std::string_view w = r.args[i].word;
    bool known = true;
    if (word_is(w, "RPM") || word_is(w, "SFM") || word_is(w, "SMM")) {
      e.mode = word_is(w, "RPM")   ? spindle_mode::rpm
               : word_is(w, "SFM") ? spindle_mode::sfm
                                   : spindle_mode::smm;
      unit_given = true;
      use.used[i] = true;
      if (auto v = use.value_near(i)) e.speed = *v;
    } else if (word_is(w, "CLW"))
      e.dir = rotation::cw;
    else if (word_is(w, "CCLW"))
      e.dir = rotation::ccw;
    else if (word_is(w, "OFF"))
      e.mode = spindle_mode::off;
    else if (word_is(w, "ON"))
      e.mode = spindle_mode::on;
    else if (word_is(w, "LOCK"))
      e.mode = spindle_mode::lock;
    else if (word_is(w, "AUTO")) {
    } else if (word_is(w, "MAIN"))
      e.spindle = "main";
    else if (word_is(w, "SUB") || word_is(w, "SIDE") || word_is(w, "OPPOS"))
      e.spindle = "sub";
    else if (word_is(w, "LIVE") || word_is(w, "MILL"))
      e.spindle = "live";
    else
      known = false;
    if (known) use.used[i] = true;
  }
  if (!unit_given && e.mode == spindle_mode::rpm) {
    if (auto v = use.first_free_number()) e.speed = *v;  // bare `SPINDL/1200`
  }
  use.report_leftovers("SPINDL", issues);
  return e;
}

feed_event read_fedrat(const cl_record& r, unit_system units, build_issues& issues) {
  feed_event e;
  e.units = units;
  arg_use use(r);
  bool unit_given = false;
  for (std::size_t i = 0; i < r.args.size(); ++i) {
    if (!is_word(r, i)) continue;
    std::string_view w = r.args[i].word;
    struct unit_word {
      std::string_view word;
      feed_mode mode;
      int units;
    };  // units: 0 mm, 1 inch, 2 job
    static constexpr unit_word table[] = {
        {"MMPM", feed_mode::per_minute, 0},     {"IPM", feed_mode::per_minute, 1},
        {"MMPR", feed_mode::per_rev, 0},        {"IPR", feed_mode::per_rev, 1},
        {"PERMIN", feed_mode::per_minute, 2},   {"PERREV", feed_mode::per_rev, 2},
        {"FPM", feed_mode::per_minute, 2},      {"FPR", feed_mode::per_rev, 2},
        {"INVERS", feed_mode::inverse_time, 2}, {"INVERSE", feed_mode::inverse_time, 2},
    };
    for (const unit_word& u : table) {
      if (!word_is(w, u.word)) continue;
      e.mode = u.mode;
      if (u.units != 2) e.units = u.units == 0 ? unit_system::mm : unit_system::inch;
      unit_given = true;
      use.used[i] = true;
      if (auto v = use.value_near(i)) e.value = *v;
      break;
    }
    if (!use.used[i] && (word_is(w, "AUTO") || word_is(w, "ON"))) use.used[i] = true;
  }
  if (!unit_given || e.value == 0) {
    if (auto v = use.first_free_number()) e.value = *v;
  }
  use.report_leftovers("FEDRAT", issues);
  return e;
}

coolant_event read_coolnt(const cl_record& r, build_issues& issues) {
  coolant_event e;
  arg_use use(r);
  for (std::size_t i = 0; i < r.args.size(); ++i) {
    if (!is_word(r, i)) continue;
    std::string w = upper(r.args[i].word);
    if (w == "ON" || w == "OFF" || w == "FLOOD" || w == "MIST" || w == "TAP" || w == "THRU" || w == "AIR" ||
        w == "THRUTOOL") {
      if (e.mode.empty()) e.mode = w, use.used[i] = true;
    } else if (w == "LOW" || w == "MEDIUM" || w == "HIGH") {
      e.level = w, use.used[i] = true;
    }
  }
  if (e.mode.empty()) e.mode = "ON";
  use.report_leftovers("COOLNT", issues);
  return e;
}

cutcom_event read_cutcom(const cl_record& r, build_issues& issues) {
  cutcom_event e;
  arg_use use(r);
  for (std::size_t i = 0; i < r.args.size(); ++i) {
    if (is_num(r, i)) {
      if (!e.reg) e.reg = as_int(use.take(i));
      continue;
    }
    if (!is_word(r, i)) continue;
    std::string w = upper(r.args[i].word);
    if (w == "LEFT" || w == "RIGHT" || w == "OFF" || w == "ON")
      e.side = w, use.used[i] = true;
    else if (w == "XYPLAN" || w == "YZPLAN" || w == "ZXPLAN")
      e.plane = w, use.used[i] = true;
  }
  use.report_leftovers("CUTCOM", issues);
  return e;
}

cycle_event read_cycle(const cl_record& r, build_issues& issues) {
  cycle_event e;
  std::size_t i = 0;
  if (is_word(r, 0)) e.type = upper(r.args[0].word), i = 1;
  // NX (and Autodesk's APT post) write the peck cycle as CYCLE/DRILL,DEEP,...: the same cycle
  // as Creo's CYCLE/DEEP, read by the same rules (a public NX reader's own example:
  // "CYCLE/DRILL,DEEP,STEP,20,CLEAR,3,FEDTO,-72,RTRCTO,AUTO,MMPM,250").
  if (e.type == "DRILL" && is_word(r, 1) && word_is(r.args[1].word, "DEEP") && !is_num(r, 2))
    e.type = "DEEP", i = 2;
  for (; i < r.args.size(); ++i) {
    const cl_arg& a = r.args[i];
    if (a.kind == arg_kind::word && is_num(r, i + 1)) {
      // A word given twice with its value (FEDTO,-10 ... FEDTO,-200): which the CAM meant is not
      // known, and the one not taken is never checked (attack 45).
      std::string name = upper(a.word);
      for (const auto& [seen, value] : e.params)
        if (seen == name && value != r.args[i + 1].number)
          issues.push_back(
              {severity::error, a.offset,
               fmt::format("CYCLE/{}: {} is given twice, {} and {}: which one is meant is not known", e.type,
                           name, format_number(value), format_number(r.args[i + 1].number))});
      e.params.emplace_back(std::move(name), r.args[i + 1].number);
      ++i;
    } else if (a.kind == arg_kind::word) {
      e.words.push_back(upper(a.word));
    } else if (a.kind == arg_kind::number) {
      e.positional.push_back(a.number);
    }
  }
  return e;
}

std::optional<thread_event> read_thread(const cl_record& r, build_issues& issues) {
  // THREAD/TURN,LEAD,l (or PITCH,p with STARTS,n / MULTRD,n) starts threading passes;
  // THREAD/OFF ends them. Every other word or number is an error: a thread cut to a lead the
  // post guessed is scrap, and THREAD/FACE (a scroll) is not carried out.
  auto fail = [&](std::size_t at, std::string message) {
    issues.push_back({severity::error, at, std::move(message)});
    return std::nullopt;
  };
  if (!is_word(r, 0) || !(word_is(r.args[0].word, "TURN") || word_is(r.args[0].word, "OFF")))
    return fail(args_offset(r), fmt::format("THREAD/{} is not supported by the post: it posts THREAD/TURN "
                                            "(with LEAD or PITCH) and THREAD/OFF",
                                            args_text(r)));
  thread_event e;
  if (word_is(r.args[0].word, "OFF")) {
    e.on = false;
    if (r.args.size() > 1) return fail(r.args[1].offset, "THREAD/OFF takes no more arguments");
    return e;
  }
  std::optional<double> lead, pitch;
  std::optional<double> starts;
  for (std::size_t i = 1; i < r.args.size(); ++i) {
    const cl_arg& a = r.args[i];
    if (a.kind == arg_kind::empty) continue;
    const bool known = a.kind == arg_kind::word && (word_is(a.word, "LEAD") || word_is(a.word, "PITCH") ||
                                                    word_is(a.word, "STARTS") || word_is(a.word, "MULTRD"));
    if (!known || !is_num(r, i + 1))
      return fail(
          a.offset,
          fmt::format("THREAD/TURN: {} is not carried out by the post (it knows LEAD, PITCH "
                      "and STARTS or MULTRD, each with its value)",
                      a.kind == arg_kind::word ? upper(a.word)
                                               : fmt::format("the value {}", format_number(a.number))));
    const double v = r.args[i + 1].number;
    if (word_is(a.word, "LEAD"))
      lead = v;
    else if (word_is(a.word, "PITCH"))
      pitch = v;
    else
      starts = v;
    ++i;
  }
  if (starts && !(*starts >= 1 && *starts <= 99 && *starts == std::floor(*starts)))
    return fail(args_offset(r), fmt::format("THREAD/TURN: STARTS {} is not a whole number of starts in 1..99",
                                            format_number(*starts)));
  e.starts = starts ? static_cast<int>(*starts) : 1;
  if (lead && pitch) return fail(args_offset(r), "THREAD/TURN gives both LEAD and PITCH: give one");
  if (!lead && !pitch) return fail(args_offset(r), "THREAD/TURN needs the lead (LEAD,l or PITCH,p)");
  e.lead = lead ? *lead : *pitch * e.starts;
  if (!(e.lead > 0) || !std::isfinite(e.lead))
    return fail(args_offset(r),
                fmt::format("THREAD/TURN: the lead {} must be above 0", format_number(e.lead)));
  return e;
}

std::optional<delay_event> read_delay(const cl_record& r, build_issues& issues) {
  arg_use use(r);
  delay_event e;
  auto v = use.first_free_number();
  if (!v) {
    issues.push_back({severity::error, r.major_offset, "DELAY needs a time"});
    return std::nullopt;
  }
  e.value = *v;
  for (std::size_t i = 0; i < r.args.size(); ++i)
    if (is_word(r, i) && (word_is(r.args[i].word, "REV") || word_is(r.args[i].word, "REVS")))
      e.revolutions = true, use.used[i] = true;
  use.report_leftovers("DELAY", issues);
  return e;
}

std::optional<aux_event> read_aux(const cl_record& r, bool prefun, build_issues& issues) {
  if (!is_num(r, 0)) {
    issues.push_back({severity::error, r.major_offset,
                      fmt::format("{} needs a code number", prefun ? "PREFUN" : "AUXFUN")});
    return std::nullopt;
  }
  // A whole number (attack 68 L7: AUXFUN/2.5 was written M3, a spindle start).
  const double v = r.args[0].number;
  if (v != std::floor(v) || v < 0 || v > 99999) {
    issues.push_back({severity::error, r.args[0].offset,
                      fmt::format("{} code {} {}", prefun ? "PREFUN" : "AUXFUN", format_number(v),
                                  v != std::floor(v) ? "is not a whole number" : "is out of range")});
    return std::nullopt;
  }
  aux_event e;
  e.prefun = prefun;
  e.code = static_cast<int>(v);
  for (std::size_t i = 1; i < r.args.size(); ++i)
    if (is_num(r, i)) e.extra.push_back(r.args[i].number);
  return e;
}

namespace {

// A tool or offset number: a whole number that fits an int, else an error at its argument
// (a silent cast would call a tool nobody asked for).
bool whole_number(const cl_record& r, std::size_t arg, std::string_view what, int& out,
                  build_issues& issues) {
  const double v = r.args[arg].number;
  std::string problem;
  if (v != std::floor(v))
    problem = "is not a whole number";
  else if (v < 0 || v > std::numeric_limits<int>::max())
    problem = "is out of range";
  if (problem.empty()) {
    out = static_cast<int>(v);
    return true;
  }
  issues.push_back({severity::error, r.args[arg].offset,
                    fmt::format("{} {} {} {}", upper(r.major), what, format_number(v), problem)});
  return false;
}

}  // namespace

std::optional<tool_event> read_tool(const cl_record& r, tool_source source, build_issues& issues) {
  tool_event e;
  e.source = source;
  e.preselect = source == tool_source::select_tool;
  arg_use use(r);
  for (std::size_t i = 0; i < r.args.size(); ++i) {
    if (!is_word(r, i)) continue;
    std::string_view w = r.args[i].word;
    if (word_is(w, "TOOL"))
      use.used[i] = true;  // LOAD/TOOL, SELECT/TOOL
    else if (word_is(w, "ADJUST") || word_is(w, "OSETNO") || word_is(w, "OFFSET")) {
      use.used[i] = true;
      if (use.value_after(i)) {
        int n = 0;
        if (!whole_number(r, use.taken, "offset number", n, issues)) return std::nullopt;
        e.offset = n;
      }
    }
  }
  auto tool = use.first_free_number();
  if (!tool) {
    std::size_t at = r.args.empty() ? r.major_offset : r.args.front().offset;
    issues.push_back({severity::error, at, fmt::format("{} needs a tool number", upper(r.major))});
    return std::nullopt;
  }
  if (!whole_number(r, use.taken, "tool number", e.tool, issues)) return std::nullopt;
  if (!e.offset) {
    if (use.first_free_number()) {
      int n = 0;
      if (!whole_number(r, use.taken, "offset number", n, issues)) return std::nullopt;
      e.offset = n;
    }
  }
  // TURRET/tool,offset,xshift,yshift: the shifts are tool data, not errors.
  if (source == tool_source::turret)
    for (std::size_t i = 0; i < r.args.size(); ++i)
      if (is_num(r, i)) use.used[i] = true;
  use.report_leftovers(upper(r.major), issues);
  return e;
}

}  // namespace twinpost::detail
