// The operations of a two-channel job as the router finds them, the waits a plan places between
// them (channels/router, under --sync optimise), and channels/wait_plan's timing, planning and
// pairs from a finding's lines, each asserted exactly.
#include <catch2/catch.hpp>

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <string>

#include "channels/router.hpp"
#include "channels/wait_plan.hpp"
#include "tests/router_test_support.hpp"

using namespace twinpost;

namespace {

machine twin() { return test::router_machine(2); }

using test::trace_sink;

event go(int line) { return {line, motion_event{}}; }
event tool(int line) { return {line, tool_event{}}; }
event stop(int line) {
  spindle_event s;
  s.mode = spindle_mode::off;
  return {line, s};
}
event head(int n, int line) { return {line, head_event{head_select::number, n}}; }
event grip(int line, bool release) {
  transfer_event t;
  t.release = release;
  return {line, t};
}

// Head 1: lines 1-3 (a tool change at 3 after a move: two operations); head 2: 5-6; head 1:
// 8; head 2: 10, then a spindle stop at 11 (an operation of its own).
std::vector<event> job() {
  return {go(1), go(2),      tool(3), go(3),      head(2, 4), go(5),
          go(6), head(1, 7), go(8),   head(2, 9), go(10),     stop(11)};
}

struct routed {
  std::string trace;
  job_operations ops;
};

routed route(const std::vector<event>& events, sync_policy p, const job_operations* plan, bool op_waits,
             diagnostic_list& d) {
  trace_sink sink;
  static const machine m = twin();  // the router keeps a reference
  channel_router r(m, p, sink, d, "job.cls", {1, 2});
  r.track_operations(true);
  r.set_plan(plan);
  r.set_operation_waits(op_waits);
  for (const event& e : events) r.route(e);
  r.finish(99);
  return {sink.trace, r.operations()};
}

// Two channels' rendezvous as the meetings of sides 0 and 1.
std::vector<meeting> meets(const std::vector<rendezvous>& r) {
  std::vector<meeting> out;
  for (const rendezvous& w : r) out.push_back(meeting{{{0, w.a}, {1, w.b}}});
  return out;
}

std::string ops_text(const job_operations& ops) {
  std::string s;
  for (std::size_t i = 0; i < ops.sections.size(); ++i)
    for (int side = 0; side < 2; ++side) {
      s += fmt::format("s{} c{}:", i, ops.channels[static_cast<std::size_t>(side)]);
      for (const channel_op& op : ops.sections[i].ops[side])
        s += fmt::format(" {}-{}@{}", op.first_line, op.last_line, op.segment);
      s += "\n";
    }
  return s;
}

}  // namespace

TEST_CASE("the router finds each head's operations, split at tool changes and spindle stops", "[wait_plan]") {
  diagnostic_list d;
  const routed r = route(job(), sync_policy::sequential, nullptr, false, d);
  CHECK(d.all().empty());
  // Segments: the channel's waits before the operation under the sequential policy.
  CHECK(ops_text(r.ops) ==
        "s0 c1: 1-2@0 3-3@0 8-8@2\n"
        "s0 c2: 5-6@1 10-10@3 11-11@3\n");
}

TEST_CASE("the timing post waits at every operation, so that each is a segment of its own", "[wait_plan]") {
  diagnostic_list d;
  const routed r = route(job(), sync_policy::sequential, nullptr, true, d);
  CHECK(d.all().empty());
  CHECK(ops_text(r.ops) ==
        "s0 c1: 1-2@0 3-3@1 8-8@3\n"
        "s0 c2: 5-6@2 10-10@4 11-11@5\n");
  CHECK(r.ops.operation_waits == 2);
}

TEST_CASE("a plan's waits go between the operations it names, one code per rendezvous", "[wait_plan]") {
  diagnostic_list d;
  job_operations plan = route(job(), sync_policy::sequential, nullptr, false, d).ops;
  // Channel 2 waits at its start for channel 1's first operation; channel 1 waits after its
  // three operations for channel 2's second (its stop after channel 1's cutting).
  plan.sections[0].waits = meets({{1, 0}, {3, 2}});
  const routed r = route(job(), sync_policy::optimise, &plan, false, d);
  CHECK(d.all().empty());
  CHECK(r.trace ==
        "c1:1\nc1:2\n"
        "c1:M100\nc1:3\nc1:3\n"  // after the first operation, before the tool change
        "c2:M100\nc2:5\nc2:6\n"
        "c1:8\n"
        "c2:10\n"
        "c2:M101\nc2:11\n"      // the stop after channel 1's last operation
        "c1:M101\n"             // placed at the end of channel 1's operations
        "c1:M102\nc2:M102\n");  // the last rendezvous before the footers
}

