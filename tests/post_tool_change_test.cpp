// A tool change as public posts make it (Fusion "FANUC Turning", "Doosan Mill/Turn" and
// "Mazak Integrex i"): coolant off, home X then Z, the call, the coolant the CL left on back
// on; a mill head also stops its spindle and turns it again before the next move.
// SPINDL/ON restores the last speed, never S0. COOLNT kinds without a code are refused.
#include <catch2/catch.hpp>

#include <string>

#include "file_test_support.hpp"
#include "machines/machine_loader.hpp"
#include "post_test_jobs.hpp"

using namespace twinpost;

namespace {

test::posted post_on(const std::string& cl, const std::string& machine_name, const std::string& tag) {
  return test::post_in_fresh_dir(cl, load_machine(machine_name), "tool-change-" + tag,
                                 [](const diagnostic& d) { return d.level == severity::error; });
}

std::string file_of(const test::posted& p, const std::string& name) {
  if (!p.ok) return "(failed)\n" + p.diagnostics;
  const auto f = p.files.find(name);
  return f == p.files.end() ? "(missing)" : f->second;
}

}  // namespace

TEST_CASE("a turret's tool change turns the coolant off, homes X then Z, and turns it on again",
          "[post][tools]") {
  const test::posted p = post_on(
      "PARTNO TC\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nCOOLNT/ON\nFEDRAT/0.2,MMPR\n"
      "GOTO/20,0,2\nGOTO/20,0,-10\nTURRET/3,3\nGOTO/15,0,2\nFINI\n",
      "fanuc-0itd-twin", "turret");
  CHECK(file_of(p, "TC_1.nc") ==
        "%\nO1000 (TC)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG97 S1000 M3\nM8\n"
        "G1 X40. Z2. F0.2\nZ-10.\nM9\nG28 U0.\nG28 W0.\nT0303\nM8\nG1 X30. Z2. "
        "F0.2\nM100\nM9\nG28 U0.\n"
        "G28 W0.\nM5\nM30\n%\n");
}

TEST_CASE("COOLNT/ON after the tool change writes no second M8", "[post][tools]") {
  const test::posted p = post_on(
      "PARTNO TC\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nCOOLNT/ON\nFEDRAT/0.2,MMPR\n"
      "GOTO/20,0,2\nTURRET/3,3\nCOOLNT/ON\nGOTO/15,0,2\nFINI\n",
      "fanuc-0itd-twin", "again");
  CHECK(file_of(p, "TC_1.nc") ==
        "%\nO1000 (TC)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG97 S1000 M3\nM8\n"
        "G1 X40. Z2. F0.2\nM9\nG28 U0.\nG28 W0.\nT0303\nM8\nG1 X30. Z2. F0.2\nM100\nM9\nG28 "
        "U0.\nG28 W0.\n"
        "M5\nM30\n%\n");
}

TEST_CASE("the mill head stops its spindle for the tool change and starts it before the next move",
          "[post][tools]") {
  // No SPINDL after the second tool: the spindle in force turns again before the first move
  // (both are turning tools: the head's milling spindle is not theirs), said again with its
  // speed, and the first feed writes its F, for a restart at the tool (review 49, M4).
  const test::posted p = post_on(
      "PARTNO TC\nHEAD/1\nTLDATA/TURN\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/0.2,MMPR\nGOTO/20,0,2\n"
      "TLDATA/TURN\nLOADTL/2\nGOTO/15,0,2\nFINI\n",
      "integrex-i200st", "mill-head");
  CHECK(file_of(p, "TC.EIA") ==
        "%\nO1000(TC)\nG109 L1\nG21\nG0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG10.9 X1\nG0 G90 G53 X0. Y0.\n"
        "G0 G90 G53 Z0.\nT01 M6\nM901\nG97 S1000 M203\nG95\nM108\nG0 G53 B0.\nM107\n"
        "G1 G43 P1 H#3020 X40. Y0. Z2. F0.2\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nT02 M6\nM901\nM108\nG0 G53 "
        "B0.\nM107\nG1 G43 P1 H#3020 X30. Y0. Z2. F0.2\nM950\nM9\nM5\nM205\nM305\nG0 G90 G53 X0. Y0.\n"
        "G0 G90 G53 Z0.\nM30\nG109 L2\nG21\nG0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG10.9 X1\nG0 G90 G53 "
        "X0.\nG0 G90 G53 Z0.\nM950\nM9\nM5\n"
        "M205\nM305\nG0 G90 G53 X0.\nG0 G90 G53 Z0.\nM30\n%\n");
}

