// Issue 22: cuts need a turning spindle, a surface speed on a rotating tool is its rpm, cutter
// compensation follows the frame as the arcs do and carries its D register, and a program's
// header and footer say nothing twice.
#include <catch2/catch.hpp>

#include <string>

#include "machine_test_support.hpp"
#include "machines/machine_loader.hpp"
#include "post_test_jobs.hpp"

using namespace twinpost;

namespace {

bool is_error(const diagnostic& d) { return d.level == severity::error; }

// The file `file` a post wrote (the only one when empty), or "(failed)" and its errors.
std::string program_of(const std::string& cl, const machine& m, const std::string& tag,
                       const std::string& file = "") {
  const test::posted p = test::post_in_fresh_dir(cl, m, tag, is_error);
  if (!p.ok) return "(failed)\n" + p.diagnostics;
  if (!file.empty()) return p.files.count(file) ? p.files.at(file) : "(no " + file + ")";
  return p.files.size() == 1 ? p.files.begin()->second : "(not one file)";
}

std::string errors_of(const std::string& cl, const machine& m, const std::string& tag) {
  const test::posted p = test::post_in_fresh_dir(cl, m, tag, is_error);
  return p.ok ? "(posted)" : p.diagnostics;
}

// A plunge at feed per minute with no SPINDL, as NX operation files come.
const std::string no_spindle =
    "PARTNO NS\nUNITS/MM\nLOADTL/1\nFEDRAT/500,MMPM\nRAPID\nGOTO/0,0,5\nGOTO/0,0,-1\nGOTO/10,0,-1\nFINI\n";

const std::string not_started_in_channel =
    "feed move with the main spindle not started: no SPINDL with a speed in this channel before the cut (a "
    "turning tool would be driven into a still part, a still cutter into the work); give the tool's speed in "
    "the machine's [[tool]] table (rpm or surface_speed) when the CL has none, or mark a tool that cuts with "
    "no "
    "spindle turning spindle = false there";
const std::string not_started_in_job =
    "feed move with the main spindle not started: no channel gives a SPINDL with a speed for it in this job "
    "(a turning tool would be driven into a still part, a still cutter into the work); give the tool's speed "
    "in the machine's [[tool]] table (rpm or surface_speed) when the CL has none, or mark a tool that cuts "
    "with no spindle turning spindle = false there";

}  // namespace

TEST_CASE("a cut with no spindle started is an error at the first cut, on every kind of machine",
          "[post][spindle]") {
  // A mill: its one spindle is no other channel's, the error comes at the cut (once).
  const std::string mill_job =
      "PARTNO NS\nUNITS/MM\nTLDATA/MILL,10,0,100,0,0\nLOADTL/1\nFEDRAT/500,MMPM\nRAPID\n"
      "GOTO/0,0,5\nGOTO/0,0,-1\nGOTO/10,0,-1\nFINI\n";
  // The trunnion holds the moves along its C axis (the pole) to the end of the job: the same
  // error, written when they are released, with the CL line kept with each held record.
  for (const char* mill : {"rotary-4axis", "head-head-5axis", "trunnion-5axis"})
    CHECK(errors_of(mill_job, load_machine(mill), std::string("ns-") + mill) ==
          "job.cls:8:1: error: channel 1: " + not_started_in_channel + "\nGOTO/0,0,-1\n^\n");
  // The lathes and the mill/turn heads: the main spindle is shared, another channel could start
  // it; none does anywhere in the job, so the cut is an error once the job is read.
  for (const char* lathe : {"fanuc-0itd-twin", "fanuc-31i-3path", "integrex-i200st"})
    CHECK(errors_of(no_spindle, load_machine(lathe), std::string("ns-") + lathe) ==
          "job.cls:7:1: error: channel 1: " + not_started_in_job + "\nGOTO/0,0,-1\n^\n");
  // A start after the cut in the same channel does not count.
  CHECK(errors_of("PARTNO NS\nUNITS/MM\nLOADTL/1\nFEDRAT/500,MMPM\nRAPID\nGOTO/0,0,5\nGOTO/0,0,-1\n"
                  "SPINDL/RPM,1000,CLW\nGOTO/10,0,-1\nFINI\n",
                  load_machine("fanuc-0itd-twin"), "ns-late") ==
        "job.cls:7:1: error: channel 1: " + not_started_in_job + "\nGOTO/0,0,-1\n^\n");
  // A drilling cycle is a cut too.
  CHECK(errors_of("PARTNO NS\nUNITS/MM\nLOADTL/1\nRAPID\nGOTO/0,0,20\n"
                  "CYCLE/DRILL,FEDTO,-5.,MMPM,100.,RAPTO,3.\nGOTO/10,10,0\nCYCLE/OFF\nFINI\n",
                  load_machine("rotary-4axis"), "ns-cycle") ==
        "job.cls:7:1: error: channel 1: " + not_started_in_channel + "\nGOTO/10,10,0\n^\n");
  // And a groove (the lathes' G75 or its plunges).
  CHECK(errors_of("PARTNO NS\nUNITS/MM\nHEAD/1\nTURRET/1,1\nRAPID\nGOTO/15,0,-25\n"
                  "CYCLE/GROOVE,DEPTH,3,RAPTO,1,MMPR,0.05\nGOTO/15,0,-25\nCYCLE/OFF\nFINI\n",
                  load_machine("fanuc-0itd-twin"), "ns-groove") ==
        "job.cls:8:1: error: channel 1: " + not_started_in_job + "\nGOTO/15,0,-25\n^\n");
  // After SPINDL/OFF the old message stands.
  CHECK(errors_of("PARTNO NS\nUNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/500,MMPM\nRAPID\nGOTO/0,0,5\n"
                  "SPINDL/OFF\nGOTO/0,0,-1\nFINI\n",
                  load_machine("rotary-4axis"), "ns-off") ==
        "job.cls:9:1: error: channel 1: feed move with the main spindle stopped by SPINDL/OFF: give SPINDL "
        "with "
        "a speed before cutting (the tool would be driven into a part that does not turn)\nGOTO/0,0,-1\n^\n");
}

