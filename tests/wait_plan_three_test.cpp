// Three channels under --sync optimise: the router places meetings that name only the paths
// concerned, and the plan of a section of three channels (channels/wait_schedule_n) keeps each
// pair by its meetings, each asserted exactly.
#include <catch2/catch.hpp>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <string>

#include "channels/router.hpp"
#include "channels/wait_plan.hpp"
#include "tests/router_test_support.hpp"

using namespace twinpost;

namespace {

machine three_paths() { return test::router_machine(3); }

// Each wait with its partners: "c<channel>:M<code>/<partners>".
struct trace_sink : test::trace_sink {
  trace_sink() : test::trace_sink(true) {}
};

event go(int line) { return {line, motion_event{}}; }
event tool(int line) { return {line, tool_event{}}; }
event head(int n, int line) { return {line, head_event{head_select::number, n}}; }

// Head 1: lines 1-2, then a tool change at 8 (its second operation); head 2: 4; head 3: 6.
std::vector<event> job() { return {go(1), go(2), head(2, 3), go(4), head(3, 5), go(6), head(1, 7), tool(8)}; }

struct routed {
  std::string trace;
  job_operations ops;
};

routed route(const job_operations* plan, diagnostic_list& d, const machine& m) {
  trace_sink sink;
  channel_router r(m, plan ? sync_policy::optimise : sync_policy::sequential, sink, d, "job.cls", {1, 2, 3});
  r.track_operations(true);
  r.set_plan(plan);
  for (const event& e : job()) r.route(e);
  r.finish(99);
  return {sink.trace, r.operations()};
}

routed route(const job_operations* plan, diagnostic_list& d) {
  static const machine m = three_paths();  // the router keeps a reference
  return route(plan, d, m);
}

}  // namespace

TEST_CASE("three channels: the router finds each one's operations", "[wait_plan]") {
  diagnostic_list d;
  const routed r = route(nullptr, d);
  CHECK(d.all().empty());
  REQUIRE(r.ops.channels == std::vector<int>{1, 2, 3});
  REQUIRE(r.ops.sections.size() == 1);
  const plan_section& s = r.ops.sections[0];
  REQUIRE(s.ops.size() == 3);
  CHECK(s.ops[0].size() == 2);
  CHECK(s.ops[1].size() == 1);
  CHECK(s.ops[2].size() == 1);
  CHECK(s.ops[0][1].first_line == 8);
}

TEST_CASE("three channels: a plan's meetings name only the paths they concern", "[wait_plan]") {
  diagnostic_list d;
  job_operations plan = route(nullptr, d).ops;
  // Path 3 starts when path 1 has done its first operation (P13); path 2 waits at its start
  // for path 3's operation (P23).
  plan.sections[0].waits = {meeting{{{0, 1}, {2, 0}}}, meeting{{{1, 0}, {2, 1}}}};
  const routed r = route(&plan, d);
  CHECK(d.all().empty());
  CHECK(r.trace ==
        "c1:1\nc1:2\n"
        "c2:M100/23\nc2:4\n"  // the second meeting's code is the first one written
        "c3:M101/13\nc3:6\n"
        "c1:M101/13\nc1:8\n"                         // after path 1's first operation, before its tool change
        "c3:M100/23\n"                               // after path 3's operation, at the end of the section
        "c1:M102/123\nc2:M102/123\nc3:M102/123\n");  // the last rendezvous before the footers
}

TEST_CASE("three channels: a meeting out of a channel's order stops the post", "[wait_plan]") {
  diagnostic_list d;
  job_operations plan = route(nullptr, d).ops;
  // Path 1 would meet after its second operation first, then after its first.
  plan.sections[0].waits = {meeting{{{0, 2}, {1, 1}}}, meeting{{{0, 1}, {2, 0}}}};
  route(&plan, d);
  REQUIRE(d.errors() == 1);
  CHECK(d.all()[0].message ==
        "--sync optimise: the wait plan does not fit the job (section 1: channel 1 passed the place of wait "
        "2): "
        "an optimiser fault, nothing is written; post the job with --sync sequential");
}

