#include "analysis/cl_compare_arc.hpp"

#include <cmath>
#include <fmt/format.h>
#include <numbers>

namespace twinpost {

namespace {

constexpr double two_pi = 2 * std::numbers::pi;

double dot(const vec3& a, const vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
vec3 minus(const vec3& a, const vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
vec3 scaled(const vec3& a, double k) { return {a.x * k, a.y * k, a.z * k}; }
double length(const vec3& a) { return std::sqrt(dot(a, a)); }

// The part of `p` - `c` square to the unit axis `n`.
vec3 radial(const vec3& p, const vec3& c, const vec3& n) {
  const vec3 r = minus(p, c);
  return minus(r, scaled(n, dot(r, n)));
}

// The angle from `u` to `v` counter-clockwise about the unit axis `n`, in [0, 2pi).
double ccw_angle(const vec3& u, const vec3& v, const vec3& n) {
  const vec3 c{u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
  double t = std::atan2(dot(c, n), dot(u, v));
  if (t < 0) t += two_pi;
  return t;
}

double degrees(double radians) { return radians * 180 / std::numbers::pi; }

}  // namespace

std::string arc_blocks_fault(std::span<const nc_arc_block> blocks, const arc_event& a, const arc_frame& f) {
  if (blocks.empty()) return {};
  const double sense = a.ccw ? 1.0 : -1.0;
  const vec3 cl_axis = scaled(a.normal, sense);  // the CL's arc turns counter-clockwise about it
  const double len = length(cl_axis);
  const vec3 c = scaled(a.center, f.cl_mm);
  const double cl_r = len > 0 ? length(radial(scaled(a.start, f.cl_mm), c, scaled(cl_axis, 1 / len))) : 0;
  for (const nc_arc_block& b : blocks) {
    if (b.plane == 0) return {};
    // The program's axis of turning in the part frame: det(M) M (sense x normal), M the
    // diagonal (sx, zs, zs) from the program's frame to the part's.
    const int axis = b.plane == 17 ? 2 : b.plane == 19 ? 0 : 1;
    const double turn = (b.ccw ? 1.0 : -1.0) * f.sx * (axis == 0 ? f.sx : f.zs);
    const double along = axis == 0 ? cl_axis.x : axis == 1 ? cl_axis.y : cl_axis.z;
    const char* g = b.ccw ? "G3" : "G2";
    if (len <= 0 || std::abs(along) < 0.999 * len)
      return fmt::format(
          "the CL's arc turns about ({:g},{:g},{:g}) here, the program's {} in G{} about its {} "
          "axis: `{}`",
          a.normal.x, a.normal.y, a.normal.z, g, b.plane, "XYZ"[axis], b.text);
    if (along * turn < 0)
      return fmt::format(
          "the CL's arc turns {} about ({:g},{:g},{:g}) here, the program's {} the other way "
          "round: `{}`",
          a.ccw ? "counter-clockwise" : "clockwise", a.normal.x, a.normal.y, a.normal.z, g, b.text);
    if (b.centre_known && b.r == 0) {
      double worst = 0;
      const double cc[3] = {c.x, c.y, c.z}, bc[3] = {b.centre.x, b.centre.y, b.centre.z};
      for (int i = 0; i < 3; ++i)
        if (i != axis) worst = std::max(worst, std::abs(bc[i] - cc[i]));
      if (worst > f.tol)
        return fmt::format(
            "the program's arc centre is {:.3f} mm from the CL's (x {:.3f} y {:.3f} z {:.3f} where the CL "
            "has "
            "x {:.3f} y {:.3f} z {:.3f}, the part frame in mm): `{}`",
            worst, b.centre.x, b.centre.y, b.centre.z, c.x, c.y, c.z, b.text);
    }
  }
  const vec3 n = scaled(cl_axis, 1 / len);
  // How far round a block goes, in the CL's sense: an end on the start's very words is a full
  // circle for the control, any other end the way round to it.
  const auto block_sweep = [&](const nc_arc_block& b) {
    const vec3 u = radial(b.start, c, n), v = radial(b.end, c, n);
    return length(minus(u, v)) < 1e-9 ? two_pi : ccw_angle(u, v, n);
  };
  // The CL's: TIMES,n full turns, then on to its end; an end on its start is a full circle. An
  // end within the tolerance of the start is either (the CL's print rounding).
  const vec3 u0 = radial(scaled(a.start, f.cl_mm), c, n), u1 = radial(scaled(a.end, f.cl_mm), c, n);
  const double cl_gap = length(minus(u0, u1));
  const bool end_on_start = cl_gap <= f.tol;
  if (blocks.size() == 1 && a.turns == 0 && blocks[0].r == 0 && blocks[0].ends_known) {
    // One I/J/K block for a plain arc (most arcs): its sense, centre and end are held above and
    // at the record; it goes the CL's way round unless one of the two is a full circle and the
    // other is not (no angle needed for that).
    const nc_arc_block& b = blocks[0];
    const bool nc_full = length(minus(radial(b.start, c, n), radial(b.end, c, n))) < 1e-9;
    if (nc_full == (cl_gap < 1e-9) || end_on_start) {
      const double off = std::abs(length(radial(b.end, c, n)) - cl_r);
      if (off <= f.tol) return {};
    }
  }
  const double cl_part = ccw_angle(u0, u1, n);
  const double cl_sweep =
      a.turns * two_pi + (length(minus(u0, u1)) < 1e-9 && a.turns == 0 ? two_pi : cl_part);
  const double cl_travel = dot(minus(a.end, a.start), n) * f.cl_mm;
  double sweep = 0;
  for (const nc_arc_block& b : blocks) {
    if (!b.ends_known) return {};
    const double s = block_sweep(b);
    if (b.r != 0) {
      const double r = std::abs(b.r) * f.out_mm;
      const bool major = s > std::numbers::pi + 1e-9;
      if (std::abs(r - cl_r) > f.tol || (b.r < 0) != major)
        return fmt::format(
            "the CL's arc has a radius of {:.3f} mm over {:.1f} degrees here, the program's R "
            "{:g} ({}): `{}`",
            cl_r, degrees(s), b.r,
            std::abs(r - cl_r) > f.tol ? "another radius"
            : major                    ? "the short way round: more than half a turn needs R < 0"
                                       : "the long way round: R < 0 is more than half a turn",
            b.text);
    }
    const double off = std::abs(length(radial(b.end, c, n)) - cl_r);
    if (off > f.tol)
      return fmt::format(
          "the program's arc block ends {:.3f} mm off the CL's circle (radius {:.3f} mm, the "
          "part frame): `{}`",
          off, cl_r, b.text);
    sweep += s;
  }
  // The blocks together go as far round as the CL's arc (a turn dropped or added: a steeper or
  // a shallower ramp, or a second pass round a finished wall).
  const double gap = sweep - cl_sweep;
  const auto near = [&](double d) { return std::abs(d) * cl_r <= f.tol; };
  if (!(near(gap) || (end_on_start && (near(gap - two_pi) || near(gap + two_pi)))))
    return fmt::format(
        "the program's arc blocks go {:.1f} degrees round the CL's circle here, the CL's arc "
        "{:.1f} degrees{}: `{}`",
        degrees(sweep), degrees(cl_sweep),
        a.turns > 0 ? fmt::format(" (TIMES,{}: full turns, then on to its end)", a.turns) : "",
        blocks.back().text);
  // Along the axis, each block its share of the CL's travel: one pitch over the whole sweep
  // (a single block's share is all of it, and its ends are the records').
  if (blocks.size() == 1) return {};
  for (const nc_arc_block& b : blocks) {
    const double s = block_sweep(b);
    const double want = cl_travel * s / sweep, have = dot(minus(b.end, b.start), n);
    if (std::abs(have - want) > f.tol)
      return fmt::format(
          "the program's helix does not keep the CL's pitch: this block goes {:.3f} mm along the "
          "circle's axis over {:.1f} degrees, where the CL's {:.3f} mm over {:.1f} degrees gives "
          "{:.3f} mm: `{}`",
          have, degrees(s), cl_travel, degrees(sweep), want, b.text);
  }
  return {};
}

}  // namespace twinpost
