// kinematics/inverse: the two-solution inverse against the forward transform (a property test
// over random poses of every chain kind), hand-computed values of a head/head machine, the
// pole, limits, preferences, unwinding and the exact errors.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "kinematics/forward.hpp"
#include "kinematics/inverse.hpp"
#include "kinematics/vec3_ops.hpp"
#include "kinematics_test_support.hpp"

using namespace twinpost;
using namespace twinpost::kin;
using test::test_chain;

namespace {

// Random joint values within the limits of `c`: a limited axis anywhere in its range, a
// continuous absolute one over two turns each way, a "shortest" one in [0, 360).
joint_values random_joints(const kinematic_chain& c, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> lin(-500, 500);
  joint_values j;
  j.linear = {lin(rng), lin(rng), lin(rng)};
  for (std::size_t i = 0; i < c.rotaries.size(); ++i) {
    const rotary_axis_def& a = c.rotaries[i];
    double lo = -720, hi = 720;
    if (!a.continuous()) lo = *a.min, hi = *a.max;
    if (a.rollover == rotary_rollover::shortest) lo = 0, hi = 360;
    j.rotary[i] = std::uniform_real_distribution<double>(lo, hi)(rng);
    if (j.rotary[i] >= hi && a.rollover == rotary_rollover::shortest) j.rotary[i] = 0;
  }
  return j;
}

bool within_limits(const kinematic_chain& c, const joint_values& j) {
  for (std::size_t i = 0; i < c.rotaries.size(); ++i) {
    const rotary_axis_def& a = c.rotaries[i];
    if (a.min && (j.rotary[i] < *a.min || j.rotary[i] > *a.max)) return false;
    if (a.rollover == rotary_rollover::shortest && (j.rotary[i] < 0 || j.rotary[i] >= 360)) return false;
  }
  return true;
}

struct worst {
  double tip = 0, axis = 0, joint = 0;
  int poses = 0;
};

// IK(FK(θ)) for `n` random poses of channel `ch`: with θ as the previous position the inverse
// gives θ back; from another random position it gives a solution within the limits whose
// forward transform is the pose.
worst property(int ch, int n, std::uint64_t seed) {
  const kinematic_chain& c = test_chain(ch);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> tool(0, 250);
  worst w;
  for (int i = 0; i < n; ++i) {
    const joint_values theta = random_joints(c, rng);
    const joint_values other = random_joints(c, rng);
    const double length = tool(rng);
    const tool_pose pose = forward(c, theta, length);
    w.axis = std::max(w.axis, angle_between(tool_axis(c, theta), pose.axis));  // the axis alone agrees

    const ik_result same = inverse(c, pose, length, theta);
    REQUIRE(same.ok());
    for (std::size_t k = 0; k < c.rotaries.size(); ++k)
      w.joint = std::max(w.joint, std::abs(same.joints.rotary[k] - theta.rotary[k]));
    w.joint = std::max(w.joint, distance(same.joints.linear, theta.linear));

    const ik_result from_other = inverse(c, pose, length, other);
    REQUIRE(from_other.ok());
    CHECK(within_limits(c, from_other.joints));
    for (const ik_result* r : {&same, &from_other}) {
      const tool_pose back = forward(c, r->joints, length);
      w.tip = std::max(w.tip, distance(back.tip, pose.tip));
      w.axis = std::max(w.axis, angle_between(back.axis, pose.axis));
      w.poses++;
    }
  }
  return w;
}

}  // namespace

TEST_CASE("IK(FK(θ)) gives θ back, and FK(IK(p)) gives p, over random poses of every chain kind",
          "[kinematics]") {
  // 3000 random poses per chain, each solved twice (from θ itself and from another random
  // position): 42,000 inverses. Figures of the last run: docs/kinematics.md.
  const int channel = GENERATE(1, 2, 3, 4, 5, 6, 8);
  const worst w = property(channel, 3000, 20261123 + channel);
  INFO("channel " << channel << " (" << name_of(kind_of(test_chain(channel))) << "): " << w.poses
                  << " inverses, worst tip " << w.tip << " mm, axis " << w.axis << " deg, joint " << w.joint);
  CHECK(w.tip < 1e-9);
  CHECK(w.axis < 1e-9);
  CHECK(w.joint < 1e-7);
}

