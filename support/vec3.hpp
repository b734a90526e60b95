#pragma once
// A point or a direction in three dimensions: the CL's coordinates (parser/events.hpp) and a
// kinematic chain's geometry (machines/kinematic_chain.hpp) are the same type. The algebra on
// it lives with the layer that computes (kinematics/vec3_ops.hpp).
namespace twinpost {

struct vec3 {
  double x = 0, y = 0, z = 0;
  friend bool operator==(const vec3&, const vec3&) = default;
};

}  // namespace twinpost
