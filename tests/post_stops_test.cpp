// STOP and OPSTOP in a post: the stop code, then the spindle and coolant in force again
// (M00/M01 stop them on most lathes; cycle start must not resume cutting with a still
// spindle). Public Fanuc posts do the same: after the stop they force the spindle speed
// and the coolant out again before the next move.
#include <catch2/catch.hpp>

#include <string>

#include "file_test_support.hpp"
#include "machines/machine_loader.hpp"
#include "post_test_jobs.hpp"

using namespace twinpost;

namespace {

std::string program_of(const std::string& cl, const std::string& tag) {
  const test::posted p = test::post_in_fresh_dir(cl, load_machine("fanuc-0itd-twin"), "stops-" + tag);
  if (!p.ok) return "(failed)";
  const auto program = p.files.find("STOPS_1.nc");
  return program == p.files.end() ? "(missing)" : program->second;
}

}  // namespace

TEST_CASE("STOP writes M0 and starts the spindle and coolant again", "[post][stops]") {
  CHECK(program_of(
            "PARTNO STOPS\nHEAD/1\nTURRET/1,1\nSPINDL/SMM,200,MAXRPM,3000,CLW\nCOOLNT/ON\nFEDRAT/0.2,MMPR\n"
            "RAPID\nGOTO/20,0,5\nGOTO/20,0,-10\nSTOP\nGOTO/20,0,-20\nOPSTOP\nGOTO/20,0,-25\nFINI\n",
            "css") ==
        "%\nO1000 (STOPS)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG50 S3000\nG96 S200 "
        "M3\nM8\nG0 X40. Z5.\n"
        "G1 Z-10. F0.2\nM0\nG50 S3000\nG96 S200 M3\nM8\nZ-20.\nM1\nG50 S3000\nG96 S200 M3\nM8\nZ-25.\n"
        "M100\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
}

TEST_CASE("a stop with the spindle and coolant off writes the stop alone", "[post][stops]") {
  CHECK(
      program_of("PARTNO STOPS\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,800,CLW\nSPINDL/OFF\nSTOP\nFINI\n", "off") ==
      "%\nO1000 (STOPS)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG97 S800 M3\nM5\nM0\nM100\nM9\n"
      "G28 U0.\nG28 W0.\nM30\n%\n");
}

TEST_CASE("a feed move after the channel's own SPINDL/OFF is an error at the move", "[post][stops]") {
  // A turning tool fed into a part that does not turn; a rapid is still allowed, and a new
  // speed lifts the stop.
  for (const char* name : {"fanuc-0itd-twin", "integrex-i200st"}) {
    INFO(name);
    const test::posted p = test::post_in_fresh_dir(
        "PARTNO STOPS\nHEAD/1\nTLDATA/TURN\nTURRET/1,1\nSPINDL/RPM,800,CLW\nFEDRAT/150,MMPM\nRAPID\n"
        "GOTO/20,0,5\nSPINDL/OFF\nRAPID\nGOTO/20,0,2\nGOTO/20,0,-10\nSPINDL/RPM,800,CLW\nGOTO/"
        "20,0,-12\nFINI\n",
        load_machine(name), std::string("spindle-off-") + name,
        [](const diagnostic& d) { return d.level == severity::error; });
    CHECK_FALSE(p.ok);
    CHECK(
        p.diagnostics ==
        "job.cls:12:1: error: channel 1: feed move with the main spindle stopped by SPINDL/OFF: give SPINDL "
        "with a speed before cutting (the tool would be driven into a part that does not turn)\n"
        "GOTO/20,0,-10\n^\n");
  }
}
