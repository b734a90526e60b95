// Drilling and tapping cycles on the lathe built-ins: each cycle form as the machine's
// [cycles] writes it (canned or expanded), asserted block by block, and the words of each
// dialect (SolidWorks CAM: FEDTO a depth, RTRCTO the retract plane).
#include <catch2/catch.hpp>

#include <functional>
#include <sstream>
#include <string>

#include "file_test_support.hpp"
#include "machine_test_support.hpp"
#include "machines/machine_loader.hpp"
#include "post_test_jobs.hpp"
#include "support/diagnostics.hpp"

using namespace twinpost;

namespace {

// A SolidWorks-style job head (UNIT/MM makes the dialect SolidWorks): tool 1 at 1000 rpm,
// parked on the centre line 25 mm in front of the face.
const std::string sw_head = "UNIT/MM\nPARTNO DRL\nLOADTL/1\nSPINDL/1000,RPM,CLW\nRAPID\nGOTO/0,0,25.\n";

// The blocks channel 1 writes between its spindle start and its footer (the first M9 or
// wait), for `cl` posted on `m`.
std::string cycle_blocks(const std::string& cl, const machine& m, const std::string& tag) {
  const test::posted p = test::post_in_fresh_dir(cl, m, "drill-" + tag);
  if (!p.ok) return "(failed)\n" + p.diagnostics;
  const std::string& text = p.files.begin()->second;
  std::istringstream in(text);
  std::string line, out;
  bool on = false;
  while (std::getline(in, line)) {
    if (!on) {
      on = line.find("S1000 M") != std::string::npos;
      continue;
    }
    if (line == "M9" || line.starts_with("M100") || line.starts_with("M200") || line.starts_with("M950"))
      break;
    out += line + "\n";
  }
  return out;
}

machine with(const std::string& name, const std::function<void(cycle_rules&)>& change) {
  machine m = load_machine(name);
  change(m.cycles);
  return m;
}

std::string errors_of(const std::string& cl, const machine& m, const std::string& tag) {
  const test::posted p = test::post_in_fresh_dir(
      cl, m, "drill-err-" + tag, [](const diagnostic& d) { return d.level == severity::error; });
  return p.ok ? "(posted)" : p.diagnostics;
}

const std::string drill =
    "CYCLE/DRILL,FEDTO,7.5,MMPM,120.,RAPTO,3.,RTRCTO,25.,DWELL,0\nGOTO/0,0,0\nCYCLE/OFF\nEND\n";
const std::string dwell =
    "CYCLE/DRILL,FEDTO,4.,MMPM,120.,RAPTO,3.,RTRCTO,25.,DWELL,0.5\nGOTO/0,0,0\nCYCLE/OFF\nEND\n";
const std::string deep = "CYCLE/DEEP,FEDTO,-12.,STEP,5.,RAPTO,2.,MMPR,0.1\nGOTO/0,0,0\nCYCLE/OFF\nEND\n";
const std::string deep2 =
    "CYCLE/DEEP2,FEDTO,12.,1STPECK,5.,SUBPECK,5.,MMPM,110.,RAPTO,3.,RTRCTO,25.\nGOTO/0,0,0\nCYCLE/OFF\nEND\n";
const std::string deep2_uneven =
    "CYCLE/DEEP2,FEDTO,9.,1STPECK,6.,SUBPECK,2.,MMPM,110.,RAPTO,3.,RTRCTO,10.\nGOTO/0,0,0\nCYCLE/OFF\nEND\n";
const std::string tap = "CYCLE/TAP,FEDTO,12.,MMPR,1.25,RAPTO,5.,RTRCTO,25.\nGOTO/0,0,0\nCYCLE/OFF\nEND\n";
// Generic APT: FEDTO a Z, no retract plane.
// The Integrex head has a turning and a milling spindle: its tool table says tool 1 is a
// drill (on the centre line: the turning spindle turns the part).
machine integrex_with_drill() {
  machine m = load_machine("integrex-i200st");
  m.tools.push_back({1, 1, "drill"});
  m.channels[0].head_index = {};  // the cycles only: the B head's index is tested in post_millturn_test
  return m;
}

const std::string apt_head = "PARTNO DRL\nUNITS/MM\nLOADTL/1\nSPINDL/1000,RPM,CLW\nRAPID\nGOTO/0,0,25.\n";

}  // namespace

