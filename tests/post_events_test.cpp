// [events] of a machine file (docs/customising.md): the user's blocks at the post's events and
// for CL records the post does not know, written through the channel's own writer and so held
// to the same checks as the post's blocks (word formats, waits paired by the self-check).
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fmt/format.h>

#include <string>

#include "file_test_support.hpp"
#include "machine_test_support.hpp"
#include "machines/machine_loader.hpp"
#include "machines/machine_search.hpp"
#include "post_test_jobs.hpp"

using namespace twinpost;

namespace {

// fanuc-0itd-twin as its file is, with `events` appended (the file ends with [timing]).
std::string twin_with(const std::string& events) {
  return test::read_file(std::string(TWINPOST_SOURCE_DIR) + "/machines/builtin/fanuc-0itd-twin.toml") + "\n" +
         events;
}

// `policy`: sequential where a test of two heads is about the events, not where the waits go.
test::posted post_with(const std::string& events, const std::string& cl, const std::string& tag,
                       sync_policy policy = sync_policy::automatic) {
  return test::post_in_fresh_dir(cl, parse_machine(twin_with(events), "twin-events.toml"), "events-" + tag,
                                 {}, {}, [&](post_options& o) { o.policy = policy; });
}

// The same machine with [events] script = "t.lua", the script `lua` beside it.
test::posted post_with_script(const std::string& events, const std::string& lua, const std::string& cl,
                              const std::string& tag, const std::function<void(post_options&)>& adjust = {}) {
  const std::string dir = test::fresh_temp_dir("script-" + tag);
  test::write_file(dir + "/t.lua", lua);
  machine m = parse_machine(twin_with(events), "twin-events.toml");
  m.events.script = "t.lua";
  m.events.script_path = dir + "/t.lua";
  test::posted p = test::post_in_fresh_dir(cl, m, "events-" + tag, {}, {}, adjust);
  std::filesystem::remove_all(dir);
  return p;
}

std::string program_1(const test::posted& p, const std::string& name = "EV_1.nc") {
  if (!p.ok) return "(failed)\n" + p.diagnostics;
  const auto f = p.files.find(name);
  return f == p.files.end() ? "(missing)" : f->second;
}

const std::string every_event = R"T([events]
program_start.after = ["(START {channel})"]
program_end.before = ["(END {channel})"]
tool_change.before = ["(OUT)"]
tool_change.after = ["(T{tool:02} OFFSET {offset} {text})"]
spindle_start.before = ["(SPINDLE {rpm})"]
spindle_start.after = ["(SPINDLE ON)"]
spindle_stop.before = ["(SPINDLE STOPS)"]
spindle_stop.after = ["(SPINDLE OFF)"]
coolant_on.before = ["(COOLANT)"]
coolant_on.after = ["(COOLANT ON)"]
coolant_off.before = ["(COOLANT STOPS)"]
coolant_off.after = ["(COOLANT OFF)"]
wait.before = ["(WAIT {code})"]
wait.after = ["(WAITED)"]
cycle.before = ["(CYCLE {text})"]
cycle.after = ["(CYCLE DONE)"]
operation.before = ["(OPERATION)"]
operation.after = ["(OPERATION {text})"]

[[tool]]
number = 1
kind = "drill"
name = "DRILL 8"
)T";

}  // namespace

TEST_CASE("[events] blocks go out before and after each of the post's events", "[post][events]") {
  const test::posted p =
      post_with(every_event,
                "PARTNO EV\nHEAD/1\nTOOL PATH/DRILL_1,TOOL,DRILL 8\nTURRET/1,1\n"
                "SPINDL/RPM,800,CLW\nCOOLNT/ON\nRAPID\nGOTO/0,0,5\nCYCLE/DRILL,DEPTH,10,CLEAR,2,MMPR,0.1\n"
                "GOTO/0,0,0\nCYCLE/OFF\nCOOLNT/OFF\nSPINDL/OFF\nFINI\n",
                "every");
  CHECK(program_1(p) ==
        "%\nO1000 (EV)\nG0 G18 G21 G40 G54 G80 G99\n(START 1)\n(OPERATION)\n"
        "(DRILL_1,TOOL,DRILL 8)\n(OPERATION DRILL_1,TOOL,DRILL 8)\n(OUT)\nG28 U0.\nG28 W0.\nT0101\n"
        "(T01 OFFSET 1 DRILL 8)\n(SPINDLE 800)\nG97 S800 M3\n(SPINDLE ON)\n(COOLANT)\nM8\n"
        "(COOLANT ON)\nG0 X0. Z5.\n(CYCLE DRILL)\nZ2.\nG83 X0. Z-10. R0. F0.1\nG80\nG0 Z2.\n"
        "(CYCLE DONE)\n(COOLANT STOPS)\nM9\n(COOLANT OFF)\n(SPINDLE STOPS)\nM5\n(SPINDLE OFF)\n"
        "(WAIT 100)\nM100\n(WAITED)\n(END 1)\nG28 U0.\nG28 W0.\nM30\n%\n");
}