TEST_CASE("a plan that does not fit the job stops the post", "[wait_plan]") {
  diagnostic_list d;
  job_operations plan = route(job(), sync_policy::sequential, nullptr, false, d).ops;
  plan.sections[0].ops[1].pop_back();
  plan.sections[0].waits = meets({{1, 0}});
  route(job(), sync_policy::optimise, &plan, false, d);
  REQUIRE(d.errors() == 1);
  CHECK(format_diagnostic(d.all().front()) ==
        "job.cls:99: error: --sync optimise: the wait plan does not fit the job (section 1: channel 2 has 3 "
        "operations, the plan 2): an optimiser fault, nothing is written; post the job with --sync "
        "sequential\n");
}

event sync(int n, int line) {
  sync_event s;
  s.index = n;
  return {line, s};
}

// Head 1 cuts at 1, meets sync 1 at 2 and cuts at 3; head 2 cuts at 5, meets sync 1 at 6 and
// cuts at 7 and 8 (a tool change at 8: two operations).
std::vector<event> synced_job() {
  return {go(1), sync(1, 2), go(3), head(2, 4), go(5), sync(1, 6), go(7), tool(8), go(8)};
}

TEST_CASE("under optimise the job's sync records bind: each ends its channel's section", "[wait_plan]") {
  diagnostic_list d;
  // The timing post: a section a side of each sync record, and a rendezvous at each, so that
  // each operation is timed on its own.
  const routed timing = route(synced_job(), sync_policy::sequential, nullptr, true, d);
  CHECK(d.all().empty());
  CHECK(ops_text(timing.ops) ==
        "s0 c1: 1-1@0\n"
        "s0 c2: 5-5@2\n"  // after the sync record's rendezvous and the head switch's
        "s1 c1: 3-3@1\n"
        "s1 c2: 7-7@3 8-8@4\n");
  CHECK(timing.ops.kept_syncs == 1);
  // The plan: after the sync record, channel 1 waits after its operation for channel 2's first.
  job_operations plan = timing.ops;
  plan.sections[1].waits = meets({{1, 1}});
  const routed r = route(synced_job(), sync_policy::optimise, &plan, false, d);
  CHECK(d.all().empty());
  CHECK(r.trace ==
        "c1:1\n"
        "c1:M100\n"  // the job's sync 1
        "c1:3\n"
        "c2:5\n"
        "c2:M100\n"
        "c2:7\n"
        "c2:M101\nc2:8\nc2:8\n"  // the planned wait, before the tool change
        "c1:M101\n"              // placed at the end of channel 1's operations
        "c1:M102\nc2:M102\n");   // the last rendezvous before the footers
}

TEST_CASE("a sync record after work is bound in the timing post and the planned post alike", "[wait_plan]") {
  // Channel 2 meets sync 1, cuts, then the job goes to head 1 and straight back: the timing
  // post's head-switch waits must not make its second sync 1 look like the first again
  // (attack 49: the two posts bound different records, and the plan did not fit).
  const std::vector<event> events = {head(2, 1),  go(2),       sync(1, 3),  go(4),  head(1, 5),  head(2, 6),
                                     sync(1, 7),  go(8),       head(1, 9),  go(10), sync(1, 11), go(12),
                                     head(2, 13), head(1, 14), sync(1, 15), go(16)};
  diagnostic_list d;
  const routed timing = route(events, sync_policy::sequential, nullptr, true, d);
  CHECK(d.all().empty());
  CHECK(timing.ops.kept_syncs == 2);
  const routed planned = route(events, sync_policy::optimise, &timing.ops, false, d);
  CHECK(d.all().empty());
  CHECK(planned.ops.kept_syncs == 2);
}

