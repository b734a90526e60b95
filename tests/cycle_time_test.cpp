// The time of blocks (analysis/block_timer.hpp) and of channels run together
// (analysis/cycle_time.hpp), against figures worked out by hand from the built-in
// fanuc-0itd-twin's [timing]: X 20000 and Z 24000 mm/min rapid, 0.5 s tool change,
// 0.1 s a wait code and an M code.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include <fmt/format.h>

#include "analysis/block_timer.hpp"
#include "analysis/cycle_time.hpp"
#include "analysis/timeline_report.hpp"
#include "file_test_support.hpp"
#include "machine_test_support.hpp"
#include "machines/machine_loader.hpp"

using namespace twinpost;

namespace {

// Each block as "seconds|untimed" with the seconds to 4 decimals.
std::string times(const machine& m, int channel, std::initializer_list<std::string_view> blocks) {
  block_timer t(m, channel);
  std::string out;
  for (std::string_view b : blocks) {
    const block_timing bt = t.time(b);
    out += fmt::format("{:.4f}{}\n", bt.seconds, bt.untimed.empty() ? "" : "|" + bt.untimed);
  }
  return out;
}

}  // namespace

TEST_CASE("block timer: rapids axis by axis, feeds per minute, X as a diameter", "[analysis][timeline]") {
  const machine m = load_machine("fanuc-0itd-twin");
  CHECK(times(m, 1,
              {"G0 G18 G21 G40 G54 G80 G98", "G0 X100. Z5.", "G1 Z-95. F200.", "G0 X110.", "G0 Z5.",
               "G0 X50. Z-7.", "U10. W-2.", "G1 X70. Z-17. F100."}) ==
        "0.0000\n"
        "0.0000|G0 from an unknown position\n"  // where the slide starts is not in the program
        "30.0000\n"                             // 100 mm at 200 mm/min
        "0.0150\n"                              // X 10 on the diameter: 5 mm at 20000 mm/min
        "0.2500\n"                              // 100 mm at 24000 mm/min
        "0.0900\n"                              // X 30 mm (0.09 s), Z 12 mm (0.03 s): the longer
        "0.0150\n"                              // U/W incremental: X 5 mm (0.015 s), Z 2 mm
        "5.6604\n");                            // X 5 mm and Z 8 mm: sqrt(89) mm at 100 mm/min
}

TEST_CASE("block timer: the unit is the modal state's, G70 and G71 in G-code system C",
          "[analysis][timeline]") {
  // The twin lathe with a header in system C (G71 millimetres, G90 absolute): G70 selects the
  // inch (analysis/modal_state), a mode block of no time; the rapid W-10. is then 254 mm at
  // 24000 mm/min, 0.635 s. (The timer kept a unit of its own and took G70 for an unknown
  // code: "G70" not timed, and 10 mm, 0.025 s.)
  const machine m = test::system_c_twin();
  CHECK(
      times(m, 1, {"G0 G18 G71 G40 G54 G80 G90 G98", "G0 X100. Z5.", "G70", "G0 W-10.", "G71", "G0 W-10."}) ==
      "0.0000\n"
      "0.0000|G0 from an unknown position\n"
      "0.0000\n"
      "0.6350\n"
      "0.0000\n"
      "0.0250\n");
  // The axes stay where they are at a unit change, their numbers said again: Z5. (mm) is Z0.19685
  // in inches, and G0 Z1. runs 20.4 mm, 0.051 s (review 41 H5: the timer kept the number 5, 5 in,
  // and timed 101.6 mm, 0.254 s).
  CHECK(times(m, 1, {"G0 G18 G71 G40 G54 G80 G90 G98", "G0 X100. Z5.", "G70", "G0 Z1.", "G71", "G0 Z5."}) ==
        "0.0000\n"
        "0.0000|G0 from an unknown position\n"
        "0.0000\n"
        "0.0510\n"
        "0.0000\n"
        "0.0510\n");
  // System C's G20 is its OD turning cycle: it and its passes are not timed (the timer knows
  // system A's cycles only), and the tool is back where the cycle began: G0 X110. from X100.
  // is 5 mm, 0.015 s (review 41 H4: G20 was timed as a rapid to X80. Z-40.).
  CHECK(
      times(m, 1,
            {"G0 G18 G71 G40 G54 G80 G90 G99", "G0 X100. Z5.", "G20 X80. Z-40. F0.2", "X76.", "G0 X110."}) ==
      "0.0000\n"
      "0.0000|G0 from an unknown position\n"
      "0.0000|G20\n"
      "0.0000|G20\n"
      "0.0150\n");
}

