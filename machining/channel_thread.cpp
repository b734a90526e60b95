// channel_writer: lathe threading (CYCLE/THREAD, THREAD/TURN) and radial grooving
// (CYCLE/GROOVE), written in the form the machine's [cycles] name (docs/machines.md):
//   thread: g76 / g276 (two-block multi-pass cycle), g92 / g292 (one box per pass),
//           g32 (each pass as G0 / G32 / G0 / G0 moves);
//   groove: g75 (two-block cycle) or expanded (G0 / G1 plunges along X).
// The pass plan is one model for every form (thread_plan below): the expanded forms write
// it move by move, the cycles hand the control the words that make it (tests compare them).
// Never an unsynchronised G1 at the pitch feed; never a thread under constant surface speed.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <span>

#include "machining/channel_writer.hpp"
#include "parser/cycle_words.hpp"

namespace twinpost {

namespace {

constexpr double pi = 3.14159265358979323846;
constexpr int max_passes = 999;

// The Fanuc / Mazak tool-angle codes of the G76 / G276 P word (its last two digits).
bool valid_tool_angle(int a) { return a == 0 || a == 29 || a == 30 || a == 55 || a == 60 || a == 80; }

bool is_two_block(std::string_view form) { return form == "g76" || form == "g276"; }

}  // namespace

bool channel_writer::spindle_ready_for_thread(std::string_view what, int line) {
  if (restart_blocks_.empty() || !last_speed_) {
    error(line,
          fmt::format("{} with the spindle stopped: threading needs the spindle turning (SPINDL/RPM)", what));
    return false;
  }
  if (last_speed_->mode == spindle_mode::sfm || last_speed_->mode == spindle_mode::smm) {
    // The control keeps the lead only at a constant speed: G96 changes the rpm with X on
    // every pass, and the passes would not meet the same helix.
    error(line, fmt::format("{} under constant surface speed ({}): threading needs a constant spindle speed; "
                            "give SPINDL/RPM before the thread",
                            what, m_.codes.css));
    return false;
  }
  return true;
}

void channel_writer::restore_feed_mode(bool had_mode, bool per_rev) {
  // The mode the CL set before the thread comes back; one it never set is not written.
  if (had_mode)
    feed_mode(per_rev);
  else
    per_rev_ = per_rev;
}

bool channel_writer::inch_thread_refused(std::string_view what, int line) {
  if (out_per_mm_ == 1.0) return false;
  // An inch lead (1/13 in = 0.076923...) needs more places than a feed; how many this
  // control's F takes in a thread, or whether it wants E, is not verified yet.
  error(line, fmt::format("{} in inch output: the lead's digits on this control are not verified; post the "
                          "thread in mm output",
                          what));
  return true;
}

long long channel_writer::increments(double v) const {
  // The least input increment, IS-B: 0.001 mm, 0.0001 in.
  return std::llround(v * (out_per_mm_ == 1.0 ? 1000 : 10000));
}

bool channel_writer::append_lead(text_buffer& out, double lead_mm) {
  if (!fits('F', lead_mm, 4)) return false;
  out += " F";
  append_number(out, lead_mm, {4, m_.program.trailing_point});
  last_f_.clear();  // the F in force is now the lead: the next feed move writes its own F
  return true;
}

bool channel_writer::lathe_cycle_supported(const cycle_event& c, int line) {
  const bool thread = c.type == "THREAD";
  const std::string& form = thread ? m_.cycles.thread : m_.cycles.groove;
  if (form.empty()) {
    error(line,
          fmt::format("CYCLE/{} is not supported by the post: machine '{}' names no {} cycle "
                      "([cycles] {} in its file)",
                      c.type, m_.name, thread ? "threading" : "grooving", thread ? "thread" : "groove"));
    return false;
  }
  static constexpr std::string_view thread_words[] = {"LEAD",   "PITCH",  "STARTS", "DEPTH",
                                                      "FIRST",  "PASSES", "MINCUT", "FINISH",
                                                      "SPRING", "ANGLE",  "TAPER",  "CHAMFR"};
  static constexpr std::string_view groove_words[] = {"DEPTH", "FEDTO", "WIDTH", "ZSTEP",
                                                      "RAPTO", "MMPR",  "IPR"};
  const std::span<const std::string_view> known = thread ? std::span<const std::string_view>(thread_words)
                                                         : std::span<const std::string_view>(groove_words);
  const char* known_text = thread ? "LEAD or PITCH, STARTS, DEPTH, FIRST or PASSES, MINCUT, FINISH, SPRING, "
                                    "ANGLE, TAPER and CHAMFR"
                                  : "DEPTH or FEDTO, WIDTH, ZSTEP, RAPTO and MMPR or IPR";
  for (const auto& [name, value] : c.params) {
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      error(line, fmt::format("CYCLE/{}: {} is not carried out by the post (it knows {})", c.type, name,
                              known_text));
      return false;
    }
    if (name == "CHAMFR" && !is_two_block(form) && value != 0) {
      error(line, fmt::format("CYCLE/THREAD: CHAMFR is not carried out by the {} form of machine '{}' (only "
                              "G76/G276 write a thread pull-out)",
                              form, m_.name));
      return false;
    }
  }
  if (!c.words.empty() || !c.positional.empty()) {
    error(line, fmt::format(
                    "CYCLE/{}: {} is not carried out by the post (it knows {}, each with its value)", c.type,
                    c.words.empty() ? fmt::format("the value {}", c.positional.front()) : c.words.front(),
                    known_text));
    return false;
  }
  return true;
}