TEST_CASE("under optimise, sync records that cross or find no partner stop the post", "[wait_plan]") {
  diagnostic_list crossed;
  route({go(1), sync(1, 2), sync(2, 3), head(2, 4), go(5), sync(2, 6), sync(1, 7)}, sync_policy::optimise,
        nullptr, false, crossed);
  REQUIRE(crossed.errors() == 1);
  CHECK(format_diagnostic(crossed.all().front()) ==
        "job.cls:6: error: sync 2 is channel 2's sync record number 1, where channel 1's number 1 is sync 1 "
        "(line 2): the two would wait at different codes, each for the other; give both channels the same "
        "sync records in the same order\n");
  diagnostic_list unmet;
  route({go(1), sync(1, 2), go(3), head(2, 4), go(5)}, sync_policy::sequential, nullptr, true, unmet);
  REQUIRE(unmet.errors() == 1);
  CHECK(format_diagnostic(unmet.all().front()) ==
        "job.cls:99: error: sync 1 of channel 1 (line 2) is not met by channel 2 by the end of the job: each "
        "sync record of the one channel needs its partner in the other before the programs meet again\n");
  // A part transfer meets every channel: channel 2's sync 1 after it would never meet channel 1's.
  machine m = twin();
  spindle_def sub;
  sub.name = "sub";
  m.spindles.push_back(sub);
  m.transfer.channel = 1;
  trace_sink sink;
  diagnostic_list before_transfer;
  channel_router r(m, sync_policy::optimise, sink, before_transfer, "job.cls", {1, 2});
  r.track_operations(true);
  for (const event& e : {go(1), sync(1, 2), head(2, 3), go(4), grip(5, false), grip(6, true), sync(1, 7)})
    r.route(e);
  r.finish(99);
  REQUIRE(before_transfer.errors() >= 1);
  CHECK(
      format_diagnostic(before_transfer.all().front()) ==
      "job.cls:5: error: sync 1 of channel 1 (line 2) is not met by channel 2 before the programs meet here: "
      "each sync record of the one channel needs its partner in the other before the programs meet again\n");
}

TEST_CASE("a part transfer is a barrier: the operations after it are a section of their own", "[wait_plan]") {
  machine m = twin();
  diagnostic_list d;
  std::vector<event> events = {go(1),         head(2, 2), go(3),      grip(4, false),
                               grip(5, true), go(6),      head(1, 7), go(8)};
  // The router needs a sub spindle and a transfer channel for TRANSFER.
  spindle_def sub;
  sub.name = "sub";
  m.spindles.push_back(sub);
  m.transfer.channel = 1;
  trace_sink sink;
  channel_router r(m, sync_policy::sequential, sink, d, "job.cls", {1, 2});
  r.track_operations(true);
  for (const event& e : events) r.route(e);
  r.finish(99);
  CHECK(d.all().empty());
  // Five sections: before the grip; between the grip's two rendezvous (its blocks); between the
  // grip and the release (a part-off goes there); between the release's two; after.
  CHECK(ops_text(r.operations()) ==
        "s0 c1: 1-1@0\n"
        "s0 c2: 3-3@1\n"
        "s1 c1:\n"
        "s1 c2:\n"
        "s2 c1:\n"
        "s2 c2:\n"
        "s3 c1:\n"
        "s3 c2:\n"
        "s4 c1: 8-8@6\n"
        "s4 c2: 6-6@5\n");
}

TEST_CASE("operations are timed by their segments, the last of a shared segment takes it", "[wait_plan]") {
  job_operations ops;
  ops.channels = {1, 2};
  for (int k = 0; k < 1; ++k) ops.add_section();
  ops.sections[0].ops[0] = {{1, 1, 0}, {2, 2, 0}, {5, 5, 2}};
  ops.sections[0].ops[1] = {{3, 3, 1}};
  time_operations(ops, [](int side, int segment) { return side * 100 + segment + 0.5; });
  CHECK(ops.sections[0].ops[0][0].us == 0);
  CHECK(ops.sections[0].ops[0][1].us == 500000);
  CHECK(ops.sections[0].ops[0][2].us == 2500000);
  CHECK(ops.sections[0].ops[1][0].us == 101500000);
}