TEST_CASE("block timer: feed per revolution, CSS at the diameter, G32 at lead x rpm",
          "[analysis][timeline]") {
  const machine m = load_machine("fanuc-0itd-twin");  // main spindle max_rpm 4000
  CHECK(times(m, 1,
              {"G50 X100. Z10.", "G97 S800 M3", "G99", "G1 Z-10. F0.2", "G50 S3000", "G96 S200", "G1 Z-30.",
               "G97 S500", "G0 Z5.", "G32 Z-25. F1.5", "G98 G4 U2.5", "M5", "G99 G1 X120. F0.2"}) ==
        "0.0000\n"  // G50 X Z: the position is set, nothing moves
        "0.1000\n"  // M3: one M code
        "0.0000\n"
        "7.5000\n"  // 20 mm at 0.2 mm/rev x 800 rpm = 160 mm/min
        "0.0000\n"
        "0.0000\n"
        "9.4248\n"  // 200 m/min at 100 mm: 636.62 rpm; 20 mm at 127.32 mm/min
        "0.0000\n"
        "0.0875\n"  // Z 35 mm at 24000 mm/min
        "2.4000\n"  // 30 mm at 1.5 mm/rev x 500 rpm
        "2.5000\n"  // the dwell: U in seconds (codes.dwell = "G4 U{seconds}")
        "0.1000\n"
        "0.0000|G1 per revolution on a stopped spindle\n");
}

TEST_CASE("block timer: arcs by I/K and by R, tool calls, Mazak's dwell in ms", "[analysis][timeline]") {
  const machine fanuc = load_machine("fanuc-0itd-twin");
  CHECK(times(fanuc, 1,
              {"G50 X0. Z0.", "G98 T0101", "T0102", "T0303", "G3 X20. Z-10. I0. K-10. F100.",
               "G2 X40. Z-20. R10.", "G3 X60. Z-30. R-10.", "G1 X60. Z-30. F100.", "G2 X60. Z-30. K-10.",
               "G2 X60. Z-30. I0. K-10."}) ==
        "0.0000\n"
        "0.5000\n"  // T0101: a tool call (0.5 s)
        "0.0000\n"  // T0102: the same tool, another offset
        "0.5000\n"
        "9.4248\n"   // a quarter circle of radius 10 (X is a diameter: 10 mm radial), 15.708 mm:
                     // counter-clockwise in the Z-X plane (Z right, X up as drawn), so G3
        "9.4248\n"   // a quarter by R
        "28.2743\n"  // R-10: the three-quarter arc, 47.124 mm
        "0.0000\n"   // no move
        "37.6991\n"  // the same start and end by K: a full circle of radius 10 at 100 mm/min
        "37.6991\n");
  const machine mazak = load_machine("integrex-i200st");  // dwell "G4 P{ms}"
  CHECK(times(mazak, 2, {"G4 P1500", "G4 U3.", "T0202", "M8"}) == "1.5000\n0.0000|G4\n0.5000\n0.1000\n");
}

TEST_CASE("block timer: reference returns, macro calls and unknown cycles are not timed, and say so",
          "[analysis][timeline]") {
  const machine m = load_machine("fanuc-0itd-twin");
  CHECK(times(m, 1,
              {"G50 X0. Z5.", "G28 U0.", "G0 X50.", "G65 P9001", "G0 X60.", "G71 U2. R0.5",
               "G71 P10 Q20 U0.4 W0.1 F0.25"}) ==
        "0.0000\n"
        "0.0000|G28\n"
        "0.0000|G0 from an unknown position\n"  // X went to the reference point
        "0.0000|G65\n"
        "0.0150\n"
        "0.0000|G71\n"  // the lathe's roughing cycle: its moves are the contour's, not in the block
        "0.0000|G71\n");
}