TEST_CASE("a tool the tool table says needs no spindle cuts without one", "[post][spindle]") {
  machine m = load_machine("rotary-4axis");
  m.tools.push_back({1, 0, "mill"});
  m.tools.back().spindle = false;  // a scribe, a burnishing roller
  CHECK(program_of(no_spindle, m, "ns-table") ==
        "%\nO5003 (NS)\nG21\nG90 G94 G17 G40 G49 G80\nG91 G28 Z0.\nG90\nT01 M6\nG54\nG0 A0.\n"
        "G0 X0. Y0.\nG0 G43 H1 X0. Y0. Z5. A0.\nG1 Z-1. F500.\nX10.\nG91 G28 Z0.\nG90\nM9\nM5\n"
        "G49\nM30\n%\n");
  // The key as the machine file gives it.
  const std::string tool = "[[tool]]\nnumber = 4\nkind = \"turn\"\nspindle = false\ndiameter = 12\n";
  const machine read =
      parse_machine(test::machine_head + test::two_channels + tool + "diameter_offset = 24\n", "t.toml");
  REQUIRE(read.tools.size() == 1);
  CHECK_FALSE(read.tools[0].spindle);
  CHECK(read.tools[0].diameter == 12.0);
  CHECK(read.tools[0].diameter_offset == 24);
  CHECK(test::machine_error_of(test::machine_head + test::two_channels + tool + "diameter_offset = 0\n") ==
        "m.toml:17:19: error: tool.diameter_offset must be >= 1, not 0");
  CHECK(
      test::machine_error_of(test::machine_head + "[codes]\ncutcom_offset = \"d\"\n" + test::two_channels) ==
      "m.toml:7:17: error: codes.cutcom_offset must be \"tool\", \"cutcom\" or \"table\", not \"d\"");
}