TEST_CASE("Fanuc lathe canned cycles: G83 face drilling, R from the initial level, M29 G84",
          "[post][drill]") {
  for (const char* name : {"fanuc-0itd-twin", "fanuc-31i-3path"}) {
    const machine m = load_machine(name);
    // SolidWorks: FEDTO 7.5 below the top at z 0, R point 3 above it, initial level 25.
    CHECK(cycle_blocks(sw_head + drill, m, "f-drill") ==
          "G0 X0. Z25.\nG98\nG83 X0. Z-7.5 R-22. F120.\nG80\nG0 Z25.\n");
    // DWELL > 0: the same cycle with P in milliseconds.
    CHECK(cycle_blocks(sw_head + dwell, m, "f-dwell") ==
          "G0 X0. Z25.\nG98\nG83 X0. Z-4. R-22. P500 F120.\nG80\nG0 Z25.\n");
    // DEEP: pecks of Q (least increments, no point) with the full retract of parameter RTR.
    CHECK(cycle_blocks(apt_head + deep, m, "f-deep") ==
          "G0 X0. Z25.\nZ2.\nG83 X0. Z-12. R0. Q5000 F0.1\nG80\nG0 Z2.\n");
    // DEEP2 (chip breaking): G73 is pattern repeating in system A, so the pecks are moves.
    CHECK(cycle_blocks(sw_head + deep2, m, "f-deep2") ==
          "G0 X0. Z25.\nG98\nZ3.\nG1 Z-2. F110.\nG0 Z-1.5\nG1 Z-7.\nG0 Z-6.5\nG1 Z-12.\nG0 Z25.\n");
    // Rigid tapping: feed per revolution, M29 S, G84 at F = pitch, the spindle and feed mode again.
    CHECK(cycle_blocks(sw_head + tap, m, "f-tap") ==
          "G0 X0. Z25.\nM29 S1000\nG84 X0. Z-12. R-20. F1.25\nG80\nG0 Z25.\nG97 S1000 M3\n");
  }
}

TEST_CASE("Integrex canned cycles: G81/G82/G83/G73 and G84.2 with G98 in G17", "[post][drill]") {
  const machine m = integrex_with_drill();
  CHECK(cycle_blocks(sw_head + drill, m, "i-drill") ==
        "G0 X0. Y0. Z25.\nG94\nG17\nG98 G81 X0. Y0. Z-7.5 R3. F120.\nG80\nG18\nG0 Z25.\n");
  CHECK(cycle_blocks(sw_head + dwell, m, "i-dwell") ==
        "G0 X0. Y0. Z25.\nG94\nG17\nG98 G82 X0. Y0. Z-4. R3. P500 F120.\nG80\nG18\nG0 Z25.\n");
  CHECK(cycle_blocks(apt_head + deep, m, "i-deep") ==
        "G0 X0. Y0. Z25.\nG95\nZ2.\nG17\nG98 G83 X0. Y0. Z-12. R2. Q5. F0.1\nG80\nG18\nG0 Z2.\n");
  CHECK(cycle_blocks(sw_head + deep2, m, "i-deep2") ==
        "G0 X0. Y0. Z25.\nG94\nG17\nG98 G73 X0. Y0. Z-12. R3. Q5. F110.\nG80\nG18\nG0 Z25.\n");
  CHECK(cycle_blocks(sw_head + tap, m, "i-tap") ==
        "G0 X0. Y0. Z25.\nG95\nG17\nG98 G84.2 X0. Y0. Z-12. R5. F1.25\nG80\nG18\nG0 Z25.\n"
        "G97 S1000 M203\nG94\n");
  // A left-hand tap (the spindle turning CCLW) takes G84.3.
  const std::string left = "UNIT/MM\nPARTNO DRL\nLOADTL/1\nSPINDL/1000,RPM,CCLW\nRAPID\nGOTO/0,0,25.\n" + tap;
  CHECK(cycle_blocks(left, m, "i-left") ==
        "G0 X0. Y0. Z25.\nG95\nG17\nG98 G84.3 X0. Y0. Z-12. R5. F1.25\nG80\nG18\nG0 Z25.\n"
        "G97 S1000 M204\nG94\n");
}