TEST_CASE("SPINDL/ON turns the spindle on again at the last speed and direction", "[post][tools]") {
  const test::posted p = post_on(
      "PARTNO TC\nHEAD/1\nTURRET/1,1\nSPINDL/SMM,200,MAXRPM,3000,CCLW\nFEDRAT/0.2,MMPR\n"
      "GOTO/20,0,2\nSPINDL/OFF\nSPINDL/ON\nGOTO/20,0,-5\nFINI\n",
      "fanuc-0itd-twin", "on");
  CHECK(file_of(p, "TC_1.nc") ==
        "%\nO1000 (TC)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG50 S3000\nG96 S200 M4\n"
        "G1 X40. Z2. F0.2\nM5\nG50 S3000\nG96 S200 M4\nZ-5.\nM100\nM9\nG28 U0.\nG28 W0.\nM5\n"
        "M30\n%\n");
}

TEST_CASE("SPINDL/ON with no speed before it is an error, never S0", "[post][tools]") {
  const test::posted p = post_on("PARTNO TC\nHEAD/1\nTURRET/1,1\nSPINDL/ON\nRAPID\nGOTO/20,0,2\nFINI\n",
                                 "fanuc-0itd-twin", "on-none");
  CHECK_FALSE(p.ok);
  CHECK(p.files.empty());
  CHECK(p.diagnostics ==
        "job.cls:4:1: error: channel 1: SPINDL/ON with no spindle speed given before in this channel: "
        "give SPINDL/RPM,n or SPINDL/SMM,n\nSPINDL/ON\n^\n");
}

TEST_CASE("a coolant kind the machine gives no code for is an error, never flood", "[post][tools]") {
  const test::posted p = post_on("PARTNO TC\nHEAD/1\nLOADTL/1\nCOOLNT/MIST\nRAPID\nGOTO/20,0,2\nFINI\n",
                                 "integrex-i200st", "mist");
  CHECK_FALSE(p.ok);
  CHECK(p.diagnostics ==
        "job.cls:4:1: error: channel 1: COOLNT/MIST: machine 'integrex-i200st' gives no code for this kind "
        "of coolant (codes.coolant_mist); writing flood instead could burn the tool or flood a dry cut\n"
        "COOLNT/MIST\n^\n");
}

TEST_CASE("each coolant kind is turned on and off with its own codes", "[post][tools]") {
  // Mazak: through-tool coolant is M51 and goes off with M163, not M9; a change of kind turns
  // the one in force off first; a tool change turns off the kind in force. On the B head the
  // coolant waits for the head's index (issue 37, item 10): the flood asked before the through
  // coolant is never written.
  const test::posted p = post_on(
      "PARTNO TC\nHEAD/1\nTLDATA/TURN\nLOADTL/1\nSPINDL/RPM,1000,CLW\nCOOLNT/ON\nCOOLNT/THRU\nRAPID\n"
      "GOTO/20,0,2\nTLDATA/TURN\nLOADTL/2\nRAPID\nGOTO/20,0,3\nCOOLNT/OFF\nFINI\n",
      "integrex-i200st", "kinds");
  CHECK(file_of(p, "TC.EIA") ==
        "%\nO1000(TC)\nG109 L1\nG21\nG0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG10.9 X1\nG0 G90 G53 X0. Y0.\n"
        "G0 G90 G53 Z0.\nT01 M6\nM901\nG97 S1000 M203\nM108\nG0 G53 B0.\nM107\nM51\n"
        "G0 G43 P1 H#3020 X40. Y0. Z2.\nM163\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nT02 M6\nM901\nM108\nG0 "
        "G53 B0.\nM107\nM51\nG0 G43 P1 H#3020 X40. Y0. Z3.\nM163\nM950\nM9\nM5\nM205\nM305\n"
        "G0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM30\nG109 L2\nG21\nG0 G90 G54 G97 G18\n"
        "G40 G49 G80 G67 G69\nG10.9 X1\nG0 G90 G53 X0.\nG0 G90 G53 Z0.\nM950\nM9\nM5\nM205\nM305\nG0 G90 G53 "
        "X0.\nG0 G90 G53 Z0.\nM30\n%\n");
}

