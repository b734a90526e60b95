// The control emulator's invariants (analysis/control_emulator.hpp), through the checker's
// reading (check_nc_resources) of hand-made programs: messages asserted to the letter.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <string>

#include "analysis/shared_resources.hpp"
#include "check/sync_report.hpp"
#include "machine_test_support.hpp"
#include "machines/machine_loader.hpp"
#include "machines/macro_variables.hpp"

using namespace twinpost;

namespace {

std::string check_mill(const std::string& program) {
  return format_sync_text(check_nc_resources({{"P.nc", program}}, load_machine("rotary-4axis")));
}

// Two paths of the twin-turret lathe: `one` is path 1's body, path 2 only starts and ends;
// both meet at an M100 before their end.
std::string check_lathe(const std::string& one) {
  const std::string head = "%\nO1000\nG0 G18 G21 G40 G54 G80 G99\n";
  const std::string end = "M100\nM30\n%\n";
  return format_sync_text(check_nc_resources({{"P_1.nc", head + one + end}, {"P_2.nc", head + end}},
                                             load_machine("fanuc-0itd-twin")));
}

const std::string mill_start = "%\nO1000\nG21\nG90 G94 G17 G40 G49 G80\nG91 G28 Z0.\nG90\nT01 M6\nS3000 M3\n";
const std::string mill_cut = "G0 X0. Y0.\nG0 G43 H1 Z50.\nG1 Z-5. F500.\nX20.\nG0 Z50.\nM30\n%\n";
const std::string clean_mill = "check: 1 channel, 0 waits paired, 0 errors\n";
const std::string clean_lathe = "check: 2 channels, 2 waits paired, 0 errors\n";

}  // namespace

TEST_CASE("emulator: a feed move with no work offset in force", "[analysis][emulator]") {
  CHECK(check_mill(mill_start + mill_cut) ==
        "P.nc:11:4: error: channel 1: a feed move with no work offset in force: the program would cut in "
        "whatever offset the last program left; set one (G54-G59, G54.1 P..) before the first cut\n"
        "G1 Z-5. F500.\n   ^\n"
        "check: 1 channel, 0 waits paired, 1 error\n");
  // Any work offset before the first cut: G54-G59, G54.1 P.., a G92 coordinate setting.
  CHECK(check_mill(mill_start + "G54\n" + mill_cut) == clean_mill);
  CHECK(check_mill(mill_start + "G59\n" + mill_cut) == clean_mill);
  CHECK(check_mill(mill_start + "G54.1 P12\n" + mill_cut) == clean_mill);
  CHECK(check_mill(mill_start + "G92 X0. Y0. Z100.\n" + mill_cut) == clean_mill);
  // A G53 feed (machine coordinates), a dwell's X and a G92 without an axis (a clamp) are no cut
  // and set nothing; a rapid is no cut.
  CHECK(check_mill(mill_start + "G1 G53 Z-10. F500.\nG4 X2.\nG0 X10.\nG54\n" + mill_cut) == clean_mill);
  CHECK(check_mill(mill_start + "G92 S2000\nG1 G53 Z-10. F500.\n" + mill_cut)
            .find("P.nc:13:4: error: channel 1: a "
                  "feed move with no work "
                  "offset") != std::string::npos);
  // A drilling cycle cuts: G81 with its hole, before any offset.
  CHECK(check_mill(mill_start + "G0 G43 H1 Z50.\nG98 G81 X10. Y0. Z-5. R2. F100.\nG80\nM30\n%\n") ==
        "P.nc:10:9: error: channel 1: a feed move with no work offset in force: the program would cut in "
        "whatever offset the last program left; set one (G54-G59, G54.1 P..) before the first cut\n"
        "G98 G81 X10. Y0. Z-5. R2. F100.\n        ^\n"
        "check: 1 channel, 0 waits paired, 1 error\n");
  // Threading is a motion of group 01, modal as G1 (analysis/modal_state): after a G32 that
  // moves nothing, the next block's Z cuts on along the thread. Read as G0's (the emulator kept
  // G0-G3 alone), it was no cut.
  const std::string no_offset = "%\nO1000\nG0 G18 G21 G40 G80 G99\n";
  CHECK(format_sync_text(check_nc_resources(
            {{"P_1.nc",
              no_offset + "T0101\nG97 S500 M3\nG0 X20. Z2.\nG32 F1.5\nZ-20.\nG0 X30.\nM100\nM30\n%\n"},
             {"P_2.nc", no_offset + "M100\nM30\n%\n"}},
            load_machine("fanuc-0itd-twin"))) ==
        "P_1.nc:8:1: error: channel 1: a feed move with no work offset in force: the program would cut in "
        "whatever offset the last program left; set one (G54-G59, G54.1 P..) before the first cut\n"
        "Z-20.\n^\n"
        "check: 2 channels, 2 waits paired, 1 error\n");
}