TEST_CASE("a finding's lines become pairs in the CL's order", "[wait_plan]") {
  job_operations ops;
  ops.channels = {1, 2};
  for (int k = 0; k < 1; ++k) ops.add_section();
  ops.sections[0].ops[0] = {{1, 4, 0}, {10, 12, 0}};
  ops.sections[0].ops[1] = {{5, 9, 0}, {13, 20, 0}};
  SECTION("an error in channel 2's second operation, its note in channel 1's first") {
    const std::vector<plan_pair> p = pairs_for_lines(ops, {15, 2});
    REQUIRE(p.size() == 1);
    CHECK(p[0] == plan_pair{0, {0, 1, pair_rule::a_first}});
  }
  SECTION("channel 2's first before channel 1's second") {
    const std::vector<plan_pair> p = pairs_for_lines(ops, {11, 6});
    REQUIRE(p.size() == 1);
    CHECK(p[0] == plan_pair{0, {1, 0, pair_rule::b_first}});
  }
  SECTION("no partner: the operation keeps the CL's order with the other channel's whole section") {
    const std::vector<plan_pair> p = pairs_for_lines(ops, {11});
    REQUIRE(p.size() == 2);
    CHECK(p[0] == plan_pair{0, {1, 0, pair_rule::b_first}});
    CHECK(p[1] == plan_pair{0, {1, 1, pair_rule::a_first}});
  }
  SECTION("a line in no operation gives nothing") { CHECK(pairs_for_lines(ops, {99}).empty()); }
}

TEST_CASE("the plan is the shortest schedule of each section", "[wait_plan]") {
  job_operations ops;
  ops.channels = {1, 2};
  for (int k = 0; k < 2; ++k) ops.add_section();
  // Section 1: A 10 s, 10 s; B 10 s with B's after A's first: B waits for A's first (one wait).
  ops.sections[0].ops[0] = {{1, 1, 0, 10000000}, {3, 3, 0, 10000000}};
  ops.sections[0].ops[1] = {{2, 2, 0, 10000000}};
  // Section 2: A 5 s, B 7 s, nothing kept apart: no wait.
  ops.sections[1].ops[0] = {{5, 5, 0, 5000000}};
  ops.sections[1].ops[1] = {{6, 6, 0, 7000000}};
  const std::vector<plan_pair> pairs = {{0, {0, 0, pair_rule::a_first}}};
  const std::optional<std::int64_t> cycle = plan_waits(ops, pairs, 100000);
  REQUIRE(cycle);
  // 10 s, a handshake, 10 s (B's beside A's second); a handshake at the barrier; 7 s.
  CHECK(*cycle == 20100000 + 100000 + 7000000);
  CHECK(ops.sections[0].waits == meets({{1, 0}}));
  CHECK(ops.sections[1].waits.empty());
  SECTION("contradicting pairs give no plan") {
    // A's second before B's, and B's before A's first: A's own order forbids it.
    const std::vector<plan_pair> both = {{0, {1, 0, pair_rule::a_first}}, {0, {0, 0, pair_rule::b_first}}};
    CHECK_FALSE(plan_waits(ops, both, 100000));
  }
}

namespace {

// One channel's events noted into one operation.
channel_op noted(const std::vector<event>& events, channel_track t = {}) {
  channel_op op;
  for (const event& e : events) note_operation_event(op, t, e);
  return op;
}

event at(double x, double z, bool rapid = false) {
  motion_event m;
  m.pos = {x, 0, z};
  m.rapid = rapid;
  return {0, m};
}

event tldata(std::string kind, double value) {
  tool_data_event d;
  d.major = "TLDATA";
  d.words = {std::move(kind)};
  d.values = {value};
  return {0, d};
}

event speed(spindle_mode mode, std::string spindle = "") {
  spindle_event s;
  s.mode = mode;
  s.spindle = std::move(spindle);
  return {0, s};
}

}  // namespace

