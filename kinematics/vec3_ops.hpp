#pragma once
// Small vector algebra over machines/kinematic_chain.hpp's vec3, and the rotation that every
// transform of kinematics/ is built from.
#include <cmath>
#include <numbers>

#include "machines/kinematic_chain.hpp"

namespace twinpost::kin {

constexpr double deg = std::numbers::pi / 180.0;

inline vec3 operator+(const vec3& a, const vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline vec3 operator-(const vec3& a, const vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline vec3 operator*(double s, const vec3& a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(const vec3& a, const vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline vec3 cross(const vec3& a, const vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(const vec3& a) { return std::sqrt(dot(a, a)); }
inline double distance(const vec3& a, const vec3& b) { return norm(a - b); }
/// The angle between two non-zero vectors in degrees, accurate near 0 (atan2, not acos).
inline double angle_between(const vec3& a, const vec3& b) {
  const double n = norm(cross(a, b)), d = dot(a, b);
  if (d > 0 && n < 1e-3 * d) {
    // Nearly parallel, as every checked axis is: atan x = x - x³/3 + x⁵/5 - ..., the terms
    // left out below x⁶/7 < 2e-19 of the result, under the last bit of a double.
    const double x = n / d, x2 = x * x;
    return x * (1 - x2 * (1.0 / 3 - x2 * (1.0 / 5))) / deg;
  }
  return std::atan2(n, d) / deg;
}

/// A rotation's cosine and sine, computed once for all the vectors it turns.
struct turn {
  double c = 1, s = 0;
};
inline turn turn_of(double degrees) { return {std::cos(degrees * deg), std::sin(degrees * deg)}; }
/// The rotation by `a` then by `b` (the angle a + b): the sum formulas.
inline turn compose(const turn& a, const turn& b) { return {a.c * b.c - a.s * b.s, a.s * b.c + a.c * b.s}; }
/// turn_of(degrees) without a call to sincos: below 0.1 rad the Taylor series to x^11
/// (the next terms are under 3e-19 of the result, below the last bit of a double).
inline turn turn_of_small(double degrees) {
  const double x = degrees * deg, x2 = x * x;
  if (!(x2 < 0.01)) return turn_of(degrees);
  return {1 - x2 / 2 * (1 - x2 / 12 * (1 - x2 / 30 * (1 - x2 / 56 * (1 - x2 / 90)))),
          x * (1 - x2 / 6 * (1 - x2 / 20 * (1 - x2 / 42 * (1 - x2 / 72 * (1 - x2 / 110)))))};
}
/// The same rotation the other way (cos and sin of -x are those of x, the sine negated: the
/// same bits as turn_of(-degrees)).
inline turn reversed(const turn& t) { return {t.c, -t.s}; }

/// `v` turned by `t` right-handed about the unit direction `d` (Rodrigues).
inline vec3 rotate(const vec3& v, const vec3& d, const turn& t) {
  // About a machine axis (most rotary axes are), the two components that turn alone.
  if (d.y == 0 && d.z == 0 && (d.x == 1 || d.x == -1)) {
    const double s = d.x * t.s;
    return {v.x, t.c * v.y - s * v.z, s * v.y + t.c * v.z};
  }
  if (d.x == 0 && d.z == 0 && (d.y == 1 || d.y == -1)) {
    const double s = d.y * t.s;
    return {t.c * v.x + s * v.z, v.y, t.c * v.z - s * v.x};
  }
  if (d.x == 0 && d.y == 0 && (d.z == 1 || d.z == -1)) {
    const double s = d.z * t.s;
    return {t.c * v.x - s * v.y, s * v.x + t.c * v.y, v.z};
  }
  return t.c * v + t.s * cross(d, v) + ((1 - t.c) * dot(d, v)) * d;
}
/// `v` turned by `degrees` right-handed about the unit direction `d`.
inline vec3 rotate(const vec3& v, const vec3& d, double degrees) { return rotate(v, d, turn_of(degrees)); }

/// The point `p` turned by `t` about the axis of direction `d` through `on`.
inline vec3 rotate_about(const vec3& p, const vec3& d, const vec3& on, const turn& t) {
  return rotate(p - on, d, t) + on;
}

/// `a` - `b` wrapped into [-180, 180] degrees (std::remainder: correct for negative values,
/// which std::fmod is not).
inline double wrap_180(double a) {
  if (a >= -180.0 && a <= 180.0) return a;  // what std::remainder gives there, bit for bit
  // Within one more turn the quotient rounds to +-1 (540 and -540 are ties, to even: +-2),
  // and a -+ 360 is exact there (Sterbenz): the same bits as std::remainder.
  if (a > 180.0 && a < 540.0) return a - 360.0;
  if (a < -180.0 && a > -540.0) return a + 360.0;
  return std::remainder(a, 360.0);
}

}  // namespace twinpost::kin