TEST_CASE("a first peck other than the later ones, or no canned code, is written as moves", "[post][drill]") {
  // One Q cannot say 6 then 2: the Integrex writes the pecks as moves too.
  CHECK(cycle_blocks(sw_head + deep2_uneven, integrex_with_drill(), "uneven") ==
        "G0 X0. Y0. Z25.\nG94\nZ10.\nZ3.\nG1 Z-3. F110.\nG0 Z-2.5\nG1 Z-5.\nG0 Z-4.5\nG1 Z-7.\nG0 Z-6.5\n"
        "G1 Z-9.\nG0 Z10.\n");
}

TEST_CASE("expanded cycles: plain moves, a dwell block, and a tap on synchronised feeds", "[post][drill]") {
  const machine m = with("fanuc-0itd-twin", [](cycle_rules& c) {
    c.drill = "expanded";
    c.tap = "expanded";
  });
  CHECK(cycle_blocks(sw_head + drill, m, "e-drill") == "G0 X0. Z25.\nG98\nZ3.\nG1 Z-7.5 F120.\nG0 Z25.\n");
  CHECK(cycle_blocks(sw_head + dwell, m, "e-dwell") ==
        "G0 X0. Z25.\nG98\nZ3.\nG1 Z-4. F120.\nG4 U0.5\nG0 Z25.\n");
  CHECK(cycle_blocks(apt_head + deep, m, "e-deep") ==
        "G0 X0. Z25.\nZ2.\nG1 Z-3. F0.1\nG0 Z2.\nZ-2.5\nG1 Z-8.\nG0 Z2.\nZ-7.5\nG1 Z-12.\nG0 Z2.\n");
  // The tap: rapid only to the R plane outside the hole, G32 in, M4 at the bottom, G32 out, M3.
  CHECK(cycle_blocks(sw_head + tap, m, "e-tap") ==
        "G0 X0. Z25.\nZ5.\nG32 Z-12. F1.25\nM4\nG32 Z5. F1.25\nM3\nG0 Z25.\n");
  // A left-hand tap turns the other way in, and back.
  const std::string left = "UNIT/MM\nPARTNO DRL\nLOADTL/1\nSPINDL/1000,RPM,CCLW\nRAPID\nGOTO/0,0,25.\n" + tap;
  CHECK(cycle_blocks(left, m, "e-left") ==
        "G0 X0. Z25.\nZ5.\nG32 Z-12. F1.25\nM3\nG32 Z5. F1.25\nM4\nG0 Z25.\n");
}

TEST_CASE("a floating tap: the canned cycle without the rigid code", "[post][drill]") {
  const machine m = with("fanuc-0itd-twin", [](cycle_rules& c) { c.tap = "floating"; });
  CHECK(cycle_blocks(sw_head + tap, m, "floating") ==
        "G0 X0. Z25.\nG84 X0. Z-12. R-20. F1.25\nG80\nG0 Z25.\n");
}