TEST_CASE("an operation is noted with the region its feed moves sweep, its tool and its part",
          "[wait_plan]") {
  SECTION("a turning pass on the lower turret (x < 0): |x|, from the rapid's end") {
    const channel_op op = noted({tldata("TURN", 0.8), tool(1), speed(spindle_mode::rpm, "main"),
                                 at(-31, 2, true), at(-29.5, 2), at(-29.5, -40), at(-31, -40)});
    CHECK(op.r0 == 29.5);
    CHECK(op.r1 == 31);
    CHECK(op.z0 == -40);
    CHECK(op.z1 == 2);
    CHECK(op.reach == 0.8);
    CHECK(op.parts == 1u);
    CHECK_FALSE(op.css);
    CHECK_FALSE(op.borrows_speed);
    CHECK_FALSE(severs_part(op));
  }
  SECTION("the speed its channel set the part's spindle to, where it cuts") {
    auto rpm = [](double v, rotation dir, std::string spindle = "") {
      spindle_event s;
      s.mode = spindle_mode::rpm;
      s.speed = v;
      s.dir = dir;
      s.spindle = std::move(spindle);
      return event{0, s};
    };
    const std::vector<event> cut = {at(31, 2, true), at(29.5, 2), at(29.5, -40)};
    auto with = [&](std::vector<event> first, channel_track t = {}) {
      first.insert(first.end(), cut.begin(), cut.end());
      return noted(first, t);
    };
    CHECK(with({rpm(1000, rotation::cw)}).rpm[0] == 1000);
    CHECK(with({rpm(1000, rotation::ccw)}).rpm[0] == -1000);
    const channel_op sub = with({rpm(800, rotation::cw, "sub")});
    CHECK(sub.rpm[0] == 0);
    CHECK(sub.rpm[1] == 800);
    CHECK(with({speed(spindle_mode::smm)}).rpm[0] == 0);  // constant surface speed: no one rpm
    // On a mill head an unnamed SPINDL may be its tool's spindle: not the part's.
    channel_track head;
    head.own_is_part = false;
    CHECK(with({rpm(3000, rotation::cw)}, head).rpm[0] == 0);
    CHECK(with({rpm(600, rotation::cw, "main")}, head).rpm[0] == 600);
    // Two speeds in one operation: more than one.
    std::vector<event> twice = {rpm(1000, rotation::cw)};
    twice.insert(twice.end(), cut.begin(), cut.end());
    twice.push_back(rpm(1200, rotation::cw));
    twice.push_back(at(29.5, -50));
    CHECK(std::isnan(noted(twice).rpm[0]));
  }
  SECTION("an unnamed spindle stop stops the spindle its channel last turned") {
    // Head 1 turned the main spindle; a transfer then put the part in the sub (the router sets
    // every track's part to the sub): its SPINDL/OFF stops the main, holding the bar, and
    // counts on both parts (review 59).
    channel_track t;
    channel_op before;
    note_operation_event(before, t, speed(spindle_mode::rpm, "main"));
    t.part = 2;
    channel_op after;
    note_operation_event(after, t, speed(spindle_mode::off));
    CHECK(after.stops);
    CHECK(after.parts == 3u);
    // Named, it stops that spindle alone.
    channel_op named;
    note_operation_event(named, t, speed(spindle_mode::off, "sub"));
    CHECK(named.parts == 2u);
  }
  SECTION("a drill: half its diameter; a tool without TLDATA reaches 10 mm; inches in mm") {
    CHECK(noted({tldata("DRILL", 16), tool(1), at(0, 5, true), at(0, -30)}).reach == 8);
    // Without a SPINDL of its own it cuts at the other channel's speed; a speed on the other
    // spindle (the sub) is not this part's.
    CHECK(noted({tool(1), at(0, 5, true), at(0, -30)}).borrows_speed);
    CHECK(noted({tool(1), speed(spindle_mode::rpm, "sub"), speed(spindle_mode::off, "main"), at(0, 5, true),
                 at(0, -30)})
              .borrows_speed);
    CHECK_FALSE(noted({tool(1), speed(spindle_mode::smm), at(0, 5, true), at(0, -30)}).borrows_speed);
    channel_track inch;
    inch.mm = 25.4;
    const channel_op op = noted({tool(1), at(1, 0, true), at(1, -1)}, inch);
    CHECK(op.reach == 10);
    CHECK(op.unknown_tool);
    CHECK(op.z0 == -25.4);
    CHECK(op.r1 == 25.4);
  }
  SECTION("a face to the centre line severs; a drill on the centre does not") {
    CHECK(severs_part(noted({at(32, 0, true), at(-0.8, 0)})));
    CHECK(severs_part(noted({at(20, -40, true), at(0, -40)})));
    // A part-off that slows down for the last millimetre, one that leaves a pip.
    CHECK(severs_part(noted({at(20, -40, true), at(1, -40), at(0, -40)})));
    CHECK(severs_part(noted({at(20, -40, true), at(0.75, -40)})));
    CHECK_FALSE(severs_part(noted({at(0, 5, true), at(0, -30)})));
  }
  SECTION("a boring bar works inside: it comes to its cut from nearer the centre line") {
    const channel_op bore = noted({tldata("TURN", 0.4), tool(1), at(7, 2, true), at(15.5, 0), at(15.5, -20),
                                   at(7, -20), at(7, 30, true)});
    CHECK(works_inside(bore));
    CHECK_FALSE(severs_part(bore));
    const channel_op od = noted({tldata("TURN", 0.8), tool(1), at(31, 2, true), at(29.5, 2), at(29.5, -40),
                                 at(31, -40), at(40, 20, true)});
    CHECK_FALSE(works_inside(od));
    // An outside finish with a lead-in from a smaller radius retracts outwards.
    const channel_op finish = noted({tldata("TURN", 0.4), tool(1), at(26, 2, true), at(28, 0), at(28, -40),
                                     at(31, -40), at(40, 20, true)});
    CHECK_FALSE(works_inside(finish));
    // Its body meets a drill on the axis of its bore, 10 mm from its cutting edge.
    job_operations ops;
    ops.channels = {1, 2};
    ops.add_section();
    channel_op drill = noted({tldata("DRILL", 8), tool(2), at(0, 5, true), at(0, -50)});
    drill.first_line = 2;
    ops.sections[0].ops[0] = {bore};
    ops.sections[0].ops[1] = {drill};
    const std::vector<plan_pair> pairs = fixed_pairs(ops, 5);
    REQUIRE(pairs.size() == 1);
    CHECK(fixed_pair_reason(ops, pairs[0], 5) ==
          "they cut closer than 9.4 mm to each other on the part in the main spindle (radius 0.0-15.5, z "
          "-20.0-2.0; "
          "radius 0.0-0.0, z -50.0-5.0; a tool working inside fills its bore to the centre line): the same "
          "material, or tools that meet");
  }
  SECTION("a groove cycle sweeps to the centre line, a drilling cycle along the axis") {
    cycle_event groove;
    groove.type = "GROOVE";
    groove.params = {{"FEDTO", 0.0}, {"RAPTO", 1.0}};
    const channel_op g = noted({at(22, -55, true), event{0, groove}, at(22, -55)});
    CHECK(severs_part(g));
    CHECK(g.z0 == -56);
    cycle_event drill;
    drill.type = "DEEP";
    drill.params = {{"FEDTO", -20.0}, {"STEP", 6.0}};
    const channel_op h = noted({at(0, 5, true), event{0, drill}, at(0, 2)});
    CHECK_FALSE(severs_part(h));
    CHECK(h.z0 == -18);
  }
  SECTION("a TLDATA after the tool call (Creo) is that tool's; none at all: unknown") {
    const channel_op creo = noted({tool(1), tldata("DRILL", 30), at(0, 5, true), at(0, -30)});
    CHECK(creo.reach == 15);
    CHECK_FALSE(creo.unknown_tool);
    CHECK(noted({tool(1), at(0, 5, true), at(0, -30)}).unknown_tool);
    // The next tool's TLDATA after the first tool's moves is not the first tool's.
    const channel_op nx =
        noted({tldata("TURN", 0.8), tool(1), at(30, 2, true), at(30, -10), tldata("DRILL", 30)});
    CHECK(nx.reach == 0.8);
  }
  SECTION("constant surface speed, the sub spindle, a stop") {
    const channel_op op = noted({speed(spindle_mode::smm, "sub"), at(10, 0, true), at(10, -5)});
    CHECK(op.unknown_tool);
    CHECK(op.css);
    CHECK(op.parts == 2u);
    CHECK(noted({event{0, stop_event{}}}).exclusive);
    const channel_op off = noted({speed(spindle_mode::off)});
    CHECK(off.stops);
    CHECK(off.parts == 1u);
    CHECK(noted({event{0, aux_event{}}}).exclusive);
    CHECK_FALSE(noted({at(10, 0, true), at(10, -5)}).exclusive);
  }
}

