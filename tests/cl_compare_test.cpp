// The comparison of a program with its CL (analysis/cl_compare.hpp): hand-made program lines
// and CL records, findings asserted to the letter.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "analysis/cl_compare.hpp"
#include "file_test_support.hpp"
#include "machine_test_support.hpp"
#include "machines/machine_loader.hpp"

using namespace twinpost;

namespace {

// One channel of a machine, fed lines and records; `text()` is what it found.
struct compared {
  compared(const std::string& machine_name, int channel)
      : m(load_machine(machine_name)),
        cmp(m, m.channels[static_cast<std::size_t>(channel - 1)], diags, "job.cls") {
    for (const char* l : {"%", "O1000", "G0 G18 G21 G40 G54 G80 G99"}) cmp.line(l);
  }
  machine m;
  diagnostic_list diags;
  cl_comparison cmp;
  int next = 10;
  void lines(std::initializer_list<const char*> ls) {
    for (const char* l : ls) cmp.line(l);
  }
  void feed(double value, feed_mode mode) { cmp.record({next++, feed_event{mode, value}, 1}, false); }
  // A GOTO to `pos` with the tool along `axis`.
  void to(vec3 pos, vec3 axis, bool rapid = true) {
    motion_event mv;
    mv.pos = pos;
    mv.axis = axis;
    mv.rapid = rapid;
    cmp.record({next++, mv, 1}, false);
  }
  void go(double x, double z, bool rapid = false, bool both = false) {
    motion_event mv;
    mv.pos = {x, 0, z};
    mv.rapid = rapid;
    cmp.record({next++, mv, 1}, both);
  }
  std::string text() const {
    std::string out;
    for (const diagnostic& d : diags.all()) out += format_diagnostic(d);
    return out;
  }
};

}  // namespace

TEST_CASE("cl comparison: the tool tip of a lathe program against the CL", "[analysis][cl_compare]") {
  compared c("fanuc-0itd-twin", 1);
  c.feed(0.2, feed_mode::per_rev);
  c.lines({"T0101", "G97 S1000 M3", "G0 X80. Z2."});
  c.go(40, 2, true);
  c.lines({"G1 Z-20. F0.2"});
  c.go(40, -20);
  CHECK(c.text().empty());
  CHECK(c.cmp.compared() == 2);
  // X is a diameter: X81. puts the tip 0.5 mm off the CL's radius 40.
  c.lines({"X81. Z-30."});
  c.go(40, -30);
  CHECK(c.text() ==
        "job.cls:13:1: error: channel 1: the program does not put the tool tip on this record's point (the "
        "part "
        "frame, mm): x 40.500 where the CL has 40.000 (0.500 mm off), after the block `X81. Z-30.`\n");
}

TEST_CASE("cl comparison: the tolerances at their edges", "[analysis][cl_compare]") {
  // Issue 37: the tip within 0.002 mm, the tool axis within 0.001 degree, the feed within 0.5 %.
  auto tip = [](const char* block) {
    compared c("fanuc-0itd-twin", 1);
    c.lines({"T0101", "G97 S1000 M3", "G0 X80. Z2."});
    c.go(40, 2, true);
    c.lines({block});
    c.go(40, -20, true);
    return c.text();
  };
  CHECK(tip("Z-20.").empty());
  CHECK(tip("X80.002 Z-20.").empty());  // 0.001 mm off on the radius
  CHECK(tip("X80.006 Z-20.") ==
        "job.cls:11:1: error: channel 1: the program does not put the tool tip on this record's point (the "
        "part frame, mm): x 40.003 where the CL has 40.000 (0.003 mm off), after the block `X80.006 "
        "Z-20.`\n");  // 0.003 mm
  CHECK(tip("X80. Z-20.003") ==
        "job.cls:11:1: error: channel 1: the program does not put the tool tip on this record's point (the "
        "part frame, mm): z -20.003 where the CL has -20.000 (0.003 mm off), after the block `X80. "
        "Z-20.003`\n");
  auto feed = [](const char* f) {
    compared c("fanuc-0itd-twin", 1);
    c.feed(0.2, feed_mode::per_rev);
    c.lines({"T0101", "G97 S1000 M3", "G0 X80. Z2."});
    c.go(40, 2, true);
    c.lines({fmt::format("G1 Z-20. {}", f).c_str()});
    c.go(40, -20);
    return c.text();
  };
  CHECK(feed("F0.2").empty());
  CHECK(feed("F0.2009").empty());  // 0.45 %
  CHECK(feed("F0.2011") ==
        "job.cls:12:1: error: channel 1: the CL feeds at 0.2 mm/rev here, the program at 0.2011 mm/rev "
        "(F0.2011 under G99)\n");  // 0.55 %
  CHECK(feed("F0.1989") ==
        "job.cls:12:1: error: channel 1: the CL feeds at 0.2 mm/rev here, the program at 0.1989 mm/rev "
        "(F0.1989 under G99)\n");
  auto axis = [](double degrees) {
    compared c("integrex-i200st", 1);
    c.lines({"T12 M6", "M901", "M200", "G10.9 X0", "G97 S2500 M3", "M108", "G0 G53 B0.", "M107", "G0 C0.",
             "G0 G43 H#3020 X20. Y0. Z2."});
    const double t = degrees * std::numbers::pi / 180;
    c.to({20, 0, 2}, {std::sin(t), 0, std::cos(t)});
    return c.text();
  };
  CHECK(axis(0.0009).empty());
  CHECK(axis(0.0011) ==
        "job.cls:10:1: error: channel 1: the CL's tool axis here is (0.0000,0.0000,1.0000), the program's "
        "head points the tool along (0.0000,0.0000,1.0000) in the part frame (0.001 degrees off): the head "
        "was indexed by `G0 G53 B0.` at line 10 of the program\n");
}

TEST_CASE("cl comparison: the lower turret's mirrored X and the sub spindle's reversed Z",
          "[analysis][cl_compare]") {
  compared c("fanuc-0itd-twin", 2);
  c.lines({"T0101", "G55", "G0 X-80. Z-2."});
  c.go(40, 2, true);
  CHECK(c.text().empty());
  c.lines({"G0 X80."});
  c.go(40, 2, true);
  CHECK(c.text() ==
        "job.cls:11:1: error: channel 2: the program does not put the tool tip on this record's point (the "
        "part "
        "frame, mm): x -40.000 where the CL has 40.000 (80.000 mm off), after the block `G0 X80.`\n");
}

TEST_CASE("cl comparison: the feed mode a user block changed", "[analysis][cl_compare]") {
  // Issue 37, item 4: `G99` from a user block, then the CL's 150 mm/min written as F150.
  compared c("fanuc-0itd-twin", 1);
  c.feed(150, feed_mode::per_minute);
  c.lines({"T0101", "G97 S1000 M3", "G0 X80. Z2.", "G98"});
  c.go(40, 2, true);
  c.lines({"G99", "G1 Z-20. F150."});
  c.go(40, -20);
  CHECK(c.text() ==
        "job.cls:12:1: error: channel 1: the CL feeds at 150 mm/min here, the program at 150000 mm/min "
        "(F150. under "
        "G99 at 1000 rpm)\n");
  // Under G98 the same F is right; per revolution, F0.15 at 1000 rpm is 150 mm/min.
  compared d("fanuc-0itd-twin", 1);
  d.feed(150, feed_mode::per_minute);
  d.lines({"T0101", "G97 S1000 M3", "G0 X80. Z2."});
  d.go(40, 2, true);
  d.lines({"G1 Z-20. F0.15"});
  d.go(40, -20);
  CHECK(d.text().empty());
  d.lines({"Z-30. F0.16"});
  d.go(40, -30);
  CHECK(d.text() ==
        "job.cls:13:1: error: channel 1: the CL feeds at 150 mm/min here, the program at 160 mm/min (F0.16 "
        "under "
        "G99 at 1000 rpm)\n");
}

TEST_CASE("cl comparison: a feed move written as a rapid", "[analysis][cl_compare]") {
  compared c("fanuc-0itd-twin", 1);
  c.feed(0.2, feed_mode::per_rev);
  c.lines({"T0101", "G97 S1000 M3", "G0 X80. Z2."});
  c.go(40, 2, true);
  c.lines({"Z-20."});
  c.go(40, -20);
  CHECK(c.text() ==
        "job.cls:12:1: error: channel 1: the CL asks for a feed move here, but the program moves in rapid: "
        "`Z-20.`\n");
  // A rapid among the blocks of one feed move (a user block plunging to just short of the end):
  // the record ends where the CL says, in G1, but most of the cut was a rapid.
  compared d("fanuc-0itd-twin", 1);
  d.feed(0.2, feed_mode::per_rev);
  d.lines({"T0101", "G97 S1000 M3", "G0 X80. Z2."});
  d.go(40, 2, true);
  d.lines({"G0 Z-29.", "G1 Z-30. F0.2"});
  d.go(40, -30);
  CHECK(d.text() ==
        "job.cls:12:1: error: channel 1: the CL asks for a feed move here, but the program moves in rapid: "
        "`G0 Z-29.`\n");
}

TEST_CASE("cl comparison: an axis left at its reference point", "[analysis][cl_compare]") {
  compared c("fanuc-0itd-twin", 1);
  c.lines({"T0101", "G0 X80. Z2.", "G28 U0.", "G0 Z5."});
  c.go(40, 5, true);
  CHECK(
      c.text() ==
      "job.cls:10:1: error: channel 1: the program does not put the tool tip on this record's point (the "
      "part "
      "frame, mm): X is where G28 at line 6 of the program left it, not at the CL's 40.000, after the block "
      "`G0 Z5.`\n");
  // Z named in G28 (as W0.) is at its reference point until a Z word moves it again.
  compared d("fanuc-0itd-twin", 1);
  d.lines({"T0101", "G0 X80. Z2.", "G28 W0.", "G0 X40."});
  d.go(20, 2, true);
  CHECK(d.text() ==
        "job.cls:10:1: error: channel 1: the program does not put the tool tip on this record's point (the "
        "part "
        "frame, mm): Z is where G28 at line 6 of the program left it, not at the CL's 2.000, after the block "
        "`G0 "
        "X40.`\n");
}

TEST_CASE("cl comparison: what it passes over", "[analysis][cl_compare]") {
  compared c("fanuc-0itd-twin", 1);
  c.lines({"T0101", "G0 X80. Z2."});
  c.go(10, 2, true, true);                // a HEAD/BOTH copy
  c.lines({"G83 Z-20. R2. Q5000 F0.1"});  // a canned cycle: its end is the cycle's
  c.go(0, -20);
  CHECK(c.text().empty());
  CHECK(c.cmp.compared() == 0);
  CHECK(c.cmp.passed_over() == 2);
  // G80 ends the cycle: compared again, from the axes the cycle left unknown.
  c.lines({"G80", "G0 X80. Z5."});
  c.go(40, 5, true);
  CHECK(c.cmp.compared() == 1);
  CHECK(c.text().empty());
}