TEST_CASE("emulator: a variable the machine reserves is not written", "[analysis][emulator]") {
  CHECK(check_lathe("M3 S500\nG0 X50. Z2.\nG1 X40. F0.2\n#501=#501+1\n") ==
        "P_1.nc:7:1: error: channel 1: #501 is written here, but machine 'fanuc-0itd-twin' reserves it (read "
        "by "
        "transfer.grip): the setup owns its value; write a variable the machine file does not name\n"
        "#501=#501+1\n^\n"
        "check: 2 channels, 2 waits paired, 1 error\n");
  // Written through an indirect #[...] or with a blank a control skips: as written.
  CHECK(
      check_lathe("#[499+2]=1\n") ==
      "P_1.nc:4:1: error: channel 1: #[...] is written here, a variable known only when the block runs, and "
      "machine 'fanuc-0itd-twin' reserves #500, #501: write a numbered variable the machine file does not "
      "name\n#[499+2]=1\n^\ncheck: 2 channels, 2 waits paired, 1 error\n");
  CHECK(check_lathe("#5 01=1\n").starts_with("P_1.nc:4:1: error: channel 1: #501 is written here"));
  // Behind a comment a bracket's '(' opens, whose ')' ends it after a ';' (attack 70 F1): the
  // control runs `IF [1 EQ 1] THEN #501=1.`.
  CHECK(check_lathe("IF [1 EQ 1(]; )] THEN #501=1.\n")
            .starts_with("P_1.nc:4:23: error: channel 1: #501 is written here"));
  // Read, or another variable written, or #501 in a comment: quiet.
  CHECK(check_lathe("#601=#501+1\nIF [#500 EQ #0] THEN #3000=1 (#500 NOT SET)\n(#501=1)\n") == clean_lathe);
}

TEST_CASE("emulator: chucks and spindles", "[analysis][emulator]") {
  // The main chuck opened with the main spindle turning, unsynchronised.
  CHECK(
      check_lathe("G97 S800 M3\nM69\n") ==
      "P_1.nc:5:1: error: channel 1: M69 opens the main spindle's chuck while the spindle turns (started at "
      "line 4) and the spindles are not synchronised: stop it first, or open it under M213\nM69\n^\n"
      "check: 2 channels, 2 waits paired, 1 error\n");
  // Stopped first, or synchronised with the sub that holds the part: quiet.
  CHECK(check_lathe("G97 S800 M3\nM5\nM69\n") == clean_lathe);
  CHECK(check_lathe("G97 S800 M3\nM169\nM213\nM168\nM69\nM205\n") == clean_lathe);
  // The sub started with its chuck open.
  CHECK(
      check_lathe("M169\nG97 S800 M103\n") ==
      "P_1.nc:5:5: error: channel 1: the sub spindle is started with its chuck open (M169 at line 4): close "
      "the chuck first (M168)\nG97 S800 M103\n    ^\n"
      "check: 2 channels, 2 waits paired, 1 error\n");
  CHECK(check_lathe("M169\nM168\nG97 S800 M103\n") == clean_lathe);
  // A part-off while the sub holds the part, then the main chuck opened: the bar would go.
  CHECK(
      check_lathe("G97 S800 M3\nM169\nM213\nM168\nG0 X30. Z-20.\nG1 X-1. F0.05\nM69\nM205\n") ==
      "P_1.nc:10:1: error: channel 1: M69 opens the main spindle's chuck after the part-off at line 9: it "
      "holds the bar, which would be released; after a part-off the sub spindle takes the part away and the "
      "bar stays clamped ([transfer] release_after_cutoff)\nM69\n^\n"
      "check: 2 channels, 2 waits paired, 1 error\n");
  // The same cut short of the centre is no part-off.
  CHECK(check_lathe("G97 S800 M3\nM169\nM213\nM168\nG0 X30. Z-20.\nG1 X2. F0.05\nM69\nM205\n") ==
        clean_lathe);
}