TEST_CASE("block timer: G codes compared as numbers however written and a code no control has is named",
          "[analysis][timeline]") {
  const machine m = load_machine("fanuc-0itd-twin");
  CHECK(times(m, 1,
              {"G50 X100. Z10.", "G00 X110.", "G01. Z0. F200.", "G1.0 Z-10.", "G098", "G0 Z5.", "G84.25 Z0.",
               "G-1 Z-5.", "G+0 X120.", "G0.5 X100."}) ==
        "0.0000\n"
        "0.0150\n"         // G00: a rapid, X 5 mm at 20000 mm/min
        "3.0000\n"         // G01.: a feed, 10 mm at 200 mm/min
        "3.0000\n"         // G1.0 as well
        "0.0000\n"         // G098: feed per minute (the machine's feed_per_min code)
        "0.0375\n"         // 15 mm at 24000 mm/min
        "0.0000|G84.25\n"  // two decimals: no control's code, named as written
        "0.0000|G-1\n"
        "0.0150\n"         // G+0 is G0
        "0.0000|G0.5\n");  // one decimal: a code (not this control's), named as the program has it
}

// Canned cycles, timed from their words as the control moves (docs/timeline.md, "Canned
// cycles"). fanuc-0itd-twin and the 31i's turrets: rapid X 20000 (the radius), Z 24000 mm/min;
// the Integrex upper head X 38000 (radius of a diameter X), Y 26000, Z 38000 mm/min.
TEST_CASE("block timer: drilling, pecking, tapping and side cycles timed from their words",
          "[analysis][timeline]") {
  const machine m = load_machine("fanuc-0itd-twin");
  CHECK(times(m, 1,
              {"G50 X0. Z5.", "G98 G83 X0. Z-20. R-3. Q5000 F100.", "G80", "G0 Z10.", "G50 X0. Z30.",
               "G97 S300 M3", "G99", "M29 S300", "G84 X0. Z-18. R-25. F1.5", "G80", "G0 Z30."}) ==
        "0.0000\n"
        // Initial level Z5, R point 5 - 3 = Z2, bottom Z-20 (22 mm), Q5000 = 5 mm pecks out to
        // the R point, back in at rapid to 0.5 mm above the last depth (G83 with Q on a Fanuc
        // lathe as the machine file writes it, parameter RTR = 1). Feeds at 100 mm/min: 5, then
        // 5.5 three times (from 4.5, 9.5, 14.5), then 2.5 (19.5 to 22): 22 + 4 x 0.5 = 24 mm,
        // 14.4 s. Rapids at 24000 mm/min: 3 (to R) + 5 + 4.5 + 10 + 9.5 + 15 + 14.5 + 20 + 19.5
        // + 25 (back to the initial level) = 126 mm, 0.315 s.
        "14.7150\n"
        "0.0000\n"
        "0.0125\n"  // the cycle returned to the initial level: Z 5 to 10
        "0.0000\n"
        "0.1000\n"
        "0.0000\n"
        "0.1000\n"  // M29
        // Tapping at F1.5 per revolution, 300 rpm: 450 mm/min. Z30 to the R point Z5 at rapid
        // (25 mm, 0.0625 s), in 23 mm (3.0667 s), out 23 mm with the spindle reversed (3.0667 s),
        // to the initial level at rapid (0.0625 s): 6.2583 s.
        "6.2583\n"
        "0.0000\n"
        "0.0000\n");  // already at the initial level

  // The Integrex upper head: G98 back to the initial level, G99 to the R point; R is the R
  // point's Z and Q a length in mm (no r_from_initial, no q_increments).
  const machine integrex = load_machine("integrex-i200st");
  CHECK(times(integrex, 1,
              {"G17 G94 G90", "G0 X0. Y0. Z30.", "G98 G73 X0. Y0. Z-24. R3. Q6. F120.", "G80",
               "G99 G82 X10. Y5. Z-3.5 R2. P400 F150.", "G80", "G0 Z30."}) ==
        "0.0000\n"
        "0.0000|G0 from an unknown position\n"
        // Z30 to R3 at rapid (27 mm), pecks of 6 backing off 0.5 mm: feeds 6 + 6.5 + 6.5 + 6.5 +
        // 3.5 = 29 mm at 120 mm/min (14.5 s), back-offs 4 x 0.5 = 2 mm, out to Z30 (54 mm): 83 mm
        // of rapid at 38000 mm/min, 0.1311 s. 14.6311 s.
        "14.6311\n"
        "0.0000\n"
        // X0 Y0 to X10 Y5 in one rapid (X a diameter: 5 mm at 38000, 0.0079 s; Y 5 mm at 26000,
        // 0.0115 s: the slower), Z30 to R2 (28 mm, 0.0442 s), 5.5 mm at 150 mm/min (2.2 s), the
        // 0.4 s dwell, back to the R point Z2 under G99 (0.0087 s).
        "2.6644\n"
        "0.0000\n"
        "0.0442\n");  // from the R point Z2 up to Z30

  // The 31i's mill head: side drilling along X (G87) and side tapping (G88), R from the
  // initial level in radius, X a diameter.
  const machine fanuc3 = load_machine("fanuc-31i-3path");
  CHECK(times(fanuc3, 3,
              {"G50 X66. Z-20.", "G98", "G87 X30. Z-20. R0. F120.", "G80", "G97 S400 M33", "G99",
               "G88 X36. Z-20. R0. F1.25", "G80"}) ==
        "0.0000\n"
        "0.0000\n"
        "9.0540\n"  // 18 mm (radius) in at 120 mm/min (9 s), out at 20000 mm/min (0.054 s)
        "0.0000\n"
        "0.1000\n"
        "0.0000\n"
        "3.6000\n"  // 15 mm in and 15 out at 1.25 x 400 = 500 mm/min
        "0.0000\n");
}