TEST_CASE("cl comparison: the tool and the spindle at a cut", "[analysis][cl_compare]") {
  compared c("fanuc-0itd-twin", 1);
  c.cmp.record({c.next++, tool_event{tool_source::loadtl, 3, 3}, 1}, false);
  spindle_event s;
  s.speed = 1000;
  s.dir = rotation::cw;
  c.cmp.record({c.next++, s, 1}, false);
  c.feed(0.2, feed_mode::per_rev);
  // T0505 on the template T{tool:02}{offset:02}: tool 5 where the CL loaded tool 3.
  c.lines({"T0505", "G97 S1000 M3", "G0 X80. Z2."});
  c.go(40, 2, true);
  CHECK(c.text() ==
        "job.cls:13:1: error: channel 1: the CL cuts with tool 3 here (the tool call at line 10), the "
        "program with "
        "tool 5 (T0505, read by the tool call T{tool:02}{offset:02})\n");
  // The spindle at a cut, the CL's SPINDL/RPM,1000,CLW against the program's spindle block.
  auto cut_under = [&s](const char* spindle_block) {
    compared d("fanuc-0itd-twin", 1);
    d.cmp.record({d.next++, s, 1}, false);
    d.feed(0.2, feed_mode::per_rev);
    d.lines({"T0101", spindle_block, "G0 X80. Z2."});
    d.go(40, 2, true);
    d.lines({"G1 Z-20. F0.2"});
    d.go(40, -20);
    return d.text();
  };
  CHECK(cut_under("G97 S1000 M3").empty());
  CHECK(cut_under("G97 S1000 M4") ==
        "job.cls:13:1: error: channel 1: the CL cuts with the spindle turning clockwise at 1000 rpm here "
        "(SPINDL at "
        "line 10), but the program's main spindle turns counter-clockwise (M4)\n");
  CHECK(cut_under("G97 S1200 M3") ==
        "job.cls:13:1: error: channel 1: the CL cuts with the spindle turning clockwise at 1000 rpm here "
        "(SPINDL at "
        "line 10), but the program's main spindle turns at S1200\n");
  CHECK(cut_under("G96 S1000 M3") ==
        "job.cls:13:1: error: channel 1: the CL cuts with the spindle turning clockwise at 1000 rpm here "
        "(SPINDL at "
        "line 10), but the program's main spindle turns under constant surface speed (G96 S1000)\n");
}

TEST_CASE("cl comparison: units, decimal points and the G91 a home block leaves", "[analysis][cl_compare]") {
  // G20 in a metric program: every word in inches.
  compared c("fanuc-0itd-twin", 1);
  c.lines({"T0101", "G20", "G0 X44. Z2."});
  c.go(22, 2, true);
  CHECK(c.text() ==
        "job.cls:10:1: error: channel 1: the program does not put the tool tip on this record's point (the "
        "part "
        "frame, mm): x 558.800 where the CL has 22.000 (536.800 mm off); z 50.800 where the CL has 2.000 "
        "(48.800 mm "
        "off), after the block `G0 X44. Z2.`\n");
  // X44 without a point is 44 least increments: 0.044 mm of diameter.
  compared d("fanuc-0itd-twin", 1);
  d.lines({"T0101", "G0 X44 Z2."});
  d.go(22, 2, true);
  CHECK(d.text() ==
        "job.cls:10:1: error: channel 1: the program does not put the tool tip on this record's point (the "
        "part "
        "frame, mm): x 0.022 where the CL has 22.000 (21.978 mm off), after the block `G0 X44 Z2.`\n");
  // A home block that leaves G91: the next move's words are increments from the reference point.
  compared e("fanuc-0itd-twin", 1);
  e.lines({"G91 G28 U0. W0.", "T0101", "G0 X44. Z2."});
  e.go(22, 2, true);
  CHECK(
      e.text() ==
      "job.cls:10:1: error: channel 1: the program does not put the tool tip on this record's point (the "
      "part "
      "frame, mm): X is where G28 at line 4 of the program left it, not at the CL's 22.000 (G91 is in force: "
      "the "
      "axis words after it are increments); Z is where G28 at line 4 of the program left it, not at the CL's "
      "2.000 (G91 is in force: the axis words after it are increments), after the block `G0 X44. Z2.`\n");
}

TEST_CASE("cl comparison: a dwell's seconds and the feed mode it is written under",
          "[analysis][cl_compare]") {
  // Issue 37, item 10: the CL's DELAY/2 as the post writes it under feed per revolution: under
  // G98 for the dwell, G99 again after it.
  const auto delay = [](compared& c, double s) { c.cmp.record({c.next++, delay_event{s, false}, 1}, false); };
  compared c("fanuc-0itd-twin", 1);
  c.lines({"T0101", "G97 S1000 M3", "G0 X80. Z2.", "G98 G4 U2.", "G99"});
  delay(c, 2);
  CHECK(c.text().empty());
  // The fix undone: the dwell under G99, where a control set to count it in revolutions waits
  // two turns of the spindle.
  compared d("fanuc-0itd-twin", 1);
  d.lines({"T0101", "G97 S1000 M3", "G0 X80. Z2.", "G4 U2."});
  delay(d, 2);
  CHECK(d.text() ==
        "job.cls:10:1: error: channel 1: the CL dwells 2 s here (DELAY), the program under G99 (`G4 U2.`): a "
        "control that counts a dwell in spindle revolutions under feed per revolution (Fanuc parameter "
        "3405#1) waits 2 revolutions\n");
  // U2 without a point is 2 ms where decimal-point programming is off; no dwell at all.
  compared e("fanuc-0itd-twin", 1);
  e.lines({"G98", "G4 U2"});
  delay(e, 2);
  CHECK(e.text() ==
        "job.cls:10:1: error: channel 1: the CL dwells 2 s here (DELAY), the program 0.002 s (`G4 U2`)\n");
  compared f("fanuc-0itd-twin", 1);
  f.lines({"G98", "G4 U2."});
  delay(f, 2);  // (its dwell)
  delay(f, 1.5);
  CHECK(f.text() ==
        "job.cls:11:1: error: channel 1: the CL dwells 1.5 s here (DELAY), the program does not\n");
  // Milliseconds in P on the Integrex: G94 for the dwell; under G95 it is named.
  compared g("integrex-i200st", 1);
  g.lines({"G95", "G94 G4 P2000", "G95"});
  delay(g, 2);
  g.lines({"G4 P1500"});
  delay(g, 1.5);
  CHECK(
      g.text() ==
      "job.cls:11:1: error: channel 1: the CL dwells 1.5 s here (DELAY), the program under G95 (`G4 P1500`): "
      "a control that counts a dwell in spindle revolutions under feed per revolution (Fanuc parameter "
      "3405#1) waits 1.5 revolutions\n");
  // No feed mode set yet (the Integrex's header sets none): a control may keep the last
  // program's G95 (attack 71 F3).
  compared h("integrex-i200st", 1);
  h.lines({"G4 P2000"});
  delay(h, 2);
  CHECK(h.text() ==
        "job.cls:10:1: error: channel 1: the CL dwells 2 s here (DELAY), the program with no feed mode set "
        "(`G4 "
        "P2000`): a control that keeps G95 from the last program and counts a dwell in spindle revolutions "
        "under it (Fanuc parameter 3405#1) waits 2 revolutions; set G94 first\n");
  // A wait's event blocks dwell too, written before the DELAY's own at its record: the DELAY is
  // held to its own, the last (attack 71 F1).
  compared w("fanuc-0itd-twin", 1);
  w.lines({"G4 U0.3", "M100", "G4 U0.5", "G98 G4 U2.", "G99"});
  delay(w, 2);
  CHECK(w.text().empty());
  // A template with a format spec: its word is read as written (`U2` without its point is 2 ms
  // where decimal-point programming is off: attack 71 F2).
  machine m = load_machine("fanuc-0itd-twin");
  m.codes.dwell = "G4 U{seconds:g}";
  diagnostic_list found;
  cl_comparison spec(m, m.channels[0], found, "job.cls");
  for (const char* l : {"G0 G18 G21 G40 G54 G80 G99", "G98 G4 U2", "G99"}) spec.line(l);
  spec.record({7, delay_event{2, false}, 1}, false);
  REQUIRE(found.all().size() == 1);
  CHECK(format_diagnostic(found.all()[0]) ==
        "job.cls:7:1: error: channel 1: the CL dwells 2 s here (DELAY), the program 0.002 s (`G98 G4 U2`)\n");
}

TEST_CASE("cl comparison: an operation for another CAM tool, cut with no tool call between",
          "[analysis][cl_compare]") {
  // Issue 37, item 6: post --tool 1 on an NX file of two operations, its writer's refusal undone.
  const auto op = [](compared& c, const char* text) {
    c.cmp.record({c.next++, text_event{text_kind::toolpath, "TOOL PATH", text}, 1}, false);
  };
  const auto cut = [](compared& c) {
    c.lines({"T01 M6", "G54", "S1000 M3", "G0 A0.", "G0 G43 H1 X0. Y0. Z5."});
    c.to({0, 0, 5}, {0, 0, 1});
    c.lines({"G1 Z-2. F250."});
    c.to({0, 0, -2}, {0, 0, 1}, false);
  };
  compared c("rotary-4axis", 1);
  op(c, "FACE,TOOL,MILL-20MM");
  cut(c);
  op(c, "DRILL_HOLE,TOOL,DRILL-8MM");
  c.lines({"G0 X30. Y0. Z5."});
  c.to({30, 0, 5}, {0, 0, 1});
  CHECK(
      c.text() ==
      "job.cls:14:1: error: channel 1: the CL's operation (TOOL PATH at line 13) names the tool 'DRILL-8MM', "
      "but the program has tool 1 (T01) in the spindle here, held since the CL named 'MILL-20MM' (line 10), "
      "and calls no tool between\n");
  // A tool call between, in the program or in the CL (LOAD/TOOL), and two names the machine's
  // tool table gives one tool: quiet.
  compared d("rotary-4axis", 1);
  op(d, "FACE,TOOL,MILL-20MM");
  cut(d);
  op(d, "DRILL_HOLE,TOOL,DRILL-8MM");
  d.lines({"T02 M6", "G0 G43 H2 X30. Y0. Z5."});
  d.to({30, 0, 5}, {0, 0, 1});
  op(d, "SPOT,TOOL,SPOT-10");
  tool_event call;
  call.tool = 2;
  d.cmp.record({d.next++, call, 1}, false);
  d.lines({"G0 X40. Y0. Z5."});
  d.to({40, 0, 5}, {0, 0, 1});
  CHECK(d.text().empty());
  compared e("rotary-4axis", 1);
  tool_def t;
  t.number = 1;
  t.kind = "mill";
  t.name = "MILL-20MM";
  tool_def u = t;
  u.name = "ROUGH-20";
  e.m.tools = {t, u};
  op(e, "FACE,TOOL,MILL-20MM");
  cut(e);
  op(e, "ROUGH,TOOL,ROUGH-20");
  e.lines({"G0 X30. Y0. Z5."});
  e.to({30, 0, 5}, {0, 0, 1});
  CHECK(e.text().empty());
}

TEST_CASE("cl comparison: a mill's tool length offset", "[analysis][cl_compare]") {
  const std::string mill = std::string(TWINPOST_SOURCE_DIR) + "/bench/bench-mill.toml";
  compared c(mill, 1);
  c.lines({"G90 G17 G40 G49 G80", "T01 M6", "S1000 M3", "G0 X0. Y0. Z5."});
  c.go(0, 5, true);
  CHECK(c.text() ==
        "job.cls:10:1: error: channel 1: the program moves Z with no tool length offset in force (G43 H..): "
        "Z is "
        "then the spindle's gauge line, one tool length below the CL's tip; give the channel a length offset "
        "(channel.length_offset = \"G43 H{offset:02}\"), after the block `G0 X0. Y0. Z5.`\n");
  compared d(mill, 1);
  d.lines({"G90 G17 G40 G49 G80", "T01 M6", "S1000 M3", "G0 G43 H01 X0. Y0. Z5."});
  d.go(0, 5, true);
  CHECK(d.text().empty());
  CHECK(d.cmp.compared() == 1);
}

TEST_CASE("cl comparison: a part frame it does not know is passed over", "[analysis][cl_compare]") {
  // Offset data written (G10, #5223), a coordinate setting (G52 Z-5. from an INSERT, attack 50
  // F3), a work offset no spindle names (G56): not followed. Passed over with a warning once a
  // channel where the program set the frame itself; G56 is a setup's other part.
  for (const char* frame : {"G10 L2 P1 Z-5.", "#5223=-5.", "G52 Z-5.", "G56"}) {
    compared c("fanuc-0itd-twin", 1);
    c.lines({"T0101", frame, "G0 X80. Z2."});
    c.go(10, 2, true);
    c.go(20, 2, true);
    CHECK(c.text() ==
          (std::string(frame) == "G56"
               ? std::string()
               : fmt::format("job.cls:10:1: warning: channel 1: this record and the channel's later "
                             "ones are not held to the CL: the program sets the part frame itself at "
                             "line 5 of its program (`{}`)\n",
                             frame)));
    CHECK(c.cmp.passed_over() == 2);
  }
}

