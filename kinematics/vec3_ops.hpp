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
  return std::atan2(norm(cross(a, b)), dot(a, b)) / deg;
}

/// `v` turned by `degrees` right-handed about the unit direction `d` (Rodrigues).
inline vec3 rotate(const vec3& v, const vec3& d, double degrees) {
  const double c = std::cos(degrees * deg), s = std::sin(degrees * deg);
  return c * v + s * cross(d, v) + ((1 - c) * dot(d, v)) * d;
}

/// The point `p` turned by `degrees` about the axis of direction `d` through `on`.
inline vec3 rotate_about(const vec3& p, const vec3& d, const vec3& on, double degrees) {
  return rotate(p - on, d, degrees) + on;
}

/// `a` - `b` wrapped into [-180, 180] degrees (std::remainder: correct for negative values,
/// which std::fmod is not).
inline double wrap_180(double a) { return std::remainder(a, 360.0); }

}  // namespace twinpost::kin