TEST_CASE("block timer: thread and grooving cycles timed pass by pass", "[analysis][timeline]") {
  const machine m = load_machine("fanuc-0itd-twin");
  CHECK(times(m, 1,
              {"G50 X30. Z5.", "G97 S500 M3", "G76 P020060 Q50 R0.05", "G76 X21.54 Z-26. P1230 Q400 F2.",
               "G0 X40."}) ==
        "0.0000\n"
        "0.1000\n"
        "0.0000\n"  // the first block sets the cycle: 2 finishing passes, 60 degrees, 0.05 least cut
        // Height 1.23, first cut 0.4, allowance 0.05: depths 0.4 sqrt(n) to 1.18 (0.4, 0.5657,
        // 0.6928, 0.8, 0.8944, 0.9798, 1.0583, 1.1314, 1.18), then 1.23 twice: 11 passes. Each
        // starts (d - 0.4) tan 30 deg later along Z (flank infeed; 3.3269 mm in all), threads to
        // Z-26 at 2 x 500 = 1000 mm/min ((11 x 31 - 3.3269) mm: 20.2604 s), comes out and back to
        // the start at rapid: Z 11 x 31 mm + 3.3269 mm (0.8608 s), X in and out 2 (3 + d) mm of
        // radius a pass (86.3248 mm: 0.2590 s). 21.3802 s.
        "21.3802\n"
        "0.0150\n");  // back at the start X30: 5 mm of radius to X40
  // G92 (the 31i) and G292 (the Integrex): one pass a block, modal. X30 to X28.5 (0.75 mm at
  // 20000: 0.00225 s), 25 mm at 1.5 x 500 = 750 mm/min (2 s), out (0.00225 s), Z back (25 mm
  // at 24000: 0.0625 s): 2.067 s; X28. the same with 1 mm in and out: 2.0685 s.
  const machine fanuc3 = load_machine("fanuc-31i-3path");
  CHECK(times(fanuc3, 1, {"G50 X30. Z5.", "G97 S500 M3", "G92 X28.5 Z-20. F1.5", "X28.", "G0 X40."}) ==
        "0.0000\n0.1000\n2.0670\n2.0685\n0.0150\n");
  const machine integrex = load_machine("integrex-i200st");
  CHECK(times(integrex, 2, {"G0 X30. Z5.", "G97 S500 M203", "G292 X28.5 Z-20. F1.5", "X28.", "G0 X40."}) ==
        "0.0000|G0 from an unknown position\n0.1000\n2.0670\n2.0685\n0.0150\n");
  // G75: from X40 Z2, plunges to X20.8 (9.6 mm of radius) in pecks of 2.6 mm (no back-off:
  // R0.), 16 of them from Z2 to Z-28 every 2 mm, at 0.06 x 600 = 36 mm/min: 16 x 16 s. Out at
  // rapid 16 x 9.6 mm (0.4608 s), along Z 30 mm and back 30 mm (0.15 s). 256.6108 s.
  CHECK(times(m, 1,
              {"G50 X40. Z2.", "G97 S600 M3", "G99", "G75 R0.", "G75 X20.8 Z-28. P2600 Q2000 F0.06",
               "G0 X50."}) == "0.0000\n0.1000\n0.0000\n0.0000\n256.6108\n0.0150\n");
}

