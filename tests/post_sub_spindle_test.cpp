// The sub spindle and the spindles by the tool: sub-spindle work is written with Z (and Y)
// reversed, G2/G3 swapped and K negated, in the sub's work offset with its own spindle codes
// (Fusion "Mazak Integrex i" and "Doosan Mill/Turn" posts); TRANSFER/GRIP and RELEASE write
// the machine's transfer blocks between waits of every channel; a milling tool turns the
// live spindle, a turning tool the workpiece spindle. Every refusal names its record.
#include <catch2/catch.hpp>

#include <string>

#include "file_test_support.hpp"
#include "machines/machine_loader.hpp"
#include "post_test_jobs.hpp"

using namespace twinpost;

namespace {

test::posted post_on(const std::string& cl, const machine& m, const std::string& tag) {
  return test::post_in_fresh_dir(cl, m, "sub-spindle-" + tag,
                                 [](const diagnostic& d) { return d.level == severity::error; });
}

test::posted post_on(const std::string& cl, const std::string& machine_name, const std::string& tag) {
  return post_on(cl, load_machine(machine_name), tag);
}

std::string file_of(const test::posted& p, const std::string& name) {
  if (!p.ok) return "(failed)\n" + p.diagnostics;
  const auto f = p.files.find(name);
  return f == p.files.end() ? "(missing)" : f->second;
}

// Head 2 (the lower turret, CL x < 0) faces and turns on the sub spindle, the CL in the
// sub's CAM frame: Z0 at the face, Z+ away from the sub chuck. A concave R1 fillet about +Y.
const std::string sub_job =
    "PARTNO SUB\nHEAD/2\nTURRET/3,3\nSPINDL/SMM,200,MAXRPM,3000,CLW,SUB\nFEDRAT/0.2,MMPR\n"
    "GOTO/-27,0,2\nGOTO/-25,0,-1\nGOTO/-25,0,-14\nCIRCLE/-26,0,-14,0,1,0,1\nGOTO/-26,0,-15\n"
    "SPINDL/OFF\nFINI\n";

// A machine with one spindle and no transfer.
const char* one_spindle =
    "[machine]\nname = \"one-spindle\"\n[waits]\nfirst = 100\nlast = 102\n"
    "[[spindle]]\nname = \"main\"\nclamp = \"G50 S{max}\"\nmax_rpm = 4000\n"
    "[[channel]]\nnumber = 1\nheads = [1]\naxis = [{address = \"X\", diameter = true}, {address = \"Z\"}]\n";

// Head 1 turns on the main spindle, the part goes over, head 2 turns it on the sub.
const std::string transfer_job =
    "PARTNO XFER\nHEAD/1\nTURRET/1,1\nSPINDL/SMM,180,MAXRPM,2500,CLW,MAIN\nFEDRAT/0.2,MMPR\nCOOLNT/ON\n"
    "GOTO/25,0,2\nGOTO/25,0,-20\nSPINDL/OFF\nTRANSFER/GRIP\nTRANSFER/RELEASE\nHEAD/2\nTURRET/3,3\n"
    "SPINDL/RPM,800,CLW\nFEDRAT/0.15,MMPR\nGOTO/-25,0,2\nGOTO/-25,0,-10\nSPINDL/OFF\nFINI\n";

}  // namespace

TEST_CASE("sub-spindle work on the Fanuc twin: G55, Z reversed, G2/G3 swapped, the sub's codes",
          "[post][sub]") {
  // Z -1 -> Z1, -14 -> Z14; the fillet, counter-clockwise about +Y in the CL's frame, is a
  // G3 on the mirrored lower turret in the reversed frame (two reflections), K stays 0.
  const test::posted p = post_on(sub_job, "fanuc-0itd-twin", "fanuc-twin");
  CHECK(file_of(p, "SUB_2.nc") ==
        "%\nO1000 (SUB)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0303\nG55\nG50 S3000\nG96 S200 M103\n"
        "G1 X54. Z-2. F0.2\nX50. Z1.\nZ14.\nG3 X52. Z15. I1. K0.\nM105\nM100\nM9\nG28 U0.\nG28 W0.\n"
        "M5\nM30\n%\n");
}