TEST_CASE("G41/G42 on a rapid stops the post where the machine takes them only on a feed move",
          "[post][tools]") {
  const std::string cl =
      "PARTNO TC\nHEAD/1\nLOADTL/1\nSPINDL/RPM,1000,CLW,MAIN\nFEDRAT/0.2,MMPR\nCUTCOM/RIGHT\nRAPID\n"
      "GOTO/20,0,2\nGOTO/20,0,-5\nFINI\n";
  const test::posted mazak = post_on(cl, "integrex-i200st", "cutcom-rapid");
  CHECK_FALSE(mazak.ok);
  CHECK(mazak.diagnostics ==
        "job.cls:8:1: error: channel 1: tool nose radius compensation (G42) would start on a rapid move; "
        "machine 'integrex-i200st' starts it only on a feed move (codes.cutcom_on_rapid = false): make "
        "the first move after CUTCOM a feed move\nGOTO/20,0,2\n^\n");
  // A Fanuc takes G42 with G0.
  const test::posted fanuc = post_on(cl, "fanuc-0itd-twin", "cutcom-rapid-fanuc");
  CHECK(fanuc.ok);
}

TEST_CASE("a move before any tool call is an error", "[post][tools]") {
  const test::posted p = post_on("PARTNO TC\nHEAD/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/20,0,2\nFINI\n",
                                 "fanuc-0itd-twin", "no-tool");
  CHECK_FALSE(p.ok);
  CHECK(p.diagnostics ==
        "job.cls:5:1: error: channel 1: a move with no tool called in this channel: give LOADTL or TURRET "
        "before the first move, the CAM's name of the tool under its [[tool]] in the machine file (name = "
        "..., as NX TOOL PATH or CATIA TPRINT gives it), or the tool in the spindle with post --tool N\n"
        "GOTO/20,0,2\n^\n");
}

TEST_CASE("an offset the channel's tool call cannot write is an error, never the last offset",
          "[post][tools]") {
  // The Integrex mill head calls T01 M6: TURRET/1,21 for the finish would run on offset 1.
  const test::posted p = post_on(
      "PARTNO TC\nHEAD/1\nTLDATA/TURN\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nFEDRAT/0.2,MMPR\nGOTO/20,0,2\n"
      "TURRET/1,21\nGOTO/19.5,0,2\nFINI\n",
      "integrex-i200st", "offset-lost");
  CHECK_FALSE(p.ok);
  CHECK(p.files.empty());
  CHECK(p.diagnostics ==
        "job.cls:8:1: error: channel 1: TURRET asks for tool 1 on offset 21, but the channel's tool call T01 "
        "M6 "
        "writes no offset (channel.tool_call has no {offset}): the tool would cut on whatever offset is "
        "active\nTURRET/1,21\n^\n");
  // The lower turret's T{tool:02}{offset:02} writes the change.
  const test::posted q = post_on(
      "PARTNO TC\nHEAD/2\nTLDATA/TURN\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nFEDRAT/0.2,MMPR\nGOTO/-20,0,2\n"
      "TURRET/1,21\nGOTO/-19.5,0,2\nFINI\n",
      "integrex-i200st", "offset-turret");
  CHECK(q.ok);
  CHECK(q.diagnostics.empty());
  // A 4-axis mill whose every move goes through its chain writes the offset in the length code
  // of the first move: LOADTL/2,5 is G43 H5 after T02 M6 (CATIA writes LOADTL/2,1).
  const test::posted r = post_on(
      "PARTNO TC\nLOADTL/2,5\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,300\nRAPID\nGOTO/10,0,20\nGOTO/10,0,0\nFINI\n",
      "rotary-4axis", "offset-chain");
  INFO(r.diagnostics);
  REQUIRE(r.ok);
  const std::string nc = r.files.at("TC.nc");
  CHECK(nc.substr(nc.find("T02")) ==
        "T02 M6\nG54\nS1000 M3\nG0 A0.\nG0 X10. Y0.\nG0 G43 H5 X10. Y0. Z20. A0.\nG1 Z0. F300.\n"
        "G91 G28 Z0.\nG90\nM9\nM5\nG49\nM30\n%\n");
}