TEST_CASE("a CL without SPINDL cuts at the tool table's speed", "[post][spindle]") {
  // NX writes its speeds into its own post, not the CLSF: [[tool]] rpm or surface_speed (with
  // direction) starts the spindle before the tool's first move when the CL gives no SPINDL
  // since the tool call; a SPINDL of the CL wins.
  machine m = load_machine("rotary-4axis");
  m.tools.push_back({1, 0, "mill"});
  m.tools.back().rpm = 2400;
  CHECK(program_of(no_spindle, m, "ts-rpm") ==
        "%\nO5003 (NS)\nG21\nG90 G94 G17 G40 G49 G80\nG91 G28 Z0.\nG90\nT01 M6\nG54\nS2400 M3\n"
        "G0 A0.\nG0 X0. Y0.\nG0 G43 H1 X0. Y0. Z5. A0.\nG1 Z-1. F500.\nX10.\nG91 G28 Z0.\nG90\nM9\n"
        "M5\nG49\nM30\n%\n");
  // 120 m/min on a 10 mm cutter (TLDATA), turning CCW: S3820 M4.
  m.tools.back().rpm.reset();
  m.tools.back().surface_speed = 120;
  m.tools.back().ccw = true;
  const std::string with_tldata =
      "PARTNO NS\nUNITS/MM\nTLDATA/MILL,10,0,75,0,0\nLOADTL/1\nFEDRAT/500,MMPM\n"
      "RAPID\nGOTO/0,0,5\nGOTO/0,0,-1\nFINI\n";
  CHECK(program_of(with_tldata, m, "ts-smm") ==
        "%\nO5003 (NS)\nG21\nG90 G94 G17 G40 G49 G80\nG91 G28 Z0.\nG90\nT01 M6\nG54\nS3820 M4\n"
        "G0 A0.\nG0 X0. Y0.\nG0 G43 H1 X0. Y0. Z5. A0.\nG1 Z-1. F500.\nG91 G28 Z0.\nG90\nM9\nM5\n"
        "G49\nM30\n%\n");
  // The CL's own SPINDL after the tool call wins.
  const std::string own = program_of(
      "PARTNO NS\nUNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/500,MMPM\n"
      "RAPID\nGOTO/0,0,5\nGOTO/0,0,-1\nFINI\n",
      m, "ts-own");
  CHECK(own ==
        "%\nO5003 (NS)\nG21\nG90 G94 G17 G40 G49 G80\nG91 G28 Z0.\nG90\nT01 M6\nG54\nS1000 M3\n"
        "G0 A0.\nG0 X0. Y0.\nG0 G43 H1 X0. Y0. Z5. A0.\nG1 Z-1. F500.\nG91 G28 Z0.\nG90\nM9\nM5\n"
        "G49\nM30\n%\n");
  // The keys as the machine file gives them, and what is refused.
  const std::string tool = "[[tool]]\nnumber = 4\nkind = \"mill\"\n";
  const machine read = parse_machine(
      test::machine_head + test::two_channels + tool + "surface_speed = 90\ndirection = \"ccw\"\n", "t.toml");
  REQUIRE(read.tools.size() == 1);
  CHECK(read.tools[0].surface_speed == 90.0);
  CHECK(read.tools[0].ccw);
  CHECK(test::machine_error_of(test::machine_head + test::two_channels + tool +
                               "rpm = 800\nsurface_speed = 90\n") ==
        "m.toml:16:17: error: tool 4: give rpm or surface_speed, not both (which would the spindle run at?)");
  CHECK(test::machine_error_of(test::machine_head + test::two_channels + tool + "rpm = 0\n") ==
        "m.toml:15:7: error: tool.rpm must be in 1..1000000, not 0");
  CHECK(test::machine_error_of(test::machine_head + test::two_channels + tool + "direction = \"cw\"\n") ==
        "m.toml:15:13: error: tool 4: a direction without a speed (rpm or surface_speed)");
  CHECK(test::machine_error_of(test::machine_head + test::two_channels + tool +
                               "rpm = 800\ndirection = \"up\"\n") ==
        "m.toml:16:13: error: tool.direction must be cw or ccw, not 'up'");
  CHECK(test::machine_error_of(test::machine_head + test::two_channels + tool +
                               "spindle = false\nrpm = 800\n") ==
        "m.toml:16:7: error: tool 4: a speed for a tool marked spindle = false");
}