namespace {

// One thread cycle as the post understands it (docs/records.md, "CYCLE/THREAD"), in mm and
// CL radius coordinates: passes cut from the start Z to the end Z at depths[k] below the
// crest, each starting shift[k] further toward the end (flank infeed).
struct thread_plan {
  double lead = 0, height = 0, first = 0, min_cut = 0, finish = 0, angle = 0, taper = 0, chamfer = 0;
  int starts = 1, spring = 0;
  std::vector<double> depths;  // cumulative depth of each pass (radius), the last ones = height
  std::string problem;         // why the cycle cannot be cut, or empty
};

thread_plan plan_thread(const cycle_event& c, double scale) {
  thread_plan t;
  auto fail = [&](std::string why) {
    t.problem = std::move(why);
    return t;
  };
  const auto lead = cycle_param(c, "LEAD"), pitch = cycle_param(c, "PITCH");
  const double starts = cycle_param(c, "STARTS").value_or(1);
  if (!(starts >= 1 && starts <= 99 && starts == std::floor(starts)))
    return fail(fmt::format("STARTS {} is not a whole number of starts in 1..99", starts));
  t.starts = static_cast<int>(starts);
  if (lead && pitch) return fail("it gives both LEAD and PITCH: give one");
  if (!lead && !pitch) return fail("it needs the lead (LEAD,l or PITCH,p)");
  t.lead = (lead ? *lead : *pitch * t.starts) * scale;
  const auto depth = cycle_param(c, "DEPTH");
  if (!depth) return fail("it needs the thread height (DEPTH)");
  t.height = *depth * scale;
  t.finish = cycle_param(c, "FINISH").value_or(0) * scale;
  t.min_cut = cycle_param(c, "MINCUT").value_or(0) * scale;
  t.angle = cycle_param(c, "ANGLE").value_or(0);
  t.taper = cycle_param(c, "TAPER").value_or(0) * scale;
  t.chamfer = cycle_param(c, "CHAMFR").value_or(0);
  const double spring = cycle_param(c, "SPRING").value_or(0);
  if (!(t.lead > 0 && std::isfinite(t.lead))) return fail(fmt::format("the lead {} must be above 0", t.lead));
  if (!(t.height > 0 && t.height < 1000)) return fail(fmt::format("DEPTH {} must be above 0", *depth));
  if (!(t.finish >= 0 && t.finish < t.height)) return fail("FINISH must be at least 0 and below DEPTH");
  if (!(t.min_cut >= 0 && t.min_cut <= t.height)) return fail("MINCUT must be at least 0 and at most DEPTH");
  if (!(spring >= 0 && spring <= 98 && spring == std::floor(spring)))
    return fail(fmt::format("SPRING {} is not a whole number of passes in 0..98", spring));
  t.spring = static_cast<int>(spring);
  if (!(t.angle >= 0 && t.angle < 60)) return fail(fmt::format("ANGLE {} must be in 0..60 degrees", t.angle));
  if (!(t.chamfer >= 0 && t.chamfer <= 9.9))
    return fail(fmt::format("CHAMFR {} must be in 0..9.9 leads", t.chamfer));
  if (!std::isfinite(t.taper)) return fail("TAPER must be a number");
  if (t.taper != 0 && t.starts > 1)
    return fail("a tapered thread with more than one start: shifted starts would move the cone");
  const auto first = cycle_param(c, "FIRST"), passes = cycle_param(c, "PASSES");
  const double rough = t.height - t.finish;
  if (first && passes) return fail("it gives both FIRST and PASSES: give one");
  if (first)
    t.first = *first * scale;
  else if (passes && *passes >= 1 && *passes <= max_passes && *passes == std::floor(*passes))
    t.first = rough / std::sqrt(*passes);  // equal chip area: pass k reaches rough * sqrt(k / n)
  else if (passes)
    return fail(fmt::format("PASSES {} is not a whole number in 1..{}", *passes, max_passes));
  else
    return fail("it needs the first cut (FIRST) or the number of passes (PASSES)");
  if (!(t.first > 0 && t.first <= t.height)) return fail("FIRST must be above 0 and at most DEPTH");
  // The roughing depths, as the Fanuc G76 cuts them: pass k at first * sqrt(k), no cut thinner
  // than MINCUT, up to the height less the finishing allowance; then the finishing pass and
  // the spring passes at the full height.
  double d = 0;
  for (int k = 1; d < rough - 1e-9; ++k) {
    double next = std::max(t.first * std::sqrt(static_cast<double>(k)), d + t.min_cut);
    d = std::min(next, rough);
    t.depths.push_back(d);
    if (static_cast<int>(t.depths.size()) > max_passes)
      return fail(fmt::format("it makes more than {} passes", max_passes));
  }
  for (int k = 0; k <= t.spring; ++k) t.depths.push_back(t.height);
  return t;
}

}  // namespace

