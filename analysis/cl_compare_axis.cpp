#include "analysis/cl_compare_axis.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "kinematics/vec3_ops.hpp"

namespace twinpost {

head_turn head_turn::of(const head_index_rules& h) {
  head_turn t;
  if (!h.axial || !h.radial) return t;
  const double span = *h.radial - *h.axial;
  if (std::abs(std::abs(span) - 90) > 1e-9) return t;  // not a quarter turn: not read
  t.axial = *h.axial;
  t.scale = 90 / span;
  return t;
}

vec3 head_turn::machine_axis(double angle) const {
  const kin::turn t = kin::turn_of((angle - axial) * scale);
  return {t.s, 0, t.c};
}

vec3 part_axis(const vec3& a, double sx, double zs, double c_deg) {
  const vec3 p{a.x * sx, a.y * zs, a.z * zs};
  if (c_deg == 0) return p;
  return kin::rotate(p, {0, 0, 1}, c_deg);
}

std::optional<std::string> axis_fault(const vec3& have, const vec3& want, double tolerance,
                                      std::string_view who) {
  const double n = kin::norm(want);
  if (!(n > 0)) return std::nullopt;  // no direction given
  // Most axes are right: within the tolerance when |have x want| <= sin(tol) |have| |want| on
  // the same side, without the arc tangent (a little under the tolerance, never over it).
  const double x = tolerance * std::numbers::pi / 180;
  const double within = x * (1 - x * x / 6) * 0.999;  // sin x to x^3; the 0.999 covers the rest
  const vec3 c = kin::cross(have, want);
  if (kin::dot(have, want) > 0 && kin::dot(c, c) <= within * within * kin::dot(have, have) * n * n)
    return std::nullopt;
  const double off = kin::angle_between(have, want);
  if (off <= tolerance) return std::nullopt;
  // Written to 4 places, a component under half the last one as 0 (never "-0.0000").
  const auto v = [](const vec3& a, double k) {
    const auto c = [k](double x) { return std::abs(x * k) < 5e-5 ? 0.0 : x * k; };
    return fmt::format("({:.4f},{:.4f},{:.4f})", c(a.x), c(a.y), c(a.z));
  };
  return fmt::format(
      "the CL's tool axis here is {}, the program's {} the tool along {} in the part frame ({:.3f} "
      "degrees off)",
      v(want, 1 / n), who, v(have, 1 / kin::norm(have)), off);
}

}  // namespace twinpost
