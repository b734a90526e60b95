// NX drilling forms on the mills (issue 24 item 5): CYCLE/DRILL before the first GOTO of a
// tool (NX's "standard drill"), CYCLE/DRILL,DEEP as the peck cycle, and the positional
// CYCLE/DRILL,d,f of CATIA, refused with the reason.
#include <catch2/catch.hpp>

#include <sstream>
#include <string>

#include "file_test_support.hpp"
#include "machines/machine_loader.hpp"
#include "post_test_jobs.hpp"
#include "support/diagnostics.hpp"

using namespace twinpost;

namespace {

// An NX operation: tool 3 loaded, spindle on, the cycle given before the first point.
const std::string nx_head =
    "TOOL PATH/DRILLING,TOOL,DRILL-8\nTLDATA/DRILL,8.0000,0.0000,75.0000,118.0000,40.0000\n"
    "LOAD/TOOL,3\nSPINDL/RPM,1200,CLW\n";
const std::string nx_points =
    "GOTO/20.0000,10.0000,0.0000,0.0000000,0.0000000,1.0000000\nGOTO/40.0000,10.0000,0.0000\n"
    "CYCLE/OFF\nEND-OF-PATH\n";

// The blocks from the tool call to the length offset's cancel, for `cl` posted on `machine`.
std::string blocks(const std::string& cl, const std::string& machine, const std::string& tag) {
  const test::posted p = test::post_in_fresh_dir(cl, load_machine(machine), "nxdrill-" + tag);
  if (!p.ok) return "(failed)\n" + p.diagnostics;
  std::istringstream in(p.files.begin()->second);
  std::string line, out;
  bool on = false;
  while (std::getline(in, line)) {
    on = on || line.ends_with(" M6");
    if (!on) continue;
    out += line + "\n";
    if (line == "G49") break;
  }
  return out;
}

std::string errors_of(const std::string& cl, const std::string& machine, const std::string& tag) {
  const test::posted p =
      test::post_in_fresh_dir(cl, load_machine(machine), "nxdrill-err-" + tag,
                              [](const diagnostic& d) { return d.level == severity::error; });
  return p.ok ? "(posted)" : p.diagnostics;
}

}  // namespace

TEST_CASE("NX: a drilling cycle as the first move after a tool call", "[post][drill][nx]") {
  // The length offset goes out with a rapid above the first hole, on its R plane (RAPTO 3 above
  // the hole's top at Z0), as a GOTO there would; the canned cycle starts from that plane.
  const std::string cl = nx_head + "CYCLE/DRILL,RAPTO,3.0000,FEDTO,-12.0000,MMPM,150.0000\n" + nx_points;
  CHECK(blocks(cl, "rotary-4axis", "std4") ==
        "T03 M6\nG54\nS1200 M3\nG0 A0.\nG0 X20. Y10.\nG0 G43 H3 X20. Y10. Z3. A0.\n"
        "G98 G81 X20. Y10. Z-12. R3. F150.\nG80\nG0 Z3.\nX40.\nG98 G81 X40. Y10. Z-12. R3. F150.\nG80\n"
        "G0 Z3.\nM9\nM5\nG91 G28 Z0.\nG90\nG49\n");
  // The trunnion has no canned cycle ([cycles] drill = "moves"): the same hole as moves.
  CHECK(blocks(cl, "trunnion-5axis", "std5") ==
        "T03 M6\nG54\nS1200 M3\nG0 A0. C0.\nG0 X20. Y10.\nG0 G43.4 H3 X20. Y10. Z3. A0. C0.\nG1 Z-12. F150.\n"
        "G0 Z3.\nX40.\nG1 Z-12.\nG0 Z3.\nM9\nM5\nG91 G28 Z0.\nG90\nG49\n");
}