TEST_CASE("cl comparison: the records under a user's mirror image are passed over with a warning",
          "[analysis][cl_compare]") {
  compared c("fanuc-0itd-twin", 1);
  c.lines({"T0101", "G51.1 Z0.", "G0 X80. Z2."});
  c.go(10, 2, true);
  c.go(20, 2, true);
  c.lines({"G50.1 Z0.", "G0 X80. Z5."});
  c.go(40, 5, true);
  CHECK(c.text() ==
        "job.cls:10:1: warning: channel 1: the records under a mirror image or a scaling are not held to the "
        "CL, "
        "from this one on: the program sets it at line 5 of its program (`G51.1 Z0.`)\n");
  CHECK(c.cmp.passed_over() == 2);
  CHECK(c.cmp.compared() == 1);
}

TEST_CASE("cl comparison: an arc's sense, centre and R", "[analysis][cl_compare]") {
  // A quarter turn from x22 z-30 to x27 z-35 about x27 z-30, counter-clockwise about -Y: G2 on
  // the upper turret in G18 (the Fanuc ZX plane, whose normal is +Y).
  auto run = [](const char* block) {
    compared c("fanuc-0itd-twin", 1);
    c.feed(0.2, feed_mode::per_rev);
    c.lines({"T0101", "G97 S1000 M3", "G0 X44. Z2."});
    c.go(22, 2, true);
    c.lines({"G1 Z-30. F0.2"});
    c.go(22, -30);
    c.lines({block});
    arc_event a;
    a.start = {22, 0, -30};
    a.end = {27, 0, -35};
    a.center = {27, 0, -30};
    a.normal = {0, -1, 0};
    a.radius = 5;
    a.ccw = true;
    c.cmp.record({c.next++, a, 1}, false);
    return c.text();
  };
  CHECK(run("G2 X54. Z-35. I5. K0.").empty());
  CHECK(run("G2 X54. Z-35. R5.").empty());
  CHECK(run("G3 X54. Z-35. I5. K0.") ==
        "job.cls:13:1: error: channel 1: the CL's arc turns counter-clockwise about (0,-1,0) here, the "
        "program's G3 "
        "the other way round: `G3 X54. Z-35. I5. K0.`\n");
  CHECK(run("G2 X54. Z-35. I6. K0.") ==
        "job.cls:13:1: error: channel 1: the program's arc centre is 1.000 mm from the CL's (x 28.000 y "
        "0.000 z "
        "-30.000 where the CL has x 27.000 y 0.000 z -30.000, the part frame in mm): `G2 X54. Z-35. I6. "
        "K0.`\n");
  CHECK(run("G2 X54. Z-35. R-5.") ==
        "job.cls:13:1: error: channel 1: the CL's arc has a radius of 5.000 mm over 90.0 degrees here, the "
        "program's R -5 (the long way round: R < 0 is more than half a turn): `G2 X54. Z-35. R-5.`\n");
  CHECK(run("G17 G2 X54. Z-35. I5. J0.") ==
        "job.cls:13:1: error: channel 1: the CL's arc turns about (0,-1,0) here, the program's G2 in G17 "
        "about its "
        "Z axis: `G17 G2 X54. Z-35. I5. J0.`\n");
}

TEST_CASE("cl comparison: the second attack's ways past it", "[analysis][cl_compare]") {
  spindle_event s;
  s.speed = 1000;
  s.dir = rotation::cw;
  // A cut after `lines`, on tool 3 offset 3 at 1000 rpm, coolant flood, 0.2 mm/rev.
  auto cut_after = [&s](std::initializer_list<const char*> lines, const char* machine = "fanuc-0itd-twin") {
    compared c(machine, 1);
    c.cmp.record({c.next++, tool_event{tool_source::loadtl, 3, 3}, 1}, false);
    c.cmp.record({c.next++, s, 1}, false);
    c.cmp.record({c.next++, coolant_event{"FLOOD", ""}, 1}, false);
    c.feed(0.2, feed_mode::per_rev);
    c.lines(lines);
    c.go(40, 2, true);
    c.lines({"G1 Z-20. F0.2"});
    c.go(40, -20);
    return c.text();
  };
  CHECK(cut_after({"T0303", "G97 S1000 M3", "M8", "G0 X80. Z2."}).empty());
  CHECK(
      cut_after({"T0300", "G97 S1000 M3", "M8", "G0 X80. Z2."}) ==
      "job.cls:14:1: error: channel 1: the CL cuts with tool 3 on offset 3 here (the tool call at line 10), "
      "the "
      "program on offset 0 (T0300): offset 0 cancels the tool's offset, and the tip runs where the turret's "
      "reference point is\n");
  CHECK(cut_after({"T0303", "G97 S1000 M3", "G0 X80. Z2."}).empty());  // no coolant code yet: not known
  CHECK(cut_after({"T0303", "G97 S1000 M3", "M8", "M9", "G0 X80. Z2."}) ==
        "job.cls:15:1: error: channel 1: the CL cuts with the coolant flood here (COOLNT at line 12), the "
        "program "
        "with it off (`M9`)\n");
  CHECK(cut_after({"T0303", "G97 S[1000] M3", "M8", "G0 X80. Z2."}) ==
        "job.cls:15:1: error: channel 1: the program cuts here under S[1000], a value known only when the "
        "block "
        "runs: the comparison with the CL cannot hold it to the CL's spindle speed; write the number\n");
  CHECK(cut_after({"T0303", "G97 S1000 M3", "M8", "/G0 X80. Z2."}) ==
        "job.cls:14:1: error: channel 1: the program has a block under block delete before this record (`/G0 "
        "X80. "
        "Z2.`): the operator's switch decides whether it runs, so where the tool is here depends on it; "
        "write it "
        "without the '/'\n");
}

TEST_CASE("cl comparison: the CSS clamp, a thread's lead, M6 T in one block", "[analysis][cl_compare]") {
  compared c("fanuc-0itd-twin", 1);
  spindle_event css;
  css.mode = spindle_mode::smm;
  css.speed = 200;
  css.dir = rotation::cw;
  css.max_rpm = 1500;
  c.cmp.record({c.next++, css, 1}, false);
  c.feed(0.2, feed_mode::per_rev);
  c.lines({"T0101", "G50 S1500", "G96 S200 M3", "G0 X80. Z2.", "G50 S4000"});
  c.go(40, 2, true);
  c.lines({"G1 Z-20. F0.2"});
  c.go(40, -20);
  CHECK(c.text() ==
        "job.cls:13:1: error: channel 1: the CL cuts with the spindle turning clockwise at 200 m/min here "
        "(SPINDL at "
        "line 10), but the program's main spindle is clamped at 4000 rpm, where the CL holds it to 1500\n");
  // THREAD/TURN,LEAD,1.5: the G32 pass's F is the lead.
  compared t("fanuc-0itd-twin", 1);
  t.cmp.record({t.next++, thread_event{true, 1.5, 1}, 1}, false);
  t.lines({"T0101", "G0 X80. Z2."});
  t.go(40, 2, true);
  t.lines({"G32 Z-20. F2."});
  t.go(40, -20);
  CHECK(t.text() ==
        "job.cls:12:1: error: channel 1: the CL threads with a lead of 1.5 mm here, the program's G32 with 2 "
        "mm "
        "(F2.)\n");
  // `M6 T02`: the control changes to tool 2, wherever the T stands in the block.
  const std::string mill = std::string(TWINPOST_SOURCE_DIR) + "/bench/bench-mill.toml";
  compared m(mill, 1);
  m.cmp.record({m.next++, tool_event{tool_source::loadtl, 2, 2}, 1}, false);
  m.lines({"G90 G17 G40 G49 G80", "M6 T02", "G0 G43 H02 X0. Y0. Z5."});
  m.go(0, 5, true);
  CHECK(m.text().empty());
}

TEST_CASE("cl comparison: the third attack's ways past it", "[analysis][cl_compare]") {
  // A mill's H00 in G43 mode: no offset, Z is the gauge line.
  const std::string mill = std::string(TWINPOST_SOURCE_DIR) + "/bench/bench-mill.toml";
  compared h(mill, 1);
  h.cmp.record({h.next++, tool_event{tool_source::loadtl, 3, 3}, 1}, false);
  h.lines({"G90 G17 G40 G49 G80", "T03 M6", "G0 G43 H03 X0. Y0. Z5."});
  h.go(0, 5, true);
  CHECK(h.text().empty());
  h.lines({"H00", "G0 Z2."});
  h.go(0, 2, true);
  CHECK(h.text() ==
        "job.cls:12:1: error: channel 1: the program moves Z with no tool length offset in force (G43 H..): "
        "Z is "
        "then the spindle's gauge line, one tool length below the CL's tip; give the channel a length offset "
        "(channel.length_offset = \"G43 H{offset:02}\"), after the block `G0 Z2.`\n");
  // The spindle the CL names: MAIN stopped while the sub turns.
  compared s("fanuc-0itd-twin", 1);
  spindle_event main;
  main.speed = 1500;
  main.dir = rotation::cw;
  main.spindle = "main";
  s.cmp.record({s.next++, main, 1}, false);
  s.feed(0.2, feed_mode::per_rev);
  s.lines({"T0101", "G97 S1500 M3", "G0 X44. Z2."});
  s.go(22, 2, true);
  s.lines({"M5", "S1500 M103", "G1 Z-30. F0.2"});
  s.go(22, -30);
  CHECK(s.text() ==
        "job.cls:13:1: error: channel 1: the CL cuts with the spindle turning clockwise at 1500 rpm here "
        "(SPINDL at "
        "line 10), but the program's main spindle is stopped\n");
}

TEST_CASE("cl comparison: G-code system C's units are G70 and G71", "[analysis][cl_compare]") {
  const machine m = test::system_c_twin();
  diagnostic_list diags;
  cl_comparison cmp(m, m.channels[0], diags, "job.cls");
  cmp.record({8, feed_event{feed_mode::per_rev, 0.2}, 1}, false);
  for (const char* l : {"%", "O1000", "G0 G18 G71 G40 G54 G80 G90 G99", "T0101", "G0 X44. Z2."}) cmp.line(l);
  motion_event mv;
  mv.pos = {22, 0, 2};
  mv.rapid = true;
  cmp.record({9, mv, 1}, false);
  CHECK(diags.all().empty());
  // G70 is inch in system C (G20 is its OD turning cycle): the next words are inches.
  cmp.line("G70");
  cmp.line("G1 X44. Z-30. F0.2");
  mv.pos = {22, 0, -30};
  mv.rapid = false;
  cmp.record({10, mv, 1}, false);
  REQUIRE(diags.all().size() == 2);
  CHECK(diags.all()[0].message ==
        "channel 1: the program does not put the tool tip on this record's point (the part frame, mm): x "
        "558.800 "
        "where the CL has 22.000 (536.800 mm off); z -762.000 where the CL has -30.000 (732.000 mm off), "
        "after the "
        "block `G1 X44. Z-30. F0.2`");
  CHECK(diags.all()[1].message ==
        "channel 1: the CL feeds at 0.2 mm/rev here, the program at 5.08 mm/rev (F0.2 under G99)");
}

