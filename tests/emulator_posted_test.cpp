// The control emulator catches each writer fix of issue 37 when it is undone: a program that
// twinpost posted is edited back to what the writer used to write, and the checker's reading
// (check_nc_resources, as `twinpost check` and post's self-check run it) names the hazard.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "analysis/shared_resources.hpp"
#include "check/sync_report.hpp"
#include "file_test_support.hpp"
#include "machines/machine_loader.hpp"
#include "post_test_jobs.hpp"

using namespace twinpost;

namespace {

std::string sample_job(const std::string& name) {
  return test::read_file(std::string(TWINPOST_SOURCE_DIR) + "/samples/" + name + "/job.cls");
}

// One edit of a posted program: its first `from` after `after` replaced by `to`.
struct edit {
  std::string after, from, to;
};

// The posted program `file` of `job` on `machine`, with `edits` made in order, checked as
// `twinpost check` would.
std::string edited_check(const std::string& job, const std::string& machine_name, const std::string& file,
                         const std::vector<edit>& edits) {
  const machine m = load_machine(machine_name);
  const test::posted p = test::post_in_fresh_dir(job, m, "emulator-" + machine_name);
  REQUIRE(p.ok);
  std::vector<nc_source> files;
  for (const auto& [name, text] : p.files) {
    std::string t = text;
    if (name == file)
      for (const edit& e : edits) {
        const std::size_t at = t.find(e.from, t.find(e.after));
        REQUIRE(at != std::string::npos);
        t.replace(at, e.from.size(), e.to);
      }
    files.push_back({name, t});
  }
  return format_sync_text(check_nc_resources(files, m));
}

std::string edited_check(const std::string& job, const std::string& machine_name, const std::string& file,
                         const std::string& after, const std::string& from, const std::string& to) {
  return edited_check(job, machine_name, file, {{after, from, to}});
}

}  // namespace