TEST_CASE("the short way of the inverse chooses as the whole way", "[kinematics]") {
  // The inverse skips the outer angle of the solution that cannot be chosen when its outer axis
  // has no preferred sign. On a continuous outer axis that rolls over in 0..360 every value is
  // positive, so prefer = positive chooses alike but goes the whole way: both must agree to
  // the bit, from random previous positions (near ones too, as in a cut) on every chain kind.
  const int channel = GENERATE(1, 2, 3, 4, 5, 6, 8);
  kinematic_chain c = test_chain(channel);
  if (c.rotaries.size() < 2) return;
  const int outer = orientation_of(c).outer;
  c.rotaries[outer].min.reset();
  c.rotaries[outer].max.reset();
  c.rotaries[outer].rollover = rotary_rollover::shortest;
  c.rotaries[outer].prefer = preferred_sign::none;
  kinematic_chain whole = c;
  whole.rotaries[outer].prefer = preferred_sign::positive;
  std::mt19937_64 rng(40 + static_cast<std::uint64_t>(channel));
  std::uniform_real_distribution<double> nudge(-2, 2);
  int solved = 0;
  for (int n = 0; n < 3000; ++n) {
    const joint_values theta = random_joints(c, rng);
    joint_values previous = random_joints(c, rng);
    if (n % 2 == 0) {  // a step of a cut: the previous position a few degrees away
      previous = theta;
      for (double& v : previous.rotary) v += nudge(rng);
      if (!within_limits(c, previous)) previous = theta;
    }
    const tool_pose pose = forward(c, theta, 100);
    const ik_result a = inverse(c, pose, 100, previous), b = inverse(whole, pose, 100, previous);
    REQUIRE(a.ok() == b.ok());
    if (!a.ok()) continue;
    REQUIRE(a.joints.rotary == b.joints.rotary);
    REQUIRE(a.joints.linear.x == b.joints.linear.x);
    REQUIRE(a.joints.linear.y == b.joints.linear.y);
    REQUIRE(a.joints.linear.z == b.joints.linear.z);
    REQUIRE(a.pole == b.pole);
    ++solved;
  }
  CHECK(solved > 2500);
}

TEST_CASE("the chains of the test machine are the kinds they describe", "[kinematics]") {
  CHECK(kind_of(test_chain(1)) == chain_kind::head_head);
  CHECK(kind_of(test_chain(2)) == chain_kind::table_table);
  CHECK(kind_of(test_chain(3)) == chain_kind::head_table);
  CHECK(kind_of(test_chain(6)) == chain_kind::one_rotary);
  const orientation_form f = orientation_of(test_chain(3));  // B head listed first, C table second
  CHECK(f.outer == 1);
  CHECK(f.inner == 0);
  CHECK(f.outer_sign == -1);
  CHECK(f.inner_sign == 1);
}