namespace {

std::vector<nc_source> hand_job() {
  // docs/timeline.md works these out by hand.
  return {{"PART_1.nc",
           "%\nO1000 (HAND)\nG21 G98 G18\nT0101\nG97 S1000 M3\nG0 X100. Z5.\nG1 Z-95. F200.\nG0 X110.\n"
           "G0 Z5.\nM100\nT0303\nG0 X60.\nG1 X40. F100.\nG4 U2.5\nG0 X110. Z5.\nM101\nM30\n%\n"},
          {"PART_2.nc",
           "%\nO1000 (HAND)\nG21 G98 G18\nT0202\nG97 S800 M4\nG0 X50. Z2.\nG1 Z-20. F300.\nG0 Z2.\n"
           "M100\nG99\nG1 Z-10. F0.2\nG0 Z2.\nM101\nM30\n%\n"}};
}

}  // namespace

TEST_CASE("timeline: two channels run together, idle at their waits, the critical path",
          "[analysis][timeline]") {
  const machine m = load_machine("fanuc-0itd-twin");
  timeline_options o;
  o.keep_blocks = true;
  const timeline t = make_timeline(hand_job(), m, o);
  REQUIRE(t.ok);
  REQUIRE(t.channels.size() == 2);
  CHECK(format_timeline_text(t) ==
        "cycle time at least 40.245 s (channel 1 ends last)\n"
        "  channel 1: 40.245 s working + 0.000 s idle at 2 waits = 40.245 s\n"
        "  channel 2: 9.785 s working + 30.460 s idle at 2 waits = 40.245 s\n"
        "  2 blocks not timed: G0 from an unknown position (2, first at PART_1.nc:6)\n"
        "  balance: channel 2 idles 25.810 s at M100 (PART_2.nc:9) waiting for channel 1; channel 2 idles "
        "4.650 s at M101 (PART_2.nc:13) waiting for channel 1\n");
  // Two blocks not timed (the first rapids, from where the slides start): a lower bound.
  CHECK(format_timeline_json(t).find(",\"cycle\":40.245,\"at_least\":true,") != std::string::npos);
  CHECK(t.channels[0].end == Approx(40.245).epsilon(1e-12));
  CHECK(t.channels[1].busy == Approx(9.785).epsilon(1e-12));
  CHECK(t.channels[1].waits[0].idle() == Approx(25.81).epsilon(1e-12));
  CHECK(t.channels[1].waits[1].idle() == Approx(4.65).epsilon(1e-12));
  // The critical path is channel 1 throughout; channel 2's operations are not on it.
  REQUIRE(t.critical.size() == 3);
  for (const critical_stretch& c : t.critical) CHECK(c.channel == 1);
  for (const tool_operation& op : t.channels[1].operations) CHECK_FALSE(op.critical);
  // Operations: per tool between waits.
  std::string ops;
  for (const tool_operation& op : t.channels[0].operations)
    ops += fmt::format("{} {:.3f}+{:.3f} ({} blocks) seg {}\n", op.tool, op.start, op.seconds, op.blocks,
                       op.segment);
  CHECK(ops ==
        " 0.000+0.000 (2 blocks) seg 0\n"
        "T01 0.000+30.965 (7 blocks) seg 0\n"
        "T03 30.965+9.280 (6 blocks) seg 1\n"
        "T03 40.245+0.000 (1 blocks) seg 2\n");  // M30 after the last wait
  REQUIRE(t.channels[1].kept.size() == 13);      // every line with words, O1000 to M30
  CHECK(t.channels[1].kept[10].text == "G0 Z2.");
  CHECK(t.channels[1].kept[10].start == Approx(35.465).epsilon(1e-12));  // released at 30.965, then 4.5 s
}

