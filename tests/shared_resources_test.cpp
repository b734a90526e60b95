// Shared resources (analysis/shared_resources.hpp): which spindles a channel may command,
// spindle commands of channels that may run at the same time, feeds per revolution on a spindle
// not known to turn; the machine-file keys; the post's balance cut and its self-check.
// Messages are asserted to the letter.
#include <catch2/catch.hpp>

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
        "%\nO1000 (BOTHSUB)\nG0 G18 G21 G40 G54 G80 G99\nM200 P12\nG28 U0.\nG28 W0.\nT0101\nG50 S2000\n"
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