// Channel 1: B head about Y carrying an A head about X, pivot 300 mm above the gauge point;
// with a 100 mm tool the tip is 400 mm from the pivot (L = 400). By hand:
//   R_x(A)·z = (0, -sin A, cos A); R_y(B)·(x, y, z) = (x cos B + z sin B, y, -x sin B + z cos B)
//   K = R_y(B)·R_x(A)·z = (sin B cos A, -sin A, cos B cos A)
//   so A = -asin(Ky), B = atan2(Kx, Kz) (cos A > 0; the twin 180° - A, B + 180° is beyond ±20°).
// The tip at home is the linear position; the pivot P = lin + (0, 0, 400) stays where it is and
// the tip turns about it: Q = P - 400·K, so lin = Q + 400·(K - z).
//   A 0,  B 10: K = (0.173648177666930, 0, 0.984807753012208), 400(K - z) = (69.459271066772, 0,
//   -6.076898795117) A 15, B 0:  K = (0, -0.258819045102521, 0.965925826289068), 400(K - z) = (0,
//   -103.527618041008, -13.629669484373) A 10, B 20: K = (0.336824088833465, -0.173648177666930,
//   0.925416578398323),
//               400(K - z) = (134.729635533386, -69.459271066772, -29.833368640671)
//   A -20, B -20 (both on a limit): K = (-0.321393804843270, 0.342020143325669, 0.883022221559489),
//               400(K - z) = (-128.557521937308, 136.808057330267, -46.791111376204)
TEST_CASE("head/head B over A with 400 mm from pivot to tip: joint values computed by hand", "[kinematics]") {
  const kinematic_chain& c = test_chain(1);
  struct known {
    vec3 k;
    double a, b;
    vec3 offset;
  };
  const known cases[] = {
      {{0.173648177666930, 0, 0.984807753012208}, 0, 10, {69.459271066772, 0, -6.076898795117}},
      {{0, -0.258819045102521, 0.965925826289068}, 15, 0, {0, -103.527618041008, -13.629669484373}},
      {{0.336824088833465, -0.173648177666930, 0.925416578398323},
       10,
       20,
       {134.729635533386, -69.459271066772, -29.833368640671}},
      {{-0.321393804843270, 0.342020143325669, 0.883022221559489},
       -20,
       -20,
       {-128.557521937308, 136.808057330267, -46.791111376204}},
  };
  const vec3 tip{10, 20, 30};
  for (const known& k : cases) {
    const ik_result r = inverse(c, {tip, k.k}, 100, {});
    REQUIRE(r.ok());
    CHECK(r.joints.rotary[0] == Approx(k.b).margin(1e-9));  // B
    CHECK(r.joints.rotary[1] == Approx(k.a).margin(1e-9));  // A
    CHECK(r.joints.linear.x == Approx(tip.x + k.offset.x).margin(1e-9));
    CHECK(r.joints.linear.y == Approx(tip.y + k.offset.y).margin(1e-9));
    CHECK(r.joints.linear.z == Approx(tip.z + k.offset.z).margin(1e-9));
    CHECK(!r.pole);
  }
  // The vertical tool: every joint 0 but the linear ones, which are the tip.
  const ik_result v = inverse(c, {tip, {0, 0, 1}}, 100, {});
  REQUIRE(v.ok());
  CHECK(v.joints.rotary == std::array<double, 2>{0, 0});
  CHECK(v.joints.linear == tip);
}

// Channel 2, table/table: K = (sin C sin A, cos C sin A, cos A) (kinematics_forward_test.cpp).
// K = (0.5, 0, cos 30°): A = ±30°, sin C = 0.5 / sin A, cos C = 0: (A 30, C 90) or (A -30, C -90).
// From (0, 0) both move 120° in all and 90° on C: the tie goes to the positive tilt, A 30.
// The part's zero in the machine frame: C 90 about Z through (12.5, -7): (0, 0) - (12.5, -7) =
// (-12.5, 7) -> (-y, x) = (-7, -12.5), + (12.5, -7) = (5.5, -19.5, 0); A 30 about X through
// (0, 0, -80): (y, z) = (-19.5, 80) -> (y cos 30 - z sin 30, y sin 30 + z cos 30) =
// (-56.887495373797, 59.532032302755), z - 80 = -20.467967697245.
TEST_CASE("table/table A over C: joint values computed by hand, and the tie", "[kinematics]") {
  const ik_result r = inverse(test_chain(2), {{0, 0, 0}, {0.5, 0, 0.8660254037844386}}, 30, {});
  REQUIRE(r.ok());
  CHECK(r.joints.rotary[0] == Approx(30).margin(1e-9));
  CHECK(r.joints.rotary[1] == Approx(90).margin(1e-9));
  CHECK(r.joints.linear.x == Approx(5.5).margin(1e-9));
  CHECK(r.joints.linear.y == Approx(-56.887495373797).margin(1e-9));
  CHECK(r.joints.linear.z == Approx(-20.467967697245).margin(1e-9));
  // From C -80 the twin (A -30, C -90) is the shorter move.
  joint_values prev;
  prev.rotary = {0, -80};
  const ik_result t = inverse(test_chain(2), {{0, 0, 0}, {0.5, 0, 0.8660254037844386}}, 30, prev);
  REQUIRE(t.ok());
  CHECK(t.joints.rotary[0] == Approx(-30).margin(1e-9));
  CHECK(t.joints.rotary[1] == Approx(-90).margin(1e-9));
}