TEST_CASE("cl comparison: the arc blocks of a helix, each against the CL's circle",
          "[analysis][cl_compare]") {
  // CIRCLE TIMES,2 ending a quarter turn on, 5 mm down from Z0: two full turns and the quarter,
  // 2.25 turns at one pitch (2.222 mm a turn), as the post writes it on bench-mill.
  const machine m = load_machine(std::string(TWINPOST_SOURCE_DIR) + "/bench/bench-mill.toml");
  auto run = [&](std::initializer_list<const char*> arc_blocks) {
    diagnostic_list diags;
    cl_comparison cmp(m, m.channels[0], diags, "job.cls");
    int line = 10;
    for (const char* l : {"%", "O1000 (HELIX)", "G21", "G90 G17 G40 G49 G80", "T01 M6", "S3000 M3", "G94"})
      cmp.line(l);
    cmp.record({line++, tool_event{tool_source::loadtl, 1, 1}, 1}, false);
    spindle_event s;
    s.speed = 3000;
    s.dir = rotation::cw;
    cmp.record({line++, s, 1}, false);
    cmp.record({line++, feed_event{feed_mode::per_minute, 600}, 1}, false);
    cmp.line("G0 G43 H01 X110. Y50. Z5.");
    motion_event mv;
    mv.pos = {110, 50, 5};
    mv.rapid = true;
    cmp.record({line++, mv, 1}, false);
    cmp.line("G1 Z0. F600.");
    mv.pos = {110, 50, 0};
    mv.rapid = false;
    cmp.record({line++, mv, 1}, false);
    for (const char* b : arc_blocks) cmp.line(b);
    arc_event a;
    a.start = {110, 50, 0};
    a.end = {100, 60, -5};
    a.center = {100, 50, -5};
    a.normal = {0, 0, 1};
    a.radius = 10;
    a.ccw = true;
    a.turns = 2;
    cmp.record({line++, a, 1}, false);
    std::string out;
    for (const diagnostic& d : diags.all()) out += format_diagnostic(d);
    return out;
  };
  CHECK(run({"G3 X110. Y50. Z-2.222 I-10. J0.", "G3 X110. Y50. Z-4.444 I-10. J0.",
             "G3 X100. Y60. Z-5. I-10. J0."})
            .empty());
  // A turn dropped: the same depth in 1.25 turns, a ramp nearly twice as steep.
  CHECK(
      run({"G3 X110. Y50. Z-4. I-10. J0.", "G3 X100. Y60. Z-5. I-10. J0."}) ==
      "job.cls:15:1: error: channel 1: the program's arc blocks go 450.0 degrees round the CL's circle here, "
      "the CL's arc 810.0 degrees (TIMES,2: full turns, then on to its end): `G3 X100. Y60. Z-5. I-10. "
      "J0.`\n");
  // The whole depth in the first turn, the rest flat: the first turn plunges.
  CHECK(run({"G3 X110. Y50. Z-5. I-10. J0.", "G3 X110. Y50. I-10. J0.", "G3 X100. Y60. I-10. J0."}) ==
        "job.cls:15:1: error: channel 1: the program's helix does not keep the CL's pitch: this block goes "
        "-5.000 mm along the circle's axis over 360.0 degrees, where the CL's -5.000 mm over 810.0 degrees "
        "gives -2.222 mm: `G3 X110. Y50. Z-5. I-10. J0.`\n");
  // A block between that ends off the circle (its centre right, its end 1 mm out).
  CHECK(run({"G3 X111. Y50. Z-2.222 I-10. J0.", "G3 X110. Y50. Z-4.444 I-11. J0.",
             "G3 X100. Y60. Z-5. I-10. J0."}) ==
        "job.cls:15:1: error: channel 1: the program's arc block ends 1.000 mm off the CL's circle (radius "
        "10.000 mm, the part frame): `G3 X111. Y50. Z-2.222 I-10. J0.`\n");
  // A block between turning the other way.
  CHECK(run({"G3 X110. Y50. Z-2.222 I-10. J0.", "G2 X110. Y50. Z-4.444 I-10. J0.",
             "G3 X100. Y60. Z-5. I-10. J0."}) ==
        "job.cls:15:1: error: channel 1: the CL's arc turns counter-clockwise about (0,0,1) here, the "
        "program's G2 the other way round: `G2 X110. Y50. Z-4.444 I-10. J0.`\n");
}

TEST_CASE("cl comparison: an indexing head's channel, and the part turned by C", "[analysis][cl_compare]") {
  // The Integrex's upper head (a kinematic chain and [channel.head_index]): X Y Z are the tip
  // once the head's offset is given after its index, in the frame C has turned the part to
  // (the program's x, y are the part's turned by -C). The second of three holes on a 40 mm
  // pitch circle, at 120 degrees: C120., then X20. Y0. (X a radius after G10.9 X0).
  auto run = [](const char* c_block, const char* move, bool with_c_mode = true) {
    compared c("integrex-i200st", 1);
    c.lines({"T12 M6", "M901"});
    if (with_c_mode) c.lines({"M200", "G10.9 X0"});
    c.lines({"G97 S2500 M3", "G94", "M108", "G0 G53 B0.", "M107", c_block, move});
    motion_event mv;
    mv.pos = {-10, 17.3205081, 10};
    mv.rapid = true;
    c.cmp.record({c.next++, mv, 1}, false);
    return std::pair{c.text(), c.cmp.compared()};
  };
  CHECK(run("G0 C120.", "G0 G43 H#3020 X20. Y0. Z10.") == std::pair{std::string(), 1L});
  CHECK(run("G0 C0.", "G0 G43 H#3020 X20. Y0. Z10.").first ==
        "job.cls:10:1: error: channel 1: the program does not put the tool tip on this record's point (the "
        "part "
        "frame, mm): x 20.000 where the CL has -10.000 (30.000 mm off); y 0.000 where the CL has 17.321 "
        "(17.321 "
        "mm off), after the block `G0 G43 H#3020 X20. Y0. Z10.`\n");
  // C given in G91 adds to where it stood: from C unknown (M200 with no C word yet) it stays
  // unknown, whichever way the block's G91 and C stand.
  CHECK(run("G91 G0 C120.", "G0 G43 H#3020 X20. Y0. Z10.") == std::pair{std::string(), 0L});
  CHECK(run("G0 C120. G91", "G0 G43 H#3020 X20. Y0. Z10.") == std::pair{std::string(), 0L});
  // The head indexed and no offset given since: not followed (the tip is not the words yet).
  CHECK(run("G0 C120.", "G0 X20. Y0. Z10.") == std::pair{std::string(), 0L});
  // The spindle made a C axis and no C word since: where the part stands is not known.
  CHECK(run("M9", "G0 G43 H#3020 X20. Y0. Z10.") == std::pair{std::string(), 0L});
  // Without M200 no C word came: the frame is the program's, and X a diameter (no G10.9 X0).
  CHECK(run("M9", "G0 G43 H#3020 X-20. Y17.321 Z10.", false) == std::pair{std::string(), 1L});
}

TEST_CASE("cl comparison: a CL cycle's holes against the program's cycle blocks", "[analysis][cl_compare]") {
  // Each GOTO between CYCLE/DRILL and CYCLE/OFF is a hole: along Z its x, y are the cycle
  // block's X, Y turned by C; a side cycle (G87, along X) drills at its Z, on the line C turns
  // to the tool. Checked in the writer by turning its C frame the wrong way: both built-ins'
  // mill/turn samples then stopped at their second hole.
  auto run = [](const char* machine_name, int channel, std::initializer_list<const char*> program,
                const vec3& hole) {
    compared c(machine_name, channel);
    cycle_event drill;
    drill.type = "DRILL";
    c.cmp.record({c.next++, drill, 1}, false);
    c.lines(program);  // the writer writes the cycle block at the hole's GOTO
    motion_event mv;
    mv.pos = hole;
    c.cmp.record({c.next++, mv, 1}, false);
    return std::pair{c.text(), c.cmp.compared()};
  };
  // The Integrex: the hole at 120 degrees on the 40 mm pitch circle, C120. then X20. Y0.
  const auto integrex = [&](const char* c_block, const vec3& hole) {
    return run("integrex-i200st", 1,
               {"T12 M6", "M901", "M200", "G10.9 X0", "G97 S2500 M3", "M108", "G0 G53 B0.", "M107", "G0 C0.",
                "G0 G43 H#3020 X20. Y0. Z10.", "M212", c_block, "M210", "X20. Y0. Z2.", "G17",
                "G98 G81 X20. Y0. Z-12. R2. F150."},
               hole);
  };
  CHECK(integrex("G0 C120.", {-10, 17.3205081, 0}) == std::pair{std::string(), 1L});
  CHECK(
      integrex("G0 C240.", {-10, 17.3205081, 0}).first ==
      "job.cls:11:1: error: channel 1: the program drills this record's hole elsewhere (the part frame, mm): "
      "x -10.000 y -17.321 where the CL has x -10.000 y 17.321 (34.641 mm off), in the block `G98 G81 X20. "
      "Y0. Z-12. R2. F150.`\n");
  // The 31i's path 3: a cross hole at 90 degrees with the side cycle G87, X the bottom's diameter.
  const auto side = [&](const char* c_block, const vec3& hole) {
    return run("fanuc-31i-3path", 3,
               {"M6 T1400", "T1414", "G97 S2000 M33", "G0 B0.", "M90", c_block, "X80. Y0. Z-20.", "M89",
                "X66.", "G87 X30. Z-20. R0. F120."},
               hole);
  };
  CHECK(side("G0 C90.", {0, 33, -20}) == std::pair{std::string(), 1L});
  CHECK(
      side("G0 C0.", {0, 33, -22}).first ==
      "job.cls:11:1: error: channel 3: the program drills this record's hole elsewhere (the part frame, mm): "
      "z -20.000 where the CL has -22.000, and 33.000 mm across the drill's line at C0, in the block `G87 "
      "X30. "
      "Z-20. R0. F120.`\n");
}

TEST_CASE("cl comparison: an axial hole's bottom against the CL's FEDTO or DEPTH", "[analysis][cl_compare]") {
  // The cycle block's Z is the hole's bottom: the CL's FEDTO (a Z in this dialect) or DEPTH
  // below the GOTO point, drilled towards -Z by a tool looking down +Z.
  auto run = [](std::initializer_list<std::pair<const char*, double>> params, const char* block,
                std::optional<vec3> axis = std::nullopt) {
    compared c("fanuc-0itd-twin", 1);
    cycle_event drill;
    drill.type = "DRILL";
    for (const auto& [k, v] : params) drill.params.emplace_back(k, v);
    c.cmp.record({c.next++, drill, 1}, false);
    c.lines({"T0505", "G97 S1200 M3", "G0 X0. Z5.", block});
    motion_event mv;
    mv.pos = {0, 0, 2};
    mv.axis = axis;
    c.cmp.record({c.next++, mv, 1}, false);
    return std::pair{c.text(), c.cmp.compared()};
  };
  CHECK(run({{"FEDTO", -30}}, "G83 X0. Z-30. R-3. F0.1") == std::pair{std::string(), 1L});
  CHECK(run({{"DEPTH", 32}}, "G83 X0. Z-30. R-3. F0.1") == std::pair{std::string(), 1L});
  CHECK(
      run({{"FEDTO", -30}}, "G83 X0. Z-25. R-3. F0.1").first ==
      "job.cls:11:1: error: channel 1: the program drills this record's hole elsewhere (the part frame, mm): "
      "its bottom at z -25.000 where the CL's bottom is z -30.000 (5.000 mm short of it), in the block `G83 "
      "X0. "
      "Z-25. R-3. F0.1`\n");
  CHECK(
      run({{"DEPTH", 20}}, "G83 X0. Z-30. R-3. F0.1").first ==
      "job.cls:11:1: error: channel 1: the program drills this record's hole elsewhere (the part frame, mm): "
      "its bottom at z -30.000 where the CL's bottom is z -18.000 (12.000 mm deeper), in the block `G83 X0. "
      "Z-30. "
      "R-3. F0.1`\n");
  // A tool off Z (a cross hole in a turned frame): the depth is passed over.
  CHECK(run({{"FEDTO", -30}}, "G83 X0. Z-25. R-3. F0.1", vec3{1, 0, 0}).first == "");
}

