// Shared resources (analysis/shared_resources.hpp): which spindles a channel may command,
// spindle commands of channels that may run at the same time, feeds per revolution on a spindle
// not known to turn; the machine-file keys; the post's balance cut and its self-check.
// Messages are asserted to the letter.
#include <catch2/catch.hpp>

#include <fmt/format.h>
#include <string>

#include "analysis/shared_resources.hpp"
#include "check/sync_report.hpp"
#include "machine_test_support.hpp"
#include "machines/machine_loader.hpp"
#include "post_test_jobs.hpp"
#include "support/errors.hpp"

using namespace twinpost;

namespace {

std::string check(const machine& m, const std::vector<nc_source>& files) {
  return format_sync_text(check_nc_resources(files, m));
}

const std::string fanuc_head = "%\nO1000\nG0 G18 G21 G40 G54 G80 G99\n";

}  // namespace

TEST_CASE("shared spindles: the machines say who may command what, and what is shared", "[analysis]") {
  const machine integrex = load_machine("integrex-i200st");
  // main, sub shared by both heads; the milling spindle is each head's own (per_channel).
  CHECK(integrex.shared_spindle(0));
  CHECK(integrex.shared_spindle(1));
  CHECK_FALSE(integrex.shared_spindle(2));
  CHECK(integrex.may_command(2, 2));
  const machine fanuc3 = load_machine("fanuc-31i-3path");
  CHECK(fanuc3.shared_spindle(0));
  CHECK(fanuc3.shared_spindle(1));
  CHECK_FALSE(fanuc3.shared_spindle(2));
  // Without channel.spindles: its own spindles and every one that is no channel's live spindle.
  machine m = fanuc3;
  for (channel_def& c : m.channels) c.spindles.clear();
  CHECK(m.may_command(1, 0));
  CHECK(m.may_command(1, 1));
  CHECK_FALSE(m.may_command(1, 2));
  CHECK(m.may_command(3, 2));
}

TEST_CASE("shared spindles: two paths set the main spindle differently between the same waits",
          "[analysis]") {
  const machine m = load_machine("fanuc-0itd-twin");
  const std::string a = fanuc_head + "T0101\nM100\nG50 S3000\nG96 S200 M3\nG1 X58. Z2. F0.25\nM101\nM30\n%\n";
  const std::string b = fanuc_head + "T0505\nM100\nG97 S1200 M3\nG1 Z-30. F0.08\nM101\nM30\n%\n";
  CHECK(check(m, {{"A_1.nc", a}, {"A_2.nc", b}}) ==
        "A_2.nc:6:1: error: channel 2 sets the shared main spindle to G97 S1200 M3 while channel 1 may set "
        "it to "
        "G96 S200 M3 at the same time (A_1.nc:7): different speed mode (CSS and rpm); no wait orders the two "
        "blocks\n"
        "G97 S1200 M3\n^\n"
        "A_1.nc:7:1: note: channel 1 sets the main spindle to G96 S200 M3 here\nG96 S200 M3\n^\n"
        "check: 2 channels, 4 waits paired, 1 error\n");
  // The same speed twice is no conflict; a different direction is.
  const std::string same = fanuc_head + "T0505\nM100\nG96 S200 M3\nG1 Z-30. F0.08\nM101\nM30\n%\n";
  CHECK(check(m, {{"A_1.nc", a}, {"A_2.nc", same}}) == "check: 2 channels, 4 waits paired, 0 errors\n");
  const std::string reverse = fanuc_head + "T0505\nM100\nM4\nM101\nM30\n%\n";
  CHECK(check(m, {{"A_1.nc", a}, {"A_2.nc", reverse}}) ==
        "A_2.nc:6:1: error: channel 2 sets the shared main spindle to M4 while channel 1 may set it to G96 "
        "S200 "
        "M3 at the same time (A_1.nc:7): different direction; no wait orders the two blocks\n"
        "M4\n^\n"
        "A_1.nc:7:1: note: channel 1 sets the main spindle to G96 S200 M3 here\nG96 S200 M3\n^\n"
        "check: 2 channels, 4 waits paired, 1 error\n");
  // A wait between the two orders them: path 2 changes the speed after path 1's cut.
  const std::string later = fanuc_head + "T0505\nM100\nM101\nG97 S1200 M3\nG1 Z-30. F0.08\nM30\n%\n";
  CHECK(check(m, {{"A_1.nc", a}, {"A_2.nc", later}}) == "check: 2 channels, 4 waits paired, 0 errors\n");
}

