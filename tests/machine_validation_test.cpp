// Every validation error of the machine loader, asserted to the letter with its line and
// column, so that a message or a position cannot drift unnoticed.
#include <catch2/catch.hpp>

#include <string>

#include "machines/machine.hpp"
#include "machines/machine_loader.hpp"
#include "machine_test_support.hpp"

using namespace twinpost;

namespace {

std::string error_of(const std::string& text) { return test::machine_error_of(text); }

const std::string& head = test::machine_head;
const std::string& xz = test::xz_axes;
using test::two_channels;

}  // namespace

TEST_CASE("validation: the test documents are valid as they stand", "[machines]") {
  CHECK(error_of(head + two_channels) == "(no error)");
}

TEST_CASE("validation: TOML syntax errors keep toml++'s message and position",
          "[machines]") {
  CHECK(error_of("[machine]\nname \"m\"\n") ==
        "m.toml:2:6: error: Error while parsing key-value pair: expected '=', saw '\"'");
  CHECK(error_of(head + "last = 104\n") ==
        "m.toml:6:8: error: Error while parsing key-value pair: cannot redefine existing "
        "integer 'last'");
}

TEST_CASE("validation: unknown keys", "[machines]") {
  CHECK(error_of(head + "stpe = 2\n" + two_channels) ==
        "m.toml:6:1: error: unknown key 'waits.stpe'");
  CHECK(error_of("[machine]\nname = \"m\"\n[wait]\nfirst = 100\n") ==
        "m.toml:3:2: error: unknown key 'wait'");
  // The first unknown key in the file, not the first in sorted order.
  CHECK(error_of("[machine]\nname = \"m\"\nzeta = 1\nalpha = 2\n") ==
        "m.toml:3:1: error: unknown key 'machine.zeta'");
  CHECK(error_of(head + "[[channel]]\nnumber = 1\n"
                        "axis = [{address = \"X\", mirrorr = true}, {address = \"Z\"}]\n") ==
        "m.toml:8:25: error: unknown key 'channel.axis.mirrorr'");
}

TEST_CASE("validation: wrong types", "[machines]") {
  CHECK(error_of("[machine]\nname = \"m\"\n[waits]\nfirst = \"100\"\nlast = 103\n") ==
        "m.toml:4:9: error: waits.first must be an integer, not a string");
  CHECK(error_of(head + "step = 1.5\n") ==
        "m.toml:6:8: error: waits.step must be an integer, not a floating-point number");
  CHECK(error_of(head + "reuse = 1\n") ==
        "m.toml:6:9: error: waits.reuse must be a boolean, not an integer");
  CHECK(error_of(head + "excluded = [101, \"x\"]\n") ==
        "m.toml:6:18: error: waits.excluded must hold only integers, not a string");
  CHECK(error_of(head + "[limits]\nrapid = \"fast\"\n") ==
        "m.toml:7:9: error: limits.rapid must be a number, not a string");
  CHECK(error_of("machine = \"m\"\n") ==
        "m.toml:1:11: error: machine must be a table, not a string");
  CHECK(error_of("channel = 1\n" + head) ==
        "m.toml:1:11: error: channel must be an array of tables ([[channel]]), not an "
        "integer");
  CHECK(error_of(head + "address = \"MM\"\n") ==
        "m.toml:6:11: error: waits.address must be one upper-case letter, not 'MM'");
}

TEST_CASE("validation: missing required keys are reported at the table lacking them",
          "[machines]") {
  CHECK(error_of("[machine]\ndescription = \"d\"\n") ==
        "m.toml:1:1: error: machine.name is required");
  CHECK(error_of("# no [machine] table\n[waits]\nfirst = 100\nlast = 103\n") ==
        "m.toml:1:1: error: machine.name is required");
  CHECK(error_of(head) == "m.toml:1:1: error: at least one [[channel]] is required");
  CHECK(error_of("[machine]\nname = \"m\"\n[waits]\nfirst = 100\n" + two_channels) ==
        "m.toml:3:1: error: waits.last is required");
  CHECK(error_of("[machine]\nname = \"m\"\n" + two_channels) ==
        "m.toml:1:1: error: waits.first is required");
  CHECK(error_of(head + "[[channel]]\nname = \"upper\"\n" + xz) ==
        "m.toml:6:1: error: channel.number is required");
}