// Channel 3, head/table: K = R_z(-C)·R_y(B)·z = (sin B cos C, -sin B sin C, cos B).
// K = (0, -0.5, cos 30°): (B 30, C 90) or (B -30, C 270). Tool 50: the pivot is (5, 0, 300)
// from the tip at home. The part point (10, 0, 5) in the machine: C 90 turns (x, y) to
// (-y, x): (0, 10, 5); C 270: (0, -10, 5). The head: the tip, (-5, 0, -300) from the pivot,
// turned by B about Y, (x cos B + z sin B, y, -x sin B + z cos B), + (5, 0, 300):
//   B 30:  (-154.330127018922, 0, -257.307621135332) + P = (-149.330127018922, 0, 42.692378864668)
//   B -30: (145.669872981078, 0, -262.307621135332) + P = (150.669872981078, 0, 37.692378864668)
// linear = machine point - head offset:
//   B 30 C 90:   (149.330127018922, 10, -37.692378864668)
//   B -30 C 270: (-150.669872981078, -10, -32.692378864668)
// From (0, 0) both move 120° (C the short way: 90 either way): the positive tilt wins. From
// (B -10, C 260) the second moves 20° + 10°, the first 40° + 170°.
TEST_CASE("head/table B over C: joint values computed by hand, from two starts", "[kinematics]") {
  const tool_pose p{{10, 0, 5}, {0, -0.5, 0.8660254037844386}};
  const ik_result a = inverse(test_chain(3), p, 50, {});
  REQUIRE(a.ok());
  CHECK(a.joints.rotary[0] == Approx(30).margin(1e-9));
  CHECK(a.joints.rotary[1] == Approx(90).margin(1e-9));
  CHECK(a.joints.linear.x == Approx(149.330127018922).margin(1e-9));
  CHECK(a.joints.linear.y == Approx(10).margin(1e-9));
  CHECK(a.joints.linear.z == Approx(-37.692378864668).margin(1e-9));
  joint_values prev;
  prev.rotary = {-10, 260};
  const ik_result b = inverse(test_chain(3), p, 50, prev);
  REQUIRE(b.ok());
  CHECK(b.joints.rotary[0] == Approx(-30).margin(1e-9));
  CHECK(b.joints.rotary[1] == Approx(270).margin(1e-9));
  CHECK(b.joints.linear.x == Approx(-150.669872981078).margin(1e-9));
  CHECK(b.joints.linear.y == Approx(-10).margin(1e-9));
  CHECK(b.joints.linear.z == Approx(-32.692378864668).margin(1e-9));
}

TEST_CASE("the two orientation solutions of the head/head machine are A, B and 180 - A, B + 180",
          "[kinematics]") {
  const two_at_most<orientation_solution> s =
      orientation_solutions(test_chain(1), {0.336824088833465, -0.173648177666930, 0.925416578398323}, {});
  REQUIRE(s.size() == 2);
  // Sorted by B, the first is the twin B - 160 (= 20 + 180 wrapped), A 170.
  std::array<std::array<double, 2>, 2> got{s[0].rotary, s[1].rotary};
  std::sort(got.begin(), got.end());
  CHECK(got[0][0] == Approx(-160).margin(1e-9));
  CHECK(got[0][1] == Approx(170).margin(1e-9));
  CHECK(got[1][0] == Approx(20).margin(1e-9));
  CHECK(got[1][1] == Approx(10).margin(1e-9));
}