TEST_CASE("cl comparison: a hole drilled with moves, its deepest feed against the CL's bottom",
          "[analysis][cl_compare]") {
  // A machine that writes the cycle as moves (pecks, a chip-break the control has no cycle
  // for): the feed block that went deepest stands on the hole and at the CL's bottom (attack 50).
  auto run = [](std::initializer_list<const char*> program, const char* type = "DEEP") {
    compared c("fanuc-0itd-twin", 1);
    cycle_event drill;
    drill.type = type;
    drill.params = {{"FEDTO", -30}};
    c.cmp.record({c.next++, drill, 1}, false);
    c.lines({"T0505", "G97 S1200 M3"});
    c.lines(program);
    motion_event mv;
    mv.pos = {0, 0, 2};
    c.cmp.record({c.next++, mv, 1}, false);
    return std::pair{c.text(), c.cmp.compared()};
  };
  CHECK(run({"G0 X0. Z2.", "G1 Z-15. F0.1", "G0 Z2.", "Z-14.5", "G1 Z-30.", "G0 Z2."}) ==
        std::pair{std::string(), 1L});
  CHECK(
      run({"G0 X0. Z2.", "G1 Z-15. F0.1", "G0 Z2.", "Z-14.5", "G1 Z-28.", "G0 Z2."}).first ==
      "job.cls:11:1: error: channel 1: the program drills this record's hole elsewhere (the part frame, mm): "
      "its deepest feed at z -28.000 where the CL's bottom is z -30.000 (2.000 mm short of it), in the block "
      "`G1 Z-28.`\n");
  CHECK(
      run({"G0 X4. Z2.", "G1 Z-30. F0.1", "G0 Z2."}).first ==
      "job.cls:11:1: error: channel 1: the program drills this record's hole elsewhere (the part frame, mm): "
      "its deepest feed at x 2.000 y 0.000 where the CL has x 0.000 y 0.000 (2.000 mm off), in the block "
      "`G1 Z-30. F0.1`\n");
  // A lathe cycle (a groove) is no hole: its moves are not held to a bottom.
  CHECK(run({"G0 X4. Z2.", "G1 Z-30. F0.1", "G0 Z2."}, "GROOVE").first == "");
}

TEST_CASE("cl comparison: the fourth attack's ways past the C axis, the holes and the head",
          "[analysis][cl_compare]") {
  // Attack 47. The Integrex's hole at 120 degrees (C120., then X20. Y0.), with what a user
  // block or INSERT may put before it.
  auto integrex = [](std::initializer_list<const char*> before, const char* cycle) {
    compared c("integrex-i200st", 1);
    cycle_event drill;
    drill.type = "DRILL";
    c.cmp.record({c.next++, drill, 1}, false);
    c.lines({"T12 M6", "M901", "M200", "G10.9 X0", "G97 S2500 M3", "M108", "G0 G53 B0.", "M107", "G0 C120.",
             "G0 G43 H#3020 X20. Y0. Z10."});
    c.lines(before);
    c.lines({"X20. Y0. Z2.", cycle});
    motion_event mv;
    mv.pos = {-10, 17.3205081, 0};
    c.cmp.record({c.next++, mv, 1}, false);
    return c.text();
  };
  const char* g81 = "G98 G81 X20. Y0. Z-12. R2. F150.";
  CHECK(integrex({}, g81).empty());
  // G91 G28 C0.: C goes to its reference point, whatever the increment says.
  CHECK(
      integrex({"G91 G28 C0.", "G90"}, g81) ==
      "job.cls:11:1: error: channel 1: the program drills this record's hole elsewhere (the part frame, mm): "
      "x 20.000 y 0.000 where the CL has x -10.000 y 17.321 (34.641 mm off), in the block `G98 G81 X20. Y0. "
      "Z-12. R2. F150.`\n");
  // C120 without a decimal point is 0.12 degrees on a control with decimal-point programming off.
  CHECK(
      integrex({"G0 C120"}, g81) ==
      "job.cls:11:1: error: channel 1: the program drills this record's hole elsewhere (the part frame, mm): "
      "x 20.000 y 0.042 where the CL has x -10.000 y 17.321 (34.620 mm off), in the block `G98 G81 X20. Y0. "
      "Z-12. R2. F150.`\n");
  // After G30 C.. where C stands is not known: passed over.
  CHECK(integrex({"G30 C0."}, g81).empty());
  // The head's length offset changed: another register, G44, G49.
  // Attack 48: an H in the block (G49 H0) made C unknown and passed everything after; G43.4,
  // a bare H and another P got past the codes.
  for (const std::string offset :
       {"G43 P1 H5", "G44 P1 H#3020", "G49", "G49 H0", "G43.4 H5", "H5", "G43 P2 H#3020"})
    CHECK(integrex({offset.c_str()}, g81) ==
          fmt::format(
              "job.cls:11:1: error: channel 1: the head's tool length offset is not the machine's here: "
              "`{}` left {} in force where the head's offset codes give `G43 P1 H#3020` or `G43 "
              "H#3020`: X Y Z are not the tool tip\n",
              offset, offset.find("G43") != std::string::npos ? "another offset" : "none"));
  // The head's codes with their words in another order and the move's words: its own offset.
  CHECK(integrex({"G0 H#3020 G43 X20. Y0. Z2."}, g81).empty());
  // The head's turning offset for a drill the live spindle turns (the issue's item 10: `G43 P1` is
  // the Integrex's offset for turning and centre drilling, the Fusion Integrex post's).
  CHECK(integrex({"G0 G43 P1 H#3020 X20. Y0. Z2."}, g81) ==
        "job.cls:11:1: error: channel 1: the head's tool length offset is not the tool's: `G0 G43 P1 H#3020 "
        "X20. Y0. Z2.` gives the head's offset for a turning or stationary tool, and the tool cuts with the "
        "live spindle, whose offset code is `G43 H#3020`: X Y Z are not the tool tip\n");
  // A coordinate setting of C (G92 C0.: C's origin moved, not C): the records after it are
  // passed over, not read as C at 0 (attack 48: a right program was refused), with a warning.
  CHECK(integrex({"G92 C0."}, g81) ==
        "job.cls:11:1: warning: channel 1: this record and the channel's later ones are not held to the CL: "
        "the "
        "program sets the part frame itself at line 14 of its program (`G92 C0.`)\n");
  // The 31i's cross hole at 90 degrees drilled from C270: the same line, the other wall.
  compared side("fanuc-31i-3path", 3);
  cycle_event drill;
  drill.type = "DRILL";
  side.cmp.record({side.next++, drill, 1}, false);
  side.lines({"M6 T1400", "T1414", "G97 S2000 M33", "G0 B0.", "M90", "G0 C270.", "X80. Y0. Z-20.", "M89",
              "X66.", "G87 X30. Z-20. R0. F120."});
  motion_event mv;
  mv.pos = {0, 33, -20};
  side.cmp.record({side.next++, mv, 1}, false);
  CHECK(side.text() ==
        "job.cls:11:1: error: channel 3: the program drills this record's hole elsewhere (the part frame, "
        "mm): at "
        "C270 the drill comes from the other side of the part than the CL's hole at x 0.000 y 33.000, in the "
        "block "
        "`G87 X30. Z-20. R0. F120.`\n");
}

TEST_CASE("cl comparison: polar interpolation, and a Y left off the centre line", "[analysis][cl_compare]") {
  // The Integrex's flat 25 mm off centre in polar interpolation (X a radius after G10.9 X0, the
  // CL's y as C in mm): the tool stands on the programmed point only with Y at 0. Before
  // G12.1 the program puts Y at `y_block` (empty: Y never given on this channel).
  auto run = [](std::vector<const char*> y_blocks, const char* c_block = "G0 C0.") {
    compared c("integrex-i200st", 1);
    c.lines({"T11 M6", "M901", "M200", "G10.9 X0", "G97 S3000 M3", "G94", "M108", "G0 G53 B0.", "M107"});
    for (const char* b : y_blocks) c.cmp.line(b);
    c.lines({c_block, "G17 XC", "G12.1", "G0 G43 H#3020 X40. C25. Z5."});
    motion_event mv;
    mv.pos = {40, 25, 5};
    mv.rapid = true;
    c.cmp.record({c.next++, mv, 1}, false);
    c.lines({"G1 Z-8. F400.", "X-40."});
    c.feed(400, feed_mode::per_minute);
    mv.pos = {-40, 25, -8};
    mv.rapid = false;
    c.cmp.record({c.next++, mv, 1}, false);
    return std::pair{c.text(), c.cmp.compared()};
  };
  CHECK(run({"G0 Y0."}) == std::pair{std::string(), 2L});
  // Y at 8 (a cross hole's or a flat's, an earlier tool's): every point is off by 8 across the
  // line from the axis to the programmed point.
  const double r = std::hypot(40.0, 25.0);
  const std::string first = fmt::format(
      "x {:.3f} where the CL has 40.000 ({:.3f} mm off); y {:.3f} where the CL has 25.000 ({:.3f} mm off)",
      40 - 8 * 25 / r, 8 * 25 / r, 25 + 8 * 40 / r, 8 * 40 / r);
  const std::string off_by_8 =
      "job.cls:10:1: error: channel 1: the program does not put the tool tip on this record's point (the "
      "part "
      "frame, mm): " +
      first + ", after the block `G0 G43 H#3020 X40. C25. Z5.`\n";
  CHECK(run({"G0 Y8."}) == std::pair{off_by_8, 2L});
  // A drilling cycle leaves Y at its hole (a cross hole 8 mm off its radial line, an earlier
  // tool's); one that repeats (K3) steps on, and where it ends is not followed.
  CHECK(run({"G98 G81 X20. Y8. Z15. R33. F120.", "G80", "G0 Z40."}) == std::pair{off_by_8, 2L});
  CHECK(run({"G91 G98 G81 X20. Y8. Z15. R33. F120. K3", "G80", "G90 G0 Z40."}) ==
        std::pair{std::string(), 0L});
  // Y never given: where it stands is not known, and nothing is compared.
  CHECK(run({}) == std::pair{std::string(), 0L});
  // The mode begun with C not at 0 (or not known): its frame is not followed.
  CHECK(run({"G0 Y0."}, "G0 C30.") == std::pair{std::string(), 0L});
  CHECK(run({"G0 Y0."}, "M9") == std::pair{std::string(), 0L});
}