TEST_CASE("three channels: the plan keeps each pair by its meetings, in the pair's order", "[wait_plan]") {
  job_operations ops;
  ops.channels = {1, 2, 3};
  ops.add_section();
  // A 10 s, B 12 s, C 5 s; A's and C's operations kept apart; B free.
  ops.sections[0].ops[0] = {{1, 1, 0, 10000000}};
  ops.sections[0].ops[1] = {{2, 2, 0, 12000000}};
  ops.sections[0].ops[2] = {{3, 3, 0, 5000000}};
  SECTION("A's first: C waits at its start for A's end") {
    const std::optional<std::int64_t> cycle =
        plan_waits(ops, {{0, {0, 0, pair_rule::a_first}, 0, 2}}, 100000);
    REQUIRE(cycle);
    CHECK(*cycle == 15100000);  // 10 s, the handshake, 5 s; B's 12 s beside them
    CHECK(ops.sections[0].waits == std::vector<meeting>{meeting{{{0, 1}, {2, 0}}}});
  }
  SECTION("C's first: A waits at its start for C's end") {
    const std::optional<std::int64_t> cycle =
        plan_waits(ops, {{0, {0, 0, pair_rule::b_first}, 0, 2}}, 100000);
    REQUIRE(cycle);
    CHECK(*cycle == 15100000);
    CHECK(ops.sections[0].waits == std::vector<meeting>{meeting{{{0, 0}, {2, 1}}}});
  }
  SECTION("contradicting orders give no plan") {
    CHECK_FALSE(plan_waits(ops,
                           {{0, {0, 0, pair_rule::a_first}, 0, 2},
                            {0, {0, 0, pair_rule::a_first}, 2, 1},
                            {0, {0, 0, pair_rule::a_first}, 1, 0}},
                           100000));
  }
}

TEST_CASE("three channels: a finding's lines give the pair of the two paths it names", "[wait_plan]") {
  job_operations ops;
  ops.channels = {1, 2, 3};
  ops.add_section();
  ops.sections[0].ops[0] = {{1, 4, 0}};
  ops.sections[0].ops[1] = {{5, 9, 0}};
  ops.sections[0].ops[2] = {{10, 12, 0}, {13, 20, 0}};
  SECTION("an error in path 3's second operation, its note in path 1's") {
    const std::vector<plan_pair> p = pairs_for_lines(ops, {15, 2});
    REQUIRE(p.size() == 1);
    CHECK(p[0] == plan_pair{0, {0, 1, pair_rule::a_first}, 0, 2});
  }
  SECTION("no partner: the operation keeps the CL's order with the other paths' operations") {
    const std::vector<plan_pair> p = pairs_for_lines(ops, {6});
    REQUIRE(p.size() == 3);
    CHECK(p[0] == plan_pair{0, {0, 0, pair_rule::a_first}, 0, 1});
    CHECK(p[1] == plan_pair{0, {0, 0, pair_rule::a_first}, 1, 2});
    CHECK(p[2] == plan_pair{0, {0, 1, pair_rule::a_first}, 1, 2});
  }
}

TEST_CASE("three channels: a code is given again only after every channel has met", "[wait_plan]") {
  diagnostic_list d;
  job_operations plan = route(nullptr, d).ops;
  plan.sections[0].waits = {meeting{{{0, 1}, {2, 0}}}, meeting{{{1, 0}, {2, 1}}}};
  // Two codes, given again in turn: the last rendezvous would take M100 while path 2 may still
  // wait at M100 P23 for path 3 (and path 1 at M101 P13): no code is free.
  machine two_codes = three_paths();
  two_codes.waits.last = 101;
  two_codes.waits.reuse = true;
  route(&plan, d, two_codes);
  REQUIRE(d.errors() == 1);
  CHECK(d.all()[0].message ==
        "no wait code left for the end of the programs: the codes M100-M101 are all held by waits of some of "
        "the job's 3 channels that may be pending at once (a code is given again only after all of them have "
        "met)");
  // Three codes: the last rendezvous takes the third.
  machine three_codes = two_codes;
  three_codes.waits.last = 102;
  diagnostic_list ok;
  const routed r = route(&plan, ok, three_codes);
  CHECK(ok.all().empty());
  CHECK(r.trace.substr(r.trace.size() - 36) == "c1:M102/123\nc2:M102/123\nc3:M102/123\n");
}