TEST_CASE("a surface speed for a rotating tool is its rpm from the diameter", "[post][spindle]") {
  const std::string job =
      "PARTNO SMM\nUNITS/MM\nTLDATA/MILL,10,0,75,0,0\nLOADTL/1\nSPINDL/SMM,150,CLW\n"
      "FEDRAT/500,MMPM\nRAPID\nGOTO/0,0,5\nGOTO/0,0,-1\nFINI\n";
  // 1000 x 150 / (pi x 10) = 4774.6: S4775, not S150 (nor G96 on a cutter).
  CHECK(program_of(job, load_machine("rotary-4axis"), "smm-mill") ==
        "%\nO5003 (SMM)\nG21\nG90 G94 G17 G40 G49 G80\nG91 G28 Z0.\nG90\nT01 M6\nG54\nS4775 M3\n"
        "G0 A0.\nG0 X0. Y0.\nG0 G43 H1 X0. Y0. Z5. A0.\nG1 Z-1. F500.\nG91 G28 Z0.\nG90\nM9\nM5\n"
        "G49\nM30\n%\n");
  // The Integrex's milling spindle: rpm mode (G97), never G96 on the live tool.
  const std::string integrex = program_of(job, load_machine("integrex-i200st"), "smm-integrex");
  CHECK(integrex.find("\nG97 S4775 M3\n") != std::string::npos);
  CHECK(integrex.find("G96") == std::string::npos);
  // SFM: 12 x 500 / (pi x 0.5 in) = 3819.7 rpm, the same as in metric (12.7 mm, 152.4 m/min).
  CHECK(program_of("PARTNO SMM\nUNITS/INCHES\nTLDATA/MILL,0.5,0,3,0,0\nLOADTL/1\nSPINDL/SFM,500,CLW\n"
                   "FEDRAT/20,IPM\nRAPID\nGOTO/0,0,0.2\nGOTO/0,0,-0.04\nFINI\n",
                   load_machine("rotary-4axis"), "sfm-mill")
            .find("\nS3820 M3\n") != std::string::npos);
  // A rigid tap after it taps at that rpm (M29 S4775), not at the surface speed's number.
  CHECK(program_of("PARTNO SMM\nUNITS/MM\nTLDATA/MILL,10,0,75,0,0\nLOADTL/1\nSPINDL/SMM,150,CLW\nRAPID\n"
                   "GOTO/10,10,20\nCYCLE/TAP,DEPTH,10.,MMPR,1.5,RAPTO,3.\nGOTO/10,10,0\nCYCLE/OFF\nFINI\n",
                   load_machine("rotary-4axis"), "smm-tap")
            .find("\nM29 S4775\n") != std::string::npos);
  // The diameter from the machine's tool table when the CL gives none.
  machine table = load_machine("rotary-4axis");
  table.tools.push_back({1, 0, "mill"});
  table.tools.back().diameter = 20.0;
  CHECK(program_of("PARTNO SMM\nUNITS/MM\nLOADTL/1\nSPINDL/SMM,150,CLW\nFEDRAT/500,MMPM\nRAPID\n"
                   "GOTO/0,0,5\nGOTO/0,0,-1\nFINI\n",
                   table, "smm-table")
            .find("\nS2387 M3\n") != std::string::npos);
}

TEST_CASE("a surface speed for a rotating tool without a diameter or over a limit is refused",
          "[post][spindle]") {
  const machine m = load_machine("rotary-4axis");
  CHECK(errors_of("PARTNO SMM\nUNITS/MM\nLOADTL/1\nSPINDL/SMM,150,CLW\nFINI\n", m, "smm-nodia") ==
        "job.cls:4:1: error: channel 1: SPINDL/SMM,150: a surface speed for tool 1, which turns on the main "
        "spindle: its rpm = 1000 v / (pi D) needs the tool's diameter; give TLDATA/MILL,<diameter>,... with "
        "the "
        "tool, or its diameter in the tool table of machine 'rotary-4axis' ([[tool]] diameter)\n"
        "SPINDL/SMM,150,CLW\n^\n");
  CHECK(errors_of("PARTNO SMM\nUNITS/MM\nTLDATA/MILL,1,0,75,0,0\nLOADTL/1\nSPINDL/SMM,150,CLW\nFINI\n", m,
                  "smm-limit") ==
        "job.cls:5:1: error: channel 1: SPINDL/SMM,150 gives 47746 rpm for the 1 mm tool 1, over the main "
        "spindle's limit of 12000 rpm ([[spindle]] max_rpm): give a lower surface speed or SPINDL/RPM\n"
        "SPINDL/SMM,150,CLW\n^\n");
  CHECK(
      errors_of("PARTNO SMM\nUNITS/MM\nTLDATA/MILL,10,0,75,0,0\nLOADTL/1\nSPINDL/SMM,150,MAXRPM,3000,CLW\n"
                "FINI\n",
                m, "smm-maxrpm") ==
      "job.cls:5:1: error: channel 1: SPINDL/SMM,150 gives 4775 rpm for the 10 mm tool 1, over its MAXRPM of "
      "3000: a clamp would cut the whole path slower than the surface speed asks, at a higher feed per "
      "tooth; give a lower surface speed or SPINDL/RPM\nSPINDL/SMM,150,MAXRPM,3000,CLW\n^\n");
}

