// kinematics/linearise: moves whose rotary axes swing by tens of degrees, cut until the tip of
// the joints' linear interpolation stays within the tolerance of the CL segment — shown by the
// forward transform at many points of every sub-move, not only at the checked ones.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

#include "kinematics/forward.hpp"
#include "kinematics/linearise.hpp"
#include "kinematics/vec3_ops.hpp"
#include "kinematics_test_support.hpp"

using namespace twinpost;
using namespace twinpost::kin;
using test::test_chain;

namespace {

joint_values rotaries(double r0, double r1) {
  joint_values j;
  j.rotary = {r0, r1};
  return j;
}

struct measured {
  double unsplit = 0;  // the tip's largest distance from the segment with no cut
  double worst = 0;    // the same over every sub-move, 200 points each
  double end = 0;      // the last point's tip and axis against the CL end
  double on_line = 0;  // every point's tip from the segment, and its axis from the great circle
};

measured measure(const kinematic_chain& c, const tool_pose& from, const joint_values& j0, const tool_pose& to,
                 double length, const linearise_result& r) {
  measured m;
  const ik_result end = inverse(c, to, length, j0);
  for (int i = 1; i < 200; ++i)
    m.unsplit = std::max(
        m.unsplit, distance_to_segment(forward(c, interpolate(c, j0, end.joints, i / 200.0), length).tip,
                                       from.tip, to.tip));
  joint_values a = j0;
  for (const joint_values& b : r.points) {
    for (int i = 0; i <= 200; ++i)
      m.worst = std::max(m.worst, distance_to_segment(forward(c, interpolate(c, a, b, i / 200.0), length).tip,
                                                      from.tip, to.tip));
    a = b;
    // Each point is a CL point: its tip on the segment, its axis in the plane of the two axes.
    const tool_pose p = forward(c, b, length);
    const vec3 normal = cross(from.axis, to.axis);
    m.on_line = std::max({m.on_line, distance_to_segment(p.tip, from.tip, to.tip),
                          std::abs(dot(p.axis, normal)) / norm(normal)});
  }
  const tool_pose last = forward(c, r.points.back(), length);
  m.end = std::max(distance(last.tip, to.tip), angle_between(last.axis, to.axis));
  return m;
}

// The tip's distance from the chord of a smooth curve falls as the square of the number of
// cuts: n equal cuts of a move that leaves the line by D stay within D / n² (about), so at least
// sqrt(D / tol) sub-moves are needed; halving overshoots that by at most two, and an uneven
// curvature by a little more. Four times the least is the most a sound cutting may take.
void check_count(std::size_t n, double unsplit, double tol) {
  const double least = std::sqrt(unsplit / tol);
  CHECK(static_cast<double>(n) >= least);
  CHECK(static_cast<double>(n) <= 4 * least);
}

}  // namespace

TEST_CASE("a table/table move swinging A by 50° and C by 70° is cut to 0.01 mm", "[kinematics]") {
  const kinematic_chain& c = test_chain(2);
  const double length = 120;
  const joint_values j0 = positions(c, {50, 0, 0}, rotaries(-10, 0), length);
  const tool_pose from = forward(c, j0, length);
  const tool_pose to{{80, 30, -10}, forward(c, rotaries(-60, 70), length).axis};
  const linearise_result r = linearise(c, from, j0, to, length, 0.01);
  REQUIRE(r.ok());
  const measured m = measure(c, from, j0, to, length, r);
  INFO("sub-moves " << r.points.size() << ", unsplit " << m.unsplit << " mm, worst " << m.worst << " mm");
  CHECK(m.unsplit > 10);  // one linear joint move would leave the line by centimetres
  CHECK(m.worst <= 0.01);
  CHECK(r.deviation <= 0.01);
  CHECK(m.end < 1e-9);
  CHECK(m.on_line < 1e-9);
  check_count(r.points.size(), m.unsplit, 0.01);  // 78 sub-moves in the last run
  CHECK(r.points.back().rotary[0] == Approx(-60).margin(1e-9));
  CHECK(r.points.back().rotary[1] == Approx(70).margin(1e-9));
}