TEST_CASE("timeline: programs that do not check sound have no timeline, the check's errors say why",
          "[analysis][timeline]") {
  const machine m = load_machine("fanuc-0itd-twin");
  std::vector<nc_source> job = hand_job();
  job[1].text = "%\nG0 X50. Z2.\nM100\nM30\n%\n";  // its M101 is missing
  const timeline t = make_timeline(job, m);
  CHECK_FALSE(t.ok);
  REQUIRE_FALSE(t.diagnostics.empty());
  CHECK(t.diagnostics[0].message ==
        "wait M101 of channel 1 is never met: channel 2 ends at PART_2.nc:4 without a matching wait");
}

TEST_CASE("timeline: programs read from files have every block timed, not only the last of a run",
          "[analysis][timeline]") {
  // The reader skips runs of plain blocks when only the waits matter; the timeline needs each.
  const machine m = load_machine("fanuc-0itd-twin");
  const std::string dir = test::fresh_temp_dir("timeline");
  const test::removed_at_end cleanup{dir};
  std::vector<nc_source> job = hand_job();
  for (nc_source& s : job) {
    REQUIRE(test::write_file(dir + "/" + s.name, s.text));
    s.path = dir + "/" + s.name;
    s.text.clear();
  }
  const timeline t = make_timeline(job, m);
  REQUIRE(t.ok);
  CHECK(t.channels[0].blocks == 16);
  CHECK(t.channels[1].blocks == 13);
  CHECK(fmt::format("{:.3f} {:.3f}", t.channels[0].end, t.channels[1].busy) == "40.245 9.785");
}

TEST_CASE("machine [timing]: per-channel overrides and the rates every axis needs", "[analysis][timeline]") {
  const machine m = load_machine("fanuc-31i-3path");
  CHECK(m.channels[0].timing.tool_change == 0.5);
  CHECK(m.channels[2].timing.tool_change == 4.0);
  CHECK(m.channels[2].timing.rapid_of('Y') == 10000);
  CHECK(m.channels[2].timing.rapid_of('X') == 20000);
  CHECK(m.channels[1].timing.wait == 0.1);
  const std::string base = R"(
[machine]
name = "t"
control = "fanuc-0i-td"
[waits]
first = 100
last = 102
[[channel]]
number = 1
heads = [1]
  [[channel.axis]]
  address = "X"
  diameter = true
  [[channel.axis]]
  address = "Z"
)";
  try {
    parse_machine(base + "[timing]\nrapid = { X = 20000 }\n", "t.toml");
    FAIL("no error");
  } catch (const config_error& e) {
    CHECK(std::string(e.what()) ==
          "t.toml:16:1: error: timing: no rapid rate for axis Z of channel 1 (timing.rapid.Z or "
          "timing.channel.1.rapid.Z)");
  }
  try {
    parse_machine(base + "[timing]\nrapid = { X = 20000, Z = 0 }\n", "t.toml");
    FAIL("no error");
  } catch (const config_error& e) {
    CHECK(std::string(e.what()) == "t.toml:17:26: error: timing.rapid.Z must be > 0, not 0");
  }
  try {
    parse_machine(base + "[timing]\nrapid = { X = 1, Z = 1 }\n[timing.channel.2]\ntool_change = 1\n",
                  "t.toml");
    FAIL("no error");
  } catch (const config_error& e) {
    CHECK(std::string(e.what()) == "t.toml:18:1: error: timing.channel.2: this machine has no channel 2");
  }
}

