// Jobs that move before any tool call (issue 24, item 1): the tool from the machine's [[tool]]
// table by the CAM's name of it, or from post --tool; the program starts as after that call.
// Tools without a kind (item 7): post --tool-kind. The TLDATA forms whose length is known.
#include <catch2/catch.hpp>

#include <string>

#include "file_test_support.hpp"
#include "machine_test_support.hpp"
#include "machines/builtin_machines.hpp"
#include "machines/machine_loader.hpp"
#include "parser/cam_tool.hpp"
#include "post_test_jobs.hpp"

using namespace twinpost;

namespace {

// The built-in machine's file with `extra` appended (a [[tool]] table).
machine builtin_with(std::string_view name, const std::string& extra) {
  for (const builtin_machine_file& f : builtin_machine_files())
    if (f.name == name) return parse_machine(std::string(f.toml) + "\n" + extra, "m.toml");
  FAIL("no built-in machine " << name);
  return {};
}

test::posted post(const std::string& cl, const machine& m, const std::string& tag,
                  const std::function<void(post_options&)>& adjust = {}) {
  return test::post_in_fresh_dir(
      cl, m, "start-tool-" + tag, [](const diagnostic& d) { return d.level == severity::error; }, {}, adjust);
}

std::string only_file(const test::posted& p) {
  if (!p.ok || p.files.size() != 1) return "(failed)\n" + p.diagnostics;
  return p.files.begin()->second;
}

// An NX operation file: the tool was loaded by an earlier operation (no LOAD/TOOL).
const std::string nx_operation =
    "TOOL PATH/FACE,TOOL,MILL-20MM\nTLDATA/MILL,20.0000,0.0000,75.0000,0.0000,0.0000\n"
    "MSYS/0,0,0,1,0,0,0,1,0\nSPINDL/RPM,1000,CLW\nCOOLNT/ON\nRAPID\nGOTO/0,0,40,0,0,1\nFEDRAT/MMPM,250\n"
    "GOTO/10,0,20\nGOTO/20,0,20\nEND-OF-PATH\n";

// The program after the call of tool `t`: as after a LOAD/TOOL record (length offset, spindle
// and coolant as the records say).
std::string nx_program(const std::string& t) {
  return "%\nO5003 (PROGRAM)\nG21\nG90 G94 G17 G40 G49 G80\n(FACE,TOOL,MILL-20MM)\nG91 G28 Z0.\nG90\nT0" + t +
         " M6\nG54\nS1000 M3\nM8\nG0 A0.\nG0 X0. Y0.\nG0 G43 H" + t +
         " X0. Y0. Z40. A0.\nG1 X10. Z20. F250.\nX20.\nG91 G28 Z0.\nG90\nM9\nM5\nG49\nM30\n%\n";
}

}  // namespace

TEST_CASE("an NX operation file starts with the tool the [[tool]] table names by the CAM's name",
          "[post][tools][start]") {
  // The name is matched without regard to case; the table's tool wins over post --tool.
  const machine m =
      builtin_with("rotary-4axis", "[[tool]]\nnumber = 7\nkind = \"mill\"\nname = \"mill-20mm\"\n");
  CHECK(only_file(post(nx_operation, m, "named")) == nx_program("7"));
  CHECK(only_file(post(nx_operation, m, "named-over-option", [](post_options& o) {
          o.start_tools = {{1, 3}};
        })) == nx_program("7"));
}

TEST_CASE("post --tool gives the tool in the spindle when the CAM's name is not in the table",
          "[post][tools][start]") {
  const machine m = load_machine("rotary-4axis");
  CHECK(only_file(post(nx_operation, m, "option", [](post_options& o) {
          o.start_tools = {{1, 3}};
        })) == nx_program("3"));
  // The same program as a job that calls the tool itself.
  const std::string called = "LOAD/TOOL,3\n" + nx_operation.substr(nx_operation.find("SPINDL"));
  const std::string with_call = only_file(
      post("TOOL PATH/FACE,TOOL,MILL-20MM\nTLDATA/MILL,20.0000,0.0000,75.0000,0.0000,0.0000\n" + called, m,
           "called"));
  CHECK(with_call == nx_program("3"));
}

TEST_CASE("a job that moves with no tool call, no known name and no --tool fails once, naming both ways",
          "[post][tools][start]") {
  const test::posted p = post(nx_operation, load_machine("trunnion-5axis"), "none");
  CHECK_FALSE(p.ok);
  CHECK(p.files.empty());
  CHECK(
      p.diagnostics ==
      "job.cls:7:1: error: channel 1: a move with no tool called in this channel: give LOADTL or TURRET "
      "before the first move, the CAM's name of the tool under its [[tool]] in machine 'trunnion-5axis' "
      "(name = \"MILL-20MM\", as TOOL PATH at line 1 names it), or the tool in the spindle with post --tool "
      "N\nGOTO/0,0,40,0,0,1\n^\n");
}