TEST_CASE("a tool axis beyond the limits of every solution is an error that names them", "[kinematics]") {
  // B 30 (twin B -150, A 180): beyond ±20 both.
  const ik_result r = inverse(test_chain(1), {{0, 0, 0}, {0.5, 0, 0.8660254037844386}}, 100, {});
  CHECK(r.error == ik_error::beyond_limits);
  CHECK(r.message ==
        "tool axis (0.5, 0, 0.866) needs B30 A0 (B beyond -20..20) or B-150 A180 (B beyond -20..20; A beyond "
        "-20..20)");
}

TEST_CASE("a tool axis no rotation reaches, and one that is no direction, are errors", "[kinematics]") {
  // The A table about X cannot tilt the tool towards X.
  const ik_result a = inverse(test_chain(6), {{0, 0, 0}, {1, 0, 0}}, 100, {});
  CHECK(a.error == ik_error::unreachable);
  CHECK(a.message == "tool axis (1, 0, 0) cannot be reached by the rotary axis A");
  // The nutating head reaches the half space Kz >= 0 only.
  const ik_result n = inverse(test_chain(5), {{0, 0, 0}, {0, 0.6, -0.8}}, 100, {});
  CHECK(n.error == ik_error::unreachable);
  CHECK(n.message == "tool axis (0, 0.6, -0.8) cannot be reached by the rotary axes C and B");
  const ik_result z = inverse(test_chain(1), {{0, 0, 0}, {0, 0, 0}}, 100, {});
  CHECK(z.error == ik_error::zero_axis);
  CHECK(z.message == "tool axis (0, 0, 0) is not a direction");
  const ik_result nan = inverse(test_chain(1), {{0, std::nan(""), 0}, {0, 0, 1}}, 100, {});
  CHECK(nan.error == ik_error::bad_tip);
  CHECK(nan.message == "tool tip (0, nan, 0) is not a point");
  kinematic_chain three_axis;
  const ik_result t = inverse(three_axis, {{0, 0, 0}, {0, 1, 0}}, 100, {});
  CHECK(t.error == ik_error::unreachable);
  CHECK(t.message ==
        "tool axis (0, 1, 0) is not the tool direction (0, 0, 1) of a machine without rotary axes");
  const ik_result ok = inverse(three_axis, {{1, 2, 3}, {0, 0, 2}}, 100, {});
  REQUIRE(ok.ok());
  CHECK(ok.joints.linear == vec3{1, 2, 3});
}

TEST_CASE("at the pole the outer axis keeps its previous angle", "[kinematics]") {
  // Table/table: K = z is on the C axis (A 0); C stays at 37.5 and the tip is turned with it.
  const kinematic_chain& tt = test_chain(2);
  joint_values prev;
  prev.rotary = {-40, 37.5};
  const ik_result r = inverse(tt, {{100, 0, 10}, {0, 0, 1}}, 50, prev);
  REQUIRE(r.ok());
  CHECK(r.pole);
  CHECK(r.joints.rotary[0] == Approx(0).margin(1e-12));
  CHECK(r.joints.rotary[1] == 37.5);
  const tool_pose back = forward(tt, r.joints, 50);
  CHECK(distance(back.tip, {100, 0, 10}) < 1e-12);
  // Head/table: the B head vertical, C kept (rollover "shortest": 355 stays 355).
  joint_values p3;
  p3.rotary = {45, 355};
  const ik_result h = inverse(test_chain(3), {{0, 0, 0}, {0, 0, 1}}, 80, p3);
  REQUIRE(h.ok());
  CHECK(h.pole);
  CHECK(h.joints.rotary[0] == Approx(0).margin(1e-12));
  CHECK(h.joints.rotary[1] == 355);
  // A C axis along the tool is always at its pole: it never moves for an orientation.
  joint_values p7;
  p7.rotary = {-123.25, 0};
  const ik_result c7 = inverse(test_chain(7), {{5, 6, 7}, {0, 0, 1}}, 80, p7);
  REQUIRE(c7.ok());
  CHECK(c7.pole);
  CHECK(c7.joints.rotary[0] == -123.25);
  CHECK(distance(forward(test_chain(7), c7.joints, 80).tip, {5, 6, 7}) < 1e-12);
}