TEST_CASE("emulator: a part-off by increments, and an increment that is none", "[analysis][emulator]") {
  // Attack 72 F4: in a transfer (M169 the sub's chuck, M213 the spindles synchronised, M168),
  // `G1 U-31.` from X30. parts off to X-1.: opening the main chuck after it releases the bar
  // (it passed); on the Integrex `G91 G1 X-10.` from X30. ends at X20., no part-off (M206 after
  // it was refused).
  CHECK(check_lathe("G97 S800 M3\nM169\nM213\nM168\nG0 X30. Z-20.\nG1 U-31. F0.05\nM69\nM205\n") ==
        "P_1.nc:10:1: error: channel 1: M69 opens the main spindle's chuck after the part-off at line 9: it "
        "holds "
        "the bar, which would be released; after a part-off the sub spindle takes the part away and the bar "
        "stays clamped ([transfer] release_after_cutoff)\n"
        "M69\n^\n"
        "check: 2 channels, 2 waits paired, 1 error\n");
  CHECK(check_lathe("G97 S800 M3\nM169\nM213\nM168\nG0 X30. Z-20.\nG1 U-20. F0.05\nM69\nM205\n") ==
        clean_lathe);
  const std::string head = "%\nO1000\nG21\nG0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG10.9 X1\n";
  CHECK(format_sync_text(check_nc_resources(
            {{"A_1.nc", head + "M950\nM30\n%\n"},
             {"A_2.nc", head +
                            "T0101\nG97 S800 M203\nM306\nM511\nM307\nG0 X30. Z-20.\nG91 G1 X-10. F0.05\nG90\n"
                            "M206\nM513\nM950\nM30\n%\n"}},
            load_machine("integrex-i200st"))) == "check: 2 channels, 2 waits paired, 0 errors\n");
}

TEST_CASE("emulator: the spindle a work offset selects takes the M-code both share", "[analysis][emulator]") {
  // A twin-spindle lathe whose sub answers the main's M3/M4/M5: G55 selects it, and the next M3
  // starts it. The emulator reads the one spindle state the rules and the timer read
  // (spindle_states); with a copy of its own that read only the blocks with an M word it lost
  // the G55, started the main instead and let the sub's chuck open on the turning part.
  machine m = load_machine("fanuc-0itd-twin");
  m.spindles[1].cw = 3;
  m.spindles[1].ccw = 4;
  m.spindles[1].stop = 5;
  const auto check = [&m](const std::string& one) {
    const std::string head = "%\nO1000\nG0 G18 G21 G40 G54 G80 G99\n";
    const std::string end = "M100\nM30\n%\n";
    return format_sync_text(check_nc_resources({{"P_1.nc", head + one + end}, {"P_2.nc", head + end}}, m));
  };
  CHECK(
      check("G97 S800 M3\nG55\nM3 S300\nM169\n") ==
      "P_1.nc:7:1: error: channel 1: M169 opens the sub spindle's chuck while the spindle turns (started at "
      "line 6) and the spindles are not synchronised: stop it first, or open it under M213\nM169\n^\n"
      "check: 2 channels, 2 waits paired, 1 error\n");
  // The sub stopped first (its M5 under G55): quiet; the main, still turning, is not its chuck.
  CHECK(check("G97 S800 M3\nG55\nM3 S300\nM5\nM169\n") == clean_lathe);
  // Under G54 the M3 starts the main: the sub's chuck opens on a spindle that stands.
  CHECK(check("G97 S800 M3\nM169\n") == clean_lathe);
}