TEST_CASE("block timer: a facing cut under CSS follows the rpm along the diameter, up to the clamp",
          "[analysis][timeline]") {
  const machine m = load_machine("fanuc-0itd-twin");
  // 200 m/min clamped at 2000 rpm: the clamp holds below d = 200000 / (pi x 2000) = 31.831 mm.
  // Facing from X100 to X20 (40 mm of path) at 0.2 mm/rev:
  //   above 31.831: the integral of d / k over the move, k = 200000 / pi;
  //   below it: 2000 rpm. Worked out: 11.4746 s (a 200000-step sum gives the same to 1e-9).
  const auto facing = [&](const char* first, const char* second) {
    return times(m, 1, {"G50 X100. Z0.", "G50 S2000", "G96 S200 M3", first, second});
  };
  CHECK(facing("G99 G1 X20. F0.2", "G1 X0.") ==
        "0.0000\n"
        "0.0000\n"
        "0.1000\n"
        "11.4746\n"
        "1.5000\n");  // 10 mm at 0.2 mm/rev x 2000 rpm (below the clamp's diameter all the way)
  // X100 to X0 in one block, across the clamp's diameter: 10.5873 s under CSS down to
  // d = 31.831 mm, then 15.9155 mm of path at 0.2 mm/rev x 2000 rpm, 2.3873 s; back out the same.
  CHECK(facing("G99 G1 X0. F0.2", "G1 X100.") ==
        "0.0000\n"
        "0.0000\n"
        "0.1000\n"
        "12.9746\n"
        "12.9746\n");
}

TEST_CASE("timeline: who meets whom is the checker's word, fixed waits of two of three paths included",
          "[analysis][timeline]") {
  // Star-style: M82 is a wait of paths 1 and 2 only, M300 (no P) of all three. Timing: X and Z
  // at 6000 mm/min, a wait 0 s, so each figure is a feed or a rapid worked out by hand.
  const machine m = parse_machine(
      "[machine]\nname = \"star-timed\"\n"
      "[waits]\nfirst = 200\nlast = 998\npartners = \"path_numbers\"\npartner_list = \"optional\"\n"
      "  [[waits.fixed]]\n  code = 82\n  channels = [1, 2]\n"
      "[timing]\nrapid = { X = 6000, Z = 6000 }\ntool_change = 0\nwait = 0\nm_code = 0\n"
      "[[channel]]\nnumber = 1\n" +
          test::xz_axes + "[[channel]]\nnumber = 2\n" + test::xz_axes + "[[channel]]\nnumber = 3\n" +
          test::xz_axes,
      "star-timed.toml");
  const std::vector<nc_source> job = {
      {"S_1.NC", "G50 X0. Z0.\nG98 G1 Z100. F600.\nM82\nM300\nM30\n"},                 // 10 s, then M82, M300
      {"S_2.NC", "G50 X0. Z0.\nG98 G1 Z50. F600.\nM82\nG1 Z150. F600.\nM300\nM30\n"},  // 5 s, M82, 10 s
      {"S_3.NC", "G50 X0. Z0.\nG98 G1 Z20. F600.\nM300\nM30\n"}};                      // 2 s, M300
  const timeline t = make_timeline(job, m);
  REQUIRE(t.ok);
  CHECK(
      format_timeline_text(t) ==
      "cycle time 20.000 s (channel 1 ends last)\n"
      "  channel 1: 10.000 s working + 10.000 s idle at 2 waits = 20.000 s\n"
      "  channel 2: 15.000 s working + 5.000 s idle at 2 waits = 20.000 s\n"
      "  channel 3: 2.000 s working + 18.000 s idle at 1 wait = 20.000 s\n"
      "  balance: channel 3 idles 18.000 s at M300 (S_3.NC:3) waiting for channel 2; channel 1 idles "
      "10.000 s at M300 (S_1.NC:4) waiting for channel 2; channel 2 idles 5.000 s at M82 (S_2.NC:3) waiting "
      "for channel 1\n");
  // Every block timed: the cycle time is the time, not a lower bound (the JSON says so too).
  CHECK(format_timeline_json(t).find(",\"cycle\":20.000,\"at_least\":false,") != std::string::npos);
}

