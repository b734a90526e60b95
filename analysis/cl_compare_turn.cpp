#include "analysis/cl_compare_turn.hpp"
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace twinpost {

void c_turn_path(const c_turn_block& b, std::vector<vec3>& out) {
  out.clear();
  const int n = std::clamp(static_cast<int>(std::ceil(std::abs(b.c1 - b.c0))), 1, 3600);
  out.reserve(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i <= n; ++i) {
    const double t = static_cast<double>(i) / n;
    const double x = b.start.x + (b.end.x - b.start.x) * t, y = b.start.y + (b.end.y - b.start.y) * t;
    const double c = (b.c0 + (b.c1 - b.c0) * t) * std::numbers::pi / 180;
    // The program's x, y are the part's turned by -C: the part's are turned back by +C.
    out.push_back({x * std::cos(c) - y * std::sin(c), x * std::sin(c) + y * std::cos(c),
                   b.start.z + (b.end.z - b.start.z) * t});
  }
}

namespace {

// How far a point stands from the part along the tool: an axial tool's height above the face
// (z, or -z for a tool looking up -Z), a radial tool's distance from the axis. None for a tool
// at another angle.
struct level_rule {
  int kind = 0;  // 1 axial, 2 radial, 0 none
  double sign = 1;
  double of(const vec3& p) const { return kind == 1 ? p.z * sign : std::hypot(p.x, p.y); }
  const char* name() const { return kind == 1 ? "z" : "the distance from the axis"; }
};

level_rule level_along(const vec3& axis) {
  const double len = std::sqrt(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z);
  if (len <= 0) return {};
  const double k = axis.z / len;
  if (std::abs(k) >= 0.9999) return {1, k > 0 ? 1.0 : -1.0};
  if (std::abs(k) <= 0.0001) return {2, 1};
  return {};
}

// The distance of `p` from the segment `a`-`b`.
double from_segment(const vec3& p, const vec3& a, const vec3& b) {
  const double dx = b.x - a.x, dy = b.y - a.y, dz = b.z - a.z;
  const double len2 = dx * dx + dy * dy + dz * dz;
  double t = len2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy + (p.z - a.z) * dz) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p.x - (a.x + dx * t), p.y - (a.y + dy * t), p.z - (a.z + dz * t));
}

}  // namespace

std::string c_turn_fault(std::span<const c_turn_block> blocks, const vec3* from, const vec3& to,
                         const vec3& axis, bool feed, double chord, double tol) {
  const level_rule level = level_along(axis);
  const double low_end = level.kind == 0 ? 0.0
                         : from          ? std::min(level.of(*from), level.of(to))
                                         : level.of(to);
  const double high_end = level.kind == 0 ? 0.0
                          : from          ? std::max(level.of(*from), level.of(to))
                                          : level.of(to);
  std::vector<vec3> path;
  for (const c_turn_block& b : blocks) {
    c_turn_path(b, path);
    if (level.kind != 0) {
      // A block that only turns C turns the part where the tip stands: as high as the CL's
      // move goes (a move up and round turns at its top, not at the bottom of the pocket it
      // leaves). One that moves the tip along as it turns keeps above the lower end.
      const bool only_turns = std::abs(level.of(b.start) - level.of(b.end)) <= tol;
      const double floor = only_turns ? high_end : low_end;
      const auto low = std::min_element(
          path.begin(), path.end(), [&](const vec3& p, const vec3& q) { return level.of(p) < level.of(q); });
      if (level.of(*low) < floor - tol)
        return fmt::format(
            "the program turns C with the tool tip below the CL's move here: {} {:.3f} (the part frame, mm), "
            "where the CL's move goes no lower than {:.3f}; the part turns into the tool: turn it with the "
            "tool "
            "clear, as high as the CL's move: `{}`",
            level.name(), level.of(*low), floor, b.text);
    }
    if (feed && from && !b.rapid) {
      double worst = 0;
      for (const vec3& p : path) worst = std::max(worst, from_segment(p, *from, to));
      if (worst > chord)
        return fmt::format(
            "the program turns C in a feed move here: the tool tip runs round the part's axis and leaves the "
            "CL's straight cut by {:.3f} mm (the part frame; {:.3f} mm allowed): `{}`",
            worst, chord, b.text);
    }
  }
  return {};
}

}  // namespace twinpost
