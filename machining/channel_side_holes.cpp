// channel_writer: cross (radial) holes on a lathe whose control drills along X with its own
// side cycles (milling.cross_holes = "side_cycle"): C turned to the tool axis's angle and
// clamped, then the tool's moves along X (the diameter) at the hole's Z, and the [cycles] side
// codes (Fanuc system A: G87 drilling, G88 tapping), as the Autodesk Fusion "Doosan Mill/Turn
// with Fanuc 31i" post writes them (docs/machines.md, "Mill/turn").
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "machining/channel_writer.hpp"

namespace twinpost {

namespace {
constexpr double deg = 180.0 / std::numbers::pi;
constexpr double off_line = 1e-3;  // mm: a point this far beside the tool's radial line
}  // namespace

bool channel_writer::side_move(bool rapid, double& x, double& y, double& z, int line) {
  if (radial_ok_) {
    // A cross hole's own points, in the turned frame's terms (side_point): back to the lathe's
    // X along the tool, Y beside it, Z the part's Z. C stands at the tool's angle already.
    const double along = z, beside = y, part_z = -x;
    x = along, y = beside, z = part_z;
    return true;
  }
  // Milling on the diameter: every feed of the radial tool goes to cylindrical interpolation
  // (a plunge or retract along the radius, or a cut on the cylinder: G18 W0 H0, G7.1 C<r>).
  if (!rapid && !m_.milling.cylindrical_on.empty()) return cylinder_feed(x, y, z, line);
  leave_cylinder();  // no G0 in the mode
  const double a = std::atan2(axis_.y, axis_.x) * deg;
  const double c = std::fmod(std::fmod(a, 360.0) + 360.0, 360.0);
  const bool at_angle = last_c_.known && std::abs(std::remainder(last_c_.value - c, 360.0)) < 5e-4;
  if (!at_angle && !rapid) {
    // The part would have to turn under a cutting tool: milling on the diameter.
    if (refused_axis_ && refused_axis_->x == axis_.x && refused_axis_->y == axis_.y) return false;
    refused_axis_ = axis_;
    error(line, fmt::format("a feed move with the tool across the spindle axis (milling on the diameter): "
                            "machine '{}' gives no cylindrical interpolation (milling.cylindrical_on), so it "
                            "cannot be posted",
                            m_.name));
    return false;
  }
  if (!at_angle) position_c(c);
  const auto [u, v] = c_frame(x, y);
  if (!rapid && std::abs(v) * cl_mm_ > off_line) {
    error(line, fmt::format("a feed move of the radial tool {} mm beside its radial line at C{}: machine "
                            "'{}' writes radial tools along X through the spindle centre only",
                            fmt::format("{:g}", std::round(v * cl_mm_ * 1000) / 1000 + 0.0),
                            format_nc_number(c, axis_style_), m_.name));
    return false;
  }
  x = u, y = v;
  return true;
}

bool channel_writer::side_point(const vec3& p, vec3& q, int line) {
  const double a = std::atan2(axis_.y, axis_.x);
  const double ca = std::cos(a), sa = std::sin(a);
  q = {-p.z, -p.x * sa + p.y * ca, p.x * ca + p.y * sa};
  if (std::abs(q.y) * cl_mm_ > off_line) {
    error(line, fmt::format("a cross hole {} mm beside its radial line: the side cycle ({}) drills along X "
                            "through the spindle centre only",
                            fmt::format("{:g}", std::round(q.y * cl_mm_ * 1000) / 1000 + 0.0),
                            m_.cycles.side_drill_code));
    return false;
  }
  q.y = 0;
  position_c(std::fmod(std::fmod(a * deg, 360.0) + 360.0, 360.0));
  clamp_c();
  return true;
}

}  // namespace twinpost