void channel_writer::thread_cycle_point(const vec3& p, int line) {
  const cycle_event& c = *cycle_;
  const std::string& form = m_.cycles.thread;
  if (inch_thread_refused("CYCLE/THREAD", line) || !spindle_ready_for_thread("CYCLE/THREAD", line)) return;
  thread_plan t = plan_thread(c, scale_);
  if (!t.problem.empty()) return error(line, fmt::format("CYCLE/THREAD: {}", t.problem));
  // Geometry in mm, CL radius: the start is where the tool is, the GOTO is the thread's end at
  // full depth (the root). The crest lies `height` outward of the root, outward being the
  // side the tool starts on (external thread: away from the axis).
  const double x0 = pos_.x * scale_, z0 = pos_.z * scale_;
  const double xr = p.x * scale_, ze = p.z * scale_;
  // TAPER is a change of the distance from the axis (start minus end, as Fanuc's R): on the
  // CL side of the thread (x < 0 for a lower turret) it runs the other way in x.
  const double side = xr < 0 ? -1.0 : 1.0;
  const double taper_x = side * t.taper;
  const double out = x0 >= xr + taper_x ? 1.0 : -1.0;  // outward: from the root toward the start
  const double along = ze < z0 ? -1.0 : 1.0;           // the cutting direction along Z
  if (std::abs(ze - z0) < 1e-6)
    return error(line, "CYCLE/THREAD: the thread's end Z is its start Z: a thread runs along Z");
  if ((x0 - (xr + taper_x + out * t.height)) * out < -1e-9)
    return error(line,
                 fmt::format("CYCLE/THREAD: the start X {} lies inside the thread (crest X {}): start the "
                             "cycle clear of the thread",
                             x0 / scale_, (xr + taper_x + out * t.height) / scale_));
  const double tan_a = std::tan(t.angle * pi / 180);
  const int tool_angle = static_cast<int>(std::lround(2 * t.angle));
  if (is_two_block(form) && (!valid_tool_angle(tool_angle) || std::abs(2 * t.angle - tool_angle) > 1e-6))
    return error(line,
                 fmt::format("CYCLE/THREAD: ANGLE {} gives a tool angle of {} degrees; the {} P word takes "
                             "0, 29, 30, 55, 60 or 80",
                             t.angle, 2 * t.angle, form == "g76" ? "G76" : "G276"));
  const double inv = 1.0 / scale_;  // mm back to CL units for linear() and nc_x()
  const double mirror = mirrored() ? -1.0 : 1.0;
  const bool was_per_rev = per_rev_;
  const bool had_mode = !feed_g_.empty();
  feed_mode(true);
  // A cycle block: G-code, X (diameter, mirrored as the channel is) and Z always, R when
  // not zero, the rest, then the lead.
  auto cycle_block = [&](std::string_view g, double x_mm, double z_mm, double r, std::string_view tail) {
    arc_.clear();
    arc_ += ' ';
    arc_ += g;
    axis_word(arc_, 'X', nc_x(x_mm * inv), last_x_, true);
    axis_word(arc_, 'Z', z_mm * z_sign_, last_z_, true);  // reversed on a sub spindle
    if (std::abs(r) >= 0.0005) {
      if (!fits('R', r, axis_style_.decimals)) return false;
      arc_ += " R";
      append_number(arc_, r, axis_style_);
    }
    arc_ += tail;
    if (!append_lead(arc_, t.lead)) return false;
    out_.block(arc_.view().substr(1));
    return true;
  };
  auto um = [&](double v) { return increments(v); };
  auto mm = [&](double v) { return format_nc_number(v, axis_style_); };
  for (int s = 0; s < t.starts; ++s) {
    // Shifted starts: each start begins one pitch further back. The control starts every pass
    // at the same spindle angle, so a start shifted by one pitch cuts the next helix.
    const double zs = z0 - along * s * t.lead / t.starts;
    if (s > 0) linear(true, x0 * inv, pos_.y, zs * inv, line);
    if (is_two_block(form)) {
      // G76 P(m finishing passes)(r pull-out in 0.1 lead)(a tool angle) Q(min cut) R(allowance);
      // G76 X Z R(taper) P(height) Q(first cut) F(lead). Fanuc reads P and Q in 0.001 mm
      // without a point; Mazak's G276 reads them in mm (F-INTGX).
      const std::string g = form == "g76" ? "G76" : "G276";
      const bool increments = form == "g76";
      const std::string p1 = fmt::format("{:02}{:02}{:02}", 1 + t.spring,
                                         static_cast<int>(std::lround(t.chamfer * 10)), tool_angle);
      out_.block(fmt::format("{} P{} Q{} R{}", g, p1,
                             increments ? fmt::format("{}", um(t.min_cut)) : mm(t.min_cut), mm(t.finish)));
      const std::string tail = increments ? fmt::format(" P{} Q{}", um(t.height), um(t.first))
                                          : fmt::format(" P{} Q{}", mm(t.height), mm(t.first));
      if (!cycle_block(g, xr, ze, taper_x * mirror, tail)) return;
      motion_g_ = -1;
      forget_axes();  // the cycle ends at its start point
      continue;
    }
    double z_now = zs;
    for (const double depth : t.depths) {
      const double zk = zs + along * (depth - t.depths.front()) * tan_a;  // flank infeed
      const double x_end = xr + out * (t.height - depth);
      const double x_start = x_end + taper_x * (ze - zk) / (ze - z0);  // on the cone, at the pass's start
      if (form == "g32") {
        // Rapid to the pass's start, G32 to its end, rapid out in X, rapid back in Z.
        linear(true, x_start * inv, pos_.y, zk * inv, line);
        if (!cycle_block("G32", x_end, ze, 0, "")) return;
        motion_g_ = 32;
        linear(true, x0 * inv, pos_.y, ze * inv, line);
        linear(true, x0 * inv, pos_.y, zs * inv, line);
        continue;
      }
      // G92 / G292 X Z R F: one box from where the tool is; it ends there again.
      if (std::abs(zk - z_now) > 1e-9) linear(true, x0 * inv, pos_.y, zk * inv, line);
      z_now = zk;
      if (!cycle_block(form == "g292" ? "G292" : "G92", x_end, ze, (x_start - x_end) * mirror, "")) return;
      motion_g_ = -1;
      forget_axes();
    }
    if (std::abs(z_now - zs) > 1e-9) linear(true, x0 * inv, pos_.y, zs * inv, line);
  }
  if (t.starts > 1) linear(true, x0 * inv, pos_.y, z0 * inv, line);
  restore_feed_mode(had_mode, was_per_rev);
}

