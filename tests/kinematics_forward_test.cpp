// kinematics/forward: the forward transform of each chain kind against values computed by hand
// (the inverse is held to it in kinematics_inverse_test.cpp, so a sign error here would pass
// there: these cases fix the signs).
#include <catch2/catch.hpp>

#include "kinematics/forward.hpp"
#include "kinematics/inverse.hpp"
#include "kinematics/vec3_ops.hpp"
#include "kinematics_test_support.hpp"

using namespace twinpost;
using namespace twinpost::kin;
using test::test_chain;

namespace {

void check_pose(const tool_pose& got, const vec3& tip, const vec3& axis) {
  CHECK(got.tip.x == Approx(tip.x).margin(1e-9));
  CHECK(got.tip.y == Approx(tip.y).margin(1e-9));
  CHECK(got.tip.z == Approx(tip.z).margin(1e-9));
  CHECK(got.axis.x == Approx(axis.x).margin(1e-12));
  CHECK(got.axis.y == Approx(axis.y).margin(1e-12));
  CHECK(got.axis.z == Approx(axis.z).margin(1e-12));
}

joint_values joints(vec3 linear, double r0, double r1) {
  joint_values j;
  j.linear = linear;
  j.rotary = {r0, r1};
  return j;
}

}  // namespace

TEST_CASE("with every rotary axis at 0 the tip is at the linear position and the tool is upright",
          "[kinematics]") {
  for (int ch = 1; ch <= 7; ++ch)
    check_pose(forward(test_chain(ch), joints({1, 2, 3}, 0, 0), 75), {1, 2, 3}, {0, 0, 1});
}

// Channel 2, table/table: A about X through (0, 0, -80) carrying C about Z through (12.5, -7, 0).
// K = R_C(-C)·R_A(-A)·z = (sin C sin A, cos C sin A, cos A), as LinuxCNC's xyzac-trt (docs/kinematics.md).
// A -90, C 90: K = (-1, 0, 0). The tip at machine (100, 20, 30) in the part frame: A undone
// (+90 about X through (0, 0, -80)): (x, y, z) - c = (100, 20, 110) -> (x, -z, y) = (100, -110, 20),
// + c = (100, -110, -60); C undone (-90 about Z through (12.5, -7)): (87.5, -103) -> (y, -x) =
// (-103, -87.5), + c = (-90.5, -94.5); z stays -60.
TEST_CASE("table/table A over C: the pose computed by hand", "[kinematics]") {
  check_pose(forward(test_chain(2), joints({100, 20, 30}, -90, 90), 40), {-90.5, -94.5, -60}, {-1, 0, 0});
  // A 30, C 0: K = (0, sin 30, cos 30); a point on the A axis does not move.
  check_pose(forward(test_chain(2), joints({0, 0, -80}, 30, 0), 40), {0, 0, -80},
             {0, 0.5, 0.8660254037844386});
}

// Channel 3, head/table: B head about Y through the gauge point + (5, 0, 250), C table about Z
// through the origin. Tool 50 mm: the pivot is (5, 0, 300) from the tip at home. B 90 turns
// (x, y, z) to (z, y, -x): the tip, (-5, 0, -300) from the pivot, goes to (-300, 0, 5), i.e.
// (-295, 0, 305); the axis z goes to x. With the linear axes at (10, 20, 30) the tip is at
// machine (-285, 20, 335). C 90 turns the part +90° about Z, so machine (x, y) is (y, -x) in
// the part: tip (20, 285, 335), axis (0, -1, 0).
TEST_CASE("head/table B head over a C table: the pose computed by hand", "[kinematics]") {
  check_pose(forward(test_chain(3), joints({10, 20, 30}, 90, 90), 50), {20, 285, 335}, {0, -1, 0});
  // B -90 alone turns (x, y, z) to (-z, y, x): the tip, (-5, 0, -300) from the pivot, goes to
  // (300, 0, -5) from it, (305, 0, 295); the axis z goes to -x.
  check_pose(forward(test_chain(3), joints({0, 0, 0}, -90, 0), 50), {305, 0, 295}, {-1, 0, 0});
}

// Channel 4, head/head bridge: C head about Z carrying B head about Y, pivot 350 mm above the
// gauge point. Tool 50: L = 400. B 90, C 90: R_y(90)·z = x, R_z(90)·x = y: K = (0, 1, 0);
// the tip is pivot - L·K = (0, 0, 400) - (0, 400, 0) = (0, -400, 400) from the linear position.
TEST_CASE("head/head C over B: the pose computed by hand", "[kinematics]") {
  check_pose(forward(test_chain(4), joints({1, 2, 3}, 90, 90), 50), {1, -398, 403}, {0, 1, 0});
}