TEST_CASE("fixed pairs: each kept in the CL's order, with why", "[wait_plan]") {
  job_operations ops;
  ops.channels = {1, 2};
  for (int k = 0; k < 1; ++k) ops.add_section();
  auto op = [](int line, double r0, double r1, double z0, double z1) {
    channel_op o;
    o.first_line = line;
    o.r0 = r0;
    o.r1 = r1;
    o.z0 = z0;
    o.z1 = z1;
    o.reach = 1;
    o.parts = 1;
    return o;
  };
  // Channel 1: a rough of the outside (line 10), channel 2: a drill (line 20) far from it, a
  // finish of the same outside (line 30).
  ops.sections[0].ops[0] = {op(10, 28, 31, -40, 2)};
  ops.sections[0].ops[1] = {op(20, 0, 0, -30, 5), op(30, 27.5, 29, -40, 2)};
  auto pairs = fixed_pairs(ops, 5);
  REQUIRE(pairs.size() == 1);
  CHECK(pairs[0] == plan_pair{0, {0, 1, pair_rule::a_first}});
  CHECK(fixed_pair_reason(ops, pairs[0], 5) ==
        "they cut closer than 7.0 mm to each other on the part in the main spindle (radius 28.0-31.0, z "
        "-40.0-2.0; radius 27.5-29.0, z -40.0-2.0): the same material, or tools that meet");
  SECTION("on different parts nothing is kept apart") {
    ops.sections[0].ops[1][1].parts = 2;
    CHECK(fixed_pairs(ops, 5).empty());
  }
  SECTION("both under CSS") {
    ops.sections[0].ops[0][0].css = ops.sections[0].ops[1][0].css = true;
    pairs = fixed_pairs(ops, 5);
    REQUIRE(pairs.size() == 2);
    CHECK(pairs[0] == plan_pair{0, {0, 0, pair_rule::a_first}});
    CHECK(fixed_pair_reason(ops, pairs[0], 5) ==
          "both cut under constant surface speed on the part in the main spindle: each clamps the spindle's "
          "rpm");
  }
  SECTION("a cut at the speed the other sets under CSS") {
    ops.sections[0].ops[0][0].css = true;
    ops.sections[0].ops[1][0].borrows_speed = true;
    pairs = fixed_pairs(ops, 5);
    REQUIRE(pairs.size() == 2);
    CHECK(pairs[0] == plan_pair{0, {0, 0, pair_rule::a_first}});
    CHECK(
        fixed_pair_reason(ops, pairs[0], 5) ==
        "one of them cuts the part in the main spindle at a speed its CL never gives (no SPINDL of its own), "
        "the other under constant surface speed: its rpm would follow the other's diameter");
    // At an rpm the other gives (G97), its speed does not follow anything.
    ops.sections[0].ops[0][0].css = false;
    CHECK(fixed_pairs(ops, 5).size() == 1);
  }
  SECTION("the part's spindle at different speeds or directions") {
    ops.sections[0].ops[0][0].rpm[0] = 1000;
    ops.sections[0].ops[1][0].rpm[0] = 800;
    pairs = fixed_pairs(ops, 5);
    REQUIRE(pairs.size() == 2);
    CHECK(pairs[0] == plan_pair{0, {0, 0, pair_rule::a_first}});
    CHECK(fixed_pair_reason(ops, pairs[0], 5) ==
          "they turn the main spindle at different speeds or directions: each would change the other's");
    ops.sections[0].ops[1][0].rpm[0] = -1000;  // counter-clockwise
    CHECK(fixed_pairs(ops, 5).size() == 2);
    ops.sections[0].ops[1][0].rpm[0] = 1000;  // the same: they may cut at once
    CHECK(fixed_pairs(ops, 5).size() == 1);
    ops.sections[0].ops[1][0].rpm[0] = 0;  // not set by its channel
    CHECK(fixed_pairs(ops, 5).size() == 1);
    ops.sections[0].ops[1][0].rpm[0] = std::numeric_limits<double>::quiet_NaN();  // it changes it
    CHECK(fixed_pairs(ops, 5).size() == 2);
    ops.sections[0].ops[1][0].rpm[0] = 800;
    ops.sections[0].ops[1][0].parts = 2;  // on the sub spindle's part
    CHECK(fixed_pairs(ops, 5).size() == 1);
  }
  SECTION("a spindle stop on the part") {
    ops.sections[0].ops[1][0].stops = true;
    pairs = fixed_pairs(ops, 5);
    REQUIRE(pairs.size() == 2);
    CHECK(fixed_pair_reason(ops, pairs[0], 5) ==
          "one of them stops the main spindle: nothing else cuts its part meanwhile");
  }
  SECTION("a stop runs alone") {
    ops.sections[0].ops[1][0].exclusive = true;
    pairs = fixed_pairs(ops, 5);
    REQUIRE(pairs.size() == 2);
    CHECK(fixed_pair_reason(ops, pairs[0], 5) ==
          "a program stop, an M or G code or a record passed through runs alone");
  }
}

