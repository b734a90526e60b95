// 3+2 work in tilted working planes (G68.2) on the table/table trunnion: arcs in the plane's
// G17/G18/G19, drilling cycles along its Z, cutter compensation in it, and the rules at a
// plane's change (docs/machines.md, "Tilted working plane").
#include <catch2/catch.hpp>
#include <string>

#include "machines/machine_loader.hpp"
#include "post_test_jobs.hpp"

using namespace twinpost;

namespace {

// The tool along +X: the plane G68.2 I90 J90 K-90 has X = -Z, Y = Y, Z = X of the part.
const std::string side_face_start =
    "MULTAX/ON\nLOADTL/1\nSPINDL/RPM,6000,CLW\nFEDRAT/MMPM,500\nRAPID\nGOTO/40,0,-10,1,0,0\n";
const std::string program_start =
    "G21\nG90 G94 G17 G40 G49 G80\nG91 G28 Z0.\nG90\nT01 M6\nG54\nS6000 M3\n"
    "G68.2 X0. Y0. Z0. I90. J90. K-90.\nG53.1\nG0 X10. Y0.\nG43 H1 X10. Y0. Z40.\n";

}  // namespace

TEST_CASE("tilted plane: an arc about an axis across the tool is written in the plane's G18",
          "[post][multiaxis][plane]") {
  const machine m = load_machine("trunnion-5axis");
  // About the part's +Y (the plane's Y), counter-clockwise: G18 G3, the centre as I K in the plane.
  const test::posted p = test::post_in_fresh_dir("PARTNO G18\n" + side_face_start +
                                                     "GOTO/20,0,-10,1,0,0\nGOTO/20,0,-20,1,0,0\n"
                                                     "CIRCLE/10,0,-20,0,1,0,10\nGOTO/0,0,-20,1,0,0\n"
                                                     "RAPID\nGOTO/40,0,-20,1,0,0\nFINI\n",
                                                 m, "plane-g18");
  REQUIRE(p.ok);
  CHECK(p.files.at("G18.nc") == "%\nO5002 (G18)\n" + program_start +
                                    "G1 Z20. F500.\nX20.\nG18 G3 X20. Z0. I0. K-10.\nG0 Z40.\nG69\nM9\nM5\n"
                                    "G91 G28 Z0.\nG90\nG49\nM30\n%\n");
}

TEST_CASE("tilted plane: a hole along the plane's Z is drilled in its frame, from the depth",
          "[post][multiaxis][plane]") {
  const machine m = load_machine("trunnion-5axis");
  // The trunnion drills in moves ([cycles] drill = "expanded"): to the clearance, feed to the
  // depth, back out, all along the plane's Z.
  const test::posted p = test::post_in_fresh_dir(
      "PARTNO DEPTH\n" + side_face_start +
          "CYCLE/DRILL,DEPTH,10,MMPM,200,CLEAR,3\nGOTO/20,0,-10,1,0,0\nCYCLE/OFF\nFINI\n",
      m, "plane-depth");
  REQUIRE(p.ok);
  CHECK(p.files.at("DEPTH.nc") ==
        "%\nO5002 (DEPTH)\n" + program_start +
            "Z23.\nG1 Z10. F200.\nG0 Z23.\nG69\nM9\nM5\nG91 G28 Z0.\nG90\nG49\nM30\n%\n");
  // An absolute FEDTO is a Z of the part frame: no depth along the tilted tool.
  const test::posted abs = test::post_in_fresh_dir(
      "PARTNO FEDTO\n" + side_face_start +
          "CYCLE/DRILL,FEDTO,10,MMPM,200,CLEAR,3\nGOTO/20,0,-10,1,0,0\nCYCLE/OFF\nFINI\n",
      m, "plane-fedto");
  CHECK_FALSE(abs.ok);
  CHECK(abs.diagnostics ==
        "job.cls:9:1: error: channel 1: CYCLE/DRILL in a tilted working plane (G68.2) with an absolute "
        "FEDTO: a "
        "Z of the part frame is no depth along the tilted tool; give the depth "
        "(DEPTH)\nGOTO/20,0,-10,1,0,0\n^\n");
}

