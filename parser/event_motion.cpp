// event_builder: motion records (GOTO, FROM, GODLTA, GOHOME, CIRCLE) and their points.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fmt/format.h>

#include "parser/detail/fast_record.hpp"
#include "parser/detail/word_events.hpp"
#include "parser/event_builder.hpp"
#include "parser/event_text.hpp"

namespace twinpost {

namespace {

// The error of a motion record without 3 or 6 numbers. Out of line: motion() stays small and
// its prologue short for the GOTOs that have them.
[[gnu::noinline, gnu::cold]] void report_motion_arguments(const cl_record& r, motion_kind kind,
                                                          build_issues& issues) {
  const char* name = kind == motion_kind::go_to   ? "GOTO"
                     : kind == motion_kind::from  ? "FROM"
                     : kind == motion_kind::delta ? "GODLTA"
                                                  : "GOHOME";
  issues.push_back({severity::error, detail::args_offset(r),
                    fmt::format("{} takes 3 or 6 numbers (x,y,z[,i,j,k]), found {} argument{}", name,
                                r.args.size(), r.args.size() == 1 ? "" : "s")});
}

double planar_radius(vec3 p, vec3 c, vec3 n) {
  double dx = p.x - c.x, dy = p.y - c.y, dz = p.z - c.z;
  double nl = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  double a = nl > 0 ? (dx * n.x + dy * n.y + dz * n.z) / nl : 0;
  double r2 = dx * dx + dy * dy + dz * dz - a * a;
  return r2 > 0 ? std::sqrt(r2) : 0;
}

}  // namespace

void event_builder::motion(const cl_record& r, motion_kind kind, int line, event_queue& out,
                           build_issues& issues) {
  const std::span<const double> n = numbers(r);
  bool words = n.size() != r.args.size();
  if (kind == motion_kind::home && r.args.empty()) {
    const double here[] = {pos_.x, pos_.y, pos_.z};
    point(here, false, kind, line, out);
    return;
  }
  if (kind == motion_kind::delta && n.size() == 1 && !words) {
    // GODLTA/d: along the tool axis.
    vec3 a = axis_.value_or(vec3{0, 0, 1});
    const double along[] = {a.x * n[0], a.y * n[0], a.z * n[0]};
    point(along, false, kind, line, out);
    return;
  }
  if ((n.size() != 3 && n.size() != 6) || words) [[unlikely]] {
    report_motion_arguments(r, kind, issues);
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

bool event_builder::build_goto(const cl_record& r, int line, event_queue& out) {
  const std::size_t count = r.args.size();
  if (r.kind != record_kind::statement || !r.numbers_only || (count != 3 && count != 6) ||
      !parser_detail::is_goto(r.major))
    return false;
  double n[6];
  for (std::size_t i = 0; i < count; ++i) n[i] = r.args[i].number;
  return build_goto(n, count, line, out);
}

bool event_builder::build_goto(const double* numbers, std::size_t count, int line, event_queue& out) {
  if (any_script_records_) return false;
  // As build(), statement() and motion() take it: a statement ends the last motion record.
  after_bad_record_ = false;
  end_of_motion_record();
  in_goto_ = true;
  rapid_record_ = rapid_;
  rapid_ = false;
  point({numbers, count}, false, motion_kind::go_to, line, out);
  return true;
}

void event_builder::point(std::span<const double> n, bool continued, motion_kind kind, int line,
                          event_queue& out) {
  vec3 p{n[0], n[1], n[2]};
  if (kind == motion_kind::delta) p = {pos_.x + p.x, pos_.y + p.y, pos_.z + p.z};
  bool turned = false;
  if (n.size() == 6) {  // modal: NX repeats it only on change
    if (circle_) [[unlikely]] {
      const vec3 was = axis_.value_or(vec3{0, 0, 1});
      turned = std::abs(n[3] - was.x) + std::abs(n[4] - was.y) + std::abs(n[5] - was.z) > 1e-7;
    }
    axis_ = vec3{n[3], n[4], n[5]};
  }
  if (kind == motion_kind::go_to && circle_) {
    arc_event a;
    a.turns_axis = turned;
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

void event_builder::circle(const cl_record& r, int line, event_queue&, build_issues& issues) {
  // The builder's scratch vector: no allocation per CIRCLE.
  std::vector<double>& n = numbers_;
  n.clear();
  pending_circle c;
  c.line = line;
  c.column = column_;
  for (std::size_t i = 0; i < r.args.size(); ++i) {
    const cl_arg& a = r.args[i];
    if (a.kind == arg_kind::number) n.push_back(a.number);
    if (a.kind != arg_kind::word) continue;
    if (word_is(a.word, "CLOCKWISE") || word_is(a.word, "CLW"))
      c.ccw = false;
    else if (word_is(a.word, "COUNTERCLOCKWISE") || word_is(a.word, "CCLW"))
      c.ccw = true;
    else if (word_is(a.word, "TIMES")) {
      // NX: CIRCLE/...,TIMES,n: the GOTO after it goes n full turns round the circle (and on to
      // the GOTO when it lies elsewhere on it).
      const bool count = i + 1 < r.args.size() && r.args[i + 1].kind == arg_kind::number;
      const double t = count ? r.args[i + 1].number : 0;
      if (!count || t != std::floor(t) || t < 1 || t > max_circle_turns) {
        issues.push_back({severity::error, count ? r.args[i + 1].offset : a.offset,
                          count ? fmt::format("CIRCLE TIMES {} is not a whole number of turns from 1 to {}",
                                              format_number(t), max_circle_turns)
                                : std::string("CIRCLE TIMES needs a number of turns")});
        return;
      }
      if (c.turns != 0 && c.turns != static_cast<int>(t)) {
        issues.push_back(
            {severity::error, a.offset,
             fmt::format("CIRCLE TIMES is given twice, {} and {}: which one is meant is not known", c.turns,
                         format_number(t))});
        return;
      }
      c.turns = static_cast<int>(t);
      ++i;
    } else
      issues.push_back({severity::warning, a.offset, fmt::format("word '{}' ignored in CIRCLE", a.word)});
  }
  // 4: xc,yc,zc,r   6: xc,yc,zc,i,j,k (SolidWorks, no radius)   7: + r (Creo)   11: NX
  if (n.size() != 4 && n.size() != 6 && n.size() != 7 && n.size() != 11) {
    issues.push_back({severity::error, detail::args_offset(r),
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

}  // namespace twinpost