TEST_CASE("cl comparison: a C turn below the CL's move, in a feed move, or off its straight line",
          "[analysis][cl_compare]") {
  // The Integrex's upper head over the face (X a radius after G10.9 X0): the tip at x 20, z 2
  // above hole 1 at C0, then the program's `blocks` for the CL's move to `to` (a rapid or a
  // feed, the tool along `axis`). A C turn runs the tip round the part's axis: it may do so no
  // lower than the CL's move goes, and not at all in a feed move's straight cut.
  // (A radial tool: the head at B90, the CL's axis at the second record turned with the part.)
  auto run = [](std::vector<const char*> blocks, vec3 to, bool rapid, vec3 axis = {0, 0, 1},
                vec3 axis_to = {0, 0, 1}, const char* index = "G0 G53 B0.") {
    compared c("integrex-i200st", 1);
    c.lines({"T12 M6", "M901", "M200", "G10.9 X0", "G97 S2500 M3", "G94", "M108", index, "M107", "M8",
             "G0 C0.", "G0 G43 H#3020 X20. Y0. Z2."});
    c.feed(400, feed_mode::per_minute);
    motion_event mv;
    mv.pos = {20, 0, 2};
    mv.axis = axis;
    mv.rapid = true;
    c.cmp.record({c.next++, mv, 1}, false);
    for (const char* b : blocks) c.cmp.line(b);
    mv.pos = to;
    mv.axis = axis_to;
    mv.rapid = rapid;
    c.cmp.record({c.next++, mv, 1}, false);
    return c.text();
  };
  const double s = std::sqrt(3.0) / 2;
  const vec3 hole2{-10, 20 * s, 2};
  // At the CL's height between the holes: the part turns clear of the tool.
  CHECK(run({"G0 C120."}, hole2, true) == "");
  // Down into the part first, turned there, and back up: the ends are right, the path is not.
  CHECK(run({"G0 Z-5.", "G0 C120.", "G0 Z2."}, hole2, true) ==
        "job.cls:12:1: error: channel 1: the program turns C with the tool tip below the CL's move here: z "
        "-5.000 (the part frame, mm), where the CL's move goes no lower than 2.000; the part turns into the "
        "tool: turn it with the tool clear, as high as the CL's move: `G0 C120.`\n");
  // Out of a pocket and round to the next: the part turns at the top of the CL's move, not at
  // the bottom of the pocket the tool leaves.
  auto up_and_round = [&](std::vector<const char*> blocks) {
    compared c("integrex-i200st", 1);
    c.lines({"T12 M6", "M901", "M200", "G10.9 X0", "G97 S2500 M3", "G94", "M108", "G0 G53 B0.", "M107", "M8",
             "G0 C0.", "G0 G43 H#3020 X20. Y0. Z2.", "G1 Z-3. F400."});
    c.feed(400, feed_mode::per_minute);
    motion_event mv;
    mv.pos = {20, 0, -3};
    c.cmp.record({c.next++, mv, 1}, false);
    for (const char* b : blocks) c.cmp.line(b);
    mv.pos = {-10, 20 * s, 5};
    mv.rapid = true;
    c.cmp.record({c.next++, mv, 1}, false);
    return c.text();
  };
  CHECK(up_and_round({"G0 Z5.", "C120."}) == "");
  CHECK(up_and_round({"G0 Z5. C120."}) == "");
  CHECK(up_and_round({"G0 C120.", "Z5."}) ==
        "job.cls:12:1: error: channel 1: the program turns C with the tool tip below the CL's move here: z "
        "-3.000 (the part frame, mm), where the CL's move goes no lower than 5.000; the part turns into the "
        "tool: turn it with the tool clear, as high as the CL's move: `G0 C120.`\n");
  // Turns written between two motion records (INSERT text, an [events] block at a coolant
  // record) are held to the next record's move (attack 60 F3).
  {
    compared c("integrex-i200st", 1);
    c.lines({"T12 M6", "M901", "M200", "G10.9 X0", "G97 S2500 M3", "G94", "M108", "G0 G53 B0.", "M107", "M8",
             "G0 C0.", "G0 G43 H#3020 X20. Y0. Z2."});
    motion_event mv;
    mv.pos = {20, 0, 2};
    mv.rapid = true;
    c.cmp.record({c.next++, mv, 1}, false);
    c.lines({"G0 Z-5.", "G0 C120."});
    c.cmp.record({c.next++, coolant_event{"OFF", ""}, 1}, false);
    c.lines({"G0 C0.", "G0 Z2."});
    c.cmp.record({c.next++, mv, 1}, false);
    CHECK(
        c.text() ==
        "job.cls:12:1: error: channel 1: the program turns C with the tool tip below the CL's move here: z "
        "-5.000 (the part frame, mm), where the CL's move goes no lower than 2.000; the part turns into the "
        "tool: turn it with the tool clear, as high as the CL's move: `G0 C120.`\n");
  }
  // A C turn at rapid inside a feed move (review 55: a `G0 C..` was no move to the comparison).
  CHECK(run({"G0 C120."}, hole2, false) ==
        "job.cls:12:1: error: channel 1: the CL asks for a feed move here, but the program moves in rapid: "
        "`G0 C120.`\n");
  // Fed round by C where the CL cuts a straight line: 20 mm from the axis, 10 degrees leave the
  // chord by 20 (1 - cos 5°).
  const double t = 10 * std::numbers::pi / 180;
  CHECK(run({"G1 C10. F400."}, {20 * std::cos(t), 20 * std::sin(t), 2}, false) ==
        fmt::format(
            "job.cls:12:1: error: channel 1: the program turns C in a feed move here: the tool tip runs "
            "round the part's axis and leaves the CL's straight cut by {:.3f} mm (the part frame; 0.010 "
            "mm allowed): `G1 C10. F400.`\n",
            20 * (1 - std::cos(t / 2))));
  // A radial tool (along x): its height is the distance from the axis. Turned at 15 mm where
  // the CL's move keeps 20.
  CHECK(run({"G0 X15.", "G0 C120.", "X20."}, hole2, true, {1, 0, 0}, {-0.5, s, 0}, "G0 G53 B90.") ==
        "job.cls:12:1: error: channel 1: the program turns C with the tool tip below the CL's move here: the "
        "distance from the axis 15.000 (the part frame, mm), where the CL's move goes no lower than 20.000; "
        "the "
        "part turns into the tool: turn it with the tool clear, as high as the CL's move: `G0 C120.`\n");
  // The tip on the axis does not move when C turns; a tool at home is far from the part.
  CHECK(run({"G0 X0.", "G0 C120.", "X20. Y0."}, hole2, true) == "");
  CHECK(run({"G0 G53 Z0.", "G0 C120.", "G0 X20. Y0. Z2."}, hole2, true) == "");
}

TEST_CASE("cl comparison: V, Y's increment on a lathe channel with Y, at home after G28 U0. V0.",
          "[analysis][cl_compare]") {
  // The 31i's path 3 homes Y with X (G-code system A: U, V, W the increments of X, Y, Z). A move
  // after it that does not give Y again leaves the tool at Y's reference point.
  compared c("fanuc-31i-3path", 3);
  c.lines({"M6 T1400", "T1414", "G97 S2000 M33", "G0 B0.", "M90", "G0 C0.", "G0 X80. Y8. Z-20."});
  motion_event mv;
  mv.pos = {40, 8, -20};
  mv.rapid = true;
  c.cmp.record({c.next++, mv, 1}, false);
  c.lines({"G28 U0. V0.", "G28 W0.", "G0 X80. Z-20."});
  c.cmp.record({c.next++, mv, 1}, false);
  CHECK(
      c.text() ==
      "job.cls:11:1: error: channel 3: the program does not put the tool tip on this record's point (the "
      "part "
      "frame, mm): Y is where G28 at line 11 of the program left it, not at the CL's 8.000, after the block "
      "`G0 X80. Z-20.`\n");
  CHECK(c.cmp.compared() == 2);
}

TEST_CASE("cl comparison: the tool axis a B head gives a live tool", "[analysis][cl_compare]") {
  // The Integrex's upper head (B0 along the spindle axis, B90 across it from the head's side)
  // with milling tool 12 turning (M3): `index` points it, `c_block` turns the part, and one
  // rapid record with the CL's tool `axis` is held to the tip and the axis.
  auto run = [](const char* index, const char* c_block, vec3 pos, vec3 axis,
                std::vector<const char*> start = {"T12 M6", "M901", "M200", "G10.9 X0", "G97 S2500 M3"},
                const char* offset = "G0 G43 H#3020 X20. Y0. Z2.") {
    compared c("integrex-i200st", 1);
    for (const char* b : start) c.cmp.line(b);
    c.lines({"M108", index, "M107", c_block, offset});
    c.to(pos, axis);
    return std::pair{c.text(), c.cmp.compared()};
  };
  // Over the face, an axial tool: B0 gives the CL's (0,0,1).
  CHECK(run("G0 G53 B0.", "G0 C0.", {20, 0, 2}, {0, 0, 1}) == std::pair{std::string(), 1L});
  CHECK(
      run("G0 G53 B0.", "G0 C0.", {20, 0, 2}, {1, 0, 0}).first ==
      "job.cls:10:1: error: channel 1: the CL's tool axis here is (1.0000,0.0000,0.0000), the program's head "
      "points the tool along (0.0000,0.0000,1.0000) in the part frame (90.000 degrees off): the head was "
      "indexed by `G0 G53 B0.` at line 10 of the program\n");
  // Half a degree off the axis (a CL the writer's axial test lets through): the hole would be
  // drilled 0.5 degrees off.
  const double t = 0.5 * std::numbers::pi / 180;
  CHECK(
      run("G0 G53 B0.", "G0 C0.", {20, 0, 2}, {std::sin(t), 0, std::cos(t)}).first ==
      "job.cls:10:1: error: channel 1: the CL's tool axis here is (0.0087,0.0000,1.0000), the program's head "
      "points the tool along (0.0000,0.0000,1.0000) in the part frame (0.500 degrees off): the head was "
      "indexed by `G0 G53 B0.` at line 10 of the program\n");
  // A radial tool at B90: at C0 along x; at C90 the part turned a quarter, the tool along y.
  CHECK(run("G0 G53 B90.", "G0 C0.", {20, 0, 2}, {1, 0, 0}).first.empty());
  CHECK(run("G0 G53 B90.", "G0 C90.", {0, 20, 2}, {0, 1, 0}).first.empty());
  CHECK(
      run("G0 G53 B90.", "G0 C270.", {0, -20, 2}, {0, 1, 0}).first ==
      "job.cls:10:1: error: channel 1: the CL's tool axis here is (0.0000,1.0000,0.0000), the program's head "
      "points the tool along (0.0000,-1.0000,0.0000) in the part frame (180.000 degrees off): the head was "
      "indexed by `G0 G53 B90.` at line 10 of the program\n");
  // A turning tool (the main spindle turns, M203): its CL gives no axis the head follows. Its
  // offset is the head's turning one, `G43 P1` (the issue's item 10: the live spindle's `G43`
  // there is named).
  const std::vector<const char*> turning{"T12 M6", "M901", "G97 S800 M203"};
  CHECK(run("G0 G53 B0.", "G0 C0.", {10, 0, 2}, {1, 0, 0}, turning, "G0 G43 P1 H#3020 X20. Y0. Z2.") ==
        std::pair{std::string(), 1L});
  // Judged where the tool cuts, not at the offset's block (attack 69 H1: a SPINDL after the
  // approach): the live code is named at the turning tool's first feed, not at its approach.
  CHECK(run("G0 G53 B0.", "G0 C0.", {10, 0, 2}, {1, 0, 0}, turning).first.empty());
  compared tt("integrex-i200st", 1);
  tt.lines({"T12 M6", "M901", "G97 S800 M203", "M108", "G0 G53 B0.", "M107", "G0 C0.",
            "G0 G43 H#3020 X20. Y0. Z2.", "G1 Z-5. F100."});
  tt.to({10, 0, -5}, {1, 0, 0}, false);
  CHECK(tt.text() ==
        "job.cls:10:1: error: channel 1: the head's tool length offset is not the tool's: `G0 G43 H#3020 "
        "X20. Y0. Z2.` gives the head's offset for a live tool, and the tool cuts with the main spindle, "
        "whose offset code is `G43 P1 H#3020`: X Y Z are not the tool tip\n");
  // The second spindle faces the main one (G55, Z reversed): B180 points the tool at its face.
  const std::vector<const char*> sub{"T12 M6", "M902", "G55", "M300", "G10.9 X0", "G97 S2500 M3"};
  CHECK(run("G0 G53 B180.", "G0 C0.", {20, 0, -2}, {0, 0, 1}, sub) == std::pair{std::string(), 1L});
  CHECK(
      run("G0 G53 B0.", "G0 C0.", {20, 0, -2}, {0, 0, 1}, sub).first ==
      "job.cls:10:1: error: channel 1: the CL's tool axis here is (0.0000,0.0000,1.0000), the program's head "
      "points the tool along (0.0000,0.0000,-1.0000) in the part frame (180.000 degrees off): the head was "
      "indexed by `G0 G53 B0.` at line 11 of the program\n");
  // An index with no length offset after it (an INSERT `G0 G53 B10.` between two drill moves):
  // the tip is not known, the tool's axis is (review 64).
  {
    compared c("integrex-i200st", 1);
    c.lines({"T12 M6", "M901", "M200", "G10.9 X0", "G97 S2500 M3", "M108", "G0 G53 B0.", "M107", "G0 C0.",
             "G0 G43 H#3020 X20. Y0. Z2.", "G0 G53 B10.", "G1 Z-5. F100."});
    c.to({20, 0, -5}, {0, 0, 1}, false);
    CHECK(c.text() ==
          "job.cls:10:1: error: channel 1: the CL's tool axis here is (0.0000,0.0000,1.0000), the program's "
          "head "
          "points the tool along (0.1736,0.0000,0.9848) in the part frame (10.000 degrees off): the head was "
          "indexed by `G0 G53 B10.` at line 14 of the program\n");
  }
  // A tool change forgets the angle (the changer may turn the head): until the next index the
  // axis is not compared (the emulator refuses a cut before it: docs/emulator.md).
  {
    compared c("integrex-i200st", 1);
    c.lines({"T11 M6", "M901", "M200", "G10.9 X0", "G97 S2500 M3", "M108", "G0 G53 B90.", "M107", "G0 C0.",
             "G0 G43 H#3020 X20. Y0. Z2.", "T12 M6", "G97 S2500 M3", "G0 G43 H#3020 X20. Y0. Z2."});
    c.to({20, 0, 2}, {0, 0, 1});
    CHECK(c.text().empty());
  }
  // The 31i's path 3: B-90 along the spindle axis, B0 across it.
  {
    compared c("fanuc-31i-3path", 3);
    c.lines({"M6 T1400", "T1414", "G97 S2000 M33", "G0 B0.", "M90", "G0 C0.", "X80. Y0. Z-20."});
    c.to({40, 0, -20}, {0, 0, 1});
    CHECK(
        c.text() ==
        "job.cls:10:1: error: channel 3: the CL's tool axis here is (0.0000,0.0000,1.0000), the program's "
        "head points the tool along (1.0000,0.0000,0.0000) in the part frame (90.000 degrees off): the head "
        "was indexed by `G0 B0.` at line 7 of the program\n");
  }
}