TEST_CASE("three channels: the channel outside a balance cut meets the pair where it opens and closes",
          "[wait_plan]") {
  // Paths 3 and 1 work (lines 2, 4), paths 1 and 2 cut together (6), paths 1 and 3 work again
  // (8, 10). The balance cut's own waits name paths 1 and 2 alone.
  const std::vector<event> events = {
      head(3, 1), go(2),      head(1, 3), go(4),      {5, head_event{head_select::both, 0}},
      go(6),      head(1, 7), go(8),      head(3, 9), go(10)};
  static const machine m = three_paths();
  auto run = [&](const job_operations* plan, diagnostic_list& d) {
    trace_sink sink;
    channel_router r(m, plan ? sync_policy::optimise : sync_policy::sequential, sink, d, "job.cls",
                     {1, 2, 3});
    r.track_operations(true);
    r.set_plan(plan);
    for (const event& e : events) r.route(e);
    r.finish(99);
    return routed{sink.trace, r.operations()};
  };
  diagnostic_list d;
  const job_operations plan = run(nullptr, d).ops;
  REQUIRE(plan.sections.size() == 3);
  const routed r = run(&plan, d);
  CHECK(d.all().empty());
  CHECK(r.trace ==
        "c3:2\nc1:4\n"
        "c1:M100/123\nc2:M100/123\nc3:M100/123\n"  // path 3's work before the cut is done
        "c1:M101/12\nc2:M101/12\n"                 // the balance cut opens
        "c1:6\nc2:6\n"
        "c1:M102/12\nc2:M102/12\n"                 // and closes
        "c1:M103/123\nc2:M103/123\nc3:M103/123\n"  // before path 3 works again
        "c1:8\nc3:10\n"
        "c1:M104/123\nc2:M104/123\nc3:M104/123\n");
  // Sequential: path 3 meets the pair beside the cut too (its head-switch waits name all three).
  diagnostic_list ds;
  CHECK(run(nullptr, ds).trace ==
        "c3:2\n"
        "c1:M100/123\nc2:M100/123\nc3:M100/123\nc1:4\n"  // head 3 to head 1
        "c1:M101/123\nc2:M101/123\nc3:M101/123\n"        // beside the cut's opening
        "c1:M102/12\nc2:M102/12\n"
        "c1:6\nc2:6\n"
        "c1:M103/12\nc2:M103/12\n"
        "c1:M104/123\nc2:M104/123\nc3:M104/123\n"  // beside its closing
        "c1:8\n"
        "c1:M105/123\nc2:M105/123\nc3:M105/123\nc3:10\n"  // head 1 to head 3
        "c1:M106/123\nc2:M106/123\nc3:M106/123\n");
  CHECK(ds.all().empty());
}

TEST_CASE("three channels: under sequential every path meets at each head switch", "[wait_plan]") {
  diagnostic_list d;
  // A wait of two paths could be pending, its code given again, while the other two meet at it.
  CHECK(route(nullptr, d).trace ==
        "c1:1\nc1:2\n"
        "c1:M100/123\nc2:M100/123\nc3:M100/123\nc2:4\n"
        "c1:M101/123\nc2:M101/123\nc3:M101/123\nc3:6\n"
        "c1:M102/123\nc2:M102/123\nc3:M102/123\nc1:8\n"
        "c1:M103/123\nc2:M103/123\nc3:M103/123\n");
  CHECK(d.all().empty());
}