TEST_CASE("a user block leaves the footer's M9 and M5 out unless its M codes may turn them on",
          "[post][events]") {
  // The CL turns both off before its end: the footer's M9 and M5 are in force (left out), and a
  // block without M codes keeps them so; the machine's coolant-on code puts M9 back, a spindle
  // start M5, an M code the machine file does not name (M13) both.
  const std::string job =
      "PARTNO EV\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,800,CLW\nCOOLNT/ON\nRAPID\nGOTO/20,0,5\n"
      "COOLNT/OFF\nSPINDL/OFF\nCATCHER\nFINI\n";
  const std::string body =
      "%\nO1000 (EV)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG97 S800 M3\nM8\nG0 X40. Z5.\n"
      "M9\nM5\n";
  const auto with = [&](const std::string& blocks, const std::string& tag) {
    return program_1(post_with("[[events.record]]\nmajor = \"CATCHER\"\nblocks = [" + blocks + "]\n", job,
                               "footer-" + tag));
  };
  CHECK(with("\"(CATCHER)\", \"#601=#601+1\", \"G4 U1.\", \"M9\", \"M5\"", "none") ==
        body + "(CATCHER)\n#601=#601+1\nG4 U1.\nM9\nM5\nM100\nG28 U0.\nG28 W0.\nM30\n%\n");
  CHECK(with("\"M8\"", "coolant") == body + "M8\nM100\nM9\nG28 U0.\nG28 W0.\nM30\n%\n");
  // Mist (codes.coolant_mist M138/M139) is turned off by its own code, which the footer lacks.
  CHECK(with("\"M138\"", "mist") == body + "M138\nM100\nM139\nM9\nG28 U0.\nG28 W0.\nM30\n%\n");
  CHECK(with("\"M3 S500\"", "spindle") == body + "M3 S500\nM100\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
  // The sub spindle (M104 turns it, M105 stops it): the footer's M5 stops only the main.
  CHECK(with("\"M104\"", "sub") == body + "M104\nM100\nM105\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
  CHECK(with("\"M13\"", "unknown") == body + "M13\nM100\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
}

TEST_CASE("a cut after a user block stopped the spindle is an error, as after SPINDL/OFF", "[post][events]") {
  const std::string job =
      "PARTNO EV\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,800,CLW\nRAPID\nGOTO/20,0,5\nFEDRAT/0.2,MMPR\n"
      "GOTO/20,0,-10\nFINI\n";
  // M5 after the start: the first cut names the user's stop.
  const test::posted stopped = post_with("[events]\nspindle_start.after = [\"M5\"]\n", job, "user-stop");
  CHECK(program_1(stopped) ==
        "(failed)\n"
        "job.cls:8:1: error: channel 1: feed move with the main spindle stopped by M5 of a user block (the "
        "machine's [events] or script) and not started again: the tool would be driven into a part that does "
        "not "
        "turn (or a still cutter into the work); start it in the user block, or give SPINDL with a speed "
        "before "
        "the cut\n"
        "GOTO/20,0,-10\n"
        "^\n");
  // Started again in the same user block (M3 at the S in force): the cut posts.
  const test::posted again =
      post_with("[events]\nspindle_start.after = [\"M5\", \"M3\"]\n", job, "user-restart");
  CHECK(program_1(again) ==
        "%\nO1000 (EV)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG97 S800 M3\nM5\nM3\n"
        "G0 X40. Z5.\nG1 Z-10. F0.2\nM100\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
  // The sub spindle's stop (M105) leaves the main turning.
  CHECK(program_1(post_with("[events]\nspindle_start.after = [\"M105\"]\n", job, "user-stop-sub")) ==
        "%\nO1000 (EV)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG97 S800 M3\nM105\n"
        "G0 X40. Z5.\nG1 Z-10. F0.2\nM100\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
}

TEST_CASE("a HEAD/BOTH copy writes no spindle event, as it writes no spindle block", "[post][events]") {
  const test::posted p =
      post_with("[events]\nspindle_start.after = [\"(SPINDLE {channel})\"]\n",
                "PARTNO EV\nHEAD/1\nTURRET/1,1\nHEAD/2\nTURRET/11,11\nHEAD/BOTH\n"
                "SPINDL/RPM,800,CLW\nRAPID\nGOTO/36,0,2\nSPINDL/RPM,900,CLW\nRAPID\nGOTO/36,0,3\n"
                "HEAD/1\nFINI\n",
                "both", sync_policy::sequential);
  CHECK(
      program_1(p) ==
      "%\nO1000 (EV)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nM100\nG97 S800 M3\n(SPINDLE 1)\n"
      "M101\nG68\nG0 X72. Z2.\nG97 S900 M3\n(SPINDLE 1)\nZ3.\nG69\nM102\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
  CHECK(program_1(p, "EV_2.nc") ==
        "%\nO1000 (EV)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nM100\nT1111\nM101\nG68\nG0 X72. "
        "Z2.\nZ3.\n"
        "G69\nM102\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
}

TEST_CASE("[[events.record]] turns a CL record the post does not know into blocks", "[post][events]") {
  const std::string events = R"T([[events.record]]
major = "PARTS_CATCHER"
words = ["ON"]
blocks = ["M10"]
[[events.record]]
major = "parts_catcher"
words = ["off"]
blocks = ["M11"]
[[events.record]]
major = "OPERATOR_NOTE"
blocks = ["(NOTE {text})", "M0"]
)T";
  const std::string job =
      "PARTNO EV\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,800,CLW\nRAPID\nGOTO/20,0,5\nparts_catcher/on\n"
      "PARTS_CATCHER / OFF\nOPERATOR_NOTE/CHECK,DIAMETER\nFINI\n";
  CHECK(program_1(post_with(events, job, "record")) ==
        "%\nO1000 (EV)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG97 S800 M3\n"
        "G0 X40. Z5.\nM10\nM11\n(NOTE CHECK,DIAMETER)\nM0\nM100\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
  SECTION("a record none of whose entries match is an error at it") {
    const test::posted p =
        post_with(events, "PARTNO EV\nHEAD/1\nTURRET/1,1\nPARTS_CATCHER/HALF\nFINI\n", "nomatch");
    CHECK_FALSE(p.ok);
    CHECK(p.diagnostics ==
          "job.cls:4:1: error: channel 1: PARTS_CATCHER/HALF matches no [[events.record]] of machine "
          "'fanuc-0itd-twin' (it has PARTS_CATCHER/ON, PARTS_CATCHER/OFF)\nPARTS_CATCHER/HALF\n^\n");
  }
  SECTION("without the entry the word stays unknown") {
    const test::posted p = post_with("", job, "unknown");
    CHECK_FALSE(p.ok);
    CHECK(p.diagnostics ==
          "job.cls:7:1: error: unknown major word 'PARTS_CATCHER': this record cannot be posted\n"
          "parts_catcher/on\n^\n"
          "job.cls:8:1: error: unknown major word 'PARTS_CATCHER': this record cannot be posted\n"
          "PARTS_CATCHER / OFF\n^\n"
          "job.cls:9:1: error: unknown major word 'OPERATOR_NOTE': this record cannot be posted\n"
          "OPERATOR_NOTE/CHECK,DIAMETER\n^\n");
  }
}

TEST_CASE("[[events.record]] for a word the post knows is an error at the entry", "[post][events]") {
  // AUXFUN is posted by the post itself: the entry would never be used, without a word.
  const test::posted p = post_with("[[events.record]]\nmajor = \"auxfun\"\nblocks = [\"M10\"]\n",
                                   "PARTNO EV\nHEAD/1\nTURRET/1,1\nAUXFUN/10\nFINI\n", "known");
  CHECK_FALSE(p.ok);
  // The entry's `major` line: after the built-in's own lines and the one appended "\n".
  const std::string text = twin_with("");
  const auto major_line = std::count(text.begin(), text.end(), '\n') + 2;
  CHECK(p.diagnostics.ends_with(
      "twin-events.toml:" + std::to_string(major_line) +
      ":9: error: events.record.major \"AUXFUN\" is a record the post knows (posted "
      "in a post, docs/records.md): it never reaches [[events.record]], which takes only "
      "words the post does not know\n"));
  CHECK(p.files.empty());
}

TEST_CASE("an event block is held to the control's word formats", "[post][events]") {
  const test::posted p = post_with("[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"M10 T12345\"]\n",
                                   "PARTNO EV\nHEAD/1\nTURRET/1,1\nCATCHER\nFINI\n", "format");
  CHECK_FALSE(p.ok);
  CHECK(p.diagnostics ==
        "job.cls:4:1: error: channel 1: T word 12345 does not fit the control's format (4: at most 9999)\n"
        "CATCHER\n^\n");
  CHECK(p.files.empty());
}

TEST_CASE("an event block's X is held to the channel's travel, as the post's own moves are",
          "[post][events]") {
  // channel.axis X of fanuc-0itd-twin: -10..460 (diameter).
  const test::posted p =
      post_with("[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"G4 X1.5\", \"G0 X470.\"]\n",
                "PARTNO EV\nHEAD/1\nTURRET/1,1\nCATCHER\nFINI\n", "travel");
  CHECK_FALSE(p.ok);
  CHECK(
      p.diagnostics ==
      "job.cls:4:1: error: channel 1: X470. is outside channel 1's X travel -10..460 (channel.axis min/max)\n"
      "CATCHER\n^\n");
  CHECK(p.files.empty());
  SECTION("within it, and X as a dwell (G4 X), posts") {
    const test::posted q =
        post_with("[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"G4 X1.5\", \"G0 X460.\"]\n",
                  "PARTNO EV\nHEAD/1\nTURRET/1,1\nCATCHER\nFINI\n", "travel-ok");
    CHECK(program_1(q) ==
          "%\nO1000 (EV)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG4 X1.5\nG0 X460.\n"
          "M100\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
  }
}

TEST_CASE("a user block's words are read as a control that skips blanks reads them", "[post][events]") {
  // channel.axis X of fanuc-0itd-twin: -10..460 (diameter). Each form the gate once let through.
  const std::pair<const char*, const char*> cases[] = {
      {"G0 X 9000.",
       "\"G0 X 9000.\" has a blank inside the word 'X 9000.': a control that skips blanks reads "
       "one word there"},
      {"M1 00",
       "\"M1 00\" has a blank inside the word 'M1 00': a control that skips blanks reads one word there"},
      {"#5 00=1",
       "\"#5 00=1\" has a blank inside the word '#5 00=1': a control that skips blanks reads one "
       "word there"},
      {"G0 X+9000.", "X+9000. is outside channel 1's X travel -10..460 (channel.axis min/max)"},
      {"G0 U9000.",
       "U9000. in \"G0 U9000.\" is an increment of X where the post does not know where X is (after a home "
       "return, G30 or G53); write an absolute X"},
      {"G0 X[9000]",
       "X[9000] in \"G0 X[9000]\": an X the post cannot hold to channel 1's X travel -10..460 (a "
       "variable or an expression); write the number"},
      {"G0 X#100",
       "X#100 in \"G0 X#100\": an X the post cannot hold to channel 1's X travel -10..460 (a "
       "variable or an expression); write the number"},
      {"G50 X-9000.",
       "\"G50 X-9000.\" sets or shifts the coordinate system (G50 or G92 with an axis word, G10 L2/L20, G52 "
       "with a shift): every later position of the post would be off by it"},
      {"G50.0 X100.",
       "\"G50.0 X100.\" sets or shifts the coordinate system (G50 or G92 with an axis word, G10 L2/L20, G52 "
       "with a shift): every later position of the post would be off by it"},
      {"G#1 X100.",
       "\"G#1 X100.\" gives a G code by a variable, an expression or with a sign: the post cannot say what "
       "it "
       "does (a frame, a unit, a wait); write the code"},
      {"M[100]",
       "\"M[100]\" gives a M code by a variable, an expression or with a sign: the post cannot say what it "
       "does (a "
       "frame, a unit, a wait); write the code"},
      {"G55",
       "\"G55\" selects another work offset, a mirror image, a scaling or a rotation (G54-G59, G54.1, G51, "
       "G51.1, G68, G50.3, G92.1): every later position of the post would be in another frame; the post "
       "writes the channel's frame itself"},
      {"G054.1 P5",
       "\"G054.1 P5\" selects another work offset, a mirror image, a scaling or a rotation (G54-G59, G54.1, "
       "G51, G51.1, G68, G50.3, G92.1): every later position of the post would be in another frame; the post "
       "writes the channel's frame itself"},
      {"G50.3 P0",
       "\"G50.3 P0\" selects another work offset, a mirror image, a scaling or a rotation (G54-G59, G54.1, "
       "G51, G51.1, G68, G50.3, G92.1): every later position of the post would be in another frame; the post "
       "writes the channel's frame itself"},
      {"G10 P0 X100.",
       "\"G10 P0 X100.\" sets or shifts the coordinate system (G50 or G92 with an axis word, G10 L2/L20, G52 "
       "with a shift): every later position of the post would be off by it"},
      {"G10.9 X0",
       "\"G10.9 X0\" turns on a mode the post neither writes nor turns off (polar or cylindrical "
       "interpolation, polar coordinates, nose radius compensation, a modal macro call, polygon turning, "
       "radius or diameter input, the stroke check off, inverse time feed: G10.9): every later block of the "
       "post would be read in it"},
      {"G41",
       "\"G41\" turns on a mode the post neither writes nor turns off (polar or cylindrical interpolation, "
       "polar coordinates, nose radius compensation, a modal macro call, polygon turning, radius or diameter "
       "input, the stroke check off, inverse time feed: G41): every later block of the post would be read in "
       "it"},
      {"G04 X1 G0 X9000.",
       "\"G04 X1 G0 X9000.\" mixes a motion with a dwell, a data setting or a macro call: its axis words "
       "cannot be held to the travel; write them in blocks of their own"},
      {"G10 L+2 P1 Z-500.",
       "\"G10 L+2 P1 Z-500.\" sets or shifts the coordinate system (G50 or G92 with an axis word, G10 "
       "L2/L20, G52 with a shift): every later position of the post would be off by it"},
      {"G10 L#1 P1 Z-500.",
       "\"G10 L#1 P1 Z-500.\" writes parameters (G10 L50): a parameter may hold a work offset or the travel "
       "limits; set them on the control, not from the program"},
      {"G50 H0",
       "\"G50 H0\" sets or shifts the coordinate system (G50 or G92 with an axis word, G10 L2/L20, G52 with "
       "a shift): every later position of the post would be off by it"},
      {"#5222=-500.",
       "\"#5222=-500.\" writes #5222, a system variable of the work offsets (#5000-#5999, "
       "#7000-#7999, #14000-#19999): every later position of the post would be off by it"},
      {"IF [#1 EQ 0] THEN G0 X9000.",
       "\"IF [#1 EQ 0] THEN G0 X9000.\" gives a G code under IF [..] THEN: whether the control runs it is "
       "known "
       "only when the block runs; write it unconditionally, or not at all"},
      {"IF [#1 EQ 0] THEN X9000.", "X9000. is outside channel 1's X travel -10..460 (channel.axis min/max)"},
      {"#1=1 G0 X9000.", "X9000. is outside channel 1's X travel -10..460 (channel.axis min/max)"},
      {"G0 X100.(",
       "\"G0 X100.(\" opens a comment it does not close: a control may read on into the next block"},
      {"O2000",
       "\"O2000\" holds a program number: a control that loads the file starts another program there, "
       "and this one loses the blocks after it"},
      {":1000",
       "\":1000\" holds a program number: a control that loads the file starts another program there, "
       "and this one loses the blocks after it"},
      // The sixth attack: lower case, a print statement with words after it, a signed code, a
      // comment inside a word, an N without its number.
      {"g55",
       "\"g55\" selects another work offset, a mirror image, a scaling or a rotation (G54-G59, G54.1, G51, "
       "G51.1, G68, G50.3, G92.1): every later position of the post would be in another frame; the post "
       "writes the channel's frame itself"},
      {"g0 x9000.", "X9000. is outside channel 1's X travel -10..460 (channel.axis min/max)"},
      {"DPRNT[A] G0 X9000.", "X9000. is outside channel 1's X travel -10..460 (channel.axis min/max)"},
      {"POPEN G55",
       "\"POPEN G55\" selects another work offset, a mirror image, a scaling or a rotation (G54-G59, G54.1, "
       "G51, G51.1, G68, G50.3, G92.1): every later position of the post would be in another frame; the post "
       "writes the channel's frame itself"},
      {"G+55",
       "\"G+55\" gives a G code by a variable, an expression or with a sign: the post cannot say what it "
       "does (a frame, a unit, a wait); write the code"},
      {"G(C)55",
       "\"G(C)55\" has a comment inside a word: a control that skips comments reads one word across it"},
      {"G0 X(C)9000.",
       "\"G0 X(C)9000.\" has a comment inside a word: a control that skips comments reads one word across "
       "it"},
      {"NG55",
       "\"NG55\" has a word glued to the letters before it (`PCLOSG20`, `XG20`): a control reads the word, "
       "the post's "
       "checks of modes and waits may not; write a blank between them"},
      {"NX100.",
       "\"NX100.\" has a word glued to the letters before it (`PCLOSG20`, `XG20`): a control reads the word, "
       "the post's "
       "checks of modes and waits may not; write a blank between them"},
      // The seventh attack: words glued to keywords and letters, comments and blanks around a
      // comment, exponents, indirect writes, the mills' modes and the tool length.
      {"IF[#1EQ0]THENG50X100.",
       "\"IF[#1EQ0]THENG50X100.\" has a word glued to the letters before it (`PCLOSG20`, `XG20`): a control "
       "reads the word, the post's "
       "checks of modes and waits may not; write a blank between them"},
      {"IF [#1 EQ 0] THEN M100",
       "\"IF [#1 EQ 0] THEN M100\" gives a wait under IF [..] THEN: whether the control runs it is known "
       "only "
       "when the block runs; write it unconditionally, or not at all"},
      {"POPENG55",
       "\"POPENG55\" has a word glued to the letters before it (`PCLOSG20`, `XG20`): a control reads the "
       "word, the post's "
       "checks of modes and waits may not; write a blank between them"},
      {"G0 ZX9000.",
       "\"G0 ZX9000.\" has a word glued to the letters before it (`PCLOSG20`, `XG20`): a control reads the "
       "word, the post's "
       "checks of modes and waits may not; write a blank between them"},
      {"G0 X9000.E-3", "X9000. is outside channel 1's X travel -10..460 (channel.axis min/max)"},
      {"G (C)55",
       "\"G (C)55\" has a comment inside a word: a control that skips comments reads one word across it"},
      {"#[5200+21]=-500.",
       "\"#[5200+21]=-500.\" writes a variable by an expression (#[...]=), known only when the block runs: "
       "it "
       "may be a work offset's (#5000-#5999, #7000-#7999, #14000-#19999); write its number"},
      // The eighth attack: parameters, a jump, a number without its point, the mills' older work
      // offset variables, a G inside brackets, a word glued to a keyword.
      {"G10 L50",
       "\"G10 L50\" writes parameters (G10 L50): a parameter may hold a work offset or the travel limits; "
       "set "
       "them on the control, not from the program"},
      {"IF [#1 EQ 0] GOTO 77",
       "\"IF [#1 EQ 0] GOTO 77\" jumps (GOTO): the control would skip or repeat the post's blocks between it "
       "and its target"},
      {"G0 X460",
       "X460 in \"G0 X460\" has no decimal point: a control without decimal-point programming reads it in "
       "its "
       "least increment; write X460."},
      {"#2501=-500.",
       "\"#2501=-500.\" writes #2501, a system variable of the work offsets (#5000-#5999, #7000-#7999, "
       "#14000-#19999): every later position of the post would be off by it"},
      {"DPRNT[G4 A]X9000.", "X9000. is outside channel 1's X travel -10..460 (channel.axis min/max)"},
      {"PCLOSG20",
       "\"PCLOSG20\" has a word glued to the letters before it (`PCLOSG20`, `XG20`): a control reads the "
       "word, "
       "the post's checks of modes and waits may not; write a blank between them"},
      {"G43 H99",
       "\"G43 H99\" sets or cancels the tool length offset (G43, G43.4, G44, G49): the post writes each "
       "tool's "
       "offset itself, and every later Z of the post would be off by a tool length"},
  };
  for (const auto& [block, message] : cases) {
    CAPTURE(block);
    const test::posted p =
        post_with(std::string("[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"") + block + "\"]\n",
                  "PARTNO EV\nHEAD/1\nTURRET/1,1\nCATCHER\nFINI\n", "gate");
    CHECK_FALSE(p.ok);
    CHECK(p.diagnostics == std::string("job.cls:4:1: error: channel 1: ") + message + "\nCATCHER\n^\n");
    CHECK(p.files.empty());
  }
  SECTION("no increment where X is not known; an X without a G code is a move the post follows") {
    // Right after the post's home return: until the thirteenth round two U300. were held to the
    // travel's span together, and one U460. passed (X920 on a travel to 460).
    const test::posted q =
        post_with("[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"U300.\", \"U300.\"]\n",
                  "PARTNO EV\nHEAD/1\nTURRET/1,1\nCATCHER\nFINI\n", "gate-sum");
    const std::string unknown =
        "job.cls:4:1: error: channel 1: U300. in \"U300.\" is an increment of X where the post does not know "
        "where X is (after a home return, G30 or G53); write an absolute X\nCATCHER\n^\n";
    CHECK(q.diagnostics == unknown + unknown);  // each block of the event is read
    // The post follows it: the next rapid record writes X44. again.
    const test::posted r = post_with(
        "[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"X20.\"]\n",
        "PARTNO EV\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,800,CLW\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/22,0,2\nCATCHER\n"
        "RAPID\nGOTO/22,0,2\nGOTO/22,0,-30\nFINI\n",
        "gate-x");
    CHECK(r.diagnostics == "");
    CHECK(
        program_1(r) ==
        "%\nO1000 (EV)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG97 S800 M3\nG0 X44. Z2.\nX20.\n"
        "G0 X44. Z2.\nG1 Z-30. F0.2\nM100\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
    // Straight into the CL's feed move, the feed would start at X20 and cut a cone to X44 Z-30:
    // the comparison holds the blocks between two records to the CL's straight move (a lathe's
    // too since the thirty-seventh session), and nothing is written.
    const test::posted cone = post_with(
        "[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"X20.\"]\n",
        "PARTNO EV\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,800,CLW\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/22,0,2\nCATCHER\n"
        "GOTO/22,0,-30\nFINI\n",
        "gate-cone");
    CHECK(
        cone.diagnostics ==
        "job.cls:9:1: error: channel 1: the program's block `X20.` (line 9 of its program) is a rapid inside "
        "the CL's straight feed move from (22.000, 0.000, 2.000) to this record's point, to (10.000, 0.000, "
        "2.000): the feed then starts there\nGOTO/22,0,-30\n^\n");
    CHECK(cone.files.empty());
  }
  SECTION("the twelfth round: no increment of X after G30 or G53 has left it where the post cannot know") {
    const test::posted g30 = post_with(
        "[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"G30 U0.\", \"U460.\"]\n",
        "PARTNO EV\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,800,CLW\nRAPID\nGOTO/40,0,2\nCATCHER\nFINI\n", "gate-g30");
    CHECK(
        g30.diagnostics ==
        "job.cls:7:1: error: channel 1: U460. in \"U460.\" is an increment of X where the post does not know "
        "where X is (after a home return, G30 or G53); write an absolute X\nCATCHER\n^\n");
    // G52 X0. cancels a local frame and moves nothing: X is still 450, and U460. ends at 910.
    const test::posted g52 = post_with(
        "[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"X450.\", \"G52 X0.\", \"U460.\"]\n",
        "PARTNO EV\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,800,CLW\nRAPID\nGOTO/40,0,2\nCATCHER\nFINI\n", "gate-g52");
    CHECK(g52.diagnostics ==
          "job.cls:7:1: error: channel 1: U460. (incremental) takes X outside channel 1's X travel -10..460 "
          "(channel.axis min/max)\nCATCHER\n^\n");
  }
  SECTION("the ninth attack: increments across events, G28 of Z alone, G90 and G91 in one block") {
    // Two records of U380. after X80.: the second starts where the first left X (840 > 460).
    const test::posted two = post_with(
        "[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"U380.\"]\n",
        "PARTNO EV\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,800,CLW\nRAPID\nGOTO/40,0,2\nCATCHER\nCATCHER\nFINI\n",
        "gate-events");
    CHECK(two.diagnostics ==
          "job.cls:8:1: error: channel 1: U380. (incremental) takes X outside channel 1's X travel -10..460 "
          "(channel.axis min/max)\nCATCHER\n^\n");
    // G28 W0. moves Z alone: X stays at 80, and U-470. ends at -390.
    const test::posted w =
        post_with("[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"G28 W0.\", \"U-470.\"]\n",
                  "PARTNO EV\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,800,CLW\nRAPID\nGOTO/40,0,2\nCATCHER\nFINI\n",
                  "gate-g28w");
    CHECK(w.diagnostics ==
          "job.cls:7:1: error: channel 1: U-470. (incremental) takes X outside channel 1's X travel -10..460 "
          "(channel.axis min/max)\nCATCHER\n^\n");
  }
  SECTION("the shop's own forms post: G28 U0., G50 S2000, a dwell, a counter") {
    // (G10 P101 U0.1, a wear adjustment, and G92 X29.2 Z-20. F1.5, system A's thread cycle,
    // posted until the eleventh round: the whitelist refuses both now.)
    const test::posted q = post_with(
        "[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"G28 U0.\", \"G50 S2000\", \"G4 U1.5\", "
        "\"#601 = #601 + 1\", \"IF [#601 GT 10] THEN #3000=1 (LIMIT)\", \"G52 X0. Z+0\", \"#1=#2 XOR "
        "#3\", "
        "\"DPRNT[X#5041[44]]\", \"POPEN\", \"N10 G4 U0.5 (DWELL)\"]\n",
        "PARTNO EV\nHEAD/1\nTURRET/1,1\nCATCHER\nFINI\n", "gate-ok");
    CHECK(q.diagnostics == "");
    CHECK(program_1(q) ==
          "%\nO1000 (EV)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG28 U0.\nG50 S2000\nG4 U1.5\n"
          "#601 = #601 + 1\nIF [#601 GT 10] THEN #3000=1 (LIMIT)\nG52 X0. Z+0\n#1=#2 XOR "
          "#3\nDPRNT[X#5041[44]]\nPOPEN\nN10 G4 U0.5 (DWELL)\nM100\nM9\n"
          "G28 U0.\nG28 W0.\nM5\nM30\n%\n");
  }
}

TEST_CASE("a user block is held to the forms the post reads: a whitelist, not a list of bad forms",
          "[post][events]") {
  // Each form refused by the last step of the gate (machining/user_block_form.cpp), not by a
  // check of its own: a canned cycle stays on, a subprogram and a macro statement are not read,
  // a value by a variable cannot be checked, G28 through a point moves there first.
  const std::pair<const char*, const char*> cases[] = {
      {"G81 X0. Z-10. R2. F100.",
       "\"G81 X0. Z-10. R2. F100.\" gives G81, a code the post does not follow in a user block: what it does "
       "to the post's later blocks is not known (a cycle stays on, a macro call or a skip moves where the "
       "post cannot see; G10 sets offsets, parameters or tool life data; an arc's path is not held to the "
       "travel). A user block may give G0, G1, G4, G9, G17-G21, G28, G30, G40, G50, G52 X0., G53, G61, G64, "
       "G80, G90-G92, G94-G99"},
      {"G27 X0.",
       "\"G27 X0.\" gives G27, a code the post does not follow in a user block: what it does to the post's "
       "later blocks is not known (a cycle stays on, a macro call or a skip moves where the post cannot see; "
       "G10 sets offsets, parameters or tool life data; an arc's path is not held to the travel). A user "
       "block may give G0, G1, G4, G9, G17-G21, G28, G30, G40, G50, G52 X0., G53, G61, G64, G80, G90-G92, "
       "G94-G99"},
      {"G65 P9010 A1.",
       "\"G65 P9010 A1.\" gives G65, a code the post does not follow in a user block: what it does to the "
       "post's later blocks is not known (a cycle stays on, a macro call or a skip moves where the post "
       "cannot see; G10 sets offsets, parameters or tool life data; an arc's path is not held to the "
       "travel). A user block may give G0, G1, G4, G9, G17-G21, G28, G30, G40, G50, G52 X0., G53, G61, G64, "
       "G80, G90-G92, G94-G99"},
      {"M98 P1000",
       "\"M98 P1000\" calls a subprogram or returns from one (M98): what the subprogram moves and the waits "
       "in it are not the post's to read, and M99 in the main program starts it again"},
      {"M99",
       "\"M99\" calls a subprogram or returns from one (M99): what the subprogram moves and the waits in it "
       "are not the post's to read, and M99 in the main program starts it again"},
      {"IF [#1 EQ 0] THEN X20.",
       "\"IF [#1 EQ 0] THEN X20.\" is a macro statement (IF, WHILE, DO, END, GOTO): the post does not follow "
       "a program's branches and loops; write the blocks it stands for"},
      {"WHILE [#1 LT 3] DO1",
       "\"WHILE [#1 LT 3] DO1\" is a macro statement (IF, WHILE, DO, END, GOTO): the post does not follow a "
       "program's branches and loops; write the blocks it stands for"},
      {"#1=1 G0 X20.",
       "\"#1=1 G0 X20.\" has more than an assignment after its `=` (words, a comparison, a second "
       "statement): the control reads all of it as one expression or stops with an alarm; write the "
       "assignment in a block of its own"},
      {"#1",
       "\"#1\" uses a variable outside an assignment `#<number>=...` and outside a word's value: the post "
       "reads neither; write the number"},
      {"S#100 M3",
       "\"S#100 M3\" gives S by a variable or an expression: the post cannot read the value; write the "
       "number"},
      {"G28 X100.",
       "\"G28 X100.\" returns to the reference position through the intermediate point X100.: G28 and G30 go "
       "there first, at rapid, and the post cannot follow it; give no move on the way (G28 U0. or G28 W0.)"},
      {"G28 W10.",
       "\"G28 W10.\" returns to the reference position through the intermediate point W10.: G28 and G30 go "
       "there first, at rapid, and the post cannot follow it; give no move on the way (G28 U0. or G28 W0.)"},
      {"G1 X20. ,C1.",
       "\"G1 X20. ,C1.\" has ',' where the post reads a word (an address and a number), an assignment "
       "(#1=...) or a print statement: a form the post cannot read is refused"},
      {"G0 X20. Z",
       "\"G0 X20. Z\" has the address Z without its number: write Z and a number, or leave it out"},
      // The eleventh round: a lathe cycle's taper, offsets and control settings written, an M
      // code with a point, G53 with G28.
      {"G90 X50. Z-20. R-300. F0.2",
       "\"G90 X50. Z-20. R-300. F0.2\" gives G90, on this lathe (G-code system A) a turning, threading or "
       "facing cycle: its passes and its taper (R) take the tool where the post does not follow it; let the "
       "CL cut them"},
      {"G92 X29.2 Z-20. F1.5",
       "\"G92 X29.2 Z-20. F1.5\" gives G92, on this lathe (G-code system A) a turning, threading or facing "
       "cycle: its passes and its taper (R) take the tool where the post does not follow it; let the CL cut "
       "them"},
      {"G10 P101 U0.1",
       "\"G10 P101 U0.1\" gives G10, a code the post does not follow in a user block: what it does to the "
       "post's later blocks is not known (a cycle stays on, a macro call or a skip moves where the post "
       "cannot see; G10 sets offsets, parameters or tool life data; an arc's path is not held to the "
       "travel). A user block may give G0, G1, G4, G9, G17-G21, G28, G30, G40, G50, G52 X0., G53, G61, G64, "
       "G80, G90-G92, G94-G99"},
      {"G10 L3",
       "\"G10 L3\" gives G10, a code the post does not follow in a user block: what it does to the post's "
       "later blocks is not known (a cycle stays on, a macro call or a skip moves where the post cannot see; "
       "G10 sets offsets, parameters or tool life data; an arc's path is not held to the travel). A user "
       "block may give G0, G1, G4, G9, G17-G21, G28, G30, G40, G50, G52 X0., G53, G61, G64, G80, G90-G92, "
       "G94-G99"},
      {"#2101=-100.",
       "\"#2101=-100.\" writes #2101, a tool offset (#2001-#2999, #10001-#13999): every later cut of that "
       "tool would be off by it, and the control keeps it for the next job: set it at the machine, not from "
       "a machine file's block"},
      {"#3004=3",
       "\"#3004=3\" writes #3004, a control setting that takes single block (#3003) or feed hold and the "
       "feed override (#3004) away from the operator: set it at the machine, not from a machine file's "
       "block"},
      {"#1100=1",
       "\"#1100=1\" writes #1100, an output to the machine's own logic (#1100-#1199): set it at the machine, "
       "not from a machine file's block"},
      {"M100.", "\"M100.\" gives M100., an M code with a decimal point: write the code as a whole number"},
      // The twelfth round: arcs, offset numbers, an axis the channel lacks (the lathe's direct
      // drawing angle), G53 with an increment, the macro interrupt, the settings word.
      {"G2 I-200. F0.2",
       "\"G2 I-200. F0.2\" gives G2, a code the post does not follow in a user block: what it does to the "
       "post's later blocks is not known (a cycle stays on, a macro call or a skip moves where the post "
       "cannot see; G10 sets offsets, parameters or tool life data; an arc's path is not held to the "
       "travel). A user block may give G0, G1, G4, G9, G17-G21, G28, G30, G40, G50, G52 X0., G53, G61, G64, "
       "G80, G90-G92, G94-G99"},
      {"D50",
       "\"D50\" gives D50, a cutter compensation offset number: the post writes each tool's own, and every "
       "later cut would take this one"},
      {"G1 A150. W-100. F0.2",
       "\"G1 A150. W-100. F0.2\" gives A150., a word of an axis this channel does not have: a Fanuc lathe "
       "reads A as the angle of a direct drawing move"},
      {"G53 U500.",
       "\"G53 U500.\" gives G53 with the increment U500.: some controls move by it in machine coordinates, "
       "others ignore G53; write an absolute machine position"},
      {"M96 P9000",
       "\"M96 P9000\" gives M96, the custom macro interrupt on a Fanuc (a jump to a subprogram on a signal): "
       "what it runs is not the post's to read"},
      {"#3005=4",
       "\"#3005=4\" writes #3005, the control's settings (#3005: among them inch input and the mirror "
       "image): set it at the machine, not from a machine file's block"},
      {"M69",
       "\"M69\" gives M69, the machine's chuck open of the main spindle: the post gives it itself where the "
       "part and the spindles allow it"},
      {"G53 G28 X-9000.",
       "\"G53 G28 X-9000.\" gives G53 with G28 or G30: two codes of one group in one block; write them in "
       "blocks of their own"},
  };
  for (const auto& [block, message] : cases) {
    CAPTURE(block);
    const test::posted p =
        post_with(std::string("[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"") + block + "\"]\n",
                  "PARTNO EV\nHEAD/1\nTURRET/1,1\nCATCHER\nFINI\n", "whitelist");
    CHECK_FALSE(p.ok);
    CHECK(p.diagnostics == std::string("job.cls:4:1: error: channel 1: ") + message + "\nCATCHER\n^\n");
    CHECK(p.files.empty());
  }
}

TEST_CASE("a wait code an event writes is checked like the post's own: unpaired, nothing is written",
          "[post][events]") {
  // M101 is a wait code of the machine (waits 100..102, no partner list); channel 2 never waits for it.
  const test::posted p = post_with(
      "[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"M101\"]\n",
      "PARTNO EV\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,800,CLW\nCATCHER\nRAPID\nGOTO/20,0,5\nFINI\n", "wait");
  CHECK_FALSE(p.ok);
  // The self-check's finding, at the CL record whose event wrote the wait.
  CHECK(
      p.diagnostics.starts_with("job.cls:5:1: error: deadlock: channel 1 waits on M101 at job.cls:5 while "
                                "channel 2 waits on M100 at job.cls:8 (different codes, Fanuc PS0160)\n"
                                "CATCHER\n^\n"));
  CHECK(
      p.diagnostics.ends_with("/out/EV_1.nc:8:1: note: the wait in the program as it would have been written "
                              "(no file is written)\nM101\n^\n"));
  CHECK(p.files.empty());
}

TEST_CASE("an event wait paired in both channels posts", "[post][events]") {
  // Both channels start with M101: the control (and the self-check) pairs them.
  const test::posted p = post_with("[events]\nprogram_start.after = [\"M101\"]\n",
                                   "PARTNO EV\nHEAD/1\nTURRET/1,1\nFINI\n", "paired");
  CHECK(program_1(p) ==
        "%\nO1000 (EV)\nG0 G18 G21 G40 G54 G80 G99\nM101\nG28 U0.\nG28 W0.\nT0101\nM100\nM9\nG28 U0.\n"
        "G28 W0.\nM5\nM30\n%\n");
  CHECK(program_1(p, "EV_2.nc") ==
        "%\nO1000 (EV)\nG0 G18 G21 G40 G54 G80 G99\nM101\nG28 U0.\nG28 W0.\nM100\nM9\nG28 U0.\nG28 "
        "W0.\nM5\nM30\n%\n");
}

TEST_CASE("[events] in the machine file: what the loader refuses", "[machines][events]") {
  const std::string head = test::machine_head + test::two_channels;
  CHECK(test::machine_error_of(head + "[events]\ntool_change.after = [\"S{rpm}\"]\n") ==
        "m.toml:13:22: error: events.tool_change.after: template \"S{rpm}\" names {rpm}, which is not known "
        "there (it "
        "is given {name}, {channel}, {tool}, {offset}, {text}, {x}, {y}, {z})");
  // {x} at the program's start (no move yet), {rpm} at a section: each event's own set.
  CHECK(test::machine_error_of(head + "[events]\nprogram_start.after = [\"(X{x})\"]\n") ==
        "m.toml:13:24: error: events.program_start.after: template \"(X{x})\" names {x}, which is not known "
        "there (it is given {channel})");
  CHECK(test::machine_error_of(head + "[events]\nsection.before = [\"S{rpm}\"]\n") ==
        "m.toml:13:19: error: events.section.before: template \"S{rpm}\" names {rpm}, which is not known "
        "there (it is given {name}, {channel}, {tool}, {offset}, {x}, {y}, {z})");
  CHECK(test::machine_error_of(head + "[events]\nspindle_start.after = [\"({name})\"]\n") ==
        "m.toml:13:24: error: events.spindle_start.after: template \"({name})\" names {name}, which is not "
        "known there (it is given {channel}, {rpm}, {x}, {y}, {z})");
  // A name no event gives is no placeholder at all: refused as a bad template, as before.
  CHECK(test::machine_error_of(head + "[events]\nsection.after = [\"(W{w})\"]\n") ==
        "m.toml:13:18: error: events.section.after: bad template \"(W{w})\": argument not found");
  CHECK(
      test::machine_error_of(head + "[events]\nprogram_start.before = [\"M10\"]\n") ==
      "m.toml:13:24: error: events.program_start takes `after` only (blocks before the safe start belong in "
      "program.header)");
  CHECK(test::machine_error_of(head + "[events]\nprogram_end.after = [\"M10\"]\n") ==
        "m.toml:13:21: error: events.program_end takes `before` only (blocks after the last ones belong in "
        "program.footer)");
  CHECK(test::machine_error_of(head + "[events]\ntool_swap.after = [\"M10\"]\n") ==
        "m.toml:13:1: error: unknown key 'events.tool_swap'");
  CHECK(test::machine_error_of(head + "[[events.record]]\nmajor = \"CATCHER\"\n") ==
        "m.toml:12:1: error: events.record.blocks is required");
  CHECK(test::machine_error_of(head + "[[events.record]]\nmajor = \"1CATCHER\"\nblocks = [\"M10\"]\n") ==
        "m.toml:13:9: error: events.record.major \"1CATCHER\" is not a CL major word");
  CHECK(test::machine_error_of(head + "[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"M{code}\"]\n") ==
        "m.toml:14:11: error: events.record.blocks: template \"M{code}\" names {code}, which is not known "
        "there (it "
        "is given {channel}, {text}, {x}, {y}, {z})");
}

TEST_CASE("a wait code an on_block replacement adds is counted by the writer, at its CL record",
          "[post][events][script]") {
  // The first G28 U0. of each channel (its tool change) becomes G28 U0. M101 (a wait code of the
  // machine; the home move kept: on_block may not leave out an axis word of the post's).
  // SYNCTR: the channels run at once, each from its tool change to the mark (M100).
  const std::string job =
      "PARTNO EV\nHEAD/1\nTURRET/1,1\nSYNCTR/NEXT\nHEAD/2\nTURRET/11,11\nSYNCTR/NEXT\nFINI\n";
  const std::string lua =
      "function on_block(text, ctx)\n"
      "  if text == 'G28 U0.' and not post.vars[ctx.channel] and ctx.channel <= CHANNELS then\n"
      "    post.vars[ctx.channel] = true\n"
      "    return 'G28 U0. M101'\n"
      "  end\n"
      "end\n";
  const auto with = [&](const std::string& channels, const std::string& tag) {
    std::string l = lua;
    l.replace(l.find("CHANNELS"), 8, channels);
    return post_with_script("", l, job, tag);
  };
  SECTION("in one channel: unpaired, the self-check's error at the tool call that wrote it") {
    const test::posted p = with("1", "onblock-unpaired");
    CHECK_FALSE(p.ok);
    CHECK(p.diagnostics.starts_with(
        "job.cls:3:1: error: deadlock: channel 1 waits on M101 at job.cls:3 while channel 2 waits on M100 at "
        "job.cls:7 (different codes, Fanuc PS0160)\nTURRET/1,1\n^\n"));
    CHECK(
        p.diagnostics.ends_with("/out/EV_1.nc:4:9: note: the wait in the program as it would have been "
                                "written (no file is written)\nG28 U0. M101\n        ^\n"));
    CHECK(p.files.empty());
  }
  SECTION("a replacement that leaves out the post's home move is refused") {
    const test::posted p = post_with_script(
        "", "function on_block(text, ctx)\n  if text == 'G28 U0.' then return 'M101' end\nend\n", job,
        "onblock-lost");
    CHECK(p.diagnostics.starts_with(
        "job.cls:3:1: error: channel 1: on_block replaces \"G28 U0.\" with \"M101\", "
        "which leaves out the word U0.: the post's next blocks rely on it; keep it in "
        "the block you give back\n"));
    CHECK(p.files.empty());
  }
  SECTION("the post's own wait dropped in one channel is no wait of that channel") {
    const test::posted p = post_with_script(
        "",
        "function on_block(text, ctx)\n  if ctx.channel == 1 and text == 'M100' then return false end\nend\n",
        job, "onblock-drop");
    CHECK_FALSE(p.ok);
    CHECK(p.diagnostics.starts_with(
        "job.cls:7:1: error: wait M100 of channel 2 is never met: channel 1 ends at "
        "job.cls:8 without a matching wait\nSYNCTR/NEXT\n^\n"));
    CHECK(
        p.diagnostics.ends_with("/out/EV_2.nc:7:1: note: the wait in the program as it would have been "
                                "written (no file is written)\nM100\n^\n"));
    CHECK(p.files.empty());
  }
  SECTION("in both: paired, it posts") {
    const test::posted p = with("2", "onblock-paired");
    CHECK(program_1(p) ==
          "%\nO1000 (EV)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0. M101\nG28 W0.\nT0101\nM100\nM9\nG28 U0.\nG28 "
          "W0.\n"
          "M5\nM30\n%\n");
    CHECK(program_1(p, "EV_2.nc") ==
          "%\nO1000 (EV)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0. M101\nG28 W0.\nT1111\nM100\nM9\n"
          "G28 U0.\nG28 W0.\nM5\nM30\n%\n");
  }
}

TEST_CASE("the channel's modes go back on after a script's blocks and on_block may not change them",
          "[post][events][script]") {
  const std::string job = "PARTNO EV\nHEAD/1\nTURRET/1,1\nFINI\n";
  SECTION("post.emit's G98 in a hook: the post's G99 follows") {
    const test::posted p =
        post_with_script("", "function on_tool_change(tool) post.emit('G0 G98') end\n", job, "script-modes");
    CHECK(p.diagnostics == "");
    CHECK(program_1(p) ==
          "%\nO1000 (EV)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG0 G98\nG99\n"
          "M100\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
  }
  SECTION("a G98 after a nested comment's first ')' is a G98: the post's G99 follows") {
    const test::posted p =
        post_with_script("", "function on_tool_change(tool) post.emit('(()G98') end\n", job, "script-nested");
    CHECK(program_1(p) ==
          "%\nO1000 (EV)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\n(()G98\nG99\n"
          "M100\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
  }
  SECTION("G20.0 is G20: refused as well") {
    const test::posted p =
        post_with_script("", "function on_tool_change(tool) post.emit('G20.0') end\n", job, "script-inch-0");
    CHECK_FALSE(p.ok);
    CHECK(p.diagnostics.starts_with(
        "job.cls:3:1: error: channel 1: post.emit writes \"G20.0\": G20 in a program in "
        "millimetres (G21)"));
  }
  SECTION("post.emit's G20 in a metric program is refused") {
    const test::posted p =
        post_with_script("", "function on_tool_change(tool) post.emit('G20') end\n", job, "script-inch");
    CHECK_FALSE(p.ok);
    CHECK(p.diagnostics ==
          "job.cls:3:1: error: channel 1: post.emit writes \"G20\": G20 in a program in millimetres (G21); "
          "every "
          "later word would be read in inches\nTURRET/1,1\n^\n");
    CHECK(p.files.empty());
  }
  SECTION("on_block's replacement with another feed mode is refused") {
    const test::posted p =
        post_with_script("", "function on_block(text) if text == 'T0101' then return 'T0101 G98' end end\n",
                         job, "script-g98");
    CHECK_FALSE(p.ok);
    CHECK(p.diagnostics ==
          "job.cls:3:1: error: channel 1: on_block gives back \"T0101 G98\": it changes the channel's feed "
          "mode "
          "in the middle of the post's blocks, and no block of the post's puts it back (write it from an "
          "event, "
          "where the post restores the mode after it)\nTURRET/1,1\n^\n"
          "t.lua: note: channel 1: the block 'T0101 G98' came from the script (on_block)\n");
    CHECK(p.files.empty());
  }
}

TEST_CASE("a script error quotes the script line with a caret under its first word",
          "[post][events][script]") {
  const test::posted p =
      post_with_script("", "function on_tool_change(tool)\n\t  post.emit(tool.life + 1)\nend\n",
                       "PARTNO EV\nHEAD/1\nTURRET/1,1\nFINI\n", "script-caret");
  CHECK_FALSE(p.ok);
  CHECK(p.diagnostics ==
        "t.lua:2: error: attempt to perform arithmetic on a nil value (field 'life')\n"
        "\t  post.emit(tool.life + 1)\n\t  ^\n"
        "job.cls:3:1: note: channel 1: the script failed while this record was posted\nTURRET/1,1\n^\n");
  CHECK(p.files.empty());
}

namespace {

// Built-in machine `name` with `events` appended.
test::posted post_on(const std::string& name, const std::string& events, const std::string& cl,
                     const std::string& tag) {
  const std::string text =
      test::read_file(std::string(TWINPOST_SOURCE_DIR) + "/machines/builtin/" + name + ".toml") + "\n" +
      events;
  return test::post_in_fresh_dir(cl, parse_machine(text, "ev.toml"), "events-" + tag);
}

const std::string section_events = R"T([events]
section.before = ["(SECTION {name} T{tool:02} OFFSET {offset})"]
section.after = ["(END {name} T{tool:02} AT X{x} Z{z})"]
operation.after = ["(OPERATION {name})"]
tool_change.after = ["(T{tool:02} {name})"]
program_end.before = ["(PROGRAM END AT X{x} Z{z})"]
)T";

}  // namespace

TEST_CASE(
    "events.section: one tool, spindle and operation of a channel, from its first move to before the next",
    "[post][events]") {
  // Two operations of tool 1 in channel 1 (a section each), tool 11 in channel 2 while channel
  // 1 waits: each channel's sections in its own program, closed before the next tool change,
  // the next operation and the program's end; {x} as written (diameter; the lower turret's X).
  const std::string job =
      "PARTNO EV\nHEAD/1\nTOOL PATH/ROUGH_OD,TOOL,OD ROUGH\nTURRET/1,1\nSPINDL/RPM,800,CLW\nRAPID\n"
      "GOTO/30,0,2\nFEDRAT/0.2,MMPR\nGOTO/30,0,-20\nTOOL PATH/FINISH_OD,TOOL,OD ROUGH\nGOTO/29,0,-20\n"
      "GOTO/29,0,2\nTOOL PATH/DRILL_1,TOOL,DRILL 8\nTURRET/3,3\nRAPID\nGOTO/0,0,5\nHEAD/2\n"
      "TOOL PATH/BACK_OD,TOOL,OD LOWER\nTURRET/11,11\nRAPID\nGOTO/-20,0,3\nFINI\n";
  const test::posted p = post_with(section_events, job, "section", sync_policy::sequential);
  CHECK(
      program_1(p) ==
      "%\nO1000 (EV)\nG0 G18 G21 G40 G54 G80 G99\n(ROUGH_OD,TOOL,OD ROUGH)\n(OPERATION ROUGH_OD)\n"
      "G28 U0.\nG28 W0.\nT0101\n(T01 OD ROUGH)\nG97 S800 M3\n(SECTION ROUGH_OD T01 OFFSET 1)\n"
      "G0 X60. Z2.\nG1 Z-20. F0.2\n(END ROUGH_OD T01 AT X60. Z-20.)\n(FINISH_OD,TOOL,OD ROUGH)\n"
      "(OPERATION FINISH_OD)\n(SECTION FINISH_OD T01 OFFSET 1)\nX58.\nZ2.\n(END FINISH_OD T01 AT X58. Z2.)\n"
      "(DRILL_1,TOOL,DRILL 8)\n(OPERATION DRILL_1)\nG28 U0.\nG28 W0.\nT0303\n(T03 DRILL 8)\n"
      "(SECTION DRILL_1 T03 OFFSET 3)\nG0 X0. Z5.\nM100\nM101\n(END DRILL_1 T03 AT X0. Z5.)\n"
      "(PROGRAM END AT X0. Z5.)\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
  CHECK(program_1(p, "EV_2.nc") ==
        "%\nO1000 (EV)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nM100\n(BACK_OD,TOOL,OD LOWER)\n"
        "(OPERATION BACK_OD)\nT1111\n(T11 OD LOWER)\n(SECTION BACK_OD T11 OFFSET 11)\nG0 X40. Z3.\nM101\n"
        "(END BACK_OD T11 AT X40. Z3.)\n(PROGRAM END AT X40. Z3.)\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
}

TEST_CASE(
    "events.section on a 4-axis mill: a new tool axis at a rapid opens a section, {y} where the channel has "
    "Y",
    "[post][events]") {
  const std::string events = R"T([events]
section.before = ["(SECTION {name} T{tool:02})"]
section.after = ["(END {name} AT X{x} Y{y} Z{z})"]
)T";
  const std::string job =
      "PARTNO EV\nUNITS/MM\nTOOL "
      "PATH/TOP,TOOL,EM10\nLOADTL/1\nSPINDL/RPM,3000,CLW\nRAPID\nGOTO/10,20,5,0,0,1\n"
      "FEDRAT/500,MMPM\nGOTO/10,20,-1,0,0,1\nGOTO/30,20,-1,0,0,1\nRAPID\nGOTO/30,20,40,0,0,1\n"
      "RAPID\nGOTO/10,-40,5,0,-1,0\nGOTO/10,-30,5,0,-1,0\nLOADTL/2\nSPINDL/RPM,2000,CLW\nRAPID\nGOTO/"
      "0,0,50,0,-1,0\nFINI\n";
  const test::posted p = post_on("rotary-4axis", events, job, "section-mill");
  // The second section: the same tool and operation, the tool axis along -Y from a rapid (A-90.).
  CHECK(program_1(p, "EV.nc") ==
        "%\nO5003 (EV)\nG21\nG90 G94 G17 G40 G49 G80\n(TOP,TOOL,EM10)\nG91 G28 Z0.\nG90\nT01 M6\nG54\nS3000 "
        "M3\n"
        "(SECTION TOP T01)\nG0 A0.\nG0 X10. Y20.\nG0 G43 H1 X10. Y20. Z5. A0.\nG1 Z-1. F500.\nX30.\nG0 Z40.\n"
        "(END TOP AT X30. Y20. Z40.)\n(SECTION TOP T01)\nG0 A-90.\nG0 X10. Y5.\nG1 Z30.\n"
        "(END TOP AT X10. Y5. Z30.)\nG91 G28 Z0.\nG90\nM5\nG49\nT02 M6\nS2000 M3\n(SECTION TOP T02)\n"
        "G0 A-90.\nG0 X0. Y50.\nG0 G43 H2 X0. Y50. Z0. A-90.\n(END TOP AT X0. Y50. Z0.)\nM9\nM5\n"
        "G91 G28 Z0.\nG90\nG49\nM30\n%\n");
}

TEST_CASE("{x} before the channel's first move and {y} on a channel without Y are errors at the CL record",
          "[post][events]") {
  const std::string job =
      "PARTNO EV\nHEAD/1\nTURRET/1,1\nRAPID\nGOTO/30,0,2\nTURRET/3,3\nRAPID\nGOTO/0,0,5\nFINI\n";
  const test::posted p = post_with("[events]\nsection.before = [\"(FROM X{x:>8})\"]\n", job, "x-first");
  CHECK_FALSE(p.ok);
  CHECK(
      p.diagnostics ==
      "job.cls:5:1: error: channel 1: events.section.before: \"(FROM X{x:>8})\" names {x}, but channel 1 has "
      "made no move before it (no position yet)\nGOTO/30,0,2\n^\n");
  CHECK(p.files.empty());
  SECTION("after a move it is the position the tool left, with the template's format spec") {
    const test::posted q = post_with("[events]\nsection.after = [\"(AT X{x:>8} Z{z})\"]\n", job, "x-later");
    CHECK(
        program_1(q) ==
        "%\nO1000 (EV)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG0 X60. Z2.\n(AT X     60. "
        "Z2.)\n"
        "G28 U0.\nG28 W0.\nT0303\nG0 X0. Z5.\nM100\n(AT X      0. Z5.)\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
  }
  SECTION("{y} on the lathe's channel") {
    const test::posted q = post_with("[events]\ntool_change.before = [\"(Y{y})\"]\n", job, "y-lathe");
    CHECK(q.diagnostics ==
          "job.cls:3:1: error: channel 1: events.tool_change.before: \"(Y{y})\" names {y}, but channel 1 has "
          "no "
          "Y axis\nTURRET/1,1\n^\n"
          "job.cls:6:1: error: channel 1: events.tool_change.before: \"(Y{y})\" names {y}, but channel 1 has "
          "no "
          "Y axis\nTURRET/3,3\n^\n");
  }
}

TEST_CASE("a CL name in a template cannot end its comment, start a line or stop the tape", "[post][events]") {
  // Issue 38, sixth and seventh attacks: `(OP {name})` with an operation named `ROUGH 50%)G55(X`
  // wrote a tape mark, or G55 outside the comment. The name's '%', parentheses and control bytes
  // become blanks, as in the post's own comments.
  const test::posted p =
      post_with("[events]\noperation.before = [\"(OP {name})\"]\n",
                "PARTNO EV\nHEAD/1\nTURRET/1,1\nOPFEATSTART/ROUGH 50%)G55(X\nFINI\n", "cl-name");
  CHECK(p.diagnostics == "");
  CHECK(program_1(p).find("\n(OP ROUGH 50  G55 X)\n") != std::string::npos);
}

TEST_CASE("a user block may not raise the speed clamp above the CL's, nor turn the indexing head",
          "[post][events]") {
  // The eleventh round: `G92 S9999 R1` on the Integrex (its own clamp block) before a face to X0
  // under G96 with MAXRPM 3000, and `G0 G53 B90.` before a turning cut.
  const std::string css_job =
      "PARTNO "
      "EV\nHEAD/1\nTLDATA/TURN\nLOADTL/1\nSPINDL/SMM,200,CLW,MAXRPM,3000\nRAPID\nGOTO/40,0,2\nCATCHER\n"
      "FEDRAT/0.2,MMPR\nGOTO/40,0,-10\nGOTO/0,0,-10\nRAPID\nGOTO/45,0,5\nFINI\n";
  const auto integrex = [&](const std::string& block, const std::string& tag) {
    const std::string text = std::string(*builtin_machine_text("integrex-i200st")) +
                             "\n[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"" + block + "\"]\n";
    return test::post_in_fresh_dir(css_job, parse_machine(text, "integrex-events.toml"), "events-" + tag);
  };
  const test::posted clamp = integrex("G92 S9999 R1", "clamp");
  CHECK(
      clamp.diagnostics ==
      "job.cls:8:1: error: channel 1: \"G92 S9999 R1\" clamps the spindle at 9999 rpm, above the CL's MAXRPM "
      "of 3000: under constant surface speed the spindle would run up to it near the centre\nCATCHER\n^\n");
  CHECK(clamp.files.empty());
  // A sign on the S is the same S (the twelfth round).
  CHECK_THAT(
      integrex("G92 S+9999 R1", "clamp-sign").diagnostics,
      Catch::StartsWith("job.cls:8:1: error: channel 1: \"G92 S+9999 R1\" clamps the spindle at 9999 rpm"));
  // At or under the CL's clamp it posts.
  CHECK(integrex("G92 S2500 R1", "clamp-ok").ok);
  // The Integrex's upper head has a kinematic chain: its program is not compared with the CL,
  // so no user block sets a spindle there (the thirteenth round).
  CHECK(
      integrex("M204 S4000", "spindle").diagnostics ==
      "job.cls:8:1: error: channel 1: \"M204 S4000\" sets a spindle's speed or direction on channel 1, whose "
      "program is not compared with the CL (a kinematic chain): the post writes the spindle from the CL's "
      "SPINDL there\nCATCHER\n^\n");
  // A bare H in G43: another tool's length for every later Z.
  CHECK(integrex("H2", "h-word").diagnostics ==
        "job.cls:8:1: error: channel 1: \"H2\" gives H2, a tool length offset number: the post writes each "
        "tool's own, and every later cut would take this one\nCATCHER\n^\n");
  const test::posted head = integrex("G0 G53 B90.", "head");
  CHECK(head.diagnostics ==
        "job.cls:8:1: error: channel 1: \"G0 G53 B90.\" turns the indexing head (B): the post indexes it for "
        "each tool, where the tool must point, and the next cut would run at the angle this block leaves\n"
        "CATCHER\n^\n");
  CHECK(head.files.empty());
  // On the lathe, its G50 clamp over the spindle's limit with no CL clamp in force.
  const test::posted lathe = post_with("[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"G50 S9999\"]\n",
                                       "PARTNO EV\nHEAD/1\nTURRET/1,1\nCATCHER\nFINI\n", "clamp-lathe");
  CHECK_THAT(lathe.diagnostics,
             Catch::StartsWith("job.cls:4:1: error: channel 1: \"G50 S9999\" clamps the spindle "
                               "at 9999 rpm, above the main spindle's limit of "));
}

TEST_CASE("events: a rotary word without its decimal point is refused", "[post][events]") {
  // Attack 47: `G0 C120` in a record's block on the 31i's path 3 (a C axis) is 0.12 degrees on
  // a control with decimal-point programming off; the comparison then found the next hole 52 mm
  // off. The gate says so at the block, as it does for X460.
  const std::string machine_text =
      test::read_file(std::string(TWINPOST_SOURCE_DIR) + "/machines/builtin/fanuc-31i-3path.toml") +
      "\n[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"BLOCK\"]\n";
  for (const auto& [block, word] :
       std::vector<std::pair<std::string, std::string>>{{"G0 C120", "C120"}, {"G0 C-90", "C-90"}}) {
    std::string text = machine_text;
    text.replace(text.find("BLOCK"), 5, block);
    const test::posted p = test::post_in_fresh_dir("PARTNO EV\nHEAD/3\nLOADTL/12\nCATCHER\nFINI\n",
                                                   parse_machine(text, "m31.toml"), "events-rotary-point");
    CHECK(p.diagnostics ==
          fmt::format("job.cls:4:1: error: channel 3: {} in \"{}\" has no decimal point: a control "
                      "without decimal-point programming reads it in its least increment (0.001 "
                      "degree); write {}.\nCATCHER\n^\n",
                      word, block, word));
    CHECK_FALSE(p.ok);
  }
  // With its point, and C0 (the same either way), it passes the gate.
  std::string text = machine_text;
  text.replace(text.find("BLOCK"), 5, "G0 C0");
  CHECK(test::post_in_fresh_dir("PARTNO EV\nHEAD/3\nLOADTL/12\nCATCHER\nFINI\n",
                                parse_machine(text, "m31.toml"), "events-rotary-zero")
            .diagnostics.find("decimal point") == std::string::npos);
}

TEST_CASE("on_block sees the header and footer blocks, each once, with ctx.part", "[post][events][script]") {
  // Each frame block announced by a comment before it (post.emit), the footer's return home
  // moved to G30; the count of header calls written at the end (one header block a channel).
  const std::string lua =
      "function on_block(text, ctx)\n"
      "  if ctx.part ~= 'body' then post.emit('(' .. string.upper(ctx.part) .. ')') end\n"
      "  if ctx.part == 'header' then post.vars.n = (post.vars.n or 0) + 1 end\n"
      "  if ctx.part == 'footer' and text:sub(1, 4) == 'G28 ' then return 'G30 ' .. text:sub(5) end\n"
      "  if ctx.part == 'footer' and text == 'M5' then return 'M5 (HEADERS ' .. post.vars.n .. ')' end\n"
      "  if ctx.part == 'header' then return text .. ' (' .. string.upper(ctx.part .. ' of ' .. ctx.program) "
      ".. ')' end\n"
      "end\n";
  const std::string ev1 =
      "%\nO1000 (EV)\n(HEADER)\nG0 G18 G21 G40 G54 G80 G99 (HEADER OF EV_1.NC)\nG28 U0.\nG28 W0.\nT0101\n"
      "M100\n(FOOTER)\nM9\n(FOOTER)\nG30 U0.\n(FOOTER)\nG30 W0.\n(FOOTER)\nM5 (HEADERS 2)\nM30\n%\n";
  SECTION("header, body and footer") {
    const test::posted p = post_with_script("", lua, "PARTNO EV\nHEAD/1\nTURRET/1,1\nFINI\n", "frame");
    CHECK(program_1(p) == ev1);
    CHECK(program_1(p, "EV_2.nc") ==
          "%\nO1000 (EV)\n(HEADER)\nG0 G18 G21 G40 G54 G80 G99 (HEADER OF EV_2.NC)\nG28 U0.\nG28 "
          "W0.\nM100\n(FOOTER)\nM9\n"
          "(FOOTER)\nG30 U0.\n(FOOTER)\nG30 W0.\n(FOOTER)\nM5 (HEADERS 2)\nM30\n%\n");
  }
  SECTION("a channel's own home in the footer: each block asked for itself") {
    // Attack 67 H3: a channel home of more blocks than codes.home shared a footer index, and the
    // script's answer for one was written for the other (path 3 ended `G30 V0.` twice, Z never
    // homed).
    const std::string dir = test::fresh_temp_dir("script-frame-home3");
    test::write_file(dir + "/t.lua", lua);
    machine m = parse_machine(twin_with(""), "twin-events.toml");
    m.events.script = "t.lua";
    m.events.script_path = dir + "/t.lua";
    m.channels[0].home = {"G28 U0.", "G28 W0.", "M1"};
    const test::posted p =
        test::post_in_fresh_dir("PARTNO EV\nHEAD/1\nTURRET/1,1\nFINI\n", m, "events-home3");
    std::filesystem::remove_all(dir);
    const std::string f = program_1(p);
    CHECK(f.substr(f.find("M100\n")) ==
          "M100\n(FOOTER)\nM9\n(FOOTER)\nG30 U0.\n(FOOTER)\nG30 W0.\n(FOOTER)\nM1\n(FOOTER)\nM5 (HEADERS "
          "2)\nM30\n%\n");
  }
  SECTION("a script that rewrites the way out of the cut: the footer still homes") {
    // Attack 68 H1: the drill left in the cut went out by `G28 W0.`, which the script wrote as
    // `G30 W0.`; the footer, told that G28 W0. was written, left its own out: Z ended at G30.
    const test::posted p = post_with_script(
        "",
        "function on_block(text, ctx)\n  if ctx.part == 'body' and text == 'G28 W0.' then return 'G30 W0.' "
        "end\nend\n",
        "PARTNO EV\nHEAD/1\nTURRET/1,1\nTLDATA/DRILL,8,118\nSPINDL/RPM,1000,CLW\nFEDRAT/0.1,MMPR\nRAPID\n"
        "GOTO/0,0,5\nGOTO/0,0,-30\nFINI\n",
        "frame-out");
    const std::string f = program_1(p);
    CHECK(f.substr(f.find("G1 Z-30.")) == "G1 Z-30. F0.1\nG30 W0.\nM100\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
  }
  SECTION("a late PARTNO: the header written again under the name gets the same answer") {
    // ctx.program is the name the program had when the block was asked for, as in the body.
    const test::posted p = post_with_script("", lua, "HEAD/1\nTURRET/1,1\nPARTNO EV\nFINI\n", "frame-late");
    std::string late = ev1;
    late.replace(late.find("EV_1.NC"), 7, "PROGRAM_1.NC");
    CHECK(program_1(p) == late);
  }
  SECTION("a wait put into the header is refused") {
    const test::posted p = post_with_script(
        "", "function on_block(text, ctx)\n  if ctx.part == 'header' then return text .. ' M101' end\nend\n",
        "PARTNO EV\nHEAD/1\nTURRET/1,1\nFINI\n", "frame-wait");
    CHECK(
        p.diagnostics ==
        "job.cls:3:1: error: channel 1: on_block puts \"G0 G18 G21 G40 G54 G80 G99 M101\" into the program's "
        "header, with a wait code: the post places, counts and proves the waits of the body only; give a "
        "wait from an event or by the CL's SYNC records\nTURRET/1,1\n^\n"
        "t.lua: note: channel 1: the block 'G0 G18 G21 G40 G54 G80 G99 M101' came from the script "
        "(on_block)\n");
    CHECK(p.files.empty());
  }
  SECTION("the header's codes are the post's, another work offset is not") {
    const test::posted p = post_with_script(
        "", "function on_block(text, ctx)\n  if ctx.part == 'header' then return text .. ' G55' end\nend\n",
        "PARTNO EV\nHEAD/1\nTURRET/1,1\nFINI\n", "frame-g55");
    CHECK(
        p.diagnostics.starts_with("job.cls:3:1: error: channel 1: \"G0 G18 G21 G40 G54 G80 G99 G55\" selects "
                                  "another work offset"));
    CHECK(p.files.empty());
  }
  SECTION("a footer block keeps its words, in the control's reading") {
    // Attack 51: the footer's M9 dropped (the coolant on at M30), a home return's U0. kept only
    // in a comment (Z home before X), a lower-case wait, an M30 before the footer's returns.
    const std::pair<const char*, const char*> cases[] = {
        {"if ctx.part == 'footer' and text == 'M9' then return false end",
         "job.cls:4:1: error: channel 1: on_block drops the footer block \"M9\": the header and the footer "
         "set "
         "the modes and end the program safely; give it back, or add to it\nFINI\n^\n"},
        {"if ctx.part == 'footer' and text == 'G28 U0.' then return 'G28 W0. (U0.)' end",
         "job.cls:4:1: error: channel 1: on_block replaces the footer block \"G28 U0.\" with \"G28 W0. "
         "(U0.)\", "
         "which leaves out the word U0.: the header and the footer set the modes and end the program safely; "
         "keep each of its words (G28 may become G30) and add to them\nFINI\n^\n"},
        {"if ctx.part == 'footer' and text == 'M9' then return 'M9 m101' end",
         "job.cls:4:1: error: channel 1: on_block puts \"M9 m101\" into the program's footer, with a wait "
         "code: "
         "the post places, counts and proves the waits of the body only; give a wait from an event or by the "
         "CL's SYNC records\nFINI\n^\nt.lua: note: channel 1: the block 'M9 m101' came from the script "
         "(on_block)\n"},
        {"if ctx.part == 'footer' and text == 'M9' then post.emit('M30') end",
         "job.cls:4:1: error: channel 1: \"M30\" gives M30, the program's end: the blocks after it (the "
         "post's, "
         "the footer's returns home) would not run; the program ends with the machine's end code\nFINI\n^\n"},
    };
    for (const auto& [line, message] : cases) {
      const test::posted p =
          post_with_script("", std::string("function on_block(text, ctx)\n  ") + line + "\nend\n",
                           "PARTNO EV\nHEAD/1\nTURRET/1,1\nFINI\n", "frame-footer");
      CHECK(p.diagnostics.starts_with(message));
      CHECK(p.files.empty());
    }
  }
  SECTION("a script error on a footer block says so") {
    const test::posted p = post_with_script(
        "", "function on_block(text, ctx)\n  if ctx.part == 'footer' then post.error('no footer') end\nend\n",
        "PARTNO EV\nHEAD/1\nTURRET/1,1\nFINI\n", "frame-error");
    CHECK(
        p.diagnostics.ends_with("job.cls:4:1: note: channel 1: the script failed on a block of the program's "
                                "footer, asked for while this record was posted\nFINI\n^\n"));
    CHECK(p.files.empty());
  }
  SECTION("a header block's own codes pass the gate with M codes added, not with other words") {
    // Attack 51: a code counted as the post's by its number alone (G54 given P2).
    const test::posted p = post_with_script(
        "", "function on_block(text, ctx)\n  if ctx.part == 'header' then return text .. ' P2' end\nend\n",
        "PARTNO EV\nHEAD/1\nTURRET/1,1\nFINI\n", "frame-p2");
    CHECK(
        p.diagnostics.starts_with("job.cls:3:1: error: channel 1: \"G0 G18 G21 G40 G54 G80 G99 P2\" selects "
                                  "another work offset"));
    const test::posted m8 = post_with_script(
        "", "function on_block(text, ctx)\n  if ctx.part == 'header' then return text .. ' M1' end\nend\n",
        "PARTNO EV\nHEAD/1\nTURRET/1,1\nFINI\n", "frame-m8");
    CHECK(m8.diagnostics == "");
    CHECK(program_1(m8) ==
          "%\nO1000 (EV)\nG0 G18 G21 G40 G54 G80 G99 M1\nG28 U0.\nG28 W0.\nT0101\nM100\nM9\nG28 U0.\nG28 "
          "W0.\nM5\n"
          "M30\n%\n");
  }
  SECTION("a header block with a G code is not dropped") {
    const test::posted p = post_with_script(
        "", "function on_block(text, ctx)\n  if ctx.part == 'header' then return false end\nend\n",
        "PARTNO EV\nHEAD/1\nTURRET/1,1\nFINI\n", "frame-drop");
    CHECK(
        p.diagnostics ==
        "job.cls:3:1: error: channel 1: on_block drops the header block \"G0 G18 G21 G40 G54 G80 G99\": the "
        "header and the footer set the modes and end the program safely; give it back, or add to it\n"
        "TURRET/1,1\n^\n");
    CHECK(p.files.empty());
  }
}

TEST_CASE("a program start longer than a piece: the comparison on the check's thread counts its lines",
          "[post][events][cl_compare]") {
  // Attack 66 H1: 1600 blocks from on_program_start (84 KB) went to the self-check's thread
  // before the writer noted its first record, uncounted; every record then came to the
  // comparison 1600 lines early, and an M4 before the cut posted on two threads.
  std::string pad = "function on_program_start(ctx)\n  for i = 1, 1600 do\n";
  pad +=
      "    post.emit('(SETUP SHEET LINE ' .. i .. ' OF THE JOB, THE FIXTURE AND THE STOCK)')\n  end\nend\n";
  const std::string cl =
      "PARTNO PAD\nLOADTL/1,1\nSPINDL/RPM,1500,CLW\nRAPID\nGOTO/22,0,2\nFEDRAT/0.2,MMPR\nGOTO/22,0,-10\n"
      "INSERT/M4\nGOTO/22,0,-30\nFINI\n";
  const std::string m4 =
      "job.cls:9:1: error: channel 1: the CL cuts with the spindle turning clockwise at 1500 rpm here "
      "(SPINDL "
      "at line 3), but the program's main spindle turns counter-clockwise (M4)\nGOTO/22,0,-30\n^\n";
  for (const int threads : {1, 2}) {
    CAPTURE(threads);
    const test::posted p =
        post_with_script("", pad, cl, "pad", [threads](post_options& o) { o.threads = threads; });
    CHECK(p.diagnostics == m4);
  }
}