TEST_CASE("block timer: X in radius under G10.9 X0 and C in mm under polar interpolation",
          "[analysis][timeline]") {
  const machine m = load_machine("integrex-i200st");  // channel 1: X 38 m/min, C 100 rev/min
  CHECK(times(m, 1,
              {"G0 X40. Y0. Z5. C0.", "G10.9 X0", "G0 X40.", "G1 X20. F400.", "G0 C90.", "G17 XC", "G12.1",
               "G0 X40. C25. Z5.", "G1 X-40. F400.", "G13.1", "G18", "G1 X30. F400.", "G10.9 X1",
               "G0 X100."}) ==
        "0.0000|G0 from an unknown position\n"
        "0.0000\n"  // G10.9 X0: a mode, no move; X40 in diameter is X20 now
        "0.0316\n"  // X20 to X40 in radius: 20 mm at 38000 mm/min
        "3.0000\n"  // 20 mm of radius at 400 mm/min
        "0.1500\n"  // C 90 degrees at 36000 deg/min
        "0.0000\n"
        "0.0000\n"
        "0.0000|G0 from an unknown position\n"  // C changed its unit: where it is in mm is unknown
        "12.0000\n"                             // X 80 mm in the plane at 400 mm/min
        "0.0000\n"
        "0.0000\n"
        "0.0000|G1 from an unknown position\n"  // the plane's X-40 is not where the X slide is
        "0.0000\n"
        "0.0316\n");  // X30 in radius is X60 in diameter: 20 mm of radius to X100 at 38000 mm/min
}

TEST_CASE("block timer: C in cylindrical interpolation is arc length on the cylinder of G7.1",
          "[analysis][timeline]") {
  const machine m = load_machine("integrex-i200st");  // G7.1 C{radius}: the cylinder's radius
  CHECK(times(m, 1,
              {"G10.9 X0", "G0 X10. Y0. Z20. C0.", "G17", "G7.1 C20.", "G1 C90. F200.", "X15. C180.",
               "G7.1 C0", "G1 C270."}) ==
        "0.0000\n"
        "0.0000|G0 from an unknown position\n"
        "0.0000\n"
        "0.0000\n"   // G7.1 C20.: a mode, no move
        "9.4248\n"   // 90 degrees on radius 20: 31.416 mm at 200 mm/min
        "9.5434\n"   // hypot(5, 31.416) mm (X in radius) at 200 mm/min
        "0.0000\n"   // G7.1 C0: the mode off
        "27.0000\n"  // C alone again: 90 degrees at F read as degrees per minute
  );
}

TEST_CASE("block timer: inverse-time feed (G93) takes 1/F minutes a block, whatever its length",
          "[analysis][timeline]") {
  const machine m = load_machine("head-head-5axis");
  CHECK(times(m, 1,
              {"G90 G94 G17", "G0 X0. Y0. Z50. A0. B0.", "G93 G1 X1. B5. F600.", "X3. B10. F60.",
               "G94 G1 X13. F600.", "G1 X14. F600."}) ==
        "0.0000\n"
        "0.0000|G0 from an unknown position\n"
        "0.1000\n"  // 1/600 min
        "1.0000\n"  // 1/60 min, 2 mm and 5 degrees
        "1.0000\n"  // G94 again: 10 mm at 600 mm/min
        "0.1000\n");
}