TEST_CASE("a coolant kind still on at the end is turned off with its own code before the footer",
          "[post][tools]") {
  // The footer's M9 is flood's; through-tool coolant (Doosan M108) goes off with M109.
  const test::posted p =
      post_on("PARTNO TC\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nCOOLNT/THRU\nRAPID\nGOTO/20,0,2\nFINI\n",
              "fanuc-0itd-twin", "kind-at-end");
  CHECK(
      file_of(p, "TC_1.nc") ==
      "%\nO1000 (TC)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG97 S1000 M3\nM108\nG0 X40. Z2.\n"
      "M100\nM109\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
}

TEST_CASE("a turret's own spindle is said again after a tool call that gives no SPINDL", "[post][tools]") {
  // Review 49, M4: a restart at T0303 finds the speed and the feed. On the built-in twin the
  // main spindle is both turrets' (not said again, the test above); here each channel's own.
  // The spindle before the coolant, as at the first call, also where the CL's SPINDL gives the
  // speed (review 52, L1).
  machine m = load_machine("fanuc-0itd-twin");
  for (spindle_def& s : m.spindles) s.per_channel = true;
  const test::posted p = test::post_in_fresh_dir(
      "PARTNO TC\nHEAD/1\nTURRET/1,1\nSPINDL/SMM,200,MAXRPM,3000,CLW\nCOOLNT/ON\nFEDRAT/0.2,MMPR\n"
      "GOTO/20,0,2\nGOTO/20,0,-10\nTURRET/3,3\nGOTO/15,0,2\nTURRET/5,5\nSPINDL/RPM,900,CLW\nGOTO/"
      "10,0,2\nFINI\n",
      m, "tool-change-own", [](const diagnostic& d) { return d.level == severity::error; });
  CHECK(file_of(p, "TC_1.nc") ==
        "%\nO1000 (TC)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG50 S3000\nG96 S200 M3\nM8\n"
        "G1 X40. Z2. F0.2\nZ-10.\nM9\nG28 U0.\nG28 W0.\nT0303\nG50 S3000\nG96 S200 M3\nM8\n"
        "G1 X30. Z2. F0.2\nM9\nG28 U0.\nG28 W0.\nT0505\nG97 S900 M3\nM8\nG1 X20. Z2. F0.2\nM100\nM9\n"
        "G28 U0.\nG28 W0.\nM5\nM30\n%\n");
}

TEST_CASE("a channel that waits before its first tool goes home first, and again after text that may move it",
          "[post][tools]") {
  // Review 49, M2: head 2 waits at M100 from home. Helper 40: INSERT text between that home and
  // the first tool call (G0 W-250.) had the turret index where the text left it.
  const std::string head1 =
      "PARTNO TC\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nFEDRAT/0.2,MMPR\nGOTO/20,0,2\n";
  const test::posted plain = post_on(head1 + "HEAD/2\nTURRET/13,13\nFEDRAT/0.2,MMPR\nGOTO/-30,0,2\nFINI\n",
                                     "fanuc-0itd-twin", "home-first");
  CHECK(file_of(plain, "TC_2.nc") ==
        "%\nO1000 (TC)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nM100\nT1313\nG1 X60. Z2. F0.2\nM101\n"
        "M9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
  const test::posted moved =
      post_on(head1 + "HEAD/2\nINSERT/G0 W-250.\nTURRET/13,13\nFEDRAT/0.2,MMPR\nGOTO/-30,0,2\nFINI\n",
              "fanuc-0itd-twin", "home-after-insert");
  CHECK(file_of(moved, "TC_2.nc") ==
        "%\nO1000 (TC)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nM100\nG0 W-250.\nG28 U0.\nG28 W0.\n"
        "T1313\nG1 X60. Z2. F0.2\nM101\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
}