TEST_CASE("macro variables: uses in a block and the machine's reserved ones", "[machines][emulator]") {
  const std::vector<macro_use> u =
      macro_uses("IF [#500 EQ #0] THEN #3000=1 (#7=1) #[#1]=2 # 12 = 3 #4==5 #5 00=6 #[499+1] = 7");
  REQUIRE(u.size() == 9);
  CHECK((u[0].number == 500 && !u[0].write && u[0].column == 5));
  CHECK((u[1].number == 0 && !u[1].write));
  CHECK((u[2].number == 3000 && u[2].write));
  CHECK((u[3].number == -1 && u[3].write && u[3].column == 37));  // the indirect #[#1]=
  CHECK((u[4].number == 1 && !u[4].write));                       // inside it
  CHECK((u[5].number == 12 && u[5].write));
  CHECK((u[6].number == 4 && !u[6].write));
  CHECK((u[7].number == 500 && u[7].write));  // a control that skips blanks reads #500
  CHECK((u[8].number == -1 && u[8].write));
  // A `;` comment to the end of the line is read as the word splitter reads it (attack 67 M10).
  const std::vector<macro_use> semi = macro_uses("#101=2 ; SET #500=0 AT SETUP");
  REQUIRE(semi.size() == 1);
  CHECK((semi[0].number == 101 && semi[0].write));
  // A control ends a comment at its first ')': comments do not nest, "(()#500=1" writes #500.
  const std::vector<macro_use> w = macro_uses("(()#500=1 (#501=2)");
  REQUIRE(w.size() == 1);
  CHECK((w[0].number == 500 && w[0].write));
  const std::vector<reserved_variable> r = reserved_variables(load_machine("integrex-i200st"));
  REQUIRE(r.size() == 2);
  CHECK((r[0].number == 500 && r[0].why == "read by transfer.grip"));
  CHECK((r[1].number == 501 && r[1].why == "read by transfer.grip"));
  CHECK(test::machine_error_of(test::machine_head + "[program]\nreserved_variables = [500, 0]\n" +
                               test::two_channels) ==
        "m.toml:7:22: error: program.reserved_variables: #0 is no variable a program could write (>= 1)");
}

TEST_CASE("emulator: the B head indexed again after every tool call", "[analysis][emulator]") {
  auto check = [](const std::string& head_one) {
    const std::string start = "G21\nG0 G90 G54 G97 G18\n";
    return format_sync_text(check_nc_resources(
        {{"P.EIA",
          "%\nO1000\nG109 L1\n" + start + head_one + "M950\nM30\nG109 L2\n" + start + "M950\nM30\n%\n"}},
        load_machine("integrex-i200st")));
  };
  const std::string first = "T01 M6\nM108\nG0 G53 B90.\nM107\nG94 G0 X54. Z2.\nG1 X40. F100.\n";
  // The second tool at the same angle, indexed again: quiet.
  CHECK(check(first + "T02 M6\nM108\nG0 G53 B90.\nM107\nG0 X54. Z2.\nG1 X40. F100.\n") ==
        "check: 2 channels, 2 waits paired, 0 errors\n");
  // Not indexed again: the cut after the tool call is refused.
  CHECK(
      check(first + "T02 M6\nG0 X54. Z2.\nG1 X40. F100.\n") ==
      "P.EIA:14:4: error: channel 1: a feed move with the B head not indexed since the tool call at line 12: "
      "the tool changer may leave it anywhere; index it (G0 G53 B..) before the cut\nG1 X40. F100.\n   ^\n"
      "check: 2 channels, 2 waits paired, 1 error\n");
  // The coolant: after the index, quiet; before it, or in its block (a Fanuc gives the block's M
  // code as it starts: attack 71 F4), a warning, once, which counts the later ones (review 40
  // L4); the through-tool pair's on code counts too; a B word of a data setting or a macro call
  // is no index (attack 71 F5).
  CHECK(check(first + "T02 M6\nM108\nG0 G53 B90. M8\nM107\nG0 X54. Z2.\nG1 X40. F100.\n") ==
        "P.EIA:14:1: warning: channel 1: M8 turns the coolant on before the B head is indexed for the tool "
        "called at line 12: it sprays while the head turns; index it (G0 G53 B..) first\nG0 G53 B90. M8\n^\n"
        "check: 2 channels, 2 waits paired, 0 errors, 1 warning\n");
  CHECK(check(first + "T02 M6\nG10 L2 P1 B0.\nM8\nM108\nG0 G53 B90.\nM107\nG0 X54. Z2.\nG1 X40. F100.\n") ==
        "P.EIA:14:1: warning: channel 1: M8 turns the coolant on before the B head is indexed for the tool "
        "called at line 12: it sprays while the head turns; index it (G0 G53 B..) first\nM8\n^\n"
        "check: 2 channels, 2 waits paired, 0 errors, 1 warning\n");
  CHECK(check(first + "T02 M6\nM51\nM108\nG0 G53 B90.\nM107\nM8\nG0 X54. Z2.\nG1 X40. F100.\nT03 M6\nM8\n"
                      "M108\nG0 G53 B0.\nM107\n") ==
        "P.EIA:13:1: warning: channel 1: M51 turns the coolant on before the B head is indexed for the tool "
        "called at line 12: it sprays while the head turns; index it (G0 G53 B..) first; the same at 1 more "
        "block (line 21)\nM51\n^\n"
        "check: 2 channels, 2 waits paired, 0 errors, 1 warning\n");
}

