// machining/kin_lookahead: the 5-axis moves worked out ahead of the writer are taken only for
// the very inputs they were worked out from, and then are what the writer would work out.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "kinematics/linearise.hpp"
#include "machines/machine_loader.hpp"
#include "machining/kin_lookahead.hpp"
#include "parser/cl_reader.hpp"
#include "post_test_jobs.hpp"

using namespace twinpost;

namespace {

std::vector<event> events_of(const std::string& cl) {
  string_source src(cl);
  cl_reader_options o;
  o.file_name = "t.cl";
  diagnostic_list d;
  cl_reader r(src, o, d);
  std::vector<event> out;
  while (const event* e = r.next()) out.push_back(*e);
  CHECK(d.all().empty());
  return out;
}

bool same_bits(const kin::joint_values& a, const kin::joint_values& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// A five-axis job of `n` feed moves along a tilted wall, with a tool change halfway.
std::string wall_job(int n) {
  std::string cl =
      "UNITS/MM\nMULTAX/ON\nTLDATA/MILL,10,5,75,0,0\nLOADTL/1\nSPINDL/RPM,8000,CLW\n"
      "FEDRAT/MMPM,1200\nRAPID\nGOTO/0,0,25,0,0,1\n";
  for (int i = 0; i < n; ++i) {
    if (i == n / 2) cl += "TLDATA/MILL,8,4,60,0,0\nLOADTL/2\nSPINDL/RPM,9000,CLW\nFEDRAT/MMPM,1000\nRAPID\n";
    const double t = i * 0.01;
    const double a = 0.3 * std::sin(t), b = 0.2 * std::cos(3 * t);
    const double k = std::sqrt(1 - a * a - b * b);
    cl += fmt::format("GOTO/{:.4f},{:.4f},{:.4f},{:.7f},{:.7f},{:.7f}\n", 40 * std::cos(t), 40 * std::sin(t),
                      5 - (i % 100) * 0.01, a, b, k);
  }
  return cl + "FINI\n";
}

}  // namespace

TEST_CASE("the look-ahead's moves are the writer's own and any bit off is not taken", "[kinematics]") {
  const machine m = load_machine("head-head-5axis");
  const kinematic_chain* c = m.chain(1);
  REQUIRE(c != nullptr);
  const std::vector<event> ev = events_of(
      "UNITS/MM\nMULTAX/ON\nTLDATA/MILL,10,5,75,0,0\nLOADTL/1\nFEDRAT/MMPM,1200\nRAPID\n"
      "GOTO/0,0,25,0,0,1\nGOTO/10,0,20,0.2,0,0.9797959\nGOTO/20,5,15,0.3,0.1,0.9486833\n");
  REQUIRE(ev.size() == 8);  // RAPID is the first GOTO's flag, not an event
  kin_lookahead ahead(m, 1);
  kin_lookahead::notes notes;
  ahead.look(ev, notes);
  CHECK(notes.of_event == std::vector<std::int32_t>{-1, -1, -1, -1, -1, 0, 1, 2});

  const kin::chain_plan plan(*c);
  const double length = 75;  // TLDATA's, before its LOADTL
  const kin::tool_pose p0{{0, 0, 25}, {0, 0, 1}};
  const vec3 a1{0.2, 0, 0.9797959}, a2{0.3, 0.1, 0.9486833};
  // The pose as the writer makes it: the axis divided by its length.
  auto unit = [](const vec3& a) {
    const double len = std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
    return vec3{a.x / len, a.y / len, a.z / len};
  };
  const kin::tool_pose p1{{10, 0, 20}, unit(a1)};
  const kin::tool_pose p2{{20, 5, 15}, unit(a2)};

  // The rapid: an inverse from where the machine starts.
  ahead.at(&notes, 5);
  const kin::ik_result* r0 = ahead.inverse(c, p0, length, {}, kin::ik_need::joints);
  REQUIRE(r0 != nullptr);
  const kin::ik_result own0 = kin::inverse(plan, p0, length, {}, kin::ik_need::joints);
  CHECK(same_bits(r0->joints, own0.joints));
  // -0 for 0 in the tip, another length, the angles only, another chain: not taken.
  CHECK(ahead.inverse(c, {{-0.0, 0, 25}, {0, 0, 1}}, length, {}, kin::ik_need::joints) == nullptr);
  CHECK(ahead.inverse(c, p0, 60, {}, kin::ik_need::joints) == nullptr);
  CHECK(ahead.inverse(c, p0, length, {}, kin::ik_need::angles) == nullptr);
  const kinematic_chain other = *c;
  CHECK(ahead.inverse(&other, p0, length, {}, kin::ik_need::joints) == nullptr);

  // The two feed moves: linearised from where the one before ended.
  ahead.at(&notes, 6);
  kin::linearise_result got, own;
  REQUIRE(ahead.linearise(c, p0, own0.joints, p1, length, c->chordal_tolerance, got));
  kin::linearise(plan, p0, own0.joints, p1, length, c->chordal_tolerance, own);
  REQUIRE(got.points.size() == own.points.size());
  for (std::size_t i = 0; i < own.points.size(); ++i) {
    CHECK(same_bits(got.points[i], own.points[i]));
    CHECK(got.fractions[i] == own.fractions[i]);
  }
  CHECK(got.deviation == own.deviation);
  CHECK(ahead.inverse(c, p1, length, own0.joints, kin::ik_need::joints) == nullptr);  // it was linearised
  kin::joint_values nudged = own0.joints;
  nudged.rotary[0] = std::nextafter(nudged.rotary[0], 1e9);  // one bit off where the machine is
  CHECK_FALSE(ahead.linearise(c, p0, nudged, p1, length, c->chordal_tolerance, got));
  CHECK_FALSE(ahead.linearise(c, p0, own0.joints, p1, length, 2 * c->chordal_tolerance, got));
  const kin::joint_values end1 = own.points.back();
  ahead.at(&notes, 7);
  CHECK(ahead.linearise(c, p1, end1, p2, length, c->chordal_tolerance, got));
  CHECK_FALSE(ahead.linearise(c, p0, own0.joints, p1, length, c->chordal_tolerance, got));  // another event's

  // No event, or one with nothing worked out: nothing.
  ahead.at(&notes, 4);
  CHECK(ahead.inverse(c, p0, length, {}, kin::ik_need::joints) == nullptr);
  ahead.at(nullptr, 0);
  CHECK(ahead.inverse(c, p0, length, {}, kin::ik_need::joints) == nullptr);
}

TEST_CASE("on three threads a five-axis job's program is the one of one thread", "[post][multiaxis]") {
  // The moves are worked out by a thread between the reader and the post (post/reader_thread,
  // machining/kin_lookahead) over more than two batches of 4096 events, with a tool change
  // (a new length) in between: the same bytes as on one thread, on both chain kinds.
  const std::string job = wall_job(9000);
  for (const char* name : {"head-head-5axis", "trunnion-5axis"}) {
    INFO(name);
    const machine m = load_machine(name);
    auto with = [](int n) { return [n](post_options& o) { o.threads = n; }; };
    const test::posted one = test::post_in_fresh_dir(job, m, "ahead-1", {}, {}, with(1));
    const test::posted three = test::post_in_fresh_dir(job, m, "ahead-3", {}, {}, with(2));
    CHECK(one.ok);
    CHECK(three.diagnostics == one.diagnostics);
    REQUIRE(one.files.size() == 1);
    CHECK(three.files == one.files);
    CHECK(one.files.begin()->second.size() > 9000 * 20);  // every move is in it
  }
}