TEST_CASE("CATIA's TPRINT names the tool", "[post][tools][start]") {
  const machine m =
      builtin_with("trunnion-5axis", "[[tool]]\nnumber = 2\nkind = \"mill\"\nname = \"T1 PointeurD10\"\n");
  const test::posted p =
      post("PARTNO P\nTPRINT/T1 PointeurD10\nSPINDL/RPM,2000,CLW\nRAPID\nGOTO/0,0,10\nFINI\n", m, "tprint");
  REQUIRE(p.ok);
  CHECK(only_file(p).find("\nT02 M6\nG54\nS2000 M3\nG0 ") != std::string::npos);
}

TEST_CASE("a tool name given to two tools of one channel is an error in the machine file",
          "[machines][tools][start]") {
  const std::string two = test::two_channels +
                          "[[tool]]\nnumber = 1\nkind = \"mill\"\nname = \"A\"\n"
                          "[[tool]]\nnumber = 2\nkind = \"mill\"\nname = \"a\"\n";
  CHECK(test::machine_error_of(test::machine_head + two) ==
        "m.toml:19:8: error: tool.name 'a' is given to tools 1 and 2");
}

TEST_CASE("the TLDATA forms whose tool length is known", "[parser][tools]") {
  const auto length = [](std::vector<std::string> words, std::vector<double> values) {
    return tldata_length(tool_data_event{"TLDATA", std::move(words), std::move(values)});
  };
  CHECK(length({"MILL"}, {20, 0, 75, 0, 0}) == 75.0);                 // NX, 5 values
  CHECK(length({"MILL"}, {20, 1, 80, 0, 0, 2, 3}) == 80.0);           // NX, 7 values
  CHECK(length({"DRILL", "MILL"}, {8.5, 0, 120, 118, 60}) == 120.0);  // NX DRILL with its module
  CHECK(length({"DRILL"}, {8.5, 0, 110, 118, 60}) == 110.0);          // without one
  CHECK_FALSE(length({"TURN"}, {1, 2, 3, 4, 5}).has_value());         // turning: none
  CHECK_FALSE(length({"MILL"}, {20, 0}).has_value());
  CHECK_FALSE(tldata_length(tool_data_event{"CUTTER", {}, {10, 0, 5, 5, 45, 0, 50}}).has_value());
  CHECK(tldata_diameter(tool_data_event{"TLDATA", {"DRILL", "MILL"}, {8.5, 0, 120}}) == 8.5);
}

TEST_CASE("the CAM's tool name in NX TOOL PATH and CATIA TPRINT", "[parser][tools]") {
  CHECK(cam_tool_name(text_event{text_kind::toolpath, "TOOL PATH", "ZLEVEL_FOLLOW_CORE,TOOL,MILL-20MM"}) ==
        "MILL-20MM");
  CHECK(cam_tool_name(text_event{text_kind::toolpath, "TOOL PATH", "OP 1, TOOL , D10 "}) == "D10");
  CHECK(cam_tool_name(text_event{text_kind::toolpath, "TOOL PATH", "OP1"}).empty());
  CHECK(cam_tool_name(text_event{text_kind::tprint, "TPRINT", "T1 PointeurD10"}) == "T1 PointeurD10");
  CHECK(cam_tool_name(text_event{text_kind::pprint, "PPRINT", "TOOL,X"}).empty());
}

TEST_CASE("post --tool-kind gives a tool without TLDATA or [[tool]] its kind on the Integrex",
          "[post][tools][kind]") {
  const std::string cl =
      "PARTNO K\nLOADTL/5\nSPINDL/RPM,2000,CLW\nFEDRAT/MMPM,300\nRAPID\nGOTO/0,0,5,0,0,1\n"
      "GOTO/0,0,-10\nFINI\n";
  const machine m = load_machine("integrex-i200st");
  // None of the three gives a kind: the refusal stays.
  const test::posted none = post(cl, m, "kind-none");
  CHECK_FALSE(none.ok);
  CHECK(
      none.diagnostics ==
      "job.cls:3:1: error: channel 1: SPINDL: the kind of tool 5 (LOADTL at line 2) is unknown, and channel "
      "1 "
      "has a workpiece spindle and a live one (live): give TLDATA/TURN, MILL or DRILL before the tool call, "
      "kind = ... under the tool's [[tool]] in the machine file, or post --tool-kind for every tool without "
      "one, or name the spindle (SPINDL/...,MAIN, SUB or LIVE)\nSPINDL/RPM,2000,CLW\n^\n");
  // A drill on the centre line turns the part (M203 on the main spindle); a mill the live tool (M200 ... M3).
  const test::posted drill = post(cl, m, "kind-drill", [](post_options& o) { o.tool_kind = "drill"; });
  REQUIRE(drill.ok);
  CHECK(only_file(drill).find("T05 M6\nM901\nG97 S2000 M203\n") != std::string::npos);
  const test::posted mill = post(cl, m, "kind-mill", [](post_options& o) { o.tool_kind = "mill"; });
  REQUIRE(mill.ok);
  CHECK(only_file(mill).find("T05 M6\nM901\nM200\nG10.9 X0\nG97 S2000 M3\n") != std::string::npos);
  // The [[tool]] table's kind comes before --tool-kind.
  const machine with_table = builtin_with("integrex-i200st", "[[tool]]\nnumber = 5\nkind = \"drill\"\n");
  const test::posted table =
      post(cl, with_table, "kind-table", [](post_options& o) { o.tool_kind = "mill"; });
  REQUIRE(table.ok);
  CHECK(only_file(table).find("T05 M6\nM901\nG97 S2000 M203\n") != std::string::npos);
}