TEST_CASE("cl comparison: a chain's tip and tool axis through the forward transform of its words",
          "[analysis][cl_compare]") {
  // One record after `blocks` on channel 1 of a built-in 5-axis mill: TLDATA gives a 100 mm
  // tool, then LOADTL/1; the CL's point `pos` with the tool along `axis`.
  auto run = [](const char* machine, std::vector<const char*> blocks, vec3 pos, vec3 axis,
                bool tool_data = true) {
    compared c(machine, 1);
    if (tool_data)
      c.cmp.record({c.next++, tool_data_event{"TLDATA", {"MILL"}, {10, 0, 100, 0, 0}}, 1}, false);
    c.cmp.record({c.next++, tool_event{tool_source::loadtl, 1, std::nullopt, false}, 1}, false);
    for (const char* b : blocks) c.cmp.line(b);
    c.to(pos, axis);
    return std::pair{c.text(), c.cmp.compared()};
  };
  const double s = std::sin(15 * std::numbers::pi / 180), k = std::cos(15 * std::numbers::pi / 180);
  // The head/head's joints (`twinpost kin --machine head-head-5axis --tool-length 100
  // 10,20,-5,sin15,0,cos15`: X113.5276 Y20 Z-18.6297 B15 A0): the tip 400 mm below the pivot.
  const std::vector<const char*> head{"G21", "G90 G94 G17 G40 G49 G80", "T01 M6", "G54", "S8000 M3"};
  auto joints = [&](const char* move) {
    std::vector<const char*> b = head;
    b.push_back(move);
    return b;
  };
  CHECK(run("head-head-5axis", joints("G0 G43 H1 X113.528 Y20. Z-18.63 A0. B15."), {10, 20, -5}, {s, 0, k}) ==
        std::pair{std::string(), 1L});
  // B a degree short: the pivot (X113.528 Y20 Z381.37, 400 mm over the tip at B0) stays, the tip
  // at 400 (sin 14, 0, -cos 14) from it: x 16.759, z -6.748; the axis a degree off.
  CHECK(run("head-head-5axis", joints("G0 G43 H1 X113.528 Y20. Z-18.63 A0. B14."), {10, 20, -5}, {s, 0, k})
            .first ==
        "job.cls:12:1: error: channel 1: the program does not put the tool tip on this record's point (the "
        "part "
        "frame, mm; the forward transform of its words): x 16.759 where the CL has 10.000 (6.759 mm off); z "
        "-6.748 where the CL has -5.000 (1.748 mm off), after the block `G0 G43 H1 X113.528 Y20. Z-18.63 A0. "
        "B14.`\n"
        "job.cls:12:1: error: channel 1: the CL's tool axis here is (0.2588,0.0000,0.9659), the program's "
        "rotary "
        "axes point the tool along (0.2419,0.0000,0.9703) in the part frame (1.000 degrees off), after the "
        "block "
        "`G0 G43 H1 X113.528 Y20. Z-18.63 A0. B14.`\n");
  // No length offset in force: X Y Z are the spindle nose's.
  CHECK(
      run("head-head-5axis", joints("G0 X113.528 Y20. Z-18.63 A0. B15."), {10, 20, -5}, {s, 0, k}).first ==
      "job.cls:12:1: error: channel 1: the program moves with no tool length offset in force (G43 H.., the "
      "chain's G43): X Y Z are then the spindle's gauge point, one tool length from the CL's tip, after the "
      "block `G0 X113.528 Y20. Z-18.63 A0. B15.`\n");
  // The H register is the CL's offset's (LOADTL/1: 1), as the chain writes it (attack 63 H2).
  CHECK(run("head-head-5axis", joints("G0 G43 H5 X10. Y20. Z-5. A0. B0."), {10, 20, -5}, {0, 0, 1}).first ==
        "job.cls:12:1: error: channel 1: the CL cuts with tool 1 on offset 1 here (the tool call at line "
        "11), the "
        "program with the length offset H5 (the chain's G43 H..)\n");
  // A tool of no known length (no TLDATA, no [[tool]] length): with the head tilted the tip
  // depends on it and is not held (the axis is); upright it does not.
  CHECK(run("head-head-5axis", joints("G0 G43 H1 X113.528 Y20. Z-18.63 A0. B15."), {0, 0, 0}, {s, 0, k},
            false) == std::pair{std::string(), 1L});
  CHECK(
      run("head-head-5axis", joints("G0 G43 H1 X113.528 Y20. Z-18.63 A0. B14."), {0, 0, 0}, {s, 0, k}, false)
          .first ==
      "job.cls:11:1: error: channel 1: the CL's tool axis here is (0.2588,0.0000,0.9659), the program's "
      "rotary "
      "axes point the tool along (0.2419,0.0000,0.9703) in the part frame (1.000 degrees off), after the "
      "block "
      "`G0 G43 H1 X113.528 Y20. Z-18.63 A0. B14.`\n");
  CHECK(run("head-head-5axis", joints("G0 G43 H1 X10. Y20. Z-5. A0. B0."), {10, 20, -5}, {0, 0, 1}, false) ==
        std::pair{std::string(), 1L});
  // The trunnion under tool-tip control (G43.4): X Y Z the tip in the part frame, A15 C90 the
  // axis; C270 turns it the other way.
  auto tcp = [&](const char* move) {
    return std::vector<const char*>{"G21", "G90 G94 G17 G40 G49 G80", "T01 M6", "G54", "S8000 M3", move};
  };
  CHECK(run("trunnion-5axis", tcp("G0 G43.4 H1 X10. Y20. Z-5. A15. C90."), {10, 20, -5}, {s, 0, k}) ==
        std::pair{std::string(), 1L});
  CHECK(run("trunnion-5axis", tcp("G0 G43.4 H1 X10. Y20. Z-5. A15. C270."), {10, 20, -5}, {s, 0, k}).first ==
        "job.cls:12:1: error: channel 1: the CL's tool axis here is (0.2588,0.0000,0.9659), the program's "
        "rotary "
        "axes point the tool along (-0.2588,0.0000,0.9659) in the part frame (30.000 degrees off), after the "
        "block `G0 G43.4 H1 X10. Y20. Z-5. A15. C270.`\n");
  // A tilted plane (G68.2, Fanuc's Z-X-Z Euler angles; G53.1 turns the table to its Z): its
  // coordinates are the tip's. I90 J15 K-90 tilts Z 15 degrees towards +X.
  const std::vector<const char*> plane{
      "G21", "G90 G94 G17 G40 G49 G80",           "T01 M6", "G54",          "S8000 M3",
      "G49", "G68.2 X0. Y0. Z0. I90. J15. K-90.", "G53.1",  "G0 X20. Y-8.", "G43 H1 X20. Y-8. Z40."};
  const vec3 at{20 * k + 40 * s, -8, -20 * s + 40 * k};
  CHECK(run("trunnion-5axis", plane, at, {s, 0, k}) == std::pair{std::string(), 1L});
  CHECK(run("head-head-5axis", plane, at, {s, 0, k}) == std::pair{std::string(), 1L});
  // A frame the comparison does not follow (G68.3, G68.4, G68.2 with P, G68, G54.2 Pn):
  // passed over, said once (attack 63 H3: silent, and G68.3's X Y Z read as a move).
  CHECK(
      run("head-head-5axis", joints("G68.3 X0. Y0. Z0. R30."), {10, 20, -5}, {0, 0, 1}) ==
      std::pair{std::string("job.cls:12:1: warning: channel 1: the records under `G68.3 X0. Y0. Z0. R30.` "
                            "(line 9 of its program) are not held to the CL: the comparison does not follow "
                            "that frame\n"),
                0L});
  CHECK(run("trunnion-5axis", plane, {at.x, at.y + 1, at.z}, {s, 0, k}).first ==
        "job.cls:12:1: error: channel 1: the program does not put the tool tip on this record's point (the "
        "part "
        "frame, mm; the forward transform of its words): y -8.000 where the CL has -7.000 (1.000 mm off), "
        "after "
        "the block `G43 H1 X20. Y-8. Z40.`\n");
}

TEST_CASE("cl comparison: a chain's feed blocks between two records, on the CL's straight move",
          "[analysis][cl_compare]") {
  // Attack 63 M4: a block in the middle of a move (an `on_block` that adds one, a linearised
  // move's sub-moves) was not held: only where the record ends was. The trunnion under tool-tip
  // control: X Y Z the tip; a feed from (10, 20, -5) to (30, 20, -5) upright.
  // `own_record`: the blocks are an earlier record's (an INSERT's), a FEDRAT after them.
  auto run = [](std::vector<const char*> mid, bool rapid = false, bool own_record = false) {
    compared c("trunnion-5axis", 1);
    c.cmp.record({c.next++, tool_data_event{"TLDATA", {"MILL"}, {10, 0, 100, 0, 0}}, 1}, false);
    c.cmp.record({c.next++, tool_event{tool_source::loadtl, 1, std::nullopt, false}, 1}, false);
    c.lines({"G21", "G90 G94 G17 G40 G49 G80", "T01 M6", "G54", "S8000 M3",
             "G0 G43.4 H1 X10. Y20. Z-5. A0. C0."});
    c.to({10, 20, -5}, {0, 0, 1});
    c.feed(500, feed_mode::per_minute);
    c.lines({"G1 F500."});
    for (const char* b : mid) c.cmp.line(b);
    if (own_record) c.feed(500, feed_mode::per_minute);
    c.lines({"X30."});
    c.to({30, 20, -5}, {0, 0, 1}, rapid);
    return c.text();
  };
  // Sub-moves on the line: nothing to say.
  CHECK(run({"X15.", "X20. A0.", "X25."}).empty());
  // A block that dips 20 mm mid-move: at the record that ends the move.
  CHECK(run({"X15.", "X20. Z-25.", "X25. Z-5."}) ==
        "job.cls:14:1: error: channel 1: the program's block `X20. Z-25.` (line 12 of its program) takes "
        "the tool tip 20.000 mm off the CL's straight move from (10.000, 20.000, -5.000) to this record's "
        "point, to (20.000, 20.000, -25.000) (the part frame, mm; the forward transform of its words)\n");
  // A rotary word that swings the tool about the tip under tool-tip control moves no tip; one
  // that leaves the tool off the CL's axis is the axis's finding at the record, not this one.
  CHECK(run({"X15.", "X20. A10.", "X25. A0."}).empty());
  // Past either end of the move.
  CHECK(run({"X35."}) ==
        "job.cls:14:1: error: channel 1: the program's block `X35.` (line 11 of its program) takes the tool "
        "tip 5.000 mm off the CL's straight move from (10.000, 20.000, -5.000) to this record's point, to "
        "(35.000, 20.000, -5.000) (the part frame, mm; the forward transform of its words)\n");
  // A rapid record's blocks are not held (the writer's own retracts and unwinds): the CL's
  // rapid is only where it ends (exact: nothing at all is said).
  CHECK(run({"X15.", "X20. Z-25.", "X25. Z-5."}, true).empty());
  // A rapid, an arc, a return to machine coordinates among them: no part of a straight move,
  // wherever they end (attack 66 M3, M4: an INSERT's G0 plunge, a G2 circle, G53 G1 Z-100.).
  // (Among the record's own blocks a rapid is "the CL asks for a feed move here, but the program
  // moves in rapid".)
  const std::string move = "the CL's straight move from (10.000, 20.000, -5.000) to this record's point\n";
  CHECK(run({"G0 X20.", "G1 X25."}, false, true) ==
        "job.cls:15:1: error: channel 1: the program's block `G0 X20.` (line 11 of its program) is a rapid "
        "inside " +
            move);
  CHECK(
      run({"G0 X20.", "G1 X25."}) ==
      "job.cls:14:1: error: channel 1: the CL asks for a feed move here, but the program moves in rapid: `G0 "
      "X20.`\n");
  CHECK(run({"G2 X10. Y20. I0. J10.", "G1 X25."}) ==
        "job.cls:14:1: error: channel 1: the program's block `G2 X10. Y20. I0. J10.` (line 11 of its "
        "program) is an "
        "arc inside " +
            move);
  // Under tool-tip control a rapid of rotary words alone turns the tool about its tip (the
  // writer's turn at the pole before a feed move leaves it): no finding (review 67 M1).
  CHECK(run({"G0 C90.", "G1 X25."}, false, true).empty());
  // (With no Z after it the records are passed over, Z not known: the block is said all the same.)
  CHECK(run({"G53 G1 Z-100.", "G1 X25."}, false, true) ==
        "job.cls:15:1: error: channel 1: the program's block `G53 G1 Z-100.` (line 11 of its program) is a "
        "return to "
        "the reference point or to machine coordinates inside " +
            move);
  // Joints output on the head/head (400 mm from the tip to the pivot): one block from the tool
  // upright at (-40, 0, -5) to B15 at (-20, 0, -5), both ends on the CL's line; halfway, as the
  // control moves X, Z and B together, the tip is 3.393 mm below it, the sagitta of a 15 degree
  // turn on 400 mm, 400 (1 - cos 7.5) = 3.42 (attack 66 M2). The writer cuts such a move into
  // sub-moves of under a degree (0.01 mm, the chordal tolerance: the samples).
  const double s = std::sin(15 * std::numbers::pi / 180), k = std::cos(15 * std::numbers::pi / 180);
  auto joints = [&](std::vector<const char*> blocks) {
    compared c("head-head-5axis", 1);
    c.cmp.record({c.next++, tool_data_event{"TLDATA", {"MILL"}, {10, 0, 100, 0, 0}}, 1}, false);
    c.cmp.record({c.next++, tool_event{tool_source::loadtl, 1, std::nullopt, false}, 1}, false);
    c.lines(
        {"G21", "G90 G94 G17 G40 G49 G80", "T01 M6", "G54", "S8000 M3", "G0 G43 H1 X-40. Y0. Z-5. A0. B0."});
    c.to({-40, 0, -5}, {0, 0, 1});
    c.feed(500, feed_mode::per_minute);
    for (const char* b : blocks) c.cmp.line(b);
    c.to({-20, 0, -5}, {s, 0, k}, false);
    return c.text();
  };
  CHECK(
      joints({"G1 X83.528 Y0. Z-18.63 B15. F500."}) ==
      "job.cls:14:1: error: channel 1: halfway along the program's block `G1 X83.528 Y0. Z-18.63 B15. F500.` "
      "(line 10 of its program) the tool tip is 3.393 mm off the CL's straight move from (-40.000, 0.000, "
      "-5.000) to this record's point, at (-30.446, 0.000, -8.393), as the control moves the joints (the "
      "part "
      "frame, mm; the forward transform of its words)\n");
}

