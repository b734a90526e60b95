// A user's [events] blocks that change a modal code (issue 37, item 4): the channel's own mode
// goes back on after them (machining/channel_user_modes.cpp), and a block in the other unit
// system stops the post.
#include <catch2/catch.hpp>

#include <string>

#include "file_test_support.hpp"
#include "machines/machine_loader.hpp"
#include "post_test_jobs.hpp"

using namespace twinpost;

namespace {

test::posted post_with(const std::string& events, const std::string& cl, const std::string& tag) {
  const std::string text =
      test::read_file(std::string(TWINPOST_SOURCE_DIR) + "/machines/builtin/fanuc-0itd-twin.toml") + "\n" +
      events;
  return test::post_in_fresh_dir(cl, parse_machine(text, "twin-modes.toml"), "modes-" + tag);
}

// Tool 1 feeds per minute (G98), tool 2 is called and feeds per minute again: the control must
// be in G98 for its F150., whatever the user's block after the tool call said.
const std::string job =
    "PARTNO UM\nHEAD/1\nTLDATA/DRILL,8,118\nTURRET/1,1\nSPINDL/RPM,800,CLW\nFEDRAT/MMPM,150\nRAPID\n"
    "GOTO/0,0,5\nGOTO/0,0,-5\nRAPID\nGOTO/0,0,5\nTLDATA/DRILL,6,118\nTURRET/2,2\nSPINDL/RPM,900,CLW\n"
    "RAPID\nGOTO/0,0,5\nGOTO/0,0,-5\nRAPID\nGOTO/0,0,5\nEND\nFINI\n";

std::string between(const std::string& text, const std::string& from, const std::string& to) {
  const std::size_t a = text.find(from);
  const std::size_t b = text.find(to, a == std::string::npos ? 0 : a);
  return a == std::string::npos || b == std::string::npos ? "(not found)" : text.substr(a, b - a);
}

}  // namespace

TEST_CASE("user blocks: the channel's feed mode, plane and G90 back on after them", "[post][events]") {
  const test::posted p = post_with("[events]\ntool_change.after = [\"G0 G17 G40 G80 G99\"]\n", job, "feed");
  REQUIRE(p.ok);
  const std::string& one = p.files.at("UM_1.nc");
  // After T0202 the user's block (G17, G99), then the channel's G18 and G98 again, and the next
  // feed move writes its F again: 150 mm/min, never 150 mm/rev.
  CHECK(between(one, "T0202", "G0 Z5.") ==
        "T0202\nG0 G17 G40 G80 G99\nG18\nG98\nG97 S900 M3\nG0 X0. Z5.\nG1 Z-5. F150.\n");
}

TEST_CASE("user blocks: a block in the other unit system stops the post", "[post][events]") {
  const test::posted p = post_with("[events]\ntool_change.after = [\"G20\"]\n", job, "units");
  CHECK(!p.ok);
  CHECK(p.diagnostics ==
        "job.cls:4:1: error: channel 1: events.tool_change.after writes \"G20\": G20 in a program in "
        "millimetres (G21); every later word would be read in inches\nTURRET/1,1\n^\n"
        "job.cls:13:1: error: channel 1: events.tool_change.after writes \"G20\": G20 in a program in "
        "millimetres (G21); every later word would be read in inches\nTURRET/2,2\n^\n");
}

TEST_CASE("user blocks: G28 on a mill only through no intermediate point", "[post][events]") {
  // G28 Z0. under G90 goes to Z0 of the work offset first, at rapid, through the part; G91 G28
  // Z0. goes straight up (machining/user_block_form.cpp). The user's block, the post's G90 after
  // it, then the tool change's own home.
  const std::string mill = test::read_file(std::string(TWINPOST_SOURCE_DIR) + "/bench/bench-mill.toml");
  const std::string cl =
      "PARTNO UM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,200\nRAPID\nGOTO/0,0,5\nGOTO/0,0,-2\nRAPID\n"
      "GOTO/0,0,5\nEND\nFINI\n";
  const test::posted bad = test::post_in_fresh_dir(
      cl, parse_machine(mill + "\n[events]\ntool_change.before = [\"G28 Z0.\"]\n", "mill.toml"), "g28-abs");
  CHECK(!bad.ok);
  CHECK(
      bad.diagnostics ==
      "job.cls:2:1: error: channel 1: \"G28 Z0.\" returns to the reference position through the "
      "intermediate point Z0.: G28 and G30 go there first, at rapid, and the post cannot follow it; give no "
      "move on the way (G91 G28 Z0.)\nLOADTL/1\n^\n");
  CHECK(bad.files.empty());
  const test::posted good = test::post_in_fresh_dir(
      cl, parse_machine(mill + "\n[events]\ntool_change.before = [\"G91 G28 Z0.\"]\n", "mill.toml"),
      "g28-inc");
  CHECK(good.diagnostics == "");
  REQUIRE(good.ok);
  CHECK(between(good.files.begin()->second, "G91 G28 Z0.", "T") == "G91 G28 Z0.\nG90\nG91 G28 Z0\nG90\n");
}

TEST_CASE("user blocks: no G40 while the CL's cutter compensation is on, no G53 with an increment",
          "[post][events]") {
  // The twelfth round on issue 38: a G40 mid-contour runs the rest on the tool's centre.
  const std::string mill = test::read_file(std::string(TWINPOST_SOURCE_DIR) + "/bench/bench-mill.toml");
  const std::string comp =
      "PARTNO "
      "CMP\nTLDATA/MILL,10,0,50\nLOADTL/1\nSPINDL/2000,RPM,CLW\nRAPID\nGOTO/20,10,30\nFEDRAT/200,MMPM\n"
      "GOTO/20,10,-1\nCUTCOM/LEFT\nGOTO/40,10,-1\nCATCHER\nGOTO/40,30,-1\nCUTCOM/OFF\nGOTO/20,30,-1\nRAPID\n"
      "GOTO/20,30,30\nFINI\n";
  const auto with = [&](const std::string& block, const std::string& tag) {
    return test::post_in_fresh_dir(
        comp,
        parse_machine(mill + "\n[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"" + block + "\"]\n",
                      "mill.toml"),
        tag);
  };
  CHECK(with("G40", "g40").diagnostics ==
        "job.cls:11:1: error: channel 1: \"G40\" cancels the cutter compensation (G40) while the CL's CUTCOM "
        "is "
        "on: the rest of the contour would run on the tool's centre\nCATCHER\n^\n");
  CHECK(with("G91 G53 X900.", "g53-inc").diagnostics ==
        "job.cls:11:1: error: channel 1: \"G91 G53 X900.\" gives G53 with the increment X900.: some controls "
        "move "
        "by it in machine coordinates, others ignore G53; write an absolute machine position\nCATCHER\n^\n");
  // G40 with no compensation on (a safe-start block) posts.
  CHECK(test::post_in_fresh_dir(
            "PARTNO CMP\nTLDATA/MILL,10,0,50\nLOADTL/1\nSPINDL/2000,RPM,CLW\nRAPID\nGOTO/20,10,30\nCATCHER\n"
            "FEDRAT/200,MMPM\nGOTO/20,10,-1\nRAPID\nGOTO/20,10,30\nFINI\n",
            parse_machine(mill + "\n[[events.record]]\nmajor = \"CATCHER\"\nblocks = [\"G80 G40\"]\n",
                          "mill.toml"),
            "g40-ok")
            .ok);
}