TEST_CASE("emulator: the posted programs check sound, and undoing a fix is named", "[analysis][emulator]") {
  // Item 8: the mill's G54 after the first tool call, dropped.
  CHECK(edited_check(sample_job("four-axis-wrap"), "rotary-4axis", "FOUR_AXIS_WRAP.nc", "T02 M6", "G54\n",
                     "") ==
        "FOUR_AXIS_WRAP.nc:16:4: error: channel 1: a feed move with no work offset in force: the program "
        "would cut in whatever offset the last program left; set one (G54-G59, G54.1 P..) before the first "
        "cut\nG1 Z30. F800.\n   ^\n"
        "check: 1 channel, 0 waits paired, 1 error\n");
  // Item 1: the B index after the second tool call on the Integrex, dropped.
  CHECK(
      edited_check(sample_job("drill-tap"), "integrex-i200st", "DRILL-TAP.EIA", "T03 M6",
                   "M108\nG0 G53 B0.\nM107\n", "") ==
      "DRILL-TAP.EIA:70:1: warning: channel 1: M8 turns the coolant on before the B head is indexed for the "
      "tool called at line 67: it sprays while the head turns; index it (G0 G53 B..) first\nM8\n^\n"
      "DRILL-TAP.EIA:74:11: error: channel 1: a feed move with the B head not indexed since the tool call at "
      "line 67: the tool changer may leave it anywhere; index it (G0 G53 B..) before the cut\n"
      "G98 G84.2 X0. Y0. Z-18. R5. F1.5\n          ^\n"
      "check: 2 channels, 2 waits paired, 1 error, 1 warning\n");
  // Item 10: the coolant turned on before the index again.
  CHECK(
      edited_check(sample_job("drill-tap"), "integrex-i200st", "DRILL-TAP.EIA", "T03 M6",
                   "M108\nG0 G53 B0.\nM107\nM8\n", "M8\nM108\nG0 G53 B0.\nM107\n") ==
      "DRILL-TAP.EIA:70:1: warning: channel 1: M8 turns the coolant on before the B head is indexed for the "
      "tool called at line 67: it sprays while the head turns; index it (G0 G53 B..) first\nM8\n^\n"
      "check: 2 channels, 2 waits paired, 0 errors, 1 warning\n");
  // Item 2: the pick-off's release opening the main chuck on the bar again.
  CHECK(edited_check(sample_job("pick-off"), "integrex-i200st", "PICK-OFF.EIA", "M952", "G0 G53 W0.\n",
                     "M206\nG0 G53 W0.\n") ==
        "PICK-OFF.EIA:62:1: error: channel 1: M206 opens the main spindle's chuck after the part-off at line "
        "56: "
        "it holds the bar, which would be released; after a part-off the sub spindle takes the part away and "
        "the bar stays clamped ([transfer] release_after_cutoff)\nM206\n^\n"
        "check: 2 channels, 12 waits paired, 1 error\n");
  // Item 5: a tool counter in the transfer's approach position.
  CHECK(
      edited_check(sample_job("pick-off"), "fanuc-0itd-twin", "PICK-OFF_1.nc", "T0303", "M8\n",
                   "M8\n#501=#501+1\n") ==
      "PICK-OFF_1.nc:39:1: error: channel 1: #501 is written here, but machine 'fanuc-0itd-twin' reserves it "
      "(read by transfer.grip): the setup owns its value; write a variable the machine file does not name\n"
      "#501=#501+1\n^\n"
      "check: 2 channels, 12 waits paired, 1 error\n");
  // Item 9: the sub's stop at the pick-off's tool change put back, the main cut next at G95.
  CHECK(edited_check(sample_job("pick-off"), "integrex-i200st", "PICK-OFF.EIA", "(", "T03 M6\n",
                     "M205\nT03 M6\n") ==
        "PICK-OFF.EIA:57:1: error: channel 1 cuts with feed per revolution (G95) on the main spindle, but "
        "channel 1 stops it at PICK-OFF.EIA:48 (M205) and no start is known to come after that\n"
        "G1 X-1. F0.05\n^\ncheck: 2 channels, 12 waits paired, 1 error\n");
  // The transfer's chucks: the sub's close before the main opens, dropped (the part let go with
  // the sub's chuck still open); the main's stop and the synchronisation before it opens, dropped.
  const std::string transfer = sample_job("transfer-to-sub");
  CHECK(edited_check(transfer, "fanuc-0itd-twin", "TRANSFER-TO-SUB_1.nc", "M213", "M168\n", "") ==
        "TRANSFER-TO-SUB_1.nc:51:1: error: channel 1: M69 opens the main spindle's chuck in the transfer "
        "while the sub spindle's is open (M169 at line 41): the part would be held by neither; close it "
        "first (M168)\n"
        "M69\n^\ncheck: 2 channels, 10 waits paired, 1 error\n");
  CHECK(edited_check(transfer, "fanuc-0itd-twin", "TRANSFER-TO-SUB_1.nc",
                     {{"X80. Z50.", "M5\n", ""}, {"M169", "M213\n", ""}}) ==
        "TRANSFER-TO-SUB_1.nc:50:1: error: channel 1: M69 opens the main spindle's chuck while the spindle "
        "turns (started at line 9) and the spindles are not synchronised: stop it first, or open it under "
        "M213\n"
        "M69\n^\ncheck: 2 channels, 10 waits paired, 1 error\n");
  // A spindle started with its chuck open: the main's chuck released before the drill's start.
  CHECK(edited_check(transfer, "fanuc-0itd-twin", "TRANSFER-TO-SUB_1.nc", "T0202", "G97 S1100 M3\n",
                     "M5\nM69\nG97 S1100 M3\n") ==
        "TRANSFER-TO-SUB_1.nc:30:5: error: channel 1: the main spindle is started with its chuck open (M69 "
        "at line 29): close the chuck first (M68)\n"
        "G97 S1100 M3\n    ^\ncheck: 2 channels, 10 waits paired, 1 error\n");
  // Item 7: the home between G69 and the heads turning back, dropped. A tilted cut on the
  // head/head mill whose retract (the tip at z 15, where the cut started) is low for the
  // swing: the heads unwind there, and the tip (the gauge point here: the machine file gives
  // no tool length) drops 300 (1 - cos 20°) = 18.1 mm into the work.
  const std::string unwind =
      "PARTNO UNWIND\nUNITS/MM\nTLDATA/MILL,10,0,100,0,0\nLOADTL/1\nSPINDL/RPM,6000,CLW\nFEDRAT/MMPM,800\n"
      "RAPID\nGOTO/0,0,60,0,0,1\nRAPID\nGOTO/-20,0,15,0.3420201,0,0.9396926\n"
      "GOTO/-20,0,-5,0.3420201,0,0.9396926\nGOTO/20,0,-5,0.3420201,0,0.9396926\nRAPID\n"
      "GOTO/20,0,15,0.3420201,0,0.9396926\nRAPID\nGOTO/20,0,15,0,0,1\nGOTO/20,0,-2,0,0,1\nRAPID\n"
      "GOTO/20,0,60,0,0,1\nEND\n";
  CHECK(
      edited_check(unwind, "head-head-5axis", "UNWIND.nc", "G69", "G69\nG91 G28 Z0.\nG90\nG49\n", "G69\n") ==
      "UNWIND.nc:25:4: error: channel 1: the rapid turns the rotary axes (B 20 to 0) with tool-tip control "
      "off and the tool not at home: the tip swings down to z -3.092 (the part frame, mm; the gauge point's: "
      "the tool's length is not known, and every tool up to 300 mm long swings below too), 18.092 mm below "
      "where the linear words, or both its ends, put it, and below z 5.000, the highest "
      "the program has fed a tool from or to: "
      "the work reaches that high; retract Z to its reference point (G91 G28 Z0.) before the rotary axes "
      "turn\nG0 A0. B0.\n   ^\n"
      "check: 1 channel, 0 waits paired, 1 error\n");
}