void channel_writer::groove_cycle_point(const vec3& p, int line) {
  if (!spindle_turning(line)) return;  // the plunges are cuts: the spindle must turn
  const cycle_event& c = *cycle_;
  // The GOTO is the groove's first side on the part's surface: X the surface radius, Z where
  // the first plunge goes. Plunges feed along X to the bottom (FEDTO: its radius; DEPTH: that
  // far toward the axis) and go back out to RAPTO above the surface; WIDTH more plunges step
  // ZSTEP apart toward -Z (a negative WIDTH: toward +Z). The control ends where it started.
  const double x = p.x * scale_, z = p.z * scale_;
  const auto fedto = cycle_param(c, "FEDTO"), depth = cycle_param(c, "DEPTH"),
             rapto = cycle_param(c, "RAPTO");
  if (fedto && depth) return error(line, "CYCLE/GROOVE gives both FEDTO and DEPTH: give one");
  if (!fedto && !depth) return error(line, "CYCLE/GROOVE needs the groove's bottom (FEDTO or DEPTH)");
  if (!rapto || !(*rapto > 0))
    return error(line, "CYCLE/GROOVE needs RAPTO above 0: the plunges start that far above the surface");
  const double bottom = fedto ? *fedto * scale_ : x - (x < 0 ? -1.0 : 1.0) * *depth * scale_;
  const double into = bottom < x ? -1.0 : 1.0;
  if (std::abs(bottom - x) < 1e-6 || (depth && !(*depth > 0)))
    return error(line, "CYCLE/GROOVE: the groove's bottom is at its surface: nothing to cut");
  const double clear = x - into * *rapto * scale_;
  const double width = cycle_param(c, "WIDTH").value_or(0) * scale_;
  const double step = cycle_param(c, "ZSTEP").value_or(0) * scale_;
  if (width != 0 && !(step > 0))
    return error(line, "CYCLE/GROOVE: a WIDTH needs ZSTEP above 0, the distance between plunges");
  if (width != 0 && !(std::abs(width) / step <= max_passes))
    return error(line, fmt::format("CYCLE/GROOVE: WIDTH {} in steps of {} makes more than {} plunges", width,
                                   step, max_passes));
  for (const char* unit : {"MMPR", "IPR"})
    if (auto f = cycle_param(c, unit)) {
      const double value = *f * (unit[0] == 'I' ? 25.4 : 1.0) * out_per_mm_;
      if (!fits('F', value, feed_decimals(true))) return;
      feed_value_ = value;
      feed_mode(true);
    }
  if (!(feed_value_ > 0)) return error(line, "CYCLE/GROOVE with no feed rate (FEDRAT or MMPR) in force");
  const double inv = 1.0 / scale_;
  const double z_end = z - (width < 0 ? -1.0 : 1.0) * std::abs(width);
  linear(true, clear * inv, p.y, z * inv, line);  // the start point
  if (m_.cycles.groove == "g75") {
    // Fanuc G75: R(e) the return of each peck (there are none: P is the whole depth), then
    // X Z of the last plunge's bottom, P the depth of cut and Q the Z step in 0.001 mm
    // (0.0001 in in inch output).
    const auto um = [&](double v) { return increments(v); };
    out_.block("G75 R0.");
    arc_.clear();
    arc_ += " G75";
    axis_word(arc_, 'X', nc_x(bottom * inv), last_x_, true);
    axis_word(arc_, 'Z', z_end * z_sign_, last_z_, true);
    arc_ += fmt::format(" P{}", um(std::abs(bottom - clear)));
    if (width != 0) arc_ += fmt::format(" Q{}", um(step));
    append_feed(arc_);
    out_.block(arc_.view().substr(1));
    motion_g_ = -1;
    forget_axes();
    pos_ = {clear * inv, p.y, z * inv};
    return;
  }
  for (double zi = z;; zi -= (width < 0 ? -1.0 : 1.0) * step) {
    const bool last = (zi - z_end) * (width < 0 ? -1.0 : 1.0) <= 1e-9;
    if (last) zi = z_end;
    linear(true, clear * inv, p.y, zi * inv, line);
    linear(false, bottom * inv, p.y, zi * inv, line);
    linear(true, clear * inv, p.y, zi * inv, line);
    if (last) break;
  }
  linear(true, clear * inv, p.y, z * inv, line);  // back to the start, as G75 ends
  pos_ = {clear * inv, p.y, z * inv};
}