TEST_CASE("shared spindles: a chain of waits through a third path orders two blocks", "[analysis]") {
  const machine m = load_machine("fanuc-31i-3path");
  // Path 1 meets path 3, path 3 then meets path 2: path 1's S1000 is before path 2's S1500,
  // but path 1's S1800 (after its wait) may run with path 2's S1500. Each path's M33 drives
  // its own turret's tools (per_channel): different speeds there are no conflict.
  const std::string p1 = fanuc_head + "G97 S1000 M3\nM200 P13\nG97 S1800 M3\nM202 P123\nM30\n%\n";
  const std::string p2 = fanuc_head + "M201 P23\nG97 S1500 M3\nG97 S2000 M33\nM202 P123\nM30\n%\n";
  const std::string p3 = fanuc_head + "M200 P13\nM201 P23\nG97 S3000 M33\nM202 P123\nM30\n%\n";
  CHECK(check(m, {{"P_1.nc", p1}, {"P_2.nc", p2}, {"P_3.nc", p3}}) ==
        "P_2.nc:5:1: error: channel 2 sets the shared main spindle to G97 S1500 M3 while channel 1 may set "
        "it to "
        "G97 S1800 M3 at the same time (P_1.nc:6): different speed; no wait orders the two blocks\n"
        "G97 S1500 M3\n^\n"
        "P_1.nc:6:1: note: channel 1 sets the main spindle to G97 S1800 M3 here\nG97 S1800 M3\n^\n"
        "check: 3 channels, 7 waits paired, 1 error\n");
  // Without path 1's second speed the chain orders everything.
  const std::string p1_once = fanuc_head + "G97 S1000 M3\nM200 P13\nM202 P123\nM30\n%\n";
  CHECK(check(m, {{"P_1.nc", p1_once}, {"P_2.nc", p2}, {"P_3.nc", p3}}) ==
        "check: 3 channels, 7 waits paired, 0 errors\n");
}

TEST_CASE("shared spindles: a feed per revolution on a spindle not known to turn", "[analysis]") {
  const machine m = load_machine("fanuc-0itd-twin");
  // Path 1 starts the spindle between the same waits as path 2's cut: not known before it.
  const std::string start = fanuc_head + "M100\nG97 S800 M3\nM101\nM5\nM30\n%\n";
  const std::string cut = fanuc_head + "M100\nG1 Z-20. F0.1\nM101\nM30\n%\n";
  CHECK(
      check(m, {{"B_1.nc", start}, {"B_2.nc", cut}}) ==
      "B_2.nc:5:1: error: channel 2 cuts with feed per revolution (G99) on the main spindle, but no channel "
      "is "
      "known to have started it before this block (a start in another channel counts only when a wait orders "
      "it before)\n"
      "G1 Z-20. F0.1\n^\n"
      "check: 2 channels, 4 waits paired, 1 error\n");
  // Started before the first wait: the cut after it is sound. Stopped again before a wait the
  // cut comes after: an error naming the stop.
  const std::string started = fanuc_head + "G97 S800 M3\nM100\nM101\nM30\n%\n";
  CHECK(check(m, {{"B_1.nc", started}, {"B_2.nc", cut}}) == "check: 2 channels, 4 waits paired, 0 errors\n");
  const std::string stopped = fanuc_head + "G97 S800 M3\nM5\nM100\nM101\nM30\n%\n";
  CHECK(check(m, {{"B_1.nc", stopped}, {"B_2.nc", cut}}) ==
        "B_2.nc:5:1: error: channel 2 cuts with feed per revolution (G99) on the main spindle, but channel 1 "
        "stops it at B_1.nc:5 (M5) and no start is known to come after that\n"
        "G1 Z-20. F0.1\n^\n"
        "check: 2 channels, 4 waits paired, 1 error\n");
  // Feeds per minute and reference returns are no cuts on the spindle.
  const std::string per_minute = fanuc_head + "M100\nG98\nG1 Z-20. F100.\nG28 U0.\nM101\nM30\n%\n";
  CHECK(check(m, {{"B_1.nc", start}, {"B_2.nc", per_minute}}) ==
        "check: 2 channels, 4 waits paired, 0 errors\n");
}