TEST_CASE("NX: CYCLE/DRILL,DEEP is the peck cycle, in pecks of STEP", "[post][drill][nx]") {
  const std::string cl =
      nx_head + "CYCLE/DRILL,DEEP,STEP,4.0000,RAPTO,3.0000,FEDTO,-12.0000,MMPM,150.0000\n" + nx_points;
  CHECK(blocks(cl, "rotary-4axis", "deep4") ==
        "T03 M6\nG54\nS1200 M3\nG0 A0.\nG0 X20. Y10.\nG0 G43 H3 X20. Y10. Z3. A0.\n"
        "G98 G83 X20. Y10. Z-12. R3. Q4. F150.\nG80\nG0 Z3.\nX40.\nG98 G83 X40. Y10. Z-12. R3. Q4. F150.\n"
        "G80\nG0 Z3.\nM9\nM5\nG91 G28 Z0.\nG90\nG49\n");
  // As moves: from R3 pecks of 4 to Z-1, -5, -9, back in to 0.5 above each, and the bottom.
  CHECK(blocks(nx_head +
                   "CYCLE/DRILL,DEEP,STEP,4.0000,RAPTO,3.0000,FEDTO,-12.0000,MMPM,150.0000\n"
                   "GOTO/20.0000,10.0000,0.0000,0.0000000,0.0000000,1.0000000\nCYCLE/OFF\nEND-OF-PATH\n",
               "trunnion-5axis", "deep5") ==
        "T03 M6\nG54\nS1200 M3\nG0 A0. C0.\nG0 X20. Y10.\nG0 G43.4 H3 X20. Y10. Z3. A0. C0.\nG1 Z-1. F150.\n"
        "G0 Z3.\nZ-0.5\nG1 Z-5.\nG0 Z3.\nZ-4.5\nG1 Z-9.\nG0 Z3.\nZ-8.5\nG1 Z-12.\nG0 Z3.\nM9\nM5\nG91 G28 "
        "Z0.\nG90\nG49\n");
}

TEST_CASE("a peck cycle without STEP, and positional cycle values, stop the post", "[post][drill][nx]") {
  // Without a peck depth a peck cycle would be drilled in one feed; so would Creo's CYCLE/DEEP.
  CHECK(errors_of(nx_head + "CYCLE/DRILL,DEEP,RAPTO,3.0000,FEDTO,0.0000,MMPM,250.0000\n" + nx_points,
                  "rotary-4axis", "nostep") ==
        "job.cls:5:1: error: channel 1: CYCLE/DEEP (NX: CYCLE/DRILL,DEEP) needs STEP, the depth of each "
        "peck\nCYCLE/DRILL,DEEP,RAPTO,3.0000,FEDTO,0.0000,MMPM,250.0000\n^\n");
  CHECK(errors_of(nx_head + "CYCLE/DEEP,FEDTO,-12.,RAPTO,3.,MMPM,150.\n" + nx_points, "rotary-4axis",
                  "creo-nostep") ==
        "job.cls:5:1: error: channel 1: CYCLE/DEEP (NX: CYCLE/DRILL,DEEP) needs STEP, the depth of each "
        "peck\nCYCLE/DEEP,FEDTO,-12.,RAPTO,3.,MMPM,150.\n^\n");
  // CATIA's CYCLE/DRILL,d,f: the values' meaning is its site's PP table's.
  CHECK(errors_of("PARTNO P\nLOADTL/2,1\nSPINDL/ 2546.4790,RPM,CLW\nRAPID\nGOTO/98,100,35,0,0,1\n"
                  "FEDRAT/300,MMPM\nGOTO/98,100,25,0,0,1\nCYCLE/DRILL,    3.000000,    5.000000\n"
                  "GOTO/98,100,20,0,0,1\nCYCLE/OFF\nEND\n",
                  "rotary-4axis", "catia") ==
        "job.cls:8:1: error: channel 1: CYCLE/DRILL: the values 3, 5 stand by position, whose meaning the "
        "CAM's post table sets (CATIA's PP table) and no public definition fixes; twinpost does not guess "
        "which is the depth (it knows FEDTO, DEPTH, RAPTO, CLEAR, STEP and the feed, each with its value)\n"
        "CYCLE/DRILL,    3.000000,    5.000000\n^\n");
}