// Channel 5, nutating: B about (0, -1, 1)/√2. B 180 turns z to the mirror of z in that axis:
// 2(n·z)n - z = 2·(1/√2)·(0, -1, 1)/√2 - (0, 0, 1) = (0, -1, 0). Tool 0: the pivot is 200 above
// the tip: the tip goes to (0, 0, 200) - 200·(0, -1, 0) = (0, 200, 200).
TEST_CASE("a 45° nutating head: the pose computed by hand", "[kinematics]") {
  check_pose(forward(test_chain(5), joints({0, 0, 0}, 0, 180), 0), {0, 200, 200}, {0, -1, 0});
}

// Independent closed forms of the orientation, over a grid of angles (the property test of
// the inverse cannot see a convention shared by both directions; these can):
// - LinuxCNC xyzac-trt (A table about X carrying C about Z): K = (sin C sin A, cos C sin A, cos A);
// - LinuxCNC xyzbc-trt (B table about Y carrying C about Z): K = (-cos C sin B, sin C sin B, cos B)
//   (both as ../shared/reference/style-and-kinematics.md §2.1 gives them, checked there numerically);
// - a head nutating about an axis at v = 45° to the tool: the tool's component along the
//   spindle after a turn θ is cos²v + sin²v cos θ (remap.py's θ2 = acos((Kz - cos²v)/(1 - cos²v))).
TEST_CASE("the orientation agrees with LinuxCNC's trt closed forms and the nutation formula",
          "[kinematics]") {
  kinematic_chain bc;
  bc.rotaries.resize(2);
  bc.rotaries[0] = {'B', rotary_kind::table, {0, 1, 0}, {0, 0, 0}, -90.0, 90.0};
  bc.rotaries[1] = {'C', rotary_kind::table, {0, 0, 1}, {0, 0, 0}, std::nullopt, std::nullopt};
  const kinematic_chain& ac = test_chain(2);
  const kinematic_chain& nutating = test_chain(5);
  int poses = 0;
  for (double p = -90; p <= 30; p += 7.5)
    for (double c = -180; c <= 180; c += 15) {
      const double sp = std::sin(p * deg), cp = std::cos(p * deg), sc = std::sin(c * deg),
                   cc = std::cos(c * deg);
      const vec3 k_ac = forward(ac, joints({0, 0, 0}, p, c), 0).axis;
      CHECK(distance(k_ac, {sc * sp, cc * sp, cp}) < 1e-15);
      const vec3 k_bc = forward(bc, joints({0, 0, 0}, p, c), 0).axis;
      CHECK(distance(k_bc, {-cc * sp, sc * sp, cp}) < 1e-15);
      const vec3 k_n = forward(nutating, joints({0, 0, 0}, c, p), 0).axis;
      CHECK(k_n.z == Approx(0.5 + 0.5 * cp).margin(1e-15));
      ++poses;
    }
  CHECK(poses == 17 * 25);
}

// The inverse of the nutating head gives the nutation formula's angle, ±acos((Kz - ½)/½), for
// axes all round the cone.
TEST_CASE("the nutating head's inverse gives remap.py's nutation angle", "[kinematics]") {
  const kinematic_chain& c = test_chain(5);
  for (double kz = 0.05; kz < 1; kz += 0.1)
    for (double az = -170; az <= 180; az += 40) {
      const double s = std::sqrt(1 - kz * kz);
      const ik_result r =
          inverse(c, {{0, 0, 0}, {s * std::cos(az * deg), s * std::sin(az * deg), kz}}, 0, {});
      REQUIRE(r.ok());
      CHECK(std::abs(r.joints.rotary[1]) == Approx(std::acos((kz - 0.5) / 0.5) / deg).margin(1e-9));
    }
}

// Channel 8: the tool along +X, B head about Y through the gauge point + (200, 0, 0), C table
// at (3, 4). At home the tool is along X. Tool 75: the pivot is (275, 0, 0) from the tip at
// home. B 90 turns (x, y, z) to (z, y, -x): the tip, (-275, 0, 0) from the pivot, goes to
// (0, 0, 275) from it, (275, 0, 275); the axis x goes to (0, 0, -1). C 180 about (3, 4) then
// maps machine (x, y) to (6 - x, 8 - y): the tip (276, 2, 278) goes to (-270, 6, 278).
TEST_CASE("a horizontal spindle's B head over a C table: the pose computed by hand", "[kinematics]") {
  check_pose(forward(test_chain(8), joints({1, 2, 3}, 0, 0), 75), {1, 2, 3}, {1, 0, 0});
  check_pose(forward(test_chain(8), joints({1, 2, 3}, 90, 0), 75), {276, 2, 278}, {0, 0, -1});
  check_pose(forward(test_chain(8), joints({1, 2, 3}, 90, 180), 75), {-270, 6, 278}, {0, 0, -1});
}