TEST_CASE("a head/head move from B -20 A 15 to B 20 A -15 is cut to 0.005 mm", "[kinematics]") {
  const kinematic_chain& c = test_chain(1);
  const double length = 100;  // 400 mm from the pivot to the tip
  const joint_values j0 = positions(c, {0, 0, 0}, rotaries(-20, 15), length);
  const tool_pose from = forward(c, j0, length);
  const tool_pose to{{40, 10, 0}, forward(c, rotaries(20, -15), length).axis};
  const linearise_result r = linearise(c, from, j0, to, length, 0.005);
  REQUIRE(r.ok());
  const measured m = measure(c, from, j0, to, length, r);
  INFO("sub-moves " << r.points.size() << ", unsplit " << m.unsplit << " mm, worst " << m.worst << " mm");
  CHECK(m.unsplit > 10);
  CHECK(m.worst <= 0.005);
  CHECK(m.end < 1e-9);
  CHECK(m.on_line < 1e-9);
  check_count(r.points.size(), m.unsplit, 0.005);  // 128 sub-moves in the last run
  CHECK(r.points.back().rotary[0] == Approx(20).margin(1e-9));
  CHECK(r.points.back().rotary[1] == Approx(-15).margin(1e-9));
}

TEST_CASE("a move that needs no cut is one point, and too many cuts are an error", "[kinematics]") {
  const kinematic_chain& c = test_chain(2);
  const joint_values j0 = positions(c, {0, 0, 0}, rotaries(-30, 10), 50);
  const tool_pose from = forward(c, j0, 50);
  // The same orientation: the joints' linear move is the straight line.
  const tool_pose to{{20, 5, -3}, from.axis};
  const linearise_result one = linearise(c, from, j0, to, 50, 0.001);
  REQUIRE(one.ok());
  CHECK(one.points.size() == 1);
  const tool_pose swing{{80, 30, -10}, forward(c, rotaries(-60, 70), 50).axis};
  const linearise_result many = linearise(c, from, j0, swing, 50, 0.001, 8);
  CHECK(many.error == ik_error::too_many_points);
  CHECK(many.message == "the move needs more than 8 points to keep the tip within 0.001 mm of the line");
  CHECK(many.points.empty());
  // An end the machine cannot reach is the inverse's error.
  const linearise_result beyond = linearise(test_chain(1), {{0, 0, 0}, {0, 0, 1}}, {},
                                            {{0, 0, 0}, {0.5, 0, 0.8660254037844386}}, 100, 0.01);
  CHECK(beyond.error == ik_error::beyond_limits);
  CHECK(beyond.message ==
        "tool axis (0.5, 0, 0.866) needs B30 A0 (B beyond -20..20) or B-150 A180 (B beyond -20..20; A beyond "
        "-20..20)");
}

TEST_CASE("slerp and the segment distance", "[kinematics]") {
  const vec3 h = slerp({1, 0, 0}, {0, 1, 0}, 0.5);
  CHECK(h.x == Approx(std::sqrt(0.5)));
  CHECK(h.y == Approx(std::sqrt(0.5)));
  CHECK(h.z == 0);
  CHECK(slerp({0, 0, 2}, {0, 0, 1}, 0.3) == vec3{0, 0, 1});
  CHECK(distance_to_segment({5, 3, 0}, {0, 0, 0}, {10, 0, 0}) == 3);
  CHECK(distance_to_segment({-4, 3, 0}, {0, 0, 0}, {10, 0, 0}) == 5);  // beyond an end: to the end
}