TEST_CASE("NX: FEDTO is a distance from the hole's point along the tool axis", "[post][drill][nx]") {
  // HumMan/CLSFProcessor's "standard drill" form: a countersink over holes whose points lie at
  // Z240, RAPTO 3 and FEDTO 0. NX's posts place the feed-to point at the hole's point + FEDTO
  // along the tool axis: the bottom is Z240, not Z0 (read as a Z, the 30 mm tool plunged 243 mm).
  const std::string head =
      "TOOL PATH/DRILLING,TOOL,COUNTERSINKING_TOOL\n"
      "TLDATA/MILL,30.0000,0.0000,30.0000,0.0000,45.0000\nLOAD/TOOL,5\n"
      "SPINDL/RPM,900,CLW\n";
  const std::string holes =
      "GOTO/66.0000,0.0000,240.0000,0.0000000,0.0000000,1.0000000\n"
      "GOTO/-55.0000,0.0000,238.5000\nCYCLE/OFF\nEND-OF-PATH\n";
  CHECK(blocks(head + "CYCLE/DRILL,RAPTO,3.0000,FEDTO,-1.5000,RTRCTO,10.0000,MMPM,250.0000\n" + holes,
               "rotary-4axis", "csink") ==
        "T05 M6\nG54\nS900 M3\nG0 A0.\nG0 X66. Y0.\nG0 G43 H5 X66. Y0. Z250. A0.\n"
        "G98 G81 X66. Y0. Z238.5 R243. F250.\nG80\nG0 Z250.\nX-55.\nZ248.5\n"
        "G98 G81 X-55. Y0. Z237. R241.5 F250.\nG80\nG0 Z248.5\nM9\nM5\nG91 G28 Z0.\nG90\nG49\n");
  // A hole deeper than the tool is long (TLDATA's third number) is refused at each hole.
  CHECK(
      errors_of(head + "CYCLE/DRILL,RAPTO,3.0000,FEDTO,-33.0000,MMPM,250.0000\n" + holes, "rotary-4axis",
                "reach") ==
      "job.cls:6:1: error: channel 1: CYCLE/DRILL: the hole goes 33 mm below its top (the GOTO point, Z 240) "
      "to Z 207, but tool 5 is 30 mm long (TLDATA): its holder would drive into the part\n"
      "GOTO/66.0000,0.0000,240.0000,0.0000000,0.0000000,1.0000000\n^\n"
      "job.cls:7:1: error: channel 1: CYCLE/DRILL: the hole goes 33 mm below its top (the GOTO point, Z "
      "238.5) to Z 205.5, but tool 5 is 30 mm long (TLDATA): its holder would drive into the part\n"
      "GOTO/-55.0000,0.0000,238.5000\n^\n");
  // The same record in a generic APT file reads FEDTO as a Z: Z-1.5, 241.5 mm below the top.
  CHECK(errors_of("PARTNO P\nTLDATA/MILL,30.0000,0.0000,30.0000,0.0000,45.0000\nLOADTL/5\n"
                  "SPINDL/RPM,900,CLW\nCYCLE/DRILL,RAPTO,3.0000,FEDTO,-1.5000,MMPM,250.0000\n"
                  "GOTO/66.0000,0.0000,240.0000,0.0000000,0.0000000,1.0000000\nCYCLE/OFF\nFINI\n",
                  "rotary-4axis", "generic") ==
        "job.cls:6:1: error: channel 1: CYCLE/DRILL: the hole goes 241.5 mm below its top (the GOTO point, Z "
        "240) to Z -1.5, but tool 5 is 30 mm long (TLDATA): its holder would drive into the part\n"
        "GOTO/66.0000,0.0000,240.0000,0.0000000,0.0000000,1.0000000\n^\n");
}

TEST_CASE("a hole drilled towards +Z on the main spindle or a machining centre is refused",
          "[post][drill][nx]") {
  // The tool axis 0,0,-1 would put the R and retract planes inside the part (NX reads them along
  // the tool): refused where the tool can only drill towards -Z.
  const std::string lathe =
      "TOOL PATH/CENTRE_DRILL,TOOL,DRILL-10\nTLDATA/DRILL,10.0000,0.0000,90.0000,118.0000,60.0000\n"
      "LOAD/TOOL,3\nSPINDL/RPM,1000,CLW\nCYCLE/DRILL,RAPTO,2.0000,FEDTO,-30.0000,MMPR,0.1000\n"
      "GOTO/0.0000,0.0000,5.0000,0.0000000,0.0000000,-1.0000000\nCYCLE/OFF\nEND-OF-PATH\n";
  CHECK(errors_of(lathe, "fanuc-0itd-twin", "up-lathe") ==
        "job.cls:6:1: error: channel 1: CYCLE/DRILL with the tool axis (0,0,-1): the tool would drill "
        "towards +Z, "
        "away from the main spindle's part; a hole is drilled down the tool towards -Z\n"
        "GOTO/0.0000,0.0000,5.0000,0.0000000,0.0000000,-1.0000000\n^\n");
}