TEST_CASE("cutter compensation swaps its side with the arcs where the frame turns the plane over",
          "[post][spindle]") {
  // Head 1 on the Z-reversed sub spindle of the 0i-TD: CUTCOM/LEFT is G42, as the CL's G3 is G2.
  const std::string job =
      "PARTNO CS\nUNITS/MM\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,800,CLW,SUB\nFEDRAT/0.2,MMPR\n"
      "RAPID\nGOTO/30,0,2\nCUTCOM/LEFT\nGOTO/25,0,0\nGOTO/25,0,10\nCIRCLE/27,0,10,0,1,0,2\n"
      "GOTO/27,0,12\nCUTCOM/OFF\nGOTO/30,0,12\nFINI\n";
  const test::posted p = test::post_in_fresh_dir(job, load_machine("fanuc-0itd-twin"), "cutcom-sub");
  REQUIRE(p.ok);
  CHECK(p.files.at("CS_1.nc") ==
        "%\nO1000 (CS)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG55\nG97 S800 M103\n"
        "G0 X60. Z-2.\nG42 G1 X50. Z0. F0.2\nZ-10.\nG2 X54. Z-12. I2. K0.\nG40 G1 X60.\nM100\nM105\nM9\n"
        "G28 U0.\nG28 W0.\nM5\nM30\n%\n");
  // The Integrex's upper head on its second spindle: the same rule.
  const test::posted integrex =
      test::post_in_fresh_dir(job, load_machine("integrex-i200st"), "cutcom-integrex");
  REQUIRE(integrex.ok);
  CHECK(integrex.files.at("CS.EIA").find("G42 G1 X50. Z0. F0.2\nZ-10.\nG2 X54. Z-12. I2. K0.\n") !=
        std::string::npos);
  // The 0i-TD's lower turret (X mirrored) on the sub (Z reversed): both turn the plane over,
  // together they give the CL's side and sense back: CUTCOM/LEFT stays G41, the arc (clockwise
  // about +Y in the CL: counter-clockwise about -Y) stays G2.
  const std::string lower =
      "PARTNO CS\nUNITS/MM\nHEAD/2\nTURRET/1,1\nSPINDL/RPM,800,CLW,SUB\n"
      "FEDRAT/0.2,MMPR\nRAPID\nGOTO/-30,0,2\nCUTCOM/LEFT\nGOTO/-25,0,0\nGOTO/-25,0,10\n"
      "CIRCLE/-27,0,10,0,-1,0,2\nGOTO/-27,0,12\nCUTCOM/OFF\nGOTO/-30,0,12\nFINI\n";
  const test::posted l = test::post_in_fresh_dir(lower, load_machine("fanuc-0itd-twin"), "cutcom-lower-sub");
  INFO(l.diagnostics);
  REQUIRE(l.ok);
  CHECK(l.files.at("CS_2.nc").find("G41 G1 X50. Z0. F0.2\nZ-10.\nG2 X54. Z-12. I2. K0.\n") !=
        std::string::npos);
  // On the main spindle the same job keeps its side and its sense.
  std::string main_job = job;
  main_job.replace(main_job.find(",SUB"), 4, "");
  const test::posted q = test::post_in_fresh_dir(main_job, load_machine("fanuc-0itd-twin"), "cutcom-main");
  REQUIRE(q.ok);
  CHECK(q.files.at("CS_1.nc").find("G41 G1 X50. Z0. F0.2\nZ10.\nG3 X54. Z12. I2. K0.\n") !=
        std::string::npos);
}