TEST_CASE("tilted plane: cutter compensation in the plane, G40 before G69, and none across a change",
          "[post][multiaxis][plane]") {
  const machine m = load_machine("trunnion-5axis");
  const std::string cut = "GOTO/20,0,-10,1,0,0\nCUTCOM/LEFT\nGOTO/20,10,-10,1,0,0\nGOTO/20,10,-20,1,0,0\n";
  // G41 in the plane's G17; the CL's CUTCOM/OFF before the RAPID that leaves the plane goes
  // out on its own, before G69; the tables turn back at the tool-change height, and G43.4
  // comes on again with the next point.
  const test::posted p = test::post_in_fresh_dir(
      "PARTNO COMP\n" + side_face_start + cut + "CUTCOM/OFF\nRAPID\nGOTO/0,0,60,0,0,1\nFINI\n", m,
      "plane-comp");
  REQUIRE(p.ok);
  CHECK(p.files.at("COMP.nc") == "%\nO5002 (COMP)\n" + program_start +
                                     "G1 Z20. F500.\nG41 D1 Y10.\nX20.\nG40\nG69\nG91 G28 Z0.\nG90\nG49\n"
                                     "G0 A0. C90.\nG0 X0. Y0.\nG0 G43.4 H1 X0. Y0. Z60. A0. C90.\nM9\nM5\n"
                                     "G91 G28 Z0.\nG90\nG49\nM30\n%\n");
  // Compensation still on where the tool axis turns: G68.2 and G69 need G40 in force.
  const test::posted on = test::post_in_fresh_dir(
      "PARTNO COMP\n" + side_face_start + cut + "RAPID\nGOTO/0,-40,-20,0,-1,0\nFINI\n", m, "plane-comp-on");
  CHECK_FALSE(on.ok);
  CHECK(on.diagnostics ==
        "job.cls:13:1: error: channel 1: the tool axis turns with cutter compensation on: the tilted working "
        "plane (G68.2) is set and cancelled with G40 in force; give CUTCOM/OFF and a move before the RAPID\n"
        "GOTO/0,-40,-20,0,-1,0\n^\n");
}

TEST_CASE("tilted plane: an arc whose written centre misses the CL's is refused",
          "[post][multiaxis][plane]") {
  // Every point lies on the 0.001 mm grid of the words, the centre 0.0004 mm off it (J0.0004
  // in the plane, written J0.): with a tolerance of 0.0001 mm only the centre fails.
  machine m = load_machine("trunnion-5axis");
  m.kinematics[0].tolerance = 1e-4;
  const test::posted p = test::post_in_fresh_dir("PARTNO ARC\n" + side_face_start +
                                                     "GOTO/20,0,-10,1,0,0\nCIRCLE/20,0.0004,-20,1,0,0,10\n"
                                                     "GOTO/20,0,-30,1,0,0\nFINI\n",
                                                 m, "plane-arc-centre");
  CHECK_FALSE(p.ok);
  CHECK(p.diagnostics ==
        "job.cls:10:1: error: channel 1: the written arc fails the tilted plane's rotation: end 0 mm and "
        "centre "
        "0.0004 mm from the CL's (tolerance 0.0001 mm)\nGOTO/20,0,-30,1,0,0\n^\n");
}

TEST_CASE("tilted plane: only a cut that keeps its axis opens a plane", "[post][multiaxis][plane]") {
  const machine m = load_machine("trunnion-5axis");
  auto planes = [](const std::string& nc) {
    int n = 0;
    for (std::size_t at = 0; (at = nc.find("G68.2", at)) != std::string::npos; ++at) ++n;
    return n;
  };
  // A rapid under one tilted axis and then a rapid under another: positioning, no plane for
  // the first; the cut under the second keeps its axis: one plane.
  const test::posted p = test::post_in_fresh_dir(
      "PARTNO POS\nMULTAX/ON\nLOADTL/1\nSPINDL/RPM,6000,CLW\nFEDRAT/MMPM,500\nRAPID\n"
      "GOTO/0,0,25,0.4881149,-0.3206994,0.8117239\nRAPID\nGOTO/0,1,25,0.2588190,0,0.9659258\n"
      "GOTO/0,1,5,0.2588190,0,0.9659258\nGOTO/10,1,5\nRAPID\nGOTO/0,0,60,0,0,1\nFINI\n",
      m, "plane-positioning");
  INFO(p.diagnostics);
  REQUIRE(p.ok);
  CHECK(planes(p.files.at("POS.nc")) == 1);
  CHECK(p.files.at("POS.nc").find("G68.2 X0. Y0. Z0. I90. J15. K-90.") != std::string::npos);
  // The same with the cut turning the tool: simultaneous work under G43.4, no plane.
  const test::posted s = test::post_in_fresh_dir(
      "PARTNO SIM\nMULTAX/ON\nLOADTL/1\nSPINDL/RPM,6000,CLW\nFEDRAT/MMPM,500\nRAPID\n"
      "GOTO/0,1,25,0.2588190,0,0.9659258\nGOTO/0,1,5,0.2588190,0,0.9659258\n"
      "GOTO/10,1,5,0.3420201,0,0.9396926\nRAPID\nGOTO/0,0,60,0,0,1\nFINI\n",
      m, "plane-simultaneous");
  INFO(s.diagnostics);
  REQUIRE(s.ok);
  CHECK(planes(s.files.at("SIM.nc")) == 0);
  CHECK(s.files.at("SIM.nc").find("G43.4 H1") != std::string::npos);
}