TEST_CASE("between holes at different heights the tool goes up, across, then down", "[post][drill][nx]") {
  // Holes at Z0, on a boss at Z50, and at Z0 again, each with its retract plane 10 above its
  // point: a rapid that climbed while it travelled would cut the boss's corner.
  const std::string cl = nx_head +
                         "CYCLE/DRILL,RAPTO,3.0000,FEDTO,-10.0000,RTRCTO,10.0000,MMPM,250.0000\n"
                         "GOTO/0.0000,0.0000,0.0000,0.0000000,0.0000000,1.0000000\n"
                         "GOTO/100.0000,0.0000,50.0000\nGOTO/200.0000,0.0000,0.0000\nCYCLE/OFF\n"
                         "END-OF-PATH\n";
  CHECK(blocks(cl, "rotary-4axis", "steps4") ==
        "T03 M6\nG54\nS1200 M3\nG0 A0.\nG0 X0. Y0.\nG0 G43 H3 X0. Y0. Z10. A0.\n"
        "G98 G81 X0. Y0. Z-10. R3. F250.\nG80\nG0 Z10.\nZ60.\nX100.\nG98 G81 X100. Y0. Z40. R53. F250.\nG80\n"
        "G0 Z60.\nX200.\nZ10.\nG98 G81 X200. Y0. Z-10. R3. F250.\nG80\nG0 Z10.\nM9\nM5\nG91 G28 "
        "Z0.\nG90\nG49\n");
  // As moves on the trunnion: the same order.
  CHECK(
      blocks(cl, "trunnion-5axis", "steps5") ==
      "T03 M6\nG54\nS1200 M3\nG0 A0. C0.\nG0 X0. Y0.\nG0 G43.4 H3 X0. Y0. Z10. A0. C0.\nZ3.\nG1 Z-10. F250.\n"
      "G0 Z10.\nZ60.\nX100.\nZ53.\nG1 Z40.\nG0 Z60.\nX200.\nZ10.\nZ3.\nG1 Z-10.\nG0 Z10.\nM9\nM5\nG91 G28 "
      "Z0.\nG90\nG49\n");
}

TEST_CASE("a tool called again keeps its TLDATA length", "[post][drill][nx]") {
  // Tool 2 is 20 mm long (its TLDATA before its first call); called again with no TLDATA, the
  // 50 mm hole is still too deep for it.
  const std::string cl =
      "TOOL "
      "PATH/A,TOOL,D2\nTLDATA/DRILL,8.0000,0.0000,20.0000,118.0000,15.0000\nLOAD/TOOL,2\nSPINDL/"
      "RPM,1200,CLW\n"
      "CYCLE/DRILL,RAPTO,3.0000,FEDTO,-10.0000,MMPM,150.0000\nGOTO/0.0000,0.0000,0.0000,0.0000000,0.0000000,"
      "1.0000000\nCYCLE/OFF\nEND-OF-PATH\nTOOL PATH/B,TOOL,D1\nTLDATA/DRILL,8.0000,0.0000,100.0000,118.0000,"
      "80.0000\nLOAD/TOOL,1\nSPINDL/RPM,1200,CLW\nCYCLE/DRILL,RAPTO,3.0000,FEDTO,-50.0000,MMPM,150.0000\n"
      "GOTO/50.0000,0.0000,0.0000,0.0000000,0.0000000,1.0000000\nCYCLE/OFF\nEND-OF-PATH\nTOOL "
      "PATH/C,TOOL,D2\n"
      "LOAD/TOOL,2\nSPINDL/RPM,1200,CLW\nCYCLE/DRILL,RAPTO,3.0000,FEDTO,-50.0000,MMPM,150.0000\n"
      "GOTO/150.0000,0.0000,0.0000,0.0000000,0.0000000,1.0000000\nCYCLE/OFF\nEND-OF-PATH\n";
  CHECK(errors_of(cl, "rotary-4axis", "reload") ==
        "job.cls:21:1: error: channel 1: CYCLE/DRILL: the hole goes 50 mm below its top (the GOTO point, Z "
        "0) to "
        "Z -50, but tool 2 is 20 mm long (TLDATA): its holder would drive into the part\n"
        "GOTO/150.0000,0.0000,0.0000,0.0000000,0.0000000,1.0000000\n^\n");
  // "TOOL PATH/" in a comment does not make a generic file NX: FEDTO stays a Z there.
  CHECK(errors_of(
            "PARTNO P\n$$ ops exported per TOOL PATH/ from the CAM\nTLDATA/DRILL,8,0,100,118,80\nLOADTL/1\n"
            "SPINDL/RPM,1200,CLW\nRAPID\nGOTO/10,10,20,0,0,1\nCYCLE/DRILL,FEDTO,-30,RAPTO,3,MMPM,100\n"
            "GOTO/10,10,-10\nCYCLE/OFF\nFINI\n",
            "rotary-4axis", "comment-nx") == "(posted)");
  CHECK(
      blocks("PARTNO P\n$$ ops exported per TOOL PATH/ from the CAM\nTLDATA/DRILL,8,0,100,118,80\nLOADTL/1\n"
             "SPINDL/RPM,1200,CLW\nRAPID\nGOTO/10,10,20,0,0,1\nCYCLE/DRILL,FEDTO,-30,RAPTO,3,MMPM,100\n"
             "GOTO/10,10,-10\nCYCLE/OFF\nFINI\n",
             "rotary-4axis", "comment-nx-blocks")
          .find("G98 G81 X10. Y10. Z-30. R-7. F100.") != std::string::npos);
}