TEST_CASE("approaching the pole from several sides keeps the tip and axis exact", "[kinematics]") {
  // Table/table: the axis 1e-2 .. 1e-6 degrees from C, from eight directions. C follows the
  // direction of approach; the tip and axis stay exact, and A is the angle from the pole to
  // 6 digits (an acos would give 1e-6° as 0.0000011°).
  const kinematic_chain& tt = test_chain(2);
  for (double eps : {1e-2, 1e-4, 1e-6})
    for (int side = 0; side < 8; ++side) {
      const double az = side * 45.0 * deg, e = eps * deg;
      const tool_pose p{{30, -20, 5}, {std::sin(e) * std::cos(az), std::sin(e) * std::sin(az), std::cos(e)}};
      const ik_result r = inverse(tt, p, 60, {});
      REQUIRE(r.ok());
      const tool_pose back = forward(tt, r.joints, 60);
      CHECK(distance(back.tip, p.tip) < 1e-9);
      CHECK(angle_between(back.axis, p.axis) < 1e-9);
      CHECK(std::abs(r.joints.rotary[0]) == Approx(eps).epsilon(1e-6));
    }
}

TEST_CASE("a limited axis takes the long way when the short one leaves its limits", "[kinematics]") {
  // A trunnion limited to 0..120 and C to 0..360: from C 350 to C 10 the short way (370) is
  // beyond 360, so C goes back 340° to 10; the twin (A -25) is beyond A's limits.
  kinematic_chain c = test_chain(2);
  c.rotaries[0].min = 0;
  c.rotaries[0].max = 120;
  c.rotaries[1].min = 0;
  c.rotaries[1].max = 360;
  joint_values from;
  from.rotary = {25, 350};
  joint_values to;
  to.rotary = {25, 10};
  const tool_pose p = forward(c, to, 40);
  const ik_result r = inverse(c, p, 40, from);
  REQUIRE(r.ok());
  CHECK(r.joints.rotary[0] == Approx(25).margin(1e-9));
  CHECK(r.joints.rotary[1] == Approx(10).margin(1e-9));
  // With A free to go to -25, the twin (A -25, C 190: 50° + 160°) is the shorter move.
  c.rotaries[0].min = -120;
  const ik_result t = inverse(c, p, 40, from);
  REQUIRE(t.ok());
  CHECK(t.joints.rotary[0] == Approx(-25).margin(1e-9));
  CHECK(t.joints.rotary[1] == Approx(190).margin(1e-9));
  CHECK(distance(forward(c, t.joints, 40).tip, p.tip) < 1e-9);
}

TEST_CASE("the preferred tilt sign chooses between the two solutions", "[kinematics]") {
  // Head/table B over C: the tool tilted 30° towards -X is B -30, C 0 or B 30, C 180.
  kinematic_chain c = test_chain(3);
  const tool_pose p{{10, 0, 0}, {-0.5, 0, 0.8660254037844386}};
  const ik_result near = inverse(c, p, 80, {});
  REQUIRE(near.ok());
  CHECK(near.joints.rotary[0] == Approx(-30).margin(1e-9));
  CHECK(near.joints.rotary[1] == Approx(0).margin(1e-9));
  c.rotaries[0].prefer = preferred_sign::positive;
  const ik_result pos = inverse(c, p, 80, {});
  REQUIRE(pos.ok());
  CHECK(pos.joints.rotary[0] == Approx(30).margin(1e-9));
  CHECK(pos.joints.rotary[1] == Approx(180).margin(1e-9));
}