TEST_CASE("emulator: a rapid that turns a head swings the tip below the work's top", "[analysis][emulator]") {
  // Issue 37, item 7: the head/head mill (B about Y through a pivot 300 mm above the gauge
  // point) with a tool 100 mm long: 400 mm from pivot to tip. At B20 the linear words are the
  // tip's place with the heads at 0, so the tip stands 400 (1 - cos 20°) = 24.123 mm above them:
  // `Z-9.123` puts it at the CAM's clearance, z 15, where the cut starts (the work reaches that
  // high). Turned back to B0 there, the tip swings 137 mm across and drops to z -9.123.
  machine m = load_machine("head-head-5axis");
  for (const auto& [number, length] : {std::pair{1, 100.0}, {2, 250.0}}) {
    tool_def t;
    t.number = number;
    t.kind = "mill";
    t.length = length;
    m.tools.push_back(t);
  }
  const auto run = [&](const std::string& before_unwind, const std::string& on = "G43 H1",
                       const std::string& unwind = "G0 A0. B0.\n", const std::string& call = "") {
    const std::string program = mill_start + call + "G54\nG0 A0. B20.\nG0 X0. Y0.\nG0 " + on +
                                " X0. Y0. Z-9.123\nG1 Z-20. F500.\nG0 Z-9.123\n" + before_unwind + unwind +
                                "M30\n%\n";
    return format_sync_text(check_nc_resources({{"P.nc", program}}, m));
  };
  const auto said = [](int line, const std::string& turn, const std::string& low, const std::string& tool,
                       const std::string& drop = "24.123", const std::string& top = "13.000") {
    return fmt::format(
        "P.nc:{}:4: error: channel 1: the rapid turns the rotary axes ({}) with tool-tip control off and the "
        "tool not at home: the tip swings down to z {} (the part frame, mm; {}), {} mm below where the "
        "linear words, or both its ends, put it, and below z {}, the highest the program "
        "has fed a tool from or to: the work reaches "
        "that high; retract Z to its reference point (G91 G28 Z0.) before the rotary axes turn\n",
        line, turn, low, tool, drop, top);
  };

  const std::string tool1 = "a tool 100 mm long";
  CHECK(run("") == said(15, "B 20 to 0", "-9.123", tool1) + "G0 A0. B0.\n   ^\n" +
                       "check: 1 channel, 0 waits paired, 1 error\n");
  // Retracted first: the tool is at home while the head turns.
  CHECK(run("G91 G28 Z0.\nG90\n") == clean_mill);
  // Lifted by the swing first: the tip ends at the cut's top.
  CHECK(run("G0 Z15.\n") == clean_mill);
  // Well clear of the work (attack 60 F1: the height the tilt lends the tip is no clearance the
  // work needs): unwound at Z100 the tip ends at z 100.
  CHECK(run("G0 Z100.\n") == clean_mill);
  // A link between two tool axes at the clearance sags a little between its ends (every axis
  // moving linearly): B20 to B22 at the cut's top, 0.06 mm (attack 60 F2).
  CHECK(run("G0 Z15.\nG0 Z-11.988 B22.\n", "G43 H1", "") == clean_mill);
  // Under tool-tip control (G43.4, or G43.5 with the tool axis) the control keeps the tip.
  CHECK(run("", "G43.4 H1") == clean_mill);
  CHECK(run("", "G43.5 H1") == clean_mill);
  // Only X at home is no tool at home (attack 60 F5). G53 Z low in the machine is no home
  // either (F6), but where it leaves the tip in the part frame is not known: the swing after it
  // is not followed; nor after an increment down from home.
  CHECK(run("G91 G28 X0.\nG90\n") == said(17, "B 20 to 0", "-9.123", tool1) + "G0 A0. B0.\n   ^\n" +
                                         "check: 1 channel, 0 waits paired, 1 error\n");
  CHECK(run("G53 Z-400.\n") == clean_mill);
  CHECK(run("G91 G28 Z0.\nG0 Z-50.\nG90\n") == clean_mill);  // not known: not followed
  // G90 G28 goes through its intermediate point, the work's Z0, turning the head on the way (F7).
  CHECK(run("", "G43 H1", "G90 G28 Z0. B0.\n") ==
        fmt::format("P.nc:15:13{}", said(15, "B 20 to 0", "-0.854", tool1, "23.267").substr(9)) +
            "G90 G28 Z0. B0.\n            ^\ncheck: 1 channel, 0 waits paired, 1 error\n");
  // From vertical to tilted about the same tip point (review 61 C1): the words drop to pay for
  // the tilt, and half way the tip dips 6 mm below both its ends, into a
  // face cut at z 0.
  CHECK(format_sync_text(check_nc_resources(
            {{"P.nc", mill_start + "G54\nG0 A0. B0.\nG0 X0. Y0.\nG43 H1 Z5.\nG1 Z0. F500.\nX-30.\nG0 Z3.\n"
                                   "G0 X136.808 Z-21.123 B20.\nM30\n%\n"}},
            m)) ==
        fmt::format("P.nc:16:22{}", said(16, "B 0 to 20", "-2.985", tool1, "5.985", "3.000").substr(9)) +
            "G0 X136.808 Z-21.123 B20.\n                     ^\ncheck: 1 channel, 0 waits paired, 1 error\n");
  // A drilling cycle's R plane is where its feeds start: the work reaches that high (attack 60:
  // a program whose only cuts were a cycle's was held to nothing).
  CHECK(format_sync_text(check_nc_resources(
            {{"P.nc", mill_start + "G54\nG0 A0. B20.\nG0 X0. Y0.\nG43 H1 Z50.\nG0 Z-19.123\n"
                                   "G98 G81 X30. Y0. Z-40. R-22.123 F100.\nG80\nG0 B0.\nM30\n%\n"}},
            m)) == said(16, "B 20 to 0", "-19.123", tool1, "24.123", "2.000") +
                       "G0 B0.\n   ^\ncheck: 1 channel, 0 waits paired, 1 error\n");
  // G28 turns the head on from its intermediate point to its reference point, where the block
  // leaves Z (attack 62 M1): `G91 G28 B0.` at the clearance is the unwind.
  CHECK(run("", "G43 H1", "G91 G28 B0.\nG90\n") ==
        fmt::format("P.nc:15:9{}", said(15, "B 20 to 0", "-9.123", tool1).substr(9)) +
            "G91 G28 B0.\n        ^\ncheck: 1 channel, 0 waits paired, 1 error\n");
  // A feed from the clearance, or back up to it, is no cut there (attack 62 FP1): unwound 40 mm
  // over the cut's start, the tip stays clear.
  CHECK(format_sync_text(check_nc_resources(
            {{"P.nc", mill_start + "G54\nG0 A0. B20.\nG0 X0. Y0.\nG43 H1 Z100.\nG1 Z-20. F500.\nX20.\n"
                                   "G1 Z40.\nG0 A0. B0.\nM30\n%\n"}},
            m)) == clean_mill);
  // A G68 rotation about Z turns X and Y, not heights: the unwind under it is followed (attack
  // 62 M2).
  CHECK(run("G68 X0. Y0. R30.\n") == said(16, "B 20 to 0", "-9.123", tool1) + "G0 A0. B0.\n   ^\n" +
                                         "check: 1 channel, 0 waits paired, 1 error\n");
  // Each work offset is a part of its own (attack 62 FP6): a second part in G55, whose Z zero
  // is 100 mm lower, is not held to the first part's top.
  CHECK(format_sync_text(check_nc_resources(
            {{"P.nc", mill_start + "G54\nG0 A0. B20.\nG0 X0. Y0.\nG43 H1 Z105.\nG1 Z98. F500.\nX40.\n"
                                   "G0 Z160.\nG55 G0 X0. Y0.\nG0 Z40.\nG0 B-20.\nM30\n%\n"}},
            m)) == clean_mill);
  // The tool change takes Z to the tool-change position (attack 62 FP5).
  CHECK(run("T01 M6\n") == clean_mill);
  // The tool in the spindle is the one M6 changed to, not the one a T word preselects (F9).
  CHECK(run("", "G43 H1", "G0 A0. B0.\n", "T02\n") == said(16, "B 20 to 0", "-9.123", tool1) +
                                                          "G0 A0. B0.\n   ^\n" +
                                                          "check: 1 channel, 0 waits paired, 1 error\n");
}

TEST_CASE("emulator: a rapid that turns a table is not held to a height", "[analysis][emulator]") {
  // The A table turns the part, not the tool: the tip keeps its distance from the table's axis,
  // and whether the part reaches it is the part's size, not in the program.
  CHECK(check_mill(mill_start +
                   "G54\nG0 A0.\nG0 X0. Y0.\nG0 G43 H1 Z80.\nG1 Z30. F500.\nG0 Z80.\nG0 A90.\nM30\n%\n") ==
        clean_mill);
}
