// Drilling cycles in a post: what the writer carries out, and every other cycle or cycle
// word stopped at its record (nothing silent: a bore posted as a drill marks the bore).
// Each cycle form on each built-in: post_drill_test.cpp.
#include <catch2/catch.hpp>

#include <string>

#include "file_test_support.hpp"
#include "machines/machine_loader.hpp"
#include "post_test_jobs.hpp"
#include "support/diagnostics.hpp"

using namespace twinpost;

namespace {

const std::string head = "PARTNO CYC\nUNITS/MM\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nFEDRAT/0.2,MMPR\n";

// The errors of posting `body` (after `head`) on the Fanuc 2-path lathe, the job's path
// written "job.cls"; "(posted)" when the post succeeds.
std::string errors_of(const std::string& body, const std::string& tag) {
  const test::posted p =
      test::post_in_fresh_dir(head + body, load_machine("fanuc-0itd-twin"), "cycles-" + tag,
                              [](const diagnostic& d) { return d.level == severity::error; });
  return p.ok ? "(posted)" : p.diagnostics;
}

}  // namespace

TEST_CASE("a drilling cycle the writer carries out is posted", "[post][cycles]") {
  CHECK(errors_of("CYCLE/DEEP,FEDTO,-25.0,STEP,8.0,RAPTO,2.0,MMPR,0.12\nGOTO/0,0,0\nCYCLE/OFF\nFINI\n",
                  "deep") == "(posted)");
  CHECK(errors_of("CYCLE/DRILL,DEPTH,10,CLEAR,2,MMPR,0.1\nGOTO/0,0,0\nCYCLE/OFF\nFINI\n", "drill") ==
        "(posted)");
}

TEST_CASE("bore and ream cycles, and drill words on a thread, stop the post at the CYCLE record",
          "[post][cycles]") {
  // A tap is posted (post_drill_test.cpp); a bore fed and rapided like a drill marks the bore.
  CHECK(errors_of("CYCLE/BORE,FEDTO,-12,RAPTO,3,MMPR,0.1\nGOTO/0,0,0\nCYCLE/OFF\nFINI\n", "bore") ==
        "job.cls:6:1: error: channel 1: CYCLE/BORE is not supported by the post: only DRILL, DEEP, DEEP2 and "
        "TAP are written; a boring or reaming cycle cannot be (THREAD and GROOVE go by [cycles])\n"
        "CYCLE/BORE,FEDTO,-12,RAPTO,3,MMPR,0.1\n^\n");
  // A thread is posted by [cycles] (post_thread_test.cpp); a drill's words on it are refused.
  CHECK(errors_of("CYCLE/THREAD,FEDTO,-12,RAPTO,3,MMPR,1.5\nGOTO/0,0,0\nCYCLE/OFF\nFINI\n", "thread") ==
        "job.cls:6:1: error: channel 1: CYCLE/THREAD: FEDTO is not carried out by the post (it knows LEAD "
        "or PITCH, STARTS, DEPTH, FIRST or PASSES, MINCUT, FINISH, SPRING, ANGLE, TAPER and CHAMFR)\n"
        "CYCLE/THREAD,FEDTO,-12,RAPTO,3,MMPR,1.5\n^\n");
}

TEST_CASE("a cycle word the writer would drop stops the post", "[post][cycles]") {
  // A retract plane outside SolidWorks, pecks on a cycle written without them, a positional value.
  CHECK(errors_of("CYCLE/DRILL,FEDTO,-10,RAPTO,3,RTRCTO,25,MMPR,0.1\nGOTO/0,0,0\nFINI\n", "rtrcto") ==
        "job.cls:6:1: error: channel 1: CYCLE/DRILL: RTRCTO is not carried out by the post (it knows FEDTO, "
        "DEPTH, RAPTO, CLEAR, STEP and the feed; the meaning of this word is known only in the SolidWorks "
        "and NX dialects)\n"
        "CYCLE/DRILL,FEDTO,-10,RAPTO,3,RTRCTO,25,MMPR,0.1\n^\n");
  CHECK(errors_of("CYCLE/DRILL,FEDTO,-10,STEP,2,RAPTO,3,MMPR,0.1\nGOTO/0,0,0\nFINI\n", "step")
            .starts_with("job.cls:6:1: error: channel 1: CYCLE/DRILL: STEP is not carried out by the post"));
  CHECK(errors_of("CYCLE/DRILL,3.0,5.0\nGOTO/0,0,0\nFINI\n", "positional")
            .starts_with(
                "job.cls:6:1: error: channel 1: CYCLE/DRILL: the values 3, 5 stand by position, whose "
                "meaning the CAM's post table sets (CATIA's PP table) and no public definition fixes"));
}