TEST_CASE("tapping that cannot be done safely stops the post at the record", "[post][drill]") {
  const machine fanuc = load_machine("fanuc-0itd-twin");
  const std::string left = "UNIT/MM\nPARTNO DRL\nLOADTL/1\nSPINDL/1000,RPM,CCLW\nRAPID\nGOTO/0,0,25.\n" + tap;
  CHECK(errors_of(left, fanuc, "left") ==
        "job.cls:8:1: error: channel 1: CYCLE/TAP: a left-hand tap (LEFT, or the spindle turning CCLW), and "
        "machine 'fanuc-0itd-twin' gives no left-hand tapping cycle (cycles.tap_left_code)\nGOTO/0,0,0\n^\n");
  const machine none = with("fanuc-0itd-twin", [](cycle_rules& c) { c.tap = "none"; });
  CHECK(errors_of(sw_head + tap, none, "none") ==
        "job.cls:7:1: error: channel 1: CYCLE/TAP: machine 'fanuc-0itd-twin' has no tapping cycle ([cycles] "
        "tap = \"none\"); a tap fed as a drill would break\n"
        "CYCLE/TAP,FEDTO,12.,MMPR,1.25,RAPTO,5.,RTRCTO,25.\n^\n");
  CHECK(errors_of(sw_head + "CYCLE/TAP,FEDTO,12.,MMPM,1250.,RAPTO,5.\nGOTO/0,0,0\nEND\n", fanuc, "fpm") ==
        "job.cls:7:1: error: channel 1: CYCLE/TAP needs the pitch: PITCH or a feed per revolution (MMPR, "
        "IPR); a feed per minute would tap in step with the spindle only at one speed\n"
        "CYCLE/TAP,FEDTO,12.,MMPM,1250.,RAPTO,5.\n^\n");
  const std::string css =
      "UNIT/MM\nPARTNO DRL\nLOADTL/1\nSPINDL/SMM,100,MAXRPM,2000,CLW\nRAPID\nGOTO/0,0,25.\n";
  CHECK(errors_of(css + tap, fanuc, "css") ==
        "job.cls:8:1: error: channel 1: CYCLE/TAP needs a set spindle speed (SPINDL/RPM), not constant "
        "surface speed: the tap's feed follows the spindle\nGOTO/0,0,0\n^\n");
  CHECK(
      errors_of(sw_head + "CYCLE/TAP,FEDTO,12.,MMPR,1.25,RAPTO,5.,DWELL,1.\nGOTO/0,0,0\nEND\n", fanuc,
                "tapdwell") ==
      "job.cls:7:1: error: channel 1: CYCLE/TAP: DWELL is not carried out by the post (it knows FEDTO, "
      "DEPTH, RAPTO, CLEAR, PITCH, LEFT and the feed)\nCYCLE/TAP,FEDTO,12.,MMPR,1.25,RAPTO,5.,DWELL,1.\n^\n");
}

TEST_CASE("dialect words: RTRCTO below RAPTO, DEEP2 without SUBPECK, RTRCTO outside SolidWorks",
          "[post][drill]") {
  const machine fanuc = load_machine("fanuc-0itd-twin");
  CHECK(errors_of(sw_head + "CYCLE/DRILL,FEDTO,5.,MMPM,100.,RAPTO,3.,RTRCTO,1.\nGOTO/0,0,0\nEND\n", fanuc,
                  "below") ==
        "job.cls:8:1: error: channel 1: CYCLE/DRILL: RTRCTO 1 lies below RAPTO: the tool would return to a "
        "plane nearer the part than the one it started from\nGOTO/0,0,0\n^\n");
  CHECK(errors_of(sw_head + "CYCLE/DEEP2,FEDTO,5.,MMPM,100.,RAPTO,3.\nGOTO/0,0,0\nEND\n", fanuc, "nosub") ==
        "job.cls:7:1: error: channel 1: CYCLE/DEEP2 needs SUBPECK, the depth of each peck after the first\n"
        "CYCLE/DEEP2,FEDTO,5.,MMPM,100.,RAPTO,3.\n^\n");
  // The same record read as generic APT: RTRCTO's meaning there is not known.
  CHECK(errors_of(sw_head + drill, fanuc, "generic-rtrcto").find("(posted)") == 0);
  const test::posted p = test::post_in_fresh_dir(
      sw_head + drill, fanuc, "drill-forced-generic",
      [](const diagnostic& d) { return d.level == severity::error; }, {},
      [](post_options& o) { o.forced_dialect = dialect::generic; });
  CHECK(p.diagnostics ==
        "job.cls:7:1: error: channel 1: CYCLE/DRILL: RTRCTO is not carried out by the post (it knows FEDTO, "
        "DEPTH, RAPTO, CLEAR, STEP and the feed; the meaning of this word is known only in the SolidWorks "
        "and NX dialects)\nCYCLE/DRILL,FEDTO,7.5,MMPM,120.,RAPTO,3.,RTRCTO,25.,DWELL,0\n^\n");
}