TEST_CASE("G41/G42 on the mills carry the D register the machine file says", "[post][spindle]") {
  const std::string job =
      "PARTNO CC\nUNITS/MM\nLOADTL/3\nSPINDL/RPM,2000,CLW\nFEDRAT/400,MMPM\nRAPID\n"
      "GOTO/0,-20,5\nGOTO/0,-20,-2\nCUTCOM/LEFT\nGOTO/10,-20,-2\nCUTCOM/OFF\nGOTO/0,-20,-2\n"
      "FINI\n";
  for (const char* mill : {"rotary-4axis", "head-head-5axis", "trunnion-5axis"})
    CHECK(load_machine(mill).codes.cutcom_offset == "tool");
  // The tool number (Fusion's default diameter offset), on the first move of the compensation.
  CHECK(program_of(job, load_machine("rotary-4axis"), "d-tool") ==
        "%\nO5003 (CC)\nG21\nG90 G94 G17 G40 G49 G80\nG91 G28 Z0.\nG90\nT03 M6\nG54\nS2000 M3\n"
        "G0 A0.\nG0 X0. Y-20.\nG0 G43 H3 X0. Y-20. Z5. A0.\nG1 Z-2. F400.\nG41 D3 X10.\nG40 X0.\n"
        "G91 G28 Z0.\nG90\nM9\nM5\nG49\nM30\n%\n");
  // The CL's register wins.
  std::string with_register = job;
  with_register.replace(with_register.find("CUTCOM/LEFT"), 11, "CUTCOM/LEFT,21");
  CHECK(program_of(with_register, load_machine("rotary-4axis"), "d-cl").find("\nG41 D21 X10.\n") !=
        std::string::npos);
  // "cutcom": the CL must give it.
  machine cutcom = load_machine("rotary-4axis");
  cutcom.codes.cutcom_offset = "cutcom";
  CHECK(
      errors_of(job, cutcom, "d-cutcom") ==
      "job.cls:9:1: error: channel 1: CUTCOM/LEFT gives no register, and machine 'rotary-4axis' takes the D "
      "register from the CUTCOM record (codes.cutcom_offset = \"cutcom\"): give CUTCOM/LEFT,n; without a D "
      "word the control would compensate with whatever D register is active\nCUTCOM/LEFT\n^\n");
  // "table": the tool's diameter_offset, or an error naming the tool.
  machine table = load_machine("rotary-4axis");
  table.codes.cutcom_offset = "table";
  CHECK(errors_of(job, table, "d-table-missing") ==
        "job.cls:9:1: error: channel 1: CUTCOM/LEFT gives no register, and machine 'rotary-4axis' takes tool "
        "3's D register from its tool table (codes.cutcom_offset = \"table\"), which gives none ([[tool]] "
        "diameter_offset); without a D word the control would compensate with whatever D register is active\n"
        "CUTCOM/LEFT\n^\n");
  table.tools.push_back({3, 0, "mill"});
  table.tools.back().diameter_offset = 33;
  CHECK(program_of(job, table, "d-table").find("\nG41 D33 X10.\n") != std::string::npos);
  // A lathe writes none: its T word's offset carries the nose radius.
  CHECK(load_machine("fanuc-0itd-twin").codes.cutcom_offset.empty());
}

TEST_CASE("a refused tool call leaves no misleading error about the tool after it", "[post][spindle]") {
  // TLDATA/TURN says what tool 3 is: the refused call must not lose it (the SPINDL then asked
  // for "the kind of tool 3 ( at line 0)").
  CHECK(
      errors_of("PARTNO T\nUNITS/MM\nHEAD/1\nTLDATA/TURN\nTURRET/3,5\nSPINDL/RPM,800,CLW\nFEDRAT/0.2,MMPR\n"
                "GOTO/20,0,2\nGOTO/20,0,-5\nFINI\n",
                load_machine("integrex-i200st"), "refused-call") ==
      "job.cls:5:1: error: channel 1: TURRET asks for tool 3 on offset 5, but the channel's tool call T03 M6 "
      "writes no offset (channel.tool_call has no {offset}): the tool would cut on whatever offset is "
      "active\n"
      "TURRET/3,5\n^\n");
  // Without TLDATA the kind is unknown indeed, and the message names the call.
  CHECK(errors_of("PARTNO T\nUNITS/MM\nHEAD/1\nTURRET/3,5\nSPINDL/RPM,800,CLW\nFINI\n",
                  load_machine("integrex-i200st"), "refused-call-kind")
            .find("the kind of tool 3 (TURRET at line 4) is unknown") != std::string::npos);
}