// Head/table B over C (rollover "shortest"): K = R_z(-C)·(sin B, 0, cos B) = (sin B cos C,
// -sin B sin C, cos B). A move from the axis tilted 20° towards +X to 20° towards -X, both
// leaning e = 0.5° towards +Y, passes the pole (K = z) at 0.5°: it never reaches it, so B never
// crosses 0 and C turns the part half round instead: B stays acos(cos 20° / √(1 + sin² e)),
// C goes from -atan(sin e / sin 20°) = 358.538° to 180 + atan(sin e / sin 20°) = 181.462°.
// (The shortest move from the start, B -20 C 1.46, is on the other side of the pole: the
// joints would cross it while the CL path does not.) Through the pole itself (e = 0) C keeps
// its angle and B goes from 20 to -20.
TEST_CASE("a move past the pole follows the path round it, a move through it keeps C", "[kinematics]") {
  const kinematic_chain& c = test_chain(3);
  const double t = 20 * deg;
  for (double off : {0.5, 0.0}) {
    const double e = off * deg;
    const tool_pose from{{30, 10, 0}, {std::sin(t), std::sin(e), std::cos(t)}};
    const tool_pose to{{-30, 10, 0}, {-std::sin(t), std::sin(e), std::cos(t)}};
    const ik_result start = inverse(c, from, 100, {});
    REQUIRE(start.ok());
    const linearise_result r = linearise(c, from, start.joints, to, 100, 0.01);
    REQUIRE(r.ok());
    const measured m = measure(c, from, start.joints, to, 100, r);
    INFO("off " << off << ": sub-moves " << r.points.size() << ", worst " << m.worst << " mm");
    CHECK(m.worst <= 0.01);
    CHECK(m.end < 1e-9);
    CHECK(m.on_line < 1e-9);
    const double b = std::acos(std::cos(t) / std::sqrt(1 + std::sin(e) * std::sin(e))) / deg;
    const double turn = std::atan(std::sin(e) / std::sin(t)) / deg;
    CHECK(start.joints.rotary[0] == Approx(b).margin(1e-9));
    CHECK(start.joints.rotary[1] == Approx(off > 0 ? 360 - turn : 0).margin(1e-9));
    if (off > 0) {
      CHECK(r.points.back().rotary[0] == Approx(b).margin(1e-9));
      CHECK(r.points.back().rotary[1] == Approx(180 + turn).margin(1e-9));
      for (const joint_values& p : r.points) CHECK(p.rotary[0] > 0.5);  // B never near 0
    } else {
      CHECK(r.points.back().rotary[0] == Approx(-20).margin(1e-9));
      for (const joint_values& p : r.points) CHECK(p.rotary[1] == Approx(0).margin(1e-9));
    }
  }
}

// 50 random moves on each of six chains (fixed seed): from random joints within the limits to
// joints up to 30° away on each rotary axis and 100 mm on each linear one, cut to 0.01 mm.
// Every move succeeds, and the tip stays within the tolerance at 100 points of every
// sub-move. (This found the rollover axis interpolated the long way from 359° to 1°.)
TEST_CASE("random moves on every chain kind are cut to the tolerance", "[kinematics]") {
  std::mt19937_64 rng(7);
  int moves = 0;
  std::size_t points = 0;
  double worst = 0;
  for (int ch = 1; ch <= 6; ++ch) {
    const kinematic_chain& c = test_chain(ch);
    std::uniform_real_distribution<double> lin(-100, 100), step(-30, 30);
    for (int n = 0; n < 50; ++n) {
      joint_values a, b;
      a.linear = {lin(rng), lin(rng), lin(rng)};
      b.linear = {lin(rng), lin(rng), lin(rng)};
      for (std::size_t i = 0; i < c.rotaries.size(); ++i) {
        const rotary_axis_def& ax = c.rotaries[i];
        double lo = ax.continuous() ? -180 : *ax.min, hi = ax.continuous() ? 180 : *ax.max;
        if (ax.rollover == rotary_rollover::shortest) lo = 0, hi = 360;
        a.rotary[i] = std::uniform_real_distribution<double>(lo, hi)(rng);
        b.rotary[i] = std::clamp(a.rotary[i] + step(rng), lo, hi);
      }
      const tool_pose from = forward(c, a, 80), to = forward(c, b, 80);
      const linearise_result r = linearise(c, from, a, to, 80, 0.01);
      INFO("channel " << ch << ", move " << n << ": " << r.message);
      REQUIRE(r.ok());
      joint_values p = a;
      for (const joint_values& q : r.points) {
        for (int i = 0; i <= 100; ++i)
          worst = std::max(worst, distance_to_segment(forward(c, interpolate(c, p, q, i / 100.0), 80).tip,
                                                      from.tip, to.tip));
        p = q;
      }
      const tool_pose end = forward(c, r.points.back(), 80);
      CHECK(distance(end.tip, to.tip) < 1e-9);
      CHECK(angle_between(end.axis, to.axis) < 1e-9);
      points += r.points.size();
      ++moves;
    }
  }
  INFO(moves << " moves, " << points << " sub-moves, worst " << worst << " mm");
  CHECK(moves == 300);
  CHECK(worst <= 0.01);
}

TEST_CASE("a rollover axis is interpolated the short way round", "[kinematics]") {
  const kinematic_chain& c = test_chain(3);  // C: rollover "shortest"
  joint_values a, b;
  a.rotary = {10, 359};
  b.rotary = {20, 1};
  const joint_values m = interpolate(c, a, b, 0.5);
  CHECK(m.rotary[0] == 15);
  CHECK(m.rotary[1] == 360);
  const joint_values n = interpolate(test_chain(4), a, b, 0.5);  // C absolute: the way it says
  CHECK(n.rotary[1] == 180);
}