TEST_CASE("a pair the schedule keeps only by the operations' times gets a rendezvous", "[wait_plan]") {
  job_operations ops;
  ops.channels = {1, 2};
  for (int k = 0; k < 1; ++k) ops.add_section();
  // A: 10 s then 1 s; B: 20 s then 1 s. B's second after A's second: with these times B's
  // second starts at 20 s, long after A's second ended at 11 s, and no wait is needed for the
  // times; the order must not rest on them: a rendezvous A after 2, B after 1.
  ops.sections[0].ops[0] = {{1, 1, 0, 10000000}, {2, 2, 0, 1000000}};
  ops.sections[0].ops[1] = {{3, 3, 0, 20000000}, {4, 4, 0, 1000000}};
  const std::optional<std::int64_t> cycle = plan_waits(ops, {{0, {1, 1, pair_rule::a_first}}}, 100000);
  REQUIRE(cycle);
  CHECK(ops.sections[0].waits == meets({{2, 1}}));
  CHECK(*cycle == 21100000);  // B's 20 s, the handshake, B's 1 s
}

TEST_CASE("pairs another implies are left out", "[wait_plan]") {
  // A's 2 before B's 1 implies A's 1 before B's 1 and A's 2 before B's 3; B's 0 before A's 0
  // implies nothing of A-first pairs; a pair of another section is its own.
  const std::vector<plan_pair> pairs = {{0, {1, 1, pair_rule::a_first}}, {0, {2, 1, pair_rule::a_first}},
                                        {0, {2, 3, pair_rule::a_first}}, {0, {0, 0, pair_rule::b_first}},
                                        {0, {0, 2, pair_rule::b_first}}, {1, {0, 3, pair_rule::a_first}}};
  CHECK(minimal_pairs(pairs) == std::vector<std::size_t>{1, 4, 5});
}