TEST_CASE("cl comparison: the Integrex head's tilted tool under tool-tip control", "[analysis][cl_compare]") {
  // Attack 63 H1: a live drill at 45 degrees is written through the head's chain under tool-tip
  // control (G43.4 H#3020 with B and C: X Y Z the tip in the part frame); its records were
  // passed over (the B word left the head's offset due). An INSERT that turns C under it turns
  // the tool about the tip: the axis is 10 degrees round the part's axis from the CL's.
  auto run = [](std::vector<const char*> more) {
    compared c("integrex-i200st", 1);
    c.lines({"T13 M6", "M901", "M200", "G10.9 X0", "G97 S2000 M3", "G94", "M108", "M212", "G0 B45. C0.",
             "G0 X40. Y0.", "G0 G43.4 H#3020 X40. Y0. Z20. B45. C0."});
    const double h = std::sqrt(0.5);
    motion_event mv;
    mv.pos = {40, 0, 20};
    mv.axis = vec3{h, 0, h};
    mv.rapid = true;
    c.cmp.record({c.next++, mv, 1}, false);
    c.feed(150, feed_mode::per_minute);
    for (const char* b : more) c.cmp.line(b);
    mv.pos = {30, 0, 10};
    mv.rapid = false;
    c.cmp.record({c.next++, mv, 1}, false);
    return std::pair{c.text(), c.cmp.compared()};
  };
  CHECK(run({"G1 X30. Z10. F150."}) == std::pair{std::string(), 2L});
  CHECK(
      run({"G0 C10.", "G1 X30. Z10. F150."}).first ==
      "job.cls:12:1: error: channel 1: the CL's tool axis here is (0.7071,0.0000,0.7071), the program's "
      "rotary "
      "axes point the tool along (0.6964,0.1228,0.7071) in the part frame (7.067 degrees off), after the "
      "block "
      "`G1 X30. Z10. F150.`\n"
      "job.cls:12:1: error: channel 1: the CL asks for a feed move here, but the program moves in rapid: `G0 "
      "C10.`\n");
}

TEST_CASE("cl comparison: a chain's tool axis as I J K, and tool-tip control as an M code",
          "[analysis][cl_compare]") {
  // Attack 63 L7: under `output = "vector"` (G43.5 H1 X Y Z I J K: the tip and the tool's
  // axis in the part frame) nothing was compared; a tool-tip code that is an M code (M128) was
  // not read, and every job was refused for a move with no length offset.
  const double s = std::sin(15 * std::numbers::pi / 180), k = std::cos(15 * std::numbers::pi / 180);
  auto compare = [&](machine m, const char* move, vec3 axis) {
    diagnostic_list diags;
    cl_comparison cmp(m, m.channels[0], diags, "job.cls");
    for (const char* b : {"%", "O1000", "G21", "G90 G94 G17 G40 G49 G80", "T01 M6", "G54", "S8000 M3"})
      cmp.line(b);
    cmp.record({10, tool_event{tool_source::loadtl, 1, std::nullopt, false}, 1}, false);
    cmp.line(move);
    motion_event mv;
    mv.pos = {10, 20, -5};
    mv.axis = axis;
    mv.rapid = true;
    cmp.record({11, mv, 1}, false);
    std::string out;
    for (const diagnostic& d : diags.all()) out += format_diagnostic(d);
    return std::pair{out, cmp.compared()};
  };
  machine vector = load_machine("trunnion-5axis");
  vector.kinematics[0].output = multiaxis_output::vector;
  vector.kinematics[0].tool_tip_on = "G43.5";
  CHECK(compare(vector, "G0 G43.5 H1 X10. Y20. Z-5. I0.258819 J0. K0.965926", {s, 0, k}) ==
        std::pair{std::string(), 1L});
  CHECK(
      compare(vector, "G0 G43.5 H1 X10. Y20. Z-5. I0.258819 J0.1 K0.965926", {s, 0, k}).first ==
      "job.cls:11:1: error: channel 1: the CL's tool axis here is (0.2588,0.0000,0.9659), the program's "
      "words I J "
      "K point the tool along (0.2575,0.0995,0.9611) in the part frame (5.711 degrees off), after the block "
      "`G0 G43.5 H1 X10. Y20. Z-5. I0.258819 J0.1 K0.965926`\n");
  machine m128 = load_machine("trunnion-5axis");
  m128.kinematics[0].tool_tip_on = "M128";
  m128.kinematics[0].tool_tip_off = "M129";
  CHECK(compare(m128, "G0 X10. Y20. Z-5. A15. C90. M128", {s, 0, k}) == std::pair{std::string(), 1L});
}

TEST_CASE("cl comparison: a lathe's blocks between two records, on the CL's straight feed move",
          "[analysis][cl_compare]") {
  // The thirty-sixth note's open item: an [events] block `X20.` between a rapid record and a feed
  // record moved where the feed starts; only the record's end was held. A rapid to (40, 2), then
  // a feed to (40, -30) (the part frame, mm: X a diameter); `mid` are an earlier record's blocks
  // (an INSERT's, a FEDRAT after them), then the feed's own block.
  auto run = [](std::vector<const char*> mid, bool own_off = false, const char* after = nullptr) {
    compared c("fanuc-0itd-twin", 1);
    c.feed(0.2, feed_mode::per_rev);
    c.lines({"T0101", "G97 S1000 M3", "G0 X80. Z2."});
    c.go(40, 2, true);
    for (const char* b : mid) c.cmp.line(b);
    c.feed(0.2, feed_mode::per_rev);
    c.lines({own_off ? "G1 X60. Z-30. F0.2" : "G1 X80. Z-30. F0.2"});
    if (after) c.cmp.line(after);  // a block that moves nothing, after the record's own
    c.go(40, -30);
    return c.text();
  };
  // Blocks on the line (a user block that feeds part of the way), or a rapid back to where the
  // tool stands: nothing to say.
  CHECK(run({"G1 Z-10. F0.2"}).empty());
  CHECK(run({"G0 X80. Z2."}).empty());
  // More blocks than are held (attack 68 H3: past the first 64 an off-line block passed).
  std::vector<std::string> many(4097, "G1 Z-1. F0.2");
  many.push_back("G1 X200. Z-15.");
  std::vector<const char*> many_c;
  for (const std::string& b : many) many_c.push_back(b.c_str());
  CHECK(run(many_c) ==
        "job.cls:13:1: error: channel 1: the program writes more than 4096 blocks inside the CL's straight "
        "feed move to this record's point: they are not held to it; give the move as CL records\n");
  // A feed to an axis word given by a variable: where it ends is not known (attack 68 M5).
  CHECK(
      run({"G1 X#100 Z-10."}) ==
      "job.cls:13:1: error: channel 1: the program's block `G1 X#100 Z-10.` (line 7 of its program) moves "
      "the "
      "tool inside the CL's straight feed move from (40.000, 0.000, 2.000) to this record's point to an axis "
      "word given by a variable or an expression: where it cuts is known only when the block runs\n");
  // The record's own block stays the record's with a block after it that moves nothing.
  CHECK(run({"G1 Z-10. F0.2"}, false, "M8").empty());
  // A rapid elsewhere: the feed would start there (a cone cut from X20 to X80 Z-30).
  CHECK(run({"G0 X20."}) ==
        "job.cls:13:1: error: channel 1: the program's block `G0 X20.` (line 7 of its program) is a rapid "
        "inside the CL's straight feed move from (40.000, 0.000, 2.000) to this record's point, to (10.000, "
        "0.000, 2.000): the feed then starts there\n");
  // A feed block off the line, an arc, a return home: no part of the straight feed move.
  CHECK(run({"G1 X60. Z-10."}) ==
        "job.cls:13:1: error: channel 1: the program's block `G1 X60. Z-10.` (line 7 of its program) takes "
        "the tool tip 10.000 mm off the CL's straight feed move from (40.000, 0.000, 2.000) to this record's "
        "point, to (30.000, 0.000, -10.000) (the part frame, mm)\n");
  CHECK(run({"G2 X80. Z-10. R10."}) ==
        "job.cls:13:1: error: channel 1: the program's block `G2 X80. Z-10. R10.` (line 7 of its program) is "
        "an arc inside the CL's straight feed move from (40.000, 0.000, 2.000) to this record's point\n");
  CHECK(
      run({"G28 U0."}) ==
      "job.cls:13:1: error: channel 1: the program's block `G28 U0.` (line 7 of its program) is a return to "
      "the reference point or to machine coordinates inside the CL's straight feed move from (40.000, "
      "0.000, 2.000) to this record's point\n");
  // The record's own block is the record's comparison's (its end, its rapid), not held twice.
  CHECK(run({"G1 Z-10. F0.2"}, true) ==
        "job.cls:13:1: error: channel 1: the program does not put the tool tip on this record's point (the "
        "part frame, mm): x 30.000 where the CL has 40.000 (10.000 mm off), after the block `G1 X60. Z-30. "
        "F0.2`\n");
}
