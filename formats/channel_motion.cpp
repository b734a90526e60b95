// channel_writer: straight moves, arcs in the XZ plane, drilling cycles expanded to moves.
#include <cmath>
#include <fmt/format.h>

#include "formats/channel_writer.hpp"

namespace twinpost {

namespace {
constexpr double y_tolerance = 1e-4;
}

void channel_writer::append_feed(std::string& out) {
  // The F word is modal: formatted once per feed value, written when it changes.
  if (feed_value_ != feed_text_value_ || per_rev_ != feed_text_per_rev_) {
    feed_text_.clear();
    append_number(feed_text_, feed_value_, {per_rev_ ? 4 : 1, m_.program.trailing_point});
    feed_text_value_ = feed_value_;
    feed_text_per_rev_ = per_rev_;
  }
  if (feed_text_ == last_f_) return;
  out += " F";
  out += feed_text_;
  last_f_ = feed_text_;
}

void channel_writer::linear(bool rapid, double x_cl, double y_cl, double z_cl, int line) {
  if (!has_y_ && std::abs(y_cl * scale_) > y_tolerance)
    return error(line, fmt::format("Y {} on a channel without a Y axis", y_cl));
  int g = rapid ? 0 : 1;
  line_.clear();
  if (!pending_g_.empty()) {
    line_ += ' ';
    line_ += pending_g_;
  }
  if (g != motion_g_) {
    line_ += rapid ? " G0" : " G1";
  }
  bool moved = axis_word(line_, 'X', nc_x(x_cl), last_x_);
  if (has_y_) moved = axis_word(line_, 'Y', y_cl * scale_, last_y_) || moved;
  moved = axis_word(line_, 'Z', z_cl * scale_, last_z_) || moved;
  if (!moved) return;  // already there: nothing to write, the modal codes wait for a move
  pending_g_.clear();
  motion_g_ = g;
  if (!rapid && feed_value_ > 0) append_feed(line_);
  else if (!rapid) error(line, "feed move with no feed rate (FEDRAT) in force");
  out_.block(std::string_view(line_).substr(1));
}

void channel_writer::motion(const motion_event& mv, int line) {
  switch (mv.kind) {
    case motion_kind::from:
      pos_ = mv.pos;
      return;
    case motion_kind::home:
      out_.block(m_.codes.home);
      last_x_.clear(), last_y_.clear(), last_z_.clear();
      motion_g_ = -1;
      pos_ = mv.pos;
      return;
    case motion_kind::go_to:
    case motion_kind::delta:
      if (cycle_) {
        cycle_point(mv.pos, line);
      } else {
        linear(mv.rapid, mv.pos.x, mv.pos.y, mv.pos.z, line);
      }
      pos_ = mv.pos;
      return;
  }
}

void channel_writer::arc(const arc_event& a, int line) {
  // A lathe channel interpolates in G18 (the ZX plane): the arc's axis must be +-Y.
  double nlen = std::sqrt(a.normal.x * a.normal.x + a.normal.y * a.normal.y + a.normal.z * a.normal.z);
  if (nlen == 0 || std::abs(std::abs(a.normal.y) / nlen - 1) > 1e-6) {
    error(line, fmt::format("arc about ({},{},{}) is not in the XZ plane of a lathe channel",
                            a.normal.x, a.normal.y, a.normal.z));
    pos_ = a.end;
    return;
  }
  if (!has_y_ && std::abs(a.end.y * scale_) > y_tolerance) {
    error(line, fmt::format("Y {} on a channel without a Y axis", a.end.y));
    pos_ = a.end;
    return;
  }
  // Counter-clockwise about +Y is G3 in G18 (Y = Z x X); mirroring X reverses the sense.
  bool ccw_about_y = a.ccw == (a.normal.y > 0);
  double mirror = (x_factor_ < 0 ? -1.0 : 1.0) * side_;
  if (mirror < 0) ccw_about_y = !ccw_about_y;
  int g = ccw_about_y ? 3 : 2;
  std::string words;
  if (!pending_g_.empty()) {
    words += pending_g_ + " ";
    pending_g_.clear();
  }
  words += fmt::format("G{}", g);
  std::string x = format_nc_number(nc_x(a.end.x), axis_style_);
  std::string z = format_nc_number(a.end.z * scale_, axis_style_);
  words += fmt::format(" X{} Z{}", x, z);
  if (m_.program.arcs_ijk) {
    // I and K run from the start point to the centre; I is a radius value, in the channel's X sense.
    double i = (a.center.x - a.start.x) * scale_ * mirror;
    double k = (a.center.z - a.start.z) * scale_;
    words += fmt::format(" I{} K{}", format_nc_number(i, axis_style_), format_nc_number(k, axis_style_));
  } else {
    bool full = std::abs(a.start.x - a.end.x) < 1e-9 && std::abs(a.start.z - a.end.z) < 1e-9;
    if (full) {
      error(line, "a full circle cannot be written with R; the machine must take I/K arcs");
      pos_ = a.end;
      return;
    }
    // The long way round (over 180 degrees) takes a negative R.
    double sx = a.start.x - a.center.x, sz = a.start.z - a.center.z;
    double ex = a.end.x - a.center.x, ez = a.end.z - a.center.z;
    double cross = sz * ex - sx * ez;  // > 0: counter-clockwise about +Y from start to end
    bool ccw_y = a.ccw == (a.normal.y > 0);
    bool over_half = (cross > 0) != ccw_y;
    words += fmt::format(" R{}", format_nc_number((over_half ? -1 : 1) * a.radius * scale_, axis_style_));
  }
  if (feed_value_ > 0) {
    append_feed(words);
  } else {
    error(line, "arc with no feed rate (FEDRAT) in force");
  }
  last_x_ = x, last_z_ = z;
  motion_g_ = g;
  out_.block(words);
  pos_ = a.end;
}

void channel_writer::cycle_point(const vec3& p, int line) {
  // Drilling along the spindle axis, written as plain moves every control reads: rapid to
  // the clearance plane, feed to depth (in pecks with STEP), rapid back out. The tool axis
  // says which way is into the part: -Z for a tool looking down +Z, +Z for one facing back.
  const cycle_event& c = *cycle_;
  auto param = [&](std::string_view name) -> std::optional<double> {
    for (const auto& [k, v] : c.params)
      if (k == name) return v;
    return std::nullopt;
  };
  double into = axis_.z < 0 ? 1.0 : -1.0;  // the direction of drilling along Z
  double clear = p.z - into * param("RAPTO").value_or(param("CLEAR").value_or(0));
  std::optional<double> bottom = param("FEDTO");
  if (!bottom && param("DEPTH")) bottom = p.z + into * *param("DEPTH");
  if (!bottom) return error(line, fmt::format("CYCLE/{} needs FEDTO or DEPTH", c.type));
  for (const char* unit : {"MMPR", "IPR", "MMPM", "IPM"}) {
    if (auto f = param(unit)) {
      feed_value_ = *f * ((unit[0] == 'I') ? 25.4 : 1.0);
      feed_mode(std::string_view(unit).back() == 'R');
    }
  }
  double step = param("STEP").value_or(0);
  linear(true, p.x, p.y, clear, line);
  double z = clear;
  if (step > 0 && c.type == "DEEP") {
    while ((*bottom - (z + into * step)) * into > 0) {
      z += into * step;
      linear(false, p.x, p.y, z, line);
      linear(true, p.x, p.y, clear, line);
      linear(true, p.x, p.y, z - into * 0.5 / scale_, line);  // back down near the last depth
    }
  }
  linear(false, p.x, p.y, *bottom, line);
  linear(true, p.x, p.y, clear, line);
}

}  // namespace twinpost