TEST_CASE("an operation whose CAM name maps to another tool, with no call of its own, calls that tool",
          "[post][tools][start]") {
  const machine m = builtin_with("rotary-4axis",
                                 "[[tool]]\nnumber = 7\nkind = \"mill\"\nname = \"MILL-20MM\"\n"
                                 "[[tool]]\nnumber = 8\nkind = \"drill\"\nname = \"DRILL-8\"\n");
  // The second operation names DRILL-8 and has no LOAD/TOOL: T08 is called before its moves.
  // The third calls its tool itself (LOAD/TOOL,8 after TOOL PATH naming MILL-20MM): the call
  // record stands (the same tool: its length offset again), no call of T07.
  const test::posted p =
      post(nx_operation +
               "TOOL PATH/DRILL,TOOL,DRILL-8\nSPINDL/RPM,1500,CLW\nRAPID\nGOTO/5,5,10\n"
               "END-OF-PATH\nTOOL PATH/OTHER,TOOL,MILL-20MM\nLOAD/TOOL,8\nRAPID\nGOTO/6,6,10\n"
               "END-OF-PATH\n",
           m, "second-operation");
  CHECK(only_file(p) ==
        "%\nO5003 (PROGRAM)\nG21\nG90 G94 G17 G40 G49 G80\n(FACE,TOOL,MILL-20MM)\nG91 G28 Z0.\nG90\nT07 M6\n"
        "G54\nS1000 M3\nM8\nG0 A0.\nG0 X0. Y0.\nG0 G43 H7 X0. Y0. Z40. A0.\nG1 X10. Z20. "
        "F250.\nX20.\n(DRILL,TOOL,DRILL-8)\nG91 G28 Z0.\nG90\nM5\nM9\n"
        "G49\nT08 M6\nM8\nS1500 M3\nG0 A0.\nG0 X5. Y5.\nG0 G43 H8 X5. Y5. Z10. "
        "A0.\n(OTHER,TOOL,MILL-20MM)\n"
        "G0 A0.\nG0 X6. Y6.\nG0 G43 H8 X6. Y6. Z10. A0.\nM9\nM5\nG91 G28 Z0.\nG90\nG49\nM30\n%\n");
}

TEST_CASE("post --tool C:N gives channel C its tool, and another channel without one still fails",
          "[post][tools][start]") {
  const std::string cl =
      "PARTNO TW\nHEAD/2\nSPINDL/RPM,800,CLW\nFEDRAT/0.2,MMPR\nGOTO/-20,0,2\nGOTO/-20,0,-10\nFINI\n";
  const machine m = load_machine("fanuc-0itd-twin");
  const test::posted two = post(cl, m, "channel-2", [](post_options& o) { o.start_tools = {{2, 5}}; });
  REQUIRE(two.ok);
  CHECK(two.files.at("TW_2.nc").find("\nT0505\nG97 S800 M3\n") != std::string::npos);
  // --tool 5 is channel 1's: channel 2 still moves without a tool.
  const test::posted one = post(cl, m, "channel-1-only", [](post_options& o) { o.start_tools = {{1, 5}}; });
  CHECK_FALSE(one.ok);
  CHECK(one.diagnostics ==
        "job.cls:5:1: error: channel 2: a move with no tool called in this channel: give LOADTL or TURRET "
        "before the first move, the CAM's name of the tool under its [[tool]] in the machine file (name = "
        "..., as NX TOOL PATH or CATIA TPRINT gives it), or the tool in the spindle with post --tool 2:N\n"
        "GOTO/-20,0,2\n^\n");
}