TEST_CASE("validation: wait ranges", "[machines]") {
  CHECK(error_of("[machine]\nname = \"m\"\n[waits]\nfirst = 104\nlast = 103\n") ==
        "m.toml:4:9: error: waits.first (104) must be <= waits.last (103)");
  CHECK(error_of(head + "step = 0\n") == "m.toml:6:8: error: waits.step must be >= 1, not 0");
  CHECK(error_of(head + "excluded = [101, 99]\n") ==
        "m.toml:6:18: error: waits.excluded: 99 is outside the wait range 100..103");
  CHECK(error_of(head + "partners = \"bits\"\n") ==
        "m.toml:6:12: error: waits.partners must be none, path_numbers or binary, not "
        "'bits'");
}

TEST_CASE("validation: channel numbers and heads", "[machines]") {
  CHECK(error_of(head + "[[channel]]\nnumber = 1\n" + xz + "[[channel]]\nnumber = 1\n" + xz) ==
        "m.toml:10:10: error: duplicate channel number 1");
  CHECK(error_of(head + "[[channel]]\nnumber = 1\n" + xz + "[[channel]]\nnumber = 3\n" + xz) ==
        "m.toml:10:10: error: channel number 3 is outside 1..2 (the number of channels)");
  CHECK(error_of(head + "[[channel]]\nnumber = 1\nheads = [1]\n" + xz +
                 "[[channel]]\nnumber = 2\nheads = [2, 1]\n" + xz) ==
        "m.toml:12:13: error: head 1 is served by channels 1 and 2");
  CHECK(error_of(head + "[[channel]]\nnumber = 1\nhead_names = [\"MAIN\"]\n" + xz +
                 "[[channel]]\nnumber = 2\nhead_names = [\"SIDE\", \"main\"]\n" + xz) ==
        "m.toml:12:23: error: head main is served by channels 1 and 2");
}

TEST_CASE("validation: channel contents", "[machines]") {
  CHECK(error_of(head + "[[channel]]\nnumber = 1\nkind = \"gang\"\n" + xz) ==
        "m.toml:8:8: error: channel.kind must be turret or mill_head, not 'gang'");
  CHECK(error_of(head + "[[channel]]\nnumber = 1\naxis = [{address = \"X\"}]\n") ==
        "m.toml:6:1: error: channel 1 has no axis Z (X and Z are required)");
  CHECK(error_of(head + "[[channel]]\nnumber = 1\n"
                        "axis = [{address = \"X\"}, {address = \"X\"}]\n") ==
        "m.toml:8:37: error: channel 1 has axis X twice");
  CHECK(error_of(head + "[[channel]]\nnumber = 1\n"
                        "axis = [{address = \"X\", min = 5, max = 1}, {address = \"Z\"}]\n") ==
        "m.toml:8:31: error: channel.axis.min (5) must be <= channel.axis.max (1)");
  CHECK(error_of(head + "[[spindle]]\nname = \"main\"\n[[channel]]\nnumber = 1\n"
                        "spindle = \"sub\"\n" + xz) ==
        "m.toml:10:11: error: channel.spindle 'sub' names no [[spindle]]");
  CHECK(error_of(head + "[[spindle]]\nname = \"main\"\n[[spindle]]\nname = \"main\"\n") ==
        "m.toml:9:8: error: duplicate spindle name 'main'");
  CHECK(error_of(head + "[[channel]]\nnumber = 1\nfile_suffix = \"/../x\"\n" + xz) ==
        "m.toml:8:15: error: channel.file_suffix must not contain a path separator");
}

TEST_CASE("validation: layouts", "[machines]") {
  CHECK(error_of("[machine]\nname = \"m\"\nlayout = \"merged\"\n") ==
        "m.toml:3:10: error: machine.layout must be split, merged_appended or "
        "merged_sections, not 'merged'");
  // The [program] table lacks the key ...
  CHECK(error_of("[machine]\nname = \"m\"\nlayout = \"merged_sections\"\n"
                 "[waits]\nfirst = 100\nlast = 103\n[program]\nextension = \".nc\"\n" +
                 two_channels) ==
        "m.toml:7:1: error: layout merged_sections needs program.section_marker");
  // ... or there is no [program] table, and the layout is what asks for it.
  CHECK(error_of("[machine]\nname = \"m\"\nlayout = \"merged_appended\"\n"
                 "[waits]\nfirst = 100\nlast = 103\n" +
                 two_channels) ==
        "m.toml:3:10: error: layout merged_appended needs program.section_marker");
}