TEST_CASE("[cycles] in a machine file: the choices and the codes each needs", "[post][drill][machines]") {
  const std::string base = test::machine_head + test::two_channels;
  const machine m = parse_machine(base + "[cycles]\ndrill = \"canned\"\ndrill_code = \"G81\"\n", "m.toml");
  CHECK(m.cycles.drill == "canned");
  CHECK(m.cycles.tap == "none");
  CHECK(m.cycles.cancel == "G80");
  auto fails = [&](const std::string& cycles) {
    return test::machine_error_of(base + "[cycles]\n" + cycles);
  };
  CHECK(fails("drill = \"fast\"\n") ==
        "m.toml:13:9: error: cycles.drill must be one of \"canned\", \"expanded\", not \"fast\"");
  CHECK(fails("drill = \"canned\"\n") ==
        "m.toml:13:9: error: cycles.drill = \"canned\" needs cycles.drill_code");
  CHECK(fails("tap = \"expanded\"\n") ==
        "m.toml:13:7: error: cycles.tap = \"expanded\" needs cycles.sync_feed");
}

TEST_CASE("an inch tap with PITCH, an off-centre hole, a cycle code in the wait range", "[post][drill]") {
  // Generic APT in inches: DEPTH 0.5 below the point, R plane 0.2 above, a lead of 0.05 in.
  const std::string inch =
      "PARTNO DRL\nUNITS/INCHES\nLOADTL/1\nSPINDL/1000,RPM,CLW\nRAPID\nGOTO/0,0,1.\n"
      "CYCLE/TAP,DEPTH,0.5,PITCH,0.05,RAPTO,0.2\nGOTO/0,0,0\nCYCLE/OFF\nEND\n";
  CHECK(cycle_blocks(inch, load_machine("fanuc-0itd-twin"), "inch") ==
        "G0 X0. Z25.4\nZ5.08\nM29 S1000\nG84 X0. Z-12.7 R0. F1.27\nG80\nG0 Z5.08\nG97 S1000 M3\n");
  CHECK(
      errors_of(sw_head + "CYCLE/DRILL,FEDTO,5.,MMPM,100.,RAPTO,3.\nGOTO/10,0,0\nEND\n",
                load_machine("fanuc-0itd-twin"), "offcentre") ==
      "job.cls:8:1: error: channel 1: CYCLE/DRILL at X 10 Y 0: off the spindle centre line; channel 1 of "
      "machine "
      "'fanuc-0itd-twin' has no C axis with live tools (a C axis and [milling]): with the part turning, the "
      "drill would cut a ring\nGOTO/10,0,0\n^\n");
  CHECK(test::machine_error_of(test::machine_head + test::two_channels +
                               "[cycles]\ntap = \"rigid\"\ntap_code = \"G84\"\nrigid_code = \"M101\"\n") ==
        "m.toml:15:14: error: cycles.rigid_code M101 lies in the wait range M100-M103 ([waits]); a program "
        "could not tell it from a wait");
}