TEST_CASE("shared spindles: a channel commands only the spindles the machine gives it", "[analysis]") {
  machine m = load_machine("fanuc-0itd-twin");
  m.channels[1].spindles = {"main"};
  const std::string a = fanuc_head + "M100\nM101\nM30\n%\n";
  const std::string b = fanuc_head + "M100\nG97 S800 M103\nM105\nM101\nM30\n%\n";
  CHECK(check(m, {{"C_1.nc", a}, {"C_2.nc", b}}) ==
        "C_2.nc:5:1: error: channel 2 commands the sub spindle (G97 S800 M103), which machine "
        "'fanuc-0itd-twin' "
        "does not give it: channel 2 may command main (channel.spindles)\n"
        "G97 S800 M103\n^\n"
        "check: 2 channels, 4 waits paired, 1 error\n");
}

TEST_CASE("validation: channel.spindles and spindle.per_channel", "[machines]") {
  const std::string head = test::machine_head + "[[spindle]]\nname = \"main\"\nper_channel = false\n";
  const std::string& xz = test::xz_axes;
  auto error_of = [](const std::string& toml) {
    try {
      parse_machine(toml, "m.toml");
    } catch (const config_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(error_of(head + "[[channel]]\nnumber = 1\nspindles = [\"main\", \"live\"]\n" + xz) ==
        "m.toml:11:21: error: channel.spindles: 'live' names no [[spindle]]");
  CHECK(error_of(head + "[[channel]]\nnumber = 1\nspindles = [\"main\", \"main\"]\n" + xz) ==
        "m.toml:11:21: error: channel.spindles names 'main' twice");
  CHECK(
      error_of(head + "[[spindle]]\nname = \"sub\"\n[[channel]]\nnumber = 1\nspindles = [\"sub\"]\n" + xz) ==
      "m.toml:13:12: error: channel.spindles must name the channel's own spindle 'main' (channel.spindle)");
  CHECK(error_of(head + "[[channel]]\nnumber = 1\nspindles = [\"main\"]\n" + xz) == "no error");
}

TEST_CASE("post: under HEAD/BOTH only head 1's channel commands the spindle", "[post]") {
  // Head 2 worked on the sub spindle before; the balance cut is on the main spindle.
  const std::string cl =
      "PARTNO BOTHSUB\nUNITS/MM\nHEAD/2\nTLDATA/TURN\nTURRET/11,11\nSPINDL/RPM,800,CLW,SUB\nFEDRAT/0.2,MMPR\n"
      "GOTO/-20.0,0.0,2.0\nGOTO/-20.0,0.0,-10.0\nSPINDL/OFF\nHEAD/1\nTLDATA/TURN\nTURRET/1,1\nHEAD/BOTH\n"
      "SPINDL/SMM,200,MAXRPM,2000,CLW,MAIN\nFEDRAT/0.3,MMPR\nRAPID\nGOTO/36.0,0.0,2.0\nGOTO/36.0,0.0,-30.0\n"
      "HEAD/1\nSPINDL/OFF\nEND\nFINI\n";
  const machine m = load_machine("fanuc-31i-3path");
  const test::posted p = test::post_in_fresh_dir(
      cl, m, "balance-master", [](const diagnostic& d) { return d.level == severity::error; }, std::nullopt,
      [](post_options& o) { o.policy = sync_policy::sequential; });
  CHECK(p.diagnostics.empty());
  REQUIRE(p.ok);
  CHECK(p.files.at("BOTHSUB_1.nc") ==
        "%\nO1000 (BOTHSUB)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nM200 P12\nT0101\nG50 S2000\n"
        "G96 S200 M3\nM201 P12\nG68 P12\nG0 X72. Z2.\nG1 Z-30. F0.3\nG69\nM202 P12\nM5\nM204 P123\nM9\n"
        "G28 U0.\nG28 W0.\nM30\n%\n");
  // Path 2: no S, M3, M103 or G96 in its copy, and G54: it cuts on the master's main spindle.
  CHECK(p.files.at("BOTHSUB_2.nc") ==
        "%\nO1000 (BOTHSUB)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT1111\nG55\nG97 S800 M103\n"
        "G1 X40. Z-2. F0.2\nZ10.\nM105\nM200 P12\nM201 P12\nG68 P12\nG54\nG0 X72. Z2.\nG1 Z-30. F0.3\nG69\n"
        "M202 P12\nM204 P123\nM9\nG28 U0.\nG28 W0.\nM30\n%\n");
}

TEST_CASE("post: two heads setting the shared spindle differently are refused at their CL records",
          "[post]") {
  const std::string cl =
      "PARTNO FIGHT\nUNITS/MM\nHEAD/1\nTLDATA/TURN\nTURRET/1,1\nFEDRAT/0.25,MMPR\nSYNC/1,1,2\n"
      "SPINDL/SMM,200,MAXRPM,3000,CLW\nGOTO/29.0,0.0,2.0\nGOTO/29.0,0.0,-40.0\nSYNC/2,1,2\nHEAD/2\n"
      "TLDATA/DRILL\nTURRET/5,5\nFEDRAT/0.08,MMPR\nSYNC/1,2,1\nSPINDL/RPM,1200,CLW\nGOTO/0.0,0.0,-30.0\n"
      "SYNC/2,2,1\nEND\nFINI\n";
  const machine m = load_machine("fanuc-0itd-twin");
  const test::posted p = test::post_in_fresh_dir(cl, m, "spindle-fight");
  CHECK_FALSE(p.ok);
  CHECK(p.files.empty());
  // The programs that were not written are named in the stage's output folder: "out/...".
  std::string diags;
  for (std::size_t at = 0; at < p.diagnostics.size();) {
    const std::size_t end = p.diagnostics.find('\n', at);
    std::string line = p.diagnostics.substr(at, end - at);
    if (const std::size_t out = line.find("/out/");
        out != std::string::npos && line.find(".nc:") != std::string::npos)
      line.erase(0, out + 1);
    diags += line + "\n";
    at = end + 1;
  }
  CHECK(diags ==
        "job.cls:17:1: error: channel 2 sets the shared main spindle to G97 S1200 M3 while channel 1 may set "
        "it "
        "to G96 S200 M3 at the same time (job.cls:8): different speed mode (CSS and rpm); no wait orders the "
        "two "
        "blocks\n"
        "SPINDL/RPM,1200,CLW\n^\n"
        "out/FIGHT_2.nc:8:1: note: the block in the program as it would have been written (no file is "
        "written)\n"
        "G97 S1200 M3\n^\n"
        "job.cls:8:1: note: channel 1 sets the main spindle to G96 S200 M3 here\n"
        "SPINDL/SMM,200,MAXRPM,3000,CLW\n^\n"
        "out/FIGHT_1.nc:9:1: note: the block in the program as it would have been written (no file is "
        "written)\n"
        "G96 S200 M3\n^\n");
}

TEST_CASE("shared spindles: a stop or change of the spindle while another channel may still cut on it",
          "[analysis]") {
  const machine m = load_machine("fanuc-0itd-twin");
  // Path 1 turned at G96 S200 before the first wait; path 2 drills between the waits.
  const std::string drill = fanuc_head + "T0505\nG0 X0. Z5.\nM100\nG1 Z-25. F0.1\nG0 Z50.\nM101\nM30\n%\n";
  auto path1 = [](const std::string& after_wait) {
    return fanuc_head + "T0101\nG50 S3000\nG96 S200 M3\nG1 X58. Z2. F0.25\nM100\n" + after_wait +
           "M101\nM30\n%\n";
  };
  // The stop: an error at it, a note at the cut.
  CHECK(check(m, {{"D_1.nc", path1("M5\n")}, {"D_2.nc", drill}}) ==
        "D_1.nc:9:1: error: channel 1 stops the shared main spindle (M5) while channel 2 may still cut on it "
        "(D_2.nc:7); no wait orders the stop after that cut\n"
        "M5\n^\n"
        "D_2.nc:7:1: note: channel 2 cuts on the main spindle here\nG1 Z-25. F0.1\n^\n"
        "check: 2 channels, 4 waits paired, 1 error\n");
  // A speed, a speed mode, a direction.
  CHECK(check(m, {{"D_1.nc", path1("G96 S150\n")}, {"D_2.nc", drill}}) ==
        "D_1.nc:9:1: error: channel 1 sets the shared main spindle to G96 S150 while channel 2 may still cut "
        "on "
        "it at G96 S200 M3 (D_2.nc:7): different speed; no wait orders the change after that cut\n"
        "G96 S150\n^\n"
        "D_2.nc:7:1: note: channel 2 cuts on the main spindle here\nG1 Z-25. F0.1\n^\n"
        "check: 2 channels, 4 waits paired, 1 error\n");
  CHECK(check(m, {{"D_1.nc", path1("G97 S800\n")}, {"D_2.nc", drill}}) ==
        "D_1.nc:9:1: error: channel 1 sets the shared main spindle to G97 S800 while channel 2 may still cut "
        "on "
        "it at G96 S200 M3 (D_2.nc:7): different speed mode (CSS and rpm); no wait orders the change after "
        "that "
        "cut\n"
        "G97 S800\n^\n"
        "D_2.nc:7:1: note: channel 2 cuts on the main spindle here\nG1 Z-25. F0.1\n^\n"
        "check: 2 channels, 4 waits paired, 1 error\n");
  CHECK(check(m, {{"D_1.nc", path1("M4\n")}, {"D_2.nc", drill}}) ==
        "D_1.nc:9:1: error: channel 1 sets the shared main spindle to M4 while channel 2 may still cut on it "
        "at "
        "G96 S200 M3 (D_2.nc:7): different direction; no wait orders the change after that cut\n"
        "M4\n^\n"
        "D_2.nc:7:1: note: channel 2 cuts on the main spindle here\nG1 Z-25. F0.1\n^\n"
        "check: 2 channels, 4 waits paired, 1 error\n");
  // The same setting again is no change; a stop after the wait that follows the cut is sound;
  // a feed per minute cut relies on the turning spindle too.
  CHECK(check(m, {{"D_1.nc", path1("G96 S200 M3\n")}, {"D_2.nc", drill}}) ==
        "check: 2 channels, 4 waits paired, 0 errors\n");
  const std::string stop_later =
      fanuc_head + "T0101\nG50 S3000\nG96 S200 M3\nG1 X58. Z2. F0.25\nM100\nM101\nM5\nM102\nM30\n%\n";
  CHECK(check(m, {{"D_1.nc", stop_later},
                  {"D_2.nc",
                   fanuc_head + "T0505\nG0 X0. Z5.\nM100\nG1 Z-25. F0.1\nG0 Z50.\nM101\nM102\nM30\n%\n"}}) ==
        "check: 2 channels, 6 waits paired, 0 errors\n");
  const std::string per_minute =
      fanuc_head + "T0505\nG0 X0. Z5.\nM100\nG98\nG1 Z-25. F100.\nG0 Z50.\nM101\nM30\n%\n";
  CHECK(check(m, {{"D_1.nc", path1("M5\n")}, {"D_2.nc", per_minute}}) ==
        "D_1.nc:9:1: error: channel 1 stops the shared main spindle (M5) while channel 2 may still cut on it "
        "(D_2.nc:8); no wait orders the stop after that cut\n"
        "M5\n^\n"
        "D_2.nc:8:1: note: channel 2 cuts on the main spindle here\nG1 Z-25. F100.\n^\n"
        "check: 2 channels, 4 waits paired, 1 error\n");
  // Two turrets cutting at the one setting (a balance cut), CSS turning its rpm with X: no change.
  const std::string css_cut =
      fanuc_head + "T0101\nG50 S3000\nG96 S200 M3\nM100\nG1 X58. Z2. F0.25\nX20.\nZ-30.\nM101\nM5\nM30\n%\n";
  const std::string other_cut = fanuc_head + "T0202\nM100\nG1 X60. Z-10. F0.2\nX30.\nM101\nM30\n%\n";
  CHECK(check(m, {{"E_1.nc", css_cut}, {"E_2.nc", other_cut}}) ==
        "check: 2 channels, 4 waits paired, 0 errors\n");
}

TEST_CASE("shared spindles: a hold as the C axis while another channel's start of it may be in force",
          "[analysis]") {
  const machine integrex = load_machine("integrex-i200st");
  const std::string milling =
      "G109 L1\nG21 G54\nT11 M6\nG0 G53 B0.\nM950\nM200\nG97 S3000 M3\nG1 X20. Z-5. F300.\nM202\nM951\nM30\n";
  const std::string turning = "G109 L2\nG21 G54\nT0505\nG96 S180 M203\nG95\nG1 X40. Z-20. F0.2\n";
  CHECK(check(integrex, {{"I.EIA", "%\n" + milling + turning + "M950\nM951\nM205\nM30\n%\n"}}) ==
        "I.EIA:7:1: error: channel 1 holds the shared main spindle as the C axis (M200) while channel 2 may "
        "still turn it (G96 S180 M203, I.EIA:16); no wait orders a stop of it before the hold\n"
        "M200\n^\n"
        "I.EIA:16:1: note: channel 2 starts the main spindle here; no stop of it is known to come before the "
        "hold\nG96 S180 M203\n^\n"
        "check: 2 channels, 4 waits paired, 1 error\n");
  // Stopped before the wait that comes before the hold: sound. Stopped between the same waits
  // as the hold: the stop may come after it.
  CHECK(check(integrex, {{"I.EIA", "%\n" + milling + turning + "M205\nM950\nM951\nM30\n%\n"}}) ==
        "check: 2 channels, 4 waits paired, 0 errors\n");
  const std::string late =
      "%\nG109 L1\nG21 G54\nT11 M6\nG0 G53 B0.\nM950\nM200\nG97 S3000 M3\nG1 X20. Z-5. F300.\nM202\nM951\n"
      "M30\nG109 L2\nG21 G54\nT0505\nG96 S180 M203\nG95\nG1 X40. Z-20. F0.2\nM950\nM205\n"
      "M951\nM30\n%\n";
  CHECK(check(integrex, {{"I.EIA", late}}) ==
        "I.EIA:7:1: error: channel 1 holds the shared main spindle as the C axis (M200) while channel 2 may "
        "still turn it (G96 S180 M203, I.EIA:16); no wait orders a stop of it before the hold\n"
        "M200\n^\n"
        "I.EIA:16:1: note: channel 2 starts the main spindle here; no stop of it is known to come before the "
        "hold\nG96 S180 M203\n^\n"
        "check: 2 channels, 4 waits paired, 1 error\n");

  // The second spindle held the same way (the Fusion "Mazak Integrex i" post's M300/M302 for
  // it; the built-in file does not give them, since twinpost posts no C work there).
  machine sub_c = integrex;
  sub_c.spindles[1].c_axis.on = {"M300"};
  sub_c.spindles[1].c_axis.off = {"M302"};
  const std::string sub =
      "%\nG109 L1\nG21 G54\nT11 M6\nG0 G53 B0.\nM950\nM902\nM300\nG97 S3000 M3\nG1 X20. Z5. F300.\nM302\n"
      "M951\nM30\nG109 L2\nG21 G54\nT0505\nG92 S2500 R2\nG96 S180 M303\nG95\nG1 X40. Z20. F0.2\n"
      "M950\nM951\nM305\nM30\n%\n";
  CHECK(check(sub_c, {{"S.EIA", sub}}) ==
        "S.EIA:8:1: error: channel 1 holds the shared sub spindle as the C axis (M300) while channel 2 may "
        "still turn it (G96 S180 M303, S.EIA:18); no wait orders a stop of it before the hold\n"
        "M300\n^\n"
        "S.EIA:18:1: note: channel 2 starts the sub spindle here; no stop of it is known to come before the "
        "hold\nG96 S180 M303\n^\n"
        "check: 2 channels, 4 waits paired, 1 error\n");

  // The 31i: M35 (then G28 H0) holds the main spindle; a stop by a third path ordered between
  // path 1's start and the hold stops what path 1 started.
  const machine fanuc3 = load_machine("fanuc-31i-3path");
  const std::string p1 = fanuc_head + "G97 S1000 M3\nG1 X40. Z-5. F0.2\nM200 P123\nM201 P123\nM30\n%\n";
  const std::string p2 = fanuc_head + "M200 P123\nM201 P123\nM30\n%\n";
  const std::string p3 =
      fanuc_head + "M200 P123\nM201 P123\nM35\nG0 G28 H0.\nG97 S3000 M33\nM37\nM34\nM30\n%\n";
  CHECK(check(fanuc3, {{"T_1.nc", p1}, {"T_2.nc", p2}, {"T_3.nc", p3}}) ==
        "T_3.nc:6:1: error: channel 3 holds the shared main spindle as the C axis (M35) while channel 1 may "
        "still turn it (G97 S1000 M3, T_1.nc:4); no wait orders a stop of it before the hold\n"
        "M35\n^\n"
        "T_1.nc:4:1: note: channel 1 starts the main spindle here; no stop of it is known to come before the "
        "hold\nG97 S1000 M3\n^\n"
        "check: 3 channels, 6 waits paired, 1 error\n");
  const std::string p2_stops = fanuc_head + "M200 P123\nM5\nM201 P123\nM30\n%\n";
  CHECK(check(fanuc3, {{"T_1.nc", p1}, {"T_2.nc", p2_stops}, {"T_3.nc", p3}}) ==
        "check: 3 channels, 6 waits paired, 0 errors\n");
  // Before this rule the 31i's two-block c_on (M35, G0 G28 H0.) was not read as a hold at all:
  // a start by path 1 while path 3 holds the spindle is the start rule's error there too.
  const std::string p1_late = fanuc_head + "M200 P123\nM201 P123\nG97 S1000 M3\nM30\n%\n";
  CHECK(check(fanuc3, {{"T_1.nc", p1_late}, {"T_2.nc", p2}, {"T_3.nc", p3}}) ==
        "T_1.nc:6:1: error: channel 1 starts the shared main spindle (G97 S1000 M3) while channel 3 may hold "
        "it as the C axis (M35, T_3.nc:6); no wait orders the start before the hold or after its release\n"
        "G97 S1000 M3\n^\n"
        "T_3.nc:6:1: note: channel 3 holds the main spindle as the C axis here\nM35\n^\n"
        "check: 3 channels, 6 waits paired, 1 error\n");
}

TEST_CASE("post: a hold of the spindle another head turned is sound once that head stops it before the wait",
          "[post]") {
  // samples/post-fail/spindle-held-turning with head 2's SPINDL/OFF before the wait that comes
  // before the hold: the same job posts on both mill/turn machines.
  auto job = [](int turret, int mill, const std::string& x) {
    return fmt::format(
        "PARTNO "
        "HELD-OK\nUNITS/MM\nHEAD/{0}\nTLDATA/TURN,0.8\nTURRET/5,5\nSPINDL/SMM,180,MAXRPM,3000,CLW,MAIN\n"
        "FEDRAT/0.2,MMPR\nRAPID\nGOTO/{2}30.0,0.0,5.0\nGOTO/{2}25.0,0.0,-30.0\nRAPID\nGOTO/{2}80.0,0.0,60.0\n"
        "SPINDL/OFF\nSYNC/1,{0},{1}\nSYNC/2,{0},{1}\nHEAD/{1}\nSYNC/1,{1},{0}\nTLDATA/MILL,10.0\nLOADTL/11\n"
        "SPINDL/RPM,3000,CLW\nFEDRAT/MMPM,400\nRAPID\nGOTO/40.0,25.0,5.0,0.0,0.0,1.0\nGOTO/40.0,25.0,-8.0\n"
        "GOTO/-40.0,25.0,-8.0\nRAPID\nGOTO/-40.0,25.0,5.0\nSYNC/2,{1},{0}\nSPINDL/OFF\nEND\nFINI\n",
        turret, mill, x);
  };
  const auto errors = [](const diagnostic& d) { return d.level == severity::error; };
  const test::posted integrex =
      test::post_in_fresh_dir(job(2, 1, "-"), load_machine("integrex-i200st"), "held-ok-integrex", errors);
  CHECK(integrex.diagnostics.empty());
  CHECK(integrex.ok);
  const test::posted fanuc3 =
      test::post_in_fresh_dir(job(1, 3, ""), load_machine("fanuc-31i-3path"), "held-ok-31i", errors);
  CHECK(fanuc3.diagnostics.empty());
  CHECK(fanuc3.ok);
}

TEST_CASE("shared spindles: the change rule on the Integrex, on the sub spindle, and in a balance cut",
          "[analysis]") {
  // The Integrex: head 2 stops the main spindle (M205) between the same waits as head 1's cut.
  const machine integrex = load_machine("integrex-i200st");
  const std::string stop =
      "%\nG109 L1\nG21 G54\nT0101\nG96 S180 M203\nG95\nM950\nG1 X40. Z-20. F0.2\nM951\nM30\n"
      "G109 L2\nG21 G54\nT0505\nM950\nM205\nM951\nM30\n%\n";
  CHECK(
      check(integrex, {{"I.EIA", stop}}) ==
      "I.EIA:15:1: error: channel 2 stops the shared main spindle (M205) while channel 1 may still cut on it "
      "(I.EIA:8); no wait orders the stop after that cut\n"
      "M205\n^\n"
      "I.EIA:8:1: note: channel 1 cuts on the main spindle here\nG1 X40. Z-20. F0.2\n^\n"
      "check: 2 channels, 4 waits paired, 1 error\n");
  // The sub spindle on the Fanuc twin: path 2 drills on it (G55) while path 1 stops it (M105).
  const machine fanuc = load_machine("fanuc-0itd-twin");
  const std::string p1 = fanuc_head + "T0101\nM100\nM105\nM101\nM30\n%\n";
  const std::string p2 = fanuc_head + "T0505\nG55\nG97 S800 M103\nM100\nG1 Z20. F0.1\nM101\nM105\nM30\n%\n";
  CHECK(
      check(fanuc, {{"S_1.nc", p1}, {"S_2.nc", p2}}) ==
      "S_1.nc:6:1: error: channel 1 stops the shared sub spindle (M105) while channel 2 may still cut on it "
      "(S_2.nc:8); no wait orders the stop after that cut\n"
      "M105\n^\n"
      "S_2.nc:8:1: note: channel 2 cuts on the sub spindle here\nG1 Z20. F0.1\n^\n"
      "check: 2 channels, 4 waits paired, 1 error\n");
  // A balance cut (G68 .. G69): the paths move together block by block, so path 1's change
  // of speed between two of its cuts comes where path 2 is in the same place: no finding.
  const std::string b1 = fanuc_head +
                         "T0101\nG96 S200 M3\nM100\nG68\nG1 X72. Z-30. F0.3\nG96 S150\nZ-40.\nG69\n"
                         "M101\nM5\nM30\n%\n";
  const std::string b2 = fanuc_head + "T1111\nM100\nG68\nG1 X72. Z-30. F0.3\nZ-40.\nG69\nM101\nM30\n%\n";
  CHECK(check(fanuc, {{"B_1.nc", b1}, {"B_2.nc", b2}}) == "check: 2 channels, 4 waits paired, 0 errors\n");
  // The same change outside a balance cut is the finding.
  const std::string n1 = fanuc_head +
                         "T0101\nG96 S200 M3\nM100\nG1 X72. Z-30. F0.3\nG96 S150\nZ-40.\nM101\nM5\n"
                         "M30\n%\n";
  const std::string n2 = fanuc_head + "T1111\nM100\nG1 X72. Z-30. F0.3\nZ-40.\nM101\nM30\n%\n";
  CHECK(check(fanuc, {{"B_1.nc", n1}, {"B_2.nc", n2}}) ==
        "B_1.nc:8:1: error: channel 1 sets the shared main spindle to G96 S150 while channel 2 may still cut "
        "on "
        "it at G96 S200 M3 (B_2.nc:6): different speed; no wait orders the change after that cut\n"
        "G96 S150\n^\n"
        "B_2.nc:6:1: note: channel 2 cuts on the main spindle here\nG1 X72. Z-30. F0.3\n^\n"
        "check: 2 channels, 4 waits paired, 1 error\n");
}

TEST_CASE("post: a speed change inside HEAD/BOTH is no change under the other turret's cut", "[post]") {
  // The master writes the new speed between two cuts of the balance cut; the copy cuts in step.
  const std::string cl =
      "PARTNO "
      "BOTHMID\nUNITS/MM\nHEAD/1\nTLDATA/TURN\nTURRET/1,1\nHEAD/2\nTLDATA/TURN\nTURRET/11,11\nHEAD/BOTH\n"
      "SPINDL/SMM,200,MAXRPM,2000,CLW,MAIN\nFEDRAT/0.3,MMPR\nRAPID\nGOTO/36.0,0.0,2.0\nGOTO/36.0,0.0,-30.0\n"
      "SPINDL/SMM,150,MAXRPM,2000,CLW,MAIN\nGOTO/34.0,0.0,-30.0\nGOTO/34.0,0.0,-40.0\nHEAD/1\nSPINDL/"
      "OFF\nEND\nFINI\n";
  const auto errors = [](const diagnostic& d) { return d.level == severity::error; };
  for (const char* name : {"fanuc-0itd-twin", "fanuc-31i-3path", "integrex-i200st"}) {
    const test::posted p = test::post_in_fresh_dir(cl, load_machine(name), "both-mid", errors);
    CHECK(p.diagnostics.empty());
    CHECK(p.ok);
  }
}