TEST_CASE("validation: a wait on 3 or more channels must name its partners", "[machines]") {
  const std::string three = two_channels + "[[channel]]\nnumber = 3\n" + xz;
  CHECK(error_of(head + three) ==
        "m.toml:3:1: error: waits.partners must be path_numbers or binary on a machine with "
        "3 channels");
  CHECK(error_of(head + "partners = \"none\"\n" + three) ==
        "m.toml:6:12: error: waits.partners must be path_numbers or binary on a machine "
        "with 3 channels");
  CHECK(error_of(head + "partners = \"path_numbers\"\n" + three) == "(no error)");
}

TEST_CASE("validation: templates are formatted once at load", "[machines]") {
  CHECK(error_of(head + "[[channel]]\nnumber = 1\ntool_call = \"T{tool:02}{offst:02}\"\n" +
                 xz) ==
        "m.toml:8:13: error: channel.tool_call: bad template \"T{tool:02}{offst:02}\": "
        "argument not found");
  CHECK(error_of(head + "[program]\nheader = [\"G21\", \"G50 S{max\"]\n") ==
        "m.toml:7:18: error: program.header: bad template \"G50 S{max\": missing '}' in "
        "format string");
  CHECK(error_of(head + "[[spindle]]\nname = \"main\"\nclamp = \"G50 S{}\"\n") ==
        "m.toml:8:9: error: spindle.clamp: bad template \"G50 S{}\": positional "
        "placeholder; use a name such as {tool}");
  CHECK(error_of(head + "[codes]\ndwell = \"G4 U{seconds:d}\"\n") ==
        "m.toml:7:9: error: codes.dwell: bad template \"G4 U{seconds:d}\": invalid type "
        "specifier");
  CHECK(error_of(head + "[program]\nsection_marker = \"${chanel}\"\n") ==
        "m.toml:7:18: error: program.section_marker: bad template \"${chanel}\": argument "
        "not found");
}

TEST_CASE("a spindle code inside the wait range is refused", "[machines]") {
  CHECK(error_of(head + "[[spindle]]\nname = \"sub\"\ncw = 103\n" + two_channels) ==
        "m.toml:8:6: error: spindle.cw M103 is a wait code of this machine (waits M100-M103)");
}

TEST_CASE("validation: wait codes and steps stay within eight digits", "[machines]") {
  // 2147483640 + 5 would pass the end of an int in the allocator.
  CHECK(error_of("[machine]\nname = \"m\"\n[waits]\nfirst = 2147483640\nlast = 2147483647\n"
                 "step = 5\n") ==
        "m.toml:4:9: error: waits.first must be <= 99999999 (a code has at most 8 digits), "
        "not 2147483640");
  CHECK(error_of("[machine]\nname = \"m\"\n[waits]\nfirst = 100\nlast = 100000000\n") ==
        "m.toml:5:8: error: waits.last must be <= 99999999 (a code has at most 8 digits), "
        "not 100000000");
  CHECK(error_of(head + "step = 2147483647\n") ==
        "m.toml:6:8: error: waits.step must be <= 99999999 (a code has at most 8 digits), "
        "not 2147483647");
  CHECK(error_of("[machine]\nname = \"m\"\n[waits]\nfirst = 99999990\nlast = 99999999\n"
                 "step = 99999999\n" + two_channels) == "(no error)");
}

namespace {
// `n` valid channels, three lines each.
std::string channels(int n) {
  std::string out;
  for (int c = 1; c <= n; ++c) out += "[[channel]]\nnumber = " + std::to_string(c) + "\n" + xz;
  return out;
}
}  // namespace

TEST_CASE("validation: machines the post cannot serve", "[machines]") {
  // Path numbers are one digit per channel: channel 10 cannot be named.
  CHECK(error_of(head + "partners = \"path_numbers\"\n" + channels(10)) ==
        "m.toml:6:12: error: waits.partners = path_numbers names channels by one digit each "
        "(P12): a machine with 10 channels needs binary");
  CHECK(error_of(head + "partners = \"path_numbers\"\n" + channels(9)) == "(no error)");
  CHECK(error_of(head + "partners = \"binary\"\n" + channels(10)) == "(no error)");
  // Sets of channels are 64-bit masks: the 65th [[channel]] table is refused (line 199).
  CHECK(error_of(head + "partners = \"binary\"\n" + channels(65)) ==
        "m.toml:199:1: error: [[channel]] 65 of 65: a machine has at most 64 channels");
  CHECK(error_of(head + "partners = \"binary\"\n" + channels(64)) == "(no error)");
}