TEST_CASE("continuous axes unwind to the nearest turn, or roll over in 0..360", "[kinematics]") {
  // Bridge mill, C head continuous absolute: from C 179.9 to the axis of C -179.9 is +0.2°.
  const kinematic_chain& bm = test_chain(4);
  joint_values to;
  to.rotary = {-179.9, 30};
  joint_values from;
  from.rotary = {179.9, 30};
  const ik_result a = inverse(bm, forward(bm, to, 50), 50, from);
  REQUIRE(a.ok());
  CHECK(a.joints.rotary[0] == Approx(180.1).margin(1e-9));
  CHECK(a.joints.rotary[1] == Approx(30).margin(1e-9));
  from.rotary = {719.5, 30};  // two turns on: stays there
  to.rotary = {0.5, 30};
  const ik_result b = inverse(bm, forward(bm, to, 50), 50, from);
  REQUIRE(b.ok());
  CHECK(b.joints.rotary[0] == Approx(720.5).margin(1e-9));
  // Head/table C with rollover "shortest": from 359.9 to the axis of C 0.1 is 0.1, not 360.1.
  const kinematic_chain& ht = test_chain(3);
  joint_values f3;
  f3.rotary = {40, 359.9};
  joint_values t3;
  t3.rotary = {40, 0.1};
  const ik_result s = inverse(ht, forward(ht, t3, 50), 50, f3);
  REQUIRE(s.ok());
  CHECK(s.joints.rotary[0] == Approx(40).margin(1e-9));
  CHECK(s.joints.rotary[1] == Approx(0.1).margin(1e-9));
}

TEST_CASE("wrap_180 is correct for negative angles (the fmod pitfall)", "[kinematics]") {
  CHECK(wrap_180(-190) == Approx(170));
  CHECK(wrap_180(190) == Approx(-170));
  CHECK(wrap_180(-370) == Approx(-10));
  CHECK(wrap_180(370) == Approx(10));
  CHECK(std::abs(wrap_180(-540)) == Approx(180));
  CHECK(wrap_180(-0.25) == -0.25);
}

TEST_CASE("wrap_180's fast path within a turn gives std::remainder's bits", "[kinematics]") {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> any(-540, 540);
  for (int n = 0; n < 100000; ++n) {
    const double a = any(rng);
    REQUIRE(wrap_180(a) == std::remainder(a, 360.0));
  }
  for (double a : {540.0, -540.0, std::nextafter(540.0, 0.0), std::nextafter(-540.0, 0.0),
                   std::nextafter(180.0, 200.0), std::nextafter(-180.0, -200.0), 900.0, -900.0})
    CHECK(wrap_180(a) == std::remainder(a, 360.0));
  CHECK(wrap_180(540) == -180);
  CHECK(wrap_180(-540) == 180);
}

TEST_CASE("turn_of_small and compose give turn_of's rotation", "[kinematics]") {
  for (double d : {0.0, 1e-9, -0.0004, 0.37, -2.5, 5.7, -5.72, 5.73, 30.0, -170.0}) {
    const turn a = turn_of_small(d), b = turn_of(d);
    CHECK(a.c == Approx(b.c).margin(4e-17));
    CHECK(a.s == Approx(b.s).margin(4e-17));
    const turn sum = compose(turn_of(12.5), turn_of_small(d)), direct = turn_of(12.5 + d);
    CHECK(sum.c == Approx(direct.c).margin(4e-16));
    CHECK(sum.s == Approx(direct.s).margin(4e-16));
  }
}

TEST_CASE("number_text writes at most four decimals without trailing zeros", "[kinematics]") {
  CHECK(number_text(30) == "30");
  CHECK(number_text(-0.5) == "-0.5");
  CHECK(number_text(0.8660254) == "0.866");
  CHECK(number_text(-1e-12) == "0");
  CHECK(number_text(12.34567) == "12.3457");
}