TEST_CASE("sub-spindle work on the Integrex: M902, G92 S.. R2, M303, in G55", "[post][sub]") {
  const test::posted p = post_on(sub_job, "integrex-i200st", "integrex");
  const std::string f = file_of(p, "SUB.EIA");
  CHECK(f.substr(f.find("G109 L2")) ==
        "G109 L2\nG21\nG0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG10.9 X1\nG0 G90 G53 X0.\nG0 G90 G53 "
        "Z0.\nT0303\nG55\n"
        "M902\nG92 S3000 R2\nG96 S200 M303\nG95\nG1 X54. Z-2. F0.2\nX50. Z1.\nZ14.\nG3 X52. Z15. I1. K0.\n"
        "M305\nM950\nM9\nM5\nM205\nG0 G90 G53 X0.\nG0 G90 G53 Z0.\nM30\n%\n");
}

TEST_CASE("sub-spindle work on the 31i: the lower turret starts on the main spindle, SUB moves it",
          "[post][sub]") {
  const test::posted p = post_on(sub_job, "fanuc-31i-3path", "31i");
  CHECK(file_of(p, "SUB_2.nc") ==
        "%\nO1000 (SUB)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0303\nG55\nG50 S3000\nG96 S200 M103\n"
        "G1 X54. Z-2. F0.2\nX50. Z1.\nZ14.\nG3 X52. Z15. I1. K0.\nM105\nM200 P123\nM9\nG28 U0.\n"
        "G28 W0.\nM30\n%\n");
}