TEST_CASE("a drill bottom behind the clearance plane is an error, not a move away from the part",
          "[post][cycles]") {
  // SolidWorks CAM writes FEDTO as a depth below the hole's top: read as a Z it lies above.
  CHECK(
      errors_of("CYCLE/DRILL,FEDTO,7.85788,MMPM,326.77,RAPTO,3.\nGOTO/0,0,0\nCYCLE/OFF\nFINI\n", "upward") ==
      "job.cls:7:1: error: channel 1: CYCLE/DRILL: the bottom Z 7.85788 is not beyond the clearance plane Z "
      "3 in "
      "the drilling direction: the tool would feed away from the part (is FEDTO a depth in this CL?)\n"
      "GOTO/0,0,0\n^\n");
}

TEST_CASE("a drilling cycle with a radial tool axis stops the post", "[post][cycles]") {
  // Cross drilling with a live tool: fed along Z it would go through the side of the part.
  CHECK(
      errors_of("CYCLE/DRILL,FEDTO,10,RAPTO,3,MMPR,0.1\nGOTO/25,0,-20,1,0,0\nCYCLE/OFF\nFINI\n", "radial") ==
      "job.cls:7:1: error: channel 1: CYCLE/DRILL with the tool axis (1, 0, 0): only drilling along Z is "
      "written; "
      "cross and tilted drilling is not supported yet\n"
      "GOTO/25,0,-20,1,0,0\n^\n");
}

TEST_CASE("a peck count past any real hole stops the post instead of writing moves without end",
          "[post][cycles]") {
  CHECK(
      errors_of("CYCLE/DEEP,FEDTO,-1e300,STEP,1,RAPTO,2,MMPR,0.1\nGOTO/0,0,0\nCYCLE/OFF\nFINI\n", "pecks") ==
      "job.cls:7:1: error: channel 1: CYCLE/DEEP: a depth of 1e+300 in pecks of 1 makes more than 10000 "
      "pecks\n"
      "GOTO/0,0,0\n^\n");
}

TEST_CASE("an arc in G18 leaves the mill's G17 in force again before a cycle and after a tool call",
          "[post][cycles]") {
  // Review 45: after a CIRCLE about Y (G18) the next hole's G81 and the next tool's G43 ran in
  // G18: a Fanuc with FXY = 1 drills along Y, length offset type B applies H along Y.
  const std::string arc =
      "LOADTL/1\nSPINDL/RPM,3000,CLW\nFEDRAT/MMPM,400\nRAPID\nGOTO/0,0,50,0,0,1\n"
      "GOTO/0,0,0\nCIRCLE/10,0,0,0,1,0,10\nGOTO/10,0,-10\nGOTO/20,0,-10\nRAPID\nGOTO/20,0,10\n";
  const std::string hole = "CYCLE/DRILL,DEPTH,5,CLEAR,2,MMPM,100\nGOTO/20,10,0\nCYCLE/OFF\n";
  const machine m = load_machine("rotary-4axis");
  // The same tool drills next: G17 before the cycle.
  const test::posted same =
      test::post_in_fresh_dir("PARTNO SAME\n" + arc + hole + "FINI\n", m, "cy-planes-1");
  INFO(same.diagnostics);
  REQUIRE(same.ok);
  CHECK(same.files.at("SAME.nc").find("G1 Z0. F400.\nG18 G3 X10. Z-10. I10. K0.\nG1 X20.\nG0 Z10.\n"
                                      "Y10.\nZ2.\nG17\nG98 G81 X20. Y10. Z-5. R2. F100.\n") !=
        std::string::npos);
  // The next tool: G17 after its call, before its G43; its own arc about Y names G18 again.
  const test::posted next =
      test::post_in_fresh_dir("PARTNO NEXT\n" + arc + "LOADTL/2\nSPINDL/RPM,3000,CLW\n" + hole +
                                  "RAPID\nGOTO/0,0,50\nCIRCLE/10,0,50,0,1,0,10\nGOTO/20,0,50\nFINI\n",
                              m, "cy-planes-2");
  INFO(next.diagnostics);
  REQUIRE(next.ok);
  const std::string& nc = next.files.at("NEXT.nc");
  CHECK(nc.find("T02 M6\nG17\nS3000 M3\n") != std::string::npos);
  CHECK(nc.find("G18 G3 X20. Z50.") != std::string::npos);
}