TEST_CASE("to a hole from a GOTO, and a new tool's first hole, straight down from above it",
          "[post][drill]") {
  // From the rapid at Z50: across, then down to the R plane (one rapid would descend 47 mm while
  // it travelled). After a tool change the next tool's first hole is approached by the tool
  // call, never by way of the last tool's hole.
  const std::string cl =
      "PARTNO H\nTLDATA/DRILL,8,0,100,118,80\nLOADTL/3\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,50,0,0,1\n"
      "CYCLE/DRILL,FEDTO,-40.0,RAPTO,2.0,MMPM,120.0\nGOTO/80,20,-30\nCYCLE/OFF\nTLDATA/DRILL,8,0,100,118,80\n"
      "LOADTL/4\nSPINDL/RPM,500,CLW\nCYCLE/DRILL,FEDTO,-32.0,RAPTO,3.0,MMPM,100.0\nGOTO/15,20,-20\nCYCLE/"
      "OFF\n"
      "FINI\n";
  const test::posted p = test::post_in_fresh_dir(cl, load_machine("rotary-4axis"), "hole-approach");
  INFO(p.diagnostics);
  REQUIRE(p.ok);
  const std::string nc = p.files.begin()->second;
  CHECK(nc.substr(nc.find("T03 M6")) ==
        "T03 M6\nG54\nS1000 M3\nG0 A0.\nG0 X0. Y0.\nG0 G43 H3 X0. Y0. Z50. A0.\nX80. Y20.\nZ-28.\n"
        "G98 G81 X80. Y20. Z-40. R-28. F120.\nG80\nG0 Z-28.\nM5\nG91 G28 Z0.\nG90\nG49\nT04 M6\nS500 M3\n"
        "G0 A0.\nG0 X15. Y20.\nG0 G43 H4 X15. Y20. Z-17. A0.\nG98 G81 X15. Y20. Z-32. R-17. F100.\nG80\n"
        "G0 Z-17.\nM9\nM5\nG91 G28 Z0.\nG90\nG49\nM30\n%\n");
  // The tool table's length limits a hole as TLDATA's does (the shorter of the two).
  machine m = load_machine("rotary-4axis");
  m.tools.push_back({4, 0, "drill"});
  m.tools.back().length = 10;
  CHECK(test::post_in_fresh_dir(cl, m, "hole-table-reach",
                                [](const diagnostic& d) { return d.level == severity::error; })
            .diagnostics ==
        "job.cls:14:1: error: channel 1: CYCLE/DRILL: the hole goes 12 mm below its top (the GOTO "
        "point, Z -20) to Z -32, but tool 4 is 10 mm long ([[tool]] length): its holder would "
        "drive into the part\nGOTO/15,20,-20\n^\n");
  // A speed that writes S0 turns nothing.
  CHECK(errors_of("PARTNO S\nLOADTL/1\nSPINDL/RPM,0.4,CLW\nFEDRAT/MMPM,100\nGOTO/0,0,5\nGOTO/0,0,-1\nFINI\n",
                  "rotary-4axis", "s0") ==
        "job.cls:3:1: error: channel 1: SPINDL with a speed of 0.4: written S0, the spindle would not turn; "
        "give "
        "SPINDL/OFF to stop it, or a speed\nSPINDL/RPM,0.4,CLW\n^\n");
}