TEST_CASE("an arc on the sub spindle swaps G2/G3 and negates K", "[post][sub]") {
  // The upper turret (not mirrored): the same arc on the main spindle and on the sub.
  const std::string arc = "FEDRAT/0.2,MMPR\nGOTO/20,0,-5\nCIRCLE/20,0,-8,0,1,0,3\nGOTO/23,0,-8\nFINI\n";
  const test::posted main =
      post_on("PARTNO A\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,500,CLW\n" + arc, "fanuc-0itd-twin", "arc-main");
  const test::posted sub =
      post_on("PARTNO A\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,500,CLW,SUB\n" + arc, "fanuc-0itd-twin", "arc-sub");
  CHECK(file_of(main, "A_1.nc") ==
        "%\nO1000 (A)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG97 S500 M3\n"
        "G1 X40. Z-5. F0.2\nG3 X46. Z-8. I0. K-3.\nM100\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
  CHECK(file_of(sub, "A_1.nc") ==
        "%\nO1000 (A)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG55\nG97 S500 M103\n"
        "G1 X40. Z5. F0.2\nG2 X46. Z8. I0. K3.\nM100\nM105\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
}

TEST_CASE("a machine without a sub spindle refuses SPINDL/...,SUB and TRANSFER at their records",
          "[post][sub]") {
  const machine m = parse_machine(one_spindle, "one-spindle.toml");
  const test::posted spindl =
      post_on("PARTNO E\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,500,CLW,SUB\nFINI\n", m, "no-sub");
  CHECK_FALSE(spindl.ok);
  CHECK(spindl.diagnostics ==
        "job.cls:4:1: error: channel 1: SPINDL/...,SUB: machine 'one-spindle' has no sub spindle\n"
        "SPINDL/RPM,500,CLW,SUB\n^\n");
  const test::posted transfer =
      post_on("PARTNO E\nHEAD/1\nTURRET/1,1\nTRANSFER/GRIP\nFINI\n", m, "no-sub-xfer");
  CHECK_FALSE(transfer.ok);
  CHECK(transfer.diagnostics ==
        "job.cls:4:1: error: TRANSFER/GRIP: machine 'one-spindle' has no sub spindle to take the part\n"
        "TRANSFER/GRIP\n^\n");
}

TEST_CASE("TRANSFER takes GRIP or RELEASE", "[post][sub]") {
  const test::posted p =
      post_on("PARTNO E\nHEAD/1\nTURRET/1,1\nTRANSFER/SUB\nFINI\n", "integrex-i200st", "bad");
  CHECK_FALSE(p.ok);
  CHECK(p.diagnostics == "job.cls:4:10: error: TRANSFER needs GRIP or RELEASE\nTRANSFER/SUB\n         ^\n");
}

TEST_CASE("the part transfer on the Fanuc twin: home, waits, path 1's blocks, then G55 and Z reversed",
          "[post][sub]") {
  const test::posted p = post_on(transfer_job, "fanuc-0itd-twin", "xfer-fanuc");
  CHECK(file_of(p, "XFER_1.nc") ==
        "%\nO1000 (XFER)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG50 S2500\nG96 S180 M3\n"
        "M8\nG1 X50. Z2. F0.2\nZ-20.\nM5\nM9\nG28 U0.\nG28 W0.\nM100\nM169\nM213\nIF [#500 EQ #0] THEN "
        "#3000=1 (TRANSFER GRIP POSITION #500 NOT SET)\nIF [#501 EQ #0] THEN #3000=1 (TRANSFER APPROACH "
        "POSITION #501 NOT SET)\nG0 G53 B#501\nG98 G1 G53.2 B#500 F500.\nM168\nG4 U1.\nG99\nM101\n"
        "M102\nM69\nG98 G4 U1.\nG28 G53 B0.\nM205\nG99\nM100\nG55\nM101\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
  CHECK(file_of(p, "XFER_2.nc") ==
        "%\nO1000 (XFER)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nM100\nM101\nM102\nM100\nG55\n"
        "T0303\nG97 S800 M103\nG1 X50. Z-2. F0.15\nZ10.\nM105\nM101\nM9\nG28 U0.\n"
        "G28 W0.\nM5\nM30\n%\n");
}

TEST_CASE("a user's move after a GOHOME: the transfer goes home again first", "[post][sub]") {
  // GOHOME, then an INSERT (or an [events] block) that moves the turret: the channel was still
  // taken to be at home, and the transfer's retract wrote no home, the sub spindle coming over
  // with turret 1 at U-200. W-300. from it (thirty-sixth session).
  std::string job = transfer_job;
  const std::string off = "SPINDL/OFF\nTRANSFER/GRIP";
  REQUIRE(job.find(off) != std::string::npos);
  job.replace(job.find(off), off.size(), "SPINDL/OFF\nGOHOME\nINSERT/G0 U-200. W-300.\nTRANSFER/GRIP");
  const test::posted p = post_on(job, "fanuc-0itd-twin", "xfer-moved");
  CHECK(
      file_of(p, "XFER_1.nc") ==
      "%\nO1000 (XFER)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG50 S2500\nG96 S180 M3\n"
      "M8\nG1 X50. Z2. F0.2\nZ-20.\nM5\nG28 U0.\nG28 W0.\nG0 U-200. W-300.\nM9\nG28 U0.\nG28 W0.\nM100\n"
      "M169\nM213\nIF [#500 EQ #0] THEN #3000=1 (TRANSFER GRIP POSITION #500 NOT SET)\nIF [#501 EQ #0] THEN "
      "#3000=1 (TRANSFER APPROACH POSITION #501 NOT SET)\nG0 G53 B#501\nG98 G1 G53.2 B#500 F500.\nM168\n"
      "G4 U1.\nG99\nM101\nM102\nM69\nG98 G4 U1.\nG28 G53 B0.\nM205\nG99\nM100\nG55\nM101\nM9\nG28 U0.\n"
      "G28 W0.\nM5\nM30\n%\n");
}

TEST_CASE("the part transfer on the Integrex: transfer mode, sync, chucks, then the second spindle",
          "[post][sub]") {
  const test::posted p = post_on(transfer_job, "integrex-i200st", "xfer-integrex");
  CHECK(
      file_of(p, "XFER.EIA") ==
      "%\nO1000(XFER)\nG109 L1\nG21\nG0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG10.9 X1\nG0 G90 G53 X0. Y0.\n"
      "G0 G90 G53 Z0.\nT01 M6\nM901\nG92 S2500 R1\nG96 S180 M203\nG95\nM108\nG0 G53 B0.\nM107\nM8\n"
      "G1 G43 P1 H#3020 X50. Y0. Z2. F0.2\nZ-20.\nM205\nM9\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\n"
      "M950\nM306\nM511\nM540\nIF [#500 EQ #0] THEN #3000=1 (TRANSFER GRIP POSITION #500 NOT SET)\nIF "
      "[#501 EQ #0] THEN #3000=1 (TRANSFER APPROACH POSITION #501 NOT SET)\nG0 G53 W#501\nG94 G1 G53 W#500 "
      "F500.\nM541\nM307\nG4 P1000\nG95\nM951\nM952\nM206\nG94 G4 P1000\nG0 G53 W0.\nM513\nM305\nG95\n"
      "M953\nG55\nM954\nM9\nM5\nM205\nM305\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM30\nG109 L2\nG21\n"
      "G0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG10.9 X1\nG0 G90 G53 X0.\nG0 G90 G53 Z0.\nM950\nM951\n"
      "M952\nM953\nG55\nT0303\nM902\nG97 S800 M303\nG95\n"
      "G1 X50. Z-2. F0.15\nZ10.\nM305\nM954\nM9\nM5\nM205\nG0 G90 G53 X0.\nG0 G90 G53 Z0.\n"
      "M30\n%\n");
}

TEST_CASE("the part transfer on the 31i: the idle mill head waits and goes home too", "[post][sub]") {
  const test::posted p = post_on(transfer_job, "fanuc-31i-3path", "xfer-31i");
  CHECK(file_of(p, "XFER_1.nc") ==
        "%\nO1000 (XFER)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG50 S2500\nG96 S180 M3\n"
        "M8\nG1 X50. Z2. F0.2\nZ-20.\nM5\nM9\nG28 U0.\nG28 W0.\nM200 P123\nM169\nM213\nIF [#500 EQ #0] THEN "
        "#3000=1 (TRANSFER GRIP POSITION #500 NOT SET)\nIF [#501 EQ #0] THEN #3000=1 (TRANSFER APPROACH "
        "POSITION #501 NOT SET)\nG0 G53 B#501\nG98 G1 G53.2 B#500 F500.\nM168\nG4 U1.\nG99\n"
        "M201 P123\nM202 P123\nM69\nG98 G4 U1.\nG28 G53 B0.\nM205\nG99\nM204 P123\nG55\nM206 P123\nM9\nG28 "
        "U0.\nG28 W0.\n"
        "M30\n%\n");
  CHECK(file_of(p, "XFER_3.nc") ==
        "%\nO1000 (XFER)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0. V0.\nG28 W0.\nM200 P123\nM201 P123\nM202 P123\n"
        "M204 P123\nG55\nM206 P123\nM9\nG28 U0. V0.\nG28 W0.\nM30\n%\n");
}

TEST_CASE("the Integrex head turns the milling spindle for a milling tool, the turning one otherwise",
          "[post][spindles]") {
  const test::posted p = post_on(
      "PARTNO TOOLS\nHEAD/1\nTLDATA/TURN,0.8\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/0.2,MMPR\nGOTO/20,0,2\n"
      "TLDATA/MILL,10.0,0.0,75.0\nLOADTL/5\nSPINDL/RPM,3000,CLW\nGOTO/20,0,2\nTLDATA/DRILL,8.0,118.0\n"
      "LOADTL/6\nSPINDL/RPM,900,CLW\nGOTO/0,0,5\nGOTO/0,0,-10\nFINI\n",
      "integrex-i200st", "tools");
  const std::string f = file_of(p, "TOOLS.EIA");
  CHECK(f.substr(0, f.find("G109 L2")) ==
        "%\nO1000(TOOLS)\nG109 L1\nG21\nG0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG10.9 X1\n"
        "G0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nT01 M6\nM901\nG97 S1000 M203\nG95\nM108\nG0 G53 B0.\n"
        "M107\nG1 G43 P1 H#3020 X40. Y0. Z2. F0.2\nM205\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\n"
        "T05 M6\nM901\nM200\nG10.9 X0\nG97 S3000 M3\nM108\nG0 G53 B0.\nM107\nG0 Y0.\nG0 C0.\n"
        "G17 XC\nG12.1\nG1 G43 H#3020 X20. C0. Z2. F0.2\nG13.1\nG18\nG0 G90 G53 Z0.\nM5\n"
        "G0 G90 G53 X0. Y0.\nT06 M6\nM901\nG10.9 X1\nM202\nG97 S900 M203\nM108\nG0 G53 B0.\nM107\n"
        "G1 G43 P1 H#3020 X0. Y0. Z5. F0.2\nZ-10.\nG0 G90 G53 Z0.\nM950\nM9\nM5\nM205\nM305\n"
        "G0 G90 G53 X0. Y0.\nM30\n");
}

TEST_CASE("the 31i mill head turns its live spindle for a milling tool, the main spindle held as C",
          "[post][spindles]") {
  // M35 holds the main spindle as C and M34 lets it go (Fusion Doosan post); the head turns to
  // B-90 for an axial tool; the face is milled in polar interpolation, X in diameter.
  const test::posted p = post_on(
      "PARTNO E\nHEAD/3\nTLDATA/MILL,10\nLOADTL/7\nSPINDL/RPM,3000,CLW\nFEDRAT/200,MMPM\nGOTO/20,0,2\nFINI\n",
      "fanuc-31i-3path", "31i-mill");
  CHECK(file_of(p, "E_3.nc") ==
        "%\nO1000 (E)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0. V0.\nG28 W0.\nM6 T0700\nT0707\nM35\n"
        "G0 G28 H0.\nG97 S3000 M33\nG98\nG0 B-90.\nG0 Y0.\nG0 C0.\nG17\nG12.1\n"
        "G1 X40. C0. Z2. F200.\nG13.1\nG18\nG28 W0.\nM200 P123\nM37\nM34\nM9\nG28 U0. V0.\nM30\n%\n");
}

TEST_CASE("a speed in rpm for a tool of unknown kind on a head with two spindles is an error",
          "[post][spindles]") {
  const test::posted p =
      post_on("PARTNO E\nHEAD/1\nLOADTL/1\nSPINDL/RPM,500,CLW\nFINI\n", "integrex-i200st", "unknown");
  CHECK_FALSE(p.ok);
  CHECK(
      p.diagnostics ==
      "job.cls:4:1: error: channel 1: SPINDL: the kind of tool 1 (LOADTL at line 3) is unknown, and channel "
      "1 "
      "has a workpiece spindle and a live one (live): give TLDATA/TURN, MILL or DRILL before the tool call, "
      "kind = ... under the tool's [[tool]] in the machine file, or post --tool-kind for every tool without "
      "one, or name the spindle (SPINDL/...,MAIN, SUB or LIVE)\nSPINDL/RPM,500,CLW\n^\n");
  // A constant surface speed is a turning speed: the workpiece spindle.
  const test::posted css = post_on("PARTNO E\nHEAD/1\nLOADTL/1\nSPINDL/SMM,150,MAXRPM,2000,CLW\nFINI\n",
                                   "integrex-i200st", "unknown-css");
  CHECK(
      file_of(css, "E.EIA") ==
      "%\nO1000(E)\nG109 L1\nG21\nG0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG10.9 X1\nG0 G90 G53 X0. Y0.\nG0 "
      "G90 G53 Z0.\n"
      "T01 M6\nM901\nG92 S2000 R1\nG96 S150 M203\nM950\nM9\nM5\nM205\nM305\nG0 G90 G53 X0. Y0.\nG0 G90 G53 "
      "Z0.\nM30\n"
      "G109 L2\nG21\nG0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG10.9 X1\nG0 G90 G53 X0.\nG0 G90 G53 "
      "Z0.\nM950\nM9\nM5\nM205\nM305\nG0 G90 "
      "G53 X0.\n"
      "G0 G90 G53 Z0.\nM30\n%\n");
}

TEST_CASE("a milling tool on a turret without a live spindle is an error", "[post][spindles]") {
  const test::posted p = post_on("PARTNO E\nHEAD/1\nTLDATA/MILL,10\nTURRET/5,5\nSPINDL/RPM,3000,CLW\nFINI\n",
                                 "fanuc-0itd-twin", "mill-turret");
  CHECK_FALSE(p.ok);
  CHECK(
      p.diagnostics ==
      "job.cls:5:1: error: channel 1: SPINDL: tool 5 (TURRET at line 4) is a milling tool (TLDATA/MILL) and "
      "channel 1 has no live spindle (channel.live_spindle): the part would turn against a still cutter\n"
      "SPINDL/RPM,3000,CLW\n^\n");
  const test::posted live = post_on("PARTNO E\nHEAD/2\nTURRET/1,1\nSPINDL/RPM,500,CLW,LIVE\nFINI\n",
                                    "fanuc-31i-3path", "live-turret");
  CHECK_FALSE(live.ok);
  CHECK(live.diagnostics ==
        "job.cls:4:1: error: channel 2: SPINDL/...,LIVE: channel 2 of machine 'fanuc-31i-3path' has no live "
        "spindle (channel.live_spindle)\nSPINDL/RPM,500,CLW,LIVE\n^\n");
}

TEST_CASE("a drill turning with the part may not feed off the centre line", "[post][spindles]") {
  const test::posted p = post_on(
      "PARTNO E\nHEAD/1\nTLDATA/DRILL,8\nTURRET/1,1\nSPINDL/RPM,500,CLW\nFEDRAT/0.1,MMPR\nGOTO/0,0,2\n"
      "GOTO/5,0,-3\nFINI\n",
      "fanuc-0itd-twin", "drill");
  CHECK_FALSE(p.ok);
  CHECK(p.diagnostics ==
        "job.cls:8:1: error: channel 1: tool 1 is a drill (TLDATA/DRILL) and the part turns on the main "
        "spindle, "
        "but this feed move leaves the centre line (x = 5): off-centre drilling needs the live spindle "
        "(SPINDL/...,LIVE)\nGOTO/5,0,-3\n^\n");
}

TEST_CASE("a mill head does not turn the spindle of the last tool again for a tool of another kind",
          "[post][spindles]") {
  const test::posted p = post_on(
      "PARTNO E\nHEAD/1\nTLDATA/TURN\nLOADTL/1\nSPINDL/RPM,500,CLW\nFEDRAT/0.1,MMPR\nGOTO/20,0,2\n"
      "TLDATA/MILL,10\nLOADTL/2\nGOTO/20,0,2\nFINI\n",
      "integrex-i200st", "resume");
  CHECK_FALSE(p.ok);
  CHECK(p.diagnostics ==
        "job.cls:10:1: error: channel 1: tool 2 (LOADTL at line 9) would start with the main spindle that "
        "turned "
        "before the tool change, but it needs the live spindle: give SPINDL for this tool before its first "
        "move\nGOTO/20,0,2\n^\n");
}

TEST_CASE("SPINDL/...,SUB with a milling tool stops the post: no C-axis hold of the second spindle is known",
          "[post][spindles]") {
  const test::posted p = post_on(
      "PARTNO E\nHEAD/1\nTLDATA/MILL,10\nLOADTL/5\nSPINDL/RPM,3000,CLW,SUB\nFEDRAT/200,MMPM\nGOTO/20,5,2\n"
      "FINI\n",
      "integrex-i200st", "mill-sub");
  const std::string f = file_of(p, "E.EIA");
  // Live-tool work needs the spindle held as the C axis; the sub has no c_on in the machine file.
  CHECK(f.substr(0, f.find("M950")) ==
        "(failed)\n"
        "job.cls:5:1: error: channel 1: live-tool work on the sub spindle, which machine 'integrex-i200st' "
        "cannot hold as a C axis (spindle.c_on): the part would be free to turn under the cutter\n"
        "SPINDL/RPM,3000,CLW,SUB\n^\n");
}

TEST_CASE("the machine's tool table gives the kind where the CL gives none", "[post][spindles]") {
  machine m = load_machine("integrex-i200st");
  m.tools.push_back({5, 1, "mill"});
  m.tools.push_back({6, 0, "turn"});
  const test::posted p = post_on(
      "PARTNO E\nHEAD/1\nLOADTL/6\nSPINDL/RPM,800,CLW\nFEDRAT/0.2,MMPR\nGOTO/20,0,2\nLOADTL/5\n"
      "SPINDL/RPM,3000,CLW\nGOTO/20,0,2\nFINI\n",
      m, "table");
  const std::string f = file_of(p, "E.EIA");
  CHECK(f.substr(0, f.find("M950")) ==
        "%\nO1000(E)\nG109 L1\nG21\nG0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG10.9 X1\n"
        "G0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nT06 M6\nM901\nG97 S800 M203\nG95\nM108\nG0 G53 B0.\n"
        "M107\nG1 G43 P1 H#3020 X40. Y0. Z2. F0.2\nM205\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\n"
        "T05 M6\nM901\nM200\nG10.9 X0\nG97 S3000 M3\nM108\nG0 G53 B0.\nM107\nG0 Y0.\nG0 C0.\n"
        "G17 XC\nG12.1\nG1 G43 H#3020 X20. C0. Z2. F0.2\nG13.1\nG18\nG0 G90 G53 Z0.\n");
  const test::posted clash =
      post_on("PARTNO E\nHEAD/1\nTLDATA/TURN\nLOADTL/5\nSPINDL/RPM,800,CLW\nFINI\n", m, "table-clash");
  CHECK_FALSE(clash.ok);
  CHECK(
      clash.diagnostics ==
      "job.cls:4:1: error: channel 1: tool 5: the CL's TLDATA says TURN, machine 'integrex-i200st' lists it "
      "as mill ([[tool]]): which tool is in the turret?\nLOADTL/5\n^\n");
}

TEST_CASE("a channel the machine file puts on the sub spindle starts in G55 with Z reversed", "[post][sub]") {
  machine m = load_machine("fanuc-0itd-twin");
  m.channels[1].spindle = "sub";
  const test::posted p = post_on(
      "PARTNO "
      "S\nHEAD/2\nTURRET/3,3\nSPINDL/RPM,800,CLW\nFEDRAT/0.2,MMPR\nGOTO/-20,0,2\nGOTO/-20,0,-5\nFINI\n",
      m, "starts-on-sub");
  CHECK(file_of(p, "S_2.nc") ==
        "%\nO1000 (S)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0303\nG55\nG97 S800 M103\n"
        "G1 X40. Z-2. F0.2\nZ5.\nM100\nM105\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
}

TEST_CASE("TRANSFER/GRIP and TRANSFER/RELEASE come in pairs", "[post][sub]") {
  const test::posted release =
      post_on("PARTNO E\nHEAD/1\nTURRET/1,1\nTRANSFER/RELEASE\nFINI\n", "fanuc-0itd-twin", "release-alone");
  CHECK_FALSE(release.ok);
  CHECK(release.diagnostics ==
        "job.cls:4:1: error: TRANSFER/RELEASE with no TRANSFER/GRIP before it: the main chuck would open "
        "with the "
        "sub spindle holding nothing\nTRANSFER/RELEASE\n^\n");
  const test::posted twice = post_on(
      "PARTNO E\nHEAD/1\nTURRET/1,1\nTRANSFER/GRIP\nTRANSFER/GRIP\n"
      "TRANSFER/RELEASE\nFINI\n",
      "fanuc-0itd-twin", "grip-twice");
  CHECK_FALSE(twice.ok);
  CHECK(twice.diagnostics ==
        "job.cls:5:1: error: TRANSFER/GRIP while the TRANSFER/GRIP at line 4 has not been released\n"
        "TRANSFER/GRIP\n^\n");
  const test::posted open =
      post_on("PARTNO E\nHEAD/1\nTURRET/1,1\nTRANSFER/GRIP\nFINI\n", "fanuc-0itd-twin", "grip-alone");
  CHECK_FALSE(open.ok);
  // Said at the end of the job, where the reader no longer holds the record's text.
  CHECK(open.diagnostics ==
        "job.cls:4:1: error: TRANSFER/GRIP with no TRANSFER/RELEASE after it: the programs would end with "
        "the part "
        "held by both spindles\n");
}

TEST_CASE("every section on the Integrex selects the spindle it works on, M901 or M902", "[post][sub]") {
  // A section on the second spindle (M902), then one on the main spindle (M901 again), then a
  // tool change with no SPINDL: its first move selects the main spindle once more, whatever an
  // earlier section left selected (the Fusion "Mazak Integrex i" post: M901/M902 per section).
  const test::posted p = post_on(
      "PARTNO S\nHEAD/1\nTLDATA/TURN\nLOADTL/1\nSPINDL/RPM,800,CLW,SUB\nFEDRAT/0.2,MMPR\nGOTO/20,0,2\n"
      "TLDATA/TURN\nLOADTL/2\nSPINDL/RPM,900,CLW,MAIN\nGOTO/20,0,2\nTLDATA/TURN\nLOADTL/3\nGOTO/25,0,2\n"
      "FINI\n",
      "integrex-i200st", "select");
  const std::string f = file_of(p, "S.EIA");
  CHECK(f.substr(0, f.find("M950")) ==
        "%\nO1000(S)\nG109 L1\nG21\nG0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG10.9 X1\nG0 G90 G53 X0. Y0.\n"
        "G0 G90 G53 Z0.\nT01 M6\nG55\nM902\nG97 S800 M303\nG95\nM108\nG0 G53 B180.\nM107\n"
        "G1 G43 P1 H#3020 X40. Y0. Z-2. F0.2\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nT02 M6\nG54\nM305\nM901\n"
        "G97 S900 M203\nM108\nG0 G53 B0.\nM107\nG1 G43 P1 H#3020 X40. Y0. Z2. F0.2\nG0 G90 G53 X0. Y0.\n"
        "G0 G90 G53 Z0.\nT03 M6\nM901\nM108\nG0 G53 B0.\nM107\nG1 G43 P1 H#3020 X50. Y0. Z2. "
        "F0.2\n");
}

TEST_CASE("the transfer's grip feeds the sub spindle onto the part, and the channel's feed mode comes back",
          "[post][sub]") {
  // The built-ins check that the setup set both positions (#500 grip, #501 approach), rapid to
  // the approach position and feed the last stretch with the chuck open (G98 G1 ... F500.),
  // then path 1, which cut in G99 before, is in G99 again: F0.2 is not read per minute.
  const test::posted p = post_on(
      "PARTNO XF\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,1000,CLW,MAIN\nFEDRAT/0.2,MMPR\nGOTO/25,0,2\nGOTO/25,0,-20\n"
      "TRANSFER/GRIP\nTRANSFER/RELEASE\nHEAD/1\nSPINDL/RPM,900,CLW\nGOTO/25,0,2\nGOTO/25,0,-5\nFINI\n",
      "fanuc-0itd-twin", "grip-feed");
  CHECK(file_of(p, "XF_1.nc") ==
        "%\nO1000 (XF)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG97 S1000 M3\n"
        "G1 X50. Z2. F0.2\nZ-20.\nG28 U0.\nG28 W0.\nM100\nM169\nM213\n"
        "IF [#500 EQ #0] THEN #3000=1 (TRANSFER GRIP POSITION #500 NOT SET)\n"
        "IF [#501 EQ #0] THEN #3000=1 (TRANSFER APPROACH POSITION #501 NOT SET)\n"
        "G0 G53 B#501\nG98 G1 G53.2 B#500 F500.\nM168\nG4 U1.\nG99\nM101\nM102\nM69\nG98 G4 U1.\nG28 G53 "
        "B0.\nM205\nG99\nM100\nG55\n"
        "G97 S900 M103\nG1 X50. Z-2. F0.2\nZ5.\nM101\nM105\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
}