TEST_CASE("a feed that is 0 or below or written F0 is refused at its record", "[post][cycles]") {
  // Attack 45: G81 ... F0. and F-100. were written; FEDRAT/MMPM,0.04 became F0.
  const auto diags = [](const std::string& body, const std::string& tag) {
    return test::post_in_fresh_dir(
               "PARTNO F\nLOADTL/1\nSPINDL/RPM,3000,CLW\nRAPID\nGOTO/0,0,50,0,0,1\n" + body + "FINI\n",
               load_machine("rotary-4axis"), "cy-feed-" + tag)
        .diagnostics;
  };
  CHECK(diags("CYCLE/DRILL,DEPTH,5,CLEAR,2,MMPM,-100\nGOTO/20,10,0\nCYCLE/OFF\n", "neg") ==
        "job.cls:7:1: error: channel 1: CYCLE: a feed of -100 is no feed (above 0)\nGOTO/20,10,0\n^\n");
  CHECK(diags("CYCLE/DRILL,DEPTH,5,CLEAR,2\nGOTO/20,10,0\nCYCLE/OFF\n", "none") ==
        "job.cls:7:1: error: channel 1: a drilling cycle with no feed rate in force (the CYCLE's MMPM/MMPR "
        "or a "
        "FEDRAT)\nGOTO/20,10,0\n^\n");
  CHECK(diags("FEDRAT/MMPM,0.04\nGOTO/0,0,-5\n", "tiny") ==
        "job.cls:6:1: error: channel 1: FEDRAT: a feed of 0.04 is written F0 (F keeps 1 decimal): no control "
        "moves at it\nFEDRAT/MMPM,0.04\n^\njob.cls:7:1: error: channel 1: feed move with no feed rate "
        "(FEDRAT) in "
        "force\nGOTO/0,0,-5\n^\n");
}

TEST_CASE("a clearance plane below the hole's top is refused", "[post][cycles]") {
  // Attack 45: NX's RAPTO,-50 put R 50 mm inside the part and rapided to it.
  const test::posted p = test::post_in_fresh_dir(
      "PARTNO R\nLOADTL/1\nSPINDL/RPM,3000,CLW\nRAPID\nGOTO/0,0,50,0,0,1\nCYCLE/DRILL,DEPTH,5,CLEAR,-2,MMPM,"
      "100\nGOTO/20,10,0\nCYCLE/OFF\nFINI\n",
      load_machine("rotary-4axis"), "cy-rapto");
  CHECK(p.diagnostics ==
        "job.cls:7:1: error: channel 1: CYCLE/DRILL: CLEAR -2 puts the clearance plane 2 mm below the hole's "
        "top: the tool would rapid into the part\nGOTO/20,10,0\n^\n");
}

TEST_CASE("a tap lead past any tap's, or faster than the machine feeds, is refused", "[post][cycles]") {
  // Attack 45: PITCH,500 at 500 rpm wrote G84 ... F500. (250 m/min).
  const auto diags = [](const std::string& cycle, machine m, const std::string& tag) {
    return test::post_in_fresh_dir("PARTNO T\nLOADTL/1\nSPINDL/RPM,500,CLW\nRAPID\nGOTO/0,0,50,0,0,1\n" +
                                       cycle + "\nGOTO/20,10,0\nCYCLE/OFF\nFINI\n",
                                   m, "cy-tap-" + tag)
        .diagnostics;
  };
  machine m = load_machine("rotary-4axis");
  CHECK(
      diags("CYCLE/TAP,DEPTH,10,CLEAR,2,PITCH,500", m, "lead") ==
      "job.cls:7:1: error: channel 1: CYCLE/TAP: a lead of 500 mm is no tap's (ISO 261's coarsest pitch is 6 "
      "mm)\nGOTO/20,10,0\n^\n");
  m.limits.max_feed = 1000;
  CHECK(diags("CYCLE/TAP,DEPTH,10,CLEAR,2,PITCH,2.5", m, "feed") ==
        "job.cls:7:1: error: channel 1: CYCLE/TAP: a lead of 2.5 mm at 500 rpm feeds 1250 mm/min, over the "
        "machine's 1000 mm/min (limits.max_feed)\nGOTO/20,10,0\n^\n");
}

TEST_CASE("cutter compensation after an arc about Y starts in the mill's G17", "[post][cycles]") {
  // Verify 46: G41 D1 after a G18 arc compensated in the ZX plane.
  const test::posted p = test::post_in_fresh_dir(
      "PARTNO COMP\nLOADTL/1\nSPINDL/RPM,3000,CLW\nFEDRAT/MMPM,400\nRAPID\nGOTO/0,0,50,0,0,1\nGOTO/0,0,0\n"
      "CIRCLE/10,0,0,0,1,0,10\nGOTO/10,0,-10\nCUTCOM/LEFT,1\nGOTO/20,0,-10\nFINI\n",
      load_machine("rotary-4axis"), "cy-comp-plane");
  INFO(p.diagnostics);
  REQUIRE(p.ok);
  CHECK(p.files.at("COMP.nc").find("G18 G3 X10. Z-10. I10. K0.\nG17\nG41 D1 G1 X20.\n") != std::string::npos);
}