TEST_CASE("the footer writes no M9 or M5 the channel's end already has in force", "[post][spindle]") {
  const std::string cut =
      "PARTNO F\nUNITS/MM\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nCOOLNT/ON\n"
      "FEDRAT/0.2,MMPR\nGOTO/20,0,2\nGOTO/20,0,-5\n";
  CHECK(program_of(cut + "COOLNT/OFF\nSPINDL/OFF\nFINI\n", load_machine("fanuc-0itd-twin"), "footer-done",
                   "F_1.nc") ==
        "%\nO1000 (F)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG97 S1000 M3\nM8\n"
        "G1 X40. Z2. F0.2\nZ-5.\nM9\nM5\nM100\nG28 U0.\nG28 W0.\nM30\n%\n");
  // An AUXFUN after them may turn either on again: the footer stays whole.
  CHECK(program_of(cut + "COOLNT/OFF\nSPINDL/OFF\nAUXFUN/51\nFINI\n", load_machine("fanuc-0itd-twin"),
                   "footer-aux", "F_1.nc") ==
        "%\nO1000 (F)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG97 S1000 M3\nM8\n"
        "G1 X40. Z2. F0.2\nZ-5.\nM9\nM5\nM51\nM100\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
  // A header written without blanks says the same.
  machine packed = load_machine("fanuc-0itd-twin");
  packed.program.header = {"G0G18G21G40G54G80G99"};
  CHECK(program_of(cut + "FINI\n", packed, "header-packed", "F_1.nc").find("\nM8\nG1 X40. Z2. F0.2\n") !=
        std::string::npos);
  // The header's G99 holds for the first feed per revolution; a feed per minute writes G98.
  CHECK(program_of(cut + "FEDRAT/100,MMPM\nGOTO/20,0,-8\nFINI\n", load_machine("fanuc-0itd-twin"),
                   "header-mode", "F_1.nc")
            .find("\nM8\nG1 X40. Z2. F0.2\nZ-5.\nG98\nZ-8. F100.\n") != std::string::npos);
}

TEST_CASE("an axial hole off centre says what this machine lacks, not that C-axis holes are not posted",
          "[post][spindle]") {
  const auto hole = [](const std::string& spindle) {
    std::string cl = "PARTNO D\nUNITS/MM\nHEAD/1\nTLDATA/DRILL\nTURRET/5,5\n";
    cl += spindle;
    cl += "\nRAPID\nGOTO/10,0,20\nCYCLE/DRILL,FEDTO,-5.,MMPM,100.,RAPTO,3.\nGOTO/10,0,0\nCYCLE/OFF\nFINI\n";
    return cl;
  };
  const std::string job = hole("SPINDL/RPM,800,CLW");
  // The Integrex posts C-axis holes: with the part turning (a drill on the workpiece spindle)
  // the way is the live spindle.
  CHECK(
      errors_of(job, load_machine("integrex-i200st"), "offcentre-integrex") ==
      "job.cls:10:1: error: channel 1: CYCLE/DRILL at X 10 Y 0: off the spindle centre line; the part turns "
      "on "
      "the main spindle: drill it on the live spindle (SPINDL/...,LIVE), which holds the part as the C axis "
      "and turns it onto the hole\nGOTO/10,0,0\n^\n");
  // The 31i's turret path has no C axis.
  CHECK(errors_of(job, load_machine("fanuc-31i-3path"), "offcentre-31i") ==
        "job.cls:10:1: error: channel 1: CYCLE/DRILL at X 10 Y 0: off the spindle centre line; channel 1 of "
        "machine 'fanuc-31i-3path' has no C axis with live tools (a C axis and [milling]): with the part "
        "turning, the drill would cut a ring\nGOTO/10,0,0\n^\n");
  // With SPINDL/...,LIVE the Integrex drills it at a C position.
  CHECK(errors_of(hole("SPINDL/RPM,800,CLW,LIVE"), load_machine("integrex-i200st"), "offcentre-live") ==
        "(posted)");
}

TEST_CASE("a tool change with the CL's cutter compensation still on is said", "[post][spindle]") {
  // Attack 69 L9: `G41` of a turning tool whose CL never gave CUTCOM/OFF stayed in force through
  // the tool change to the end of the program, without a word.
  const std::string job =
      "PARTNO CC\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/40,0,5\nCUTCOM/LEFT\n"
      "GOTO/40,0,-20\nGOTO/45,0,-20\nRAPID\nGOTO/60,0,5\nTURRET/2,2\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/"
      "30,0,5\n"
      "GOTO/30,0,-10\nRAPID\nGOTO/60,0,5\nFINI\n";
  const test::posted p = test::post_in_fresh_dir(job, load_machine("fanuc-0itd-twin"), "cutcom-tool-change");
  REQUIRE(p.ok);
  CHECK(
      p.diagnostics ==
      "job.cls:13:1: warning: channel 1: the tool changes with cutter compensation still on (CUTCOM/LEFT or "
      "RIGHT without CUTCOM/OFF): the control carries G41 or G42 to the next tool; give CUTCOM/OFF with a "
      "move before the tool change\nTURRET/2,2\n^\n");
}