void channel_writer::thread_mode(const thread_event& t, int line) {
  if (!t.on) {
    if (threading_) restore_feed_mode(thread_saved_mode_, thread_saved_per_rev_);
    threading_.reset();
    return;
  }
  if (inch_thread_refused("THREAD/TURN", line)) return;
  if (m_.cycles.thread.empty())
    return error(line,
                 fmt::format("THREAD/TURN is not supported by the post: machine '{}' names no threading "
                             "cycle ([cycles] thread in its file)",
                             m_.name));
  if (t.starts > 1)
    return error(line, fmt::format("THREAD/TURN with STARTS {}: the CL passes cut one helix; post each start "
                                   "with CYCLE/THREAD (shifted starts) instead",
                                   t.starts));
  if (!threading_) thread_saved_per_rev_ = per_rev_, thread_saved_mode_ = !feed_g_.empty();
  threading_ = t;
}

void channel_writer::thread_pass(const vec3& p, int line) {
  if (!spindle_ready_for_thread("THREAD/TURN", line)) return;
  if (!has_y_ && std::abs(p.y * scale_) > 1e-4)
    return error(line, fmt::format("Y {} on a channel without a Y axis", p.y));
  if (!pending_g_.empty())
    return error(line,
                 fmt::format("{} on a threading pass: compensation cannot start on a G32 move", pending_g_));
  feed_mode(true);
  arc_.clear();
  arc_ += " G32";
  bool moved = axis_word(arc_, 'X', nc_x(p.x), last_x_);
  moved = axis_word(arc_, 'Z', nc_z(p.z), last_z_) || moved;
  if (!moved) return;
  if (!append_lead(arc_, threading_->lead * scale_)) return;
  out_.block(arc_.view().substr(1));
  motion_g_ = 32;
}

}  // namespace twinpost