TEST_CASE("HEAD/BOTH is one operation cut by both heads: its section keeps no pair apart", "[wait_plan]") {
  diagnostic_list d;
  const event both{4, head_event{head_select::both, 0}};
  const routed r = route({go(1), head(2, 2), go(3), both, go(5), go(6), head(1, 7), go(8)},
                         sync_policy::sequential, nullptr, false, d);
  CHECK(d.all().empty());
  CHECK(ops_text(r.ops) ==
        "s0 c1: 1-1@0\n"
        "s0 c2: 3-3@1\n"
        "s1 c1: 5-6@2\n"
        "s1 c2: 5-6@2\n"
        "s2 c1: 8-8@3\n"
        "s2 c2:\n");
  REQUIRE(r.ops.sections.size() == 3);
  CHECK(!r.ops.sections[0].together);
  CHECK(r.ops.sections[1].together);
  CHECK(!r.ops.sections[2].together);
  // Its operations are of unknown tools: outside the frame they would be kept in the CL's order.
  const std::vector<plan_pair> pairs = fixed_pairs(r.ops, 5);
  REQUIRE(pairs.size() == 1);
  CHECK(pairs[0] == plan_pair{0, {0, 0, pair_rule::a_first}});
  // A finding inside the frame names no pair of it either.
  CHECK(pairs_for_lines(r.ops, {5, 6}).empty());
}
