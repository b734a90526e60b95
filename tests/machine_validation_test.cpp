// Every validation error of the machine loader, asserted to the letter with its line and
// column, so that a message or a position cannot drift unnoticed.
#include <catch2/catch.hpp>

#include <string>

#include "machine_test_support.hpp"
#include "machines/layout_names.hpp"
#include "machines/layout_rules.hpp"
#include "machines/machine.hpp"
#include "machines/machine_loader.hpp"

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

TEST_CASE("validation: TOML syntax errors keep toml++'s message and position", "[machines]") {
  CHECK(error_of("[machine]\nname \"m\"\n") ==
        "m.toml:2:6: error: Error while parsing key-value pair: expected '=', saw '\"'");
  CHECK(error_of(head + "last = 104\n") ==
        "m.toml:6:8: error: Error while parsing key-value pair: cannot redefine existing "
        "integer 'last'");
}

TEST_CASE("validation: unknown keys", "[machines]") {
  CHECK(error_of(head + "stpe = 2\n" + two_channels) == "m.toml:6:1: error: unknown key 'waits.stpe'");
  CHECK(error_of("[machine]\nname = \"m\"\n[wait]\nfirst = 100\n") ==
        "m.toml:3:2: error: unknown key 'wait'");
  // The first unknown key in the file, not the first in sorted order.
  CHECK(error_of("[machine]\nname = \"m\"\nzeta = 1\nalpha = 2\n") ==
        "m.toml:3:1: error: unknown key 'machine.zeta'");
  CHECK(error_of(head + "[[channel]]\nnumber = 1\n"
                        "axis = [{address = \"X\", mirrorr = true}, {address = \"Z\"}]\n") ==
        "m.toml:8:25: error: unknown key 'channel.axis.mirrorr'");
}

TEST_CASE("validation: keys that were read and never used are unknown now", "[machines]") {
  // Deleted rather than kept as configuration nothing obeys: a file still naming one gets
  // the normal unknown-key error.
  CHECK(error_of(head + "[limits]\nmax_feed = 9000\nrapid = 24000\n") ==
        "m.toml:8:1: error: unknown key 'limits.rapid'");
  CHECK(error_of(head + "[limits]\ntool_change_seconds = 0.6\n") ==
        "m.toml:7:1: error: unknown key 'limits.tool_change_seconds'");
  CHECK(error_of(head + "[program]\nblock_max = 128\n") ==
        "m.toml:7:1: error: unknown key 'program.block_max'");
  CHECK(error_of(head + "[[channel]]\nnumber = 1\nname = \"upper\"\n" + xz) ==
        "m.toml:8:1: error: unknown key 'channel.name'");
  // max_feed is used (machining/channel_words.cpp): it must be a positive rate.
  CHECK(error_of(head + "[limits]\nmax_feed = 0\n") ==
        "m.toml:7:12: error: limits.max_feed must be > 0, not 0");
}

TEST_CASE("validation: wrong types", "[machines]") {
  CHECK(error_of("[machine]\nname = \"m\"\n[waits]\nfirst = \"100\"\nlast = 103\n") ==
        "m.toml:4:9: error: waits.first must be an integer, not a string");
  CHECK(error_of(head + "step = 1.5\n") ==
        "m.toml:6:8: error: waits.step must be an integer, not a floating-point number");
  CHECK(error_of(head + "reuse = 1\n") == "m.toml:6:9: error: waits.reuse must be a boolean, not an integer");
  CHECK(error_of(head + "excluded = [101, \"x\"]\n") ==
        "m.toml:6:18: error: waits.excluded must hold only integers, not a string");
  CHECK(error_of(head + "[limits]\nmax_feed = \"fast\"\n") ==
        "m.toml:7:12: error: limits.max_feed must be a number, not a string");
  CHECK(error_of("machine = \"m\"\n") == "m.toml:1:11: error: machine must be a table, not a string");
  CHECK(error_of("channel = 1\n" + head) ==
        "m.toml:1:11: error: channel must be an array of tables ([[channel]]), not an "
        "integer");
  CHECK(error_of(head + "address = \"MM\"\n") ==
        "m.toml:6:11: error: waits.address must be one upper-case letter, not 'MM'");
}

TEST_CASE("validation: missing required keys are reported at the table lacking them", "[machines]") {
  CHECK(error_of("[machine]\ndescription = \"d\"\n") == "m.toml:1:1: error: machine.name is required");
  CHECK(error_of("# no [machine] table\n[waits]\nfirst = 100\nlast = 103\n") ==
        "m.toml:1:1: error: machine.name is required");
  CHECK(error_of(head) == "m.toml:1:1: error: at least one [[channel]] is required");
  CHECK(error_of("[machine]\nname = \"m\"\n[waits]\nfirst = 100\n" + two_channels) ==
        "m.toml:3:1: error: waits.last is required");
  CHECK(error_of("[machine]\nname = \"m\"\n" + two_channels) == "m.toml:1:1: error: waits.first is required");
  CHECK(error_of(head + "[[channel]]\nheads = [1]\n" + xz) ==
        "m.toml:6:1: error: channel.number is required");
}

TEST_CASE("validation: wait ranges", "[machines]") {
  CHECK(error_of("[machine]\nname = \"m\"\n[waits]\nfirst = 104\nlast = 103\n") ==
        "m.toml:4:9: error: waits.first (104) must be <= waits.last (103)");
  CHECK(error_of(head + "step = 0\n") == "m.toml:6:8: error: waits.step must be >= 1, not 0");
  CHECK(error_of(head + "excluded = [101, 99]\n") ==
        "m.toml:6:18: error: waits.excluded: 99 is outside the wait range 100..103");
  CHECK(error_of(head + "partners = \"bits\"\n") ==
        "m.toml:6:12: error: waits.partners must be none, path_numbers, binary or others, not "
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
  CHECK(error_of(head +
                 "[[spindle]]\nname = \"main\"\n[[channel]]\nnumber = 1\n"
                 "spindle = \"sub\"\n" +
                 xz) == "m.toml:10:11: error: channel.spindle 'sub' names no [[spindle]]");
  CHECK(error_of(head + "[[spindle]]\nname = \"main\"\n[[channel]]\nnumber = 1\nlive_spindle = \"live\"\n" +
                 xz) == "m.toml:10:16: error: channel.live_spindle 'live' names no [[spindle]]");
  CHECK(error_of(head + "[[spindle]]\nname = \"main\"\n[[spindle]]\nname = \"main\"\n") ==
        "m.toml:9:8: error: duplicate spindle name 'main'");
  CHECK(error_of(head + "[[channel]]\nnumber = 1\nfile_suffix = \"/../x\"\n" + xz) ==
        "m.toml:8:15: error: channel.file_suffix must not contain a path separator");
  // A channel's own home blocks; none at all is refused, and without the key the machine's.
  CHECK(error_of(head + "[[channel]]\nnumber = 1\nhome = []\n" + xz) ==
        "m.toml:8:8: error: channel.home must name at least one block");
  const machine m = parse_machine(head + "[[channel]]\nnumber = 1\nhome = [\"G28 U0. V0.\", \"G28 W0.\"]\n" +
                                      xz + "[[channel]]\nnumber = 2\n" + xz,
                                  "m.toml");
  CHECK(m.home(1) == std::vector<std::string>{"G28 U0. V0.", "G28 W0."});
  CHECK(m.home(2) == std::vector<std::string>{"G28 U0.", "G28 W0."});
}

TEST_CASE("validation: layouts", "[machines]") {
  CHECK(error_of("[machine]\nname = \"m\"\nlayout = \"merged\"\n") ==
        "m.toml:3:10: error: machine.layout must be split, merged_appended or "
        "merged_sections, not 'merged'");
  // merged_appended writes the marker before each channel: the [program] table lacks it ...
  CHECK(error_of("[machine]\nname = \"m\"\nlayout = \"merged_appended\"\n"
                 "[waits]\nfirst = 100\nlast = 103\n[program]\nextension = \".nc\"\n" +
                 two_channels) ==
        "m.toml:7:1: error: layout merged_appended needs program.section_marker (the block "
        "that opens each channel's section, such as \"G109 L{channel}\")");
  // ... or there is no [program] table, and the layout is what asks for it.
  CHECK(error_of("[machine]\nname = \"m\"\nlayout = \"merged_appended\"\n"
                 "[waits]\nfirst = 100\nlast = 103\n" +
                 two_channels) ==
        "m.toml:3:10: error: layout merged_appended needs program.section_marker (the block "
        "that opens each channel's section, such as \"G109 L{channel}\")");
  // merged_sections writes `$n` and never the marker, so it does not ask for one.
  CHECK(error_of("[machine]\nname = \"m\"\nlayout = \"merged_sections\"\n"
                 "[waits]\nfirst = 100\nlast = 103\n[program]\nextension = \".nc\"\n" +
                 two_channels) == "(no error)");
}

TEST_CASE("layout_problem: one rule for the file, --layout and the post", "[machines]") {
  machine m;
  CHECK(layout_file_name(layout_kind::split) == "split");
  CHECK(layout_file_name(layout_kind::merged_appended) == "merged_appended");
  CHECK(layout_file_name(layout_kind::merged_sections) == "merged_sections");
  CHECK(layout_problem(m, layout_kind::split) == "");
  CHECK(layout_problem(m, layout_kind::merged_sections) == "");
  CHECK(layout_problem(m, layout_kind::merged_appended) ==
        "layout merged_appended needs program.section_marker (the block that opens each "
        "channel's section, such as \"G109 L{channel}\")");
  m.program.section_marker = "G109 L{channel}";
  CHECK(layout_problem(m, layout_kind::merged_appended) == "");
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
  CHECK(error_of(head + "[[channel]]\nnumber = 1\ntool_call = \"T{tool:02}{offst:02}\"\n" + xz) ==
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

TEST_CASE("validation: a template is one line of printable text with short widths", "[machines]") {
  // Issue 38, sixth attack: a line break made one template several NC lines no check read as
  // blocks; a '%' is the tape mark; a width of 2e9 took 6 GB at load.
  CHECK(error_of(head + "[program]\nfooter = [\"M5\\nG10 L2 P1 X-500.\"]\n") ==
        "m.toml:7:11: error: program.footer: a template holds the control byte 0x0a: a block is one line of "
        "printable text");
  CHECK(error_of(head + "[program]\nheader = [\"(50%)\"]\n") ==
        "m.toml:7:11: error: program.header: a template holds '%', the tape mark where a control stops "
        "reading: a block is one line of printable text");
  CHECK(error_of(head + "[program]\nprogram_line = \"O{program:>2000000000}\"\n") ==
        "m.toml:7:16: error: program.program_line: template \"O{program:>2000000000}\": a width or "
        "precision above 64; a word of the control has at most a few digits");
  CHECK(error_of(head + "[program]\nsection_marker = \"G109 L{channel:0{channel}}\"\n") ==
        "m.toml:7:18: error: program.section_marker: template \"G109 L{channel:0{channel}}\": a width or "
        "precision given by a placeholder; write the number");
  // The seventh attack: a number printed as a byte, a byte above ASCII, a file of megabytes.
  CHECK(error_of(head + "[program]\nprogram_line = \"O{program:c}\"\n") ==
        "m.toml:7:16: error: program.program_line: template \"O{program:c}\": the presentation type 'c' (a "
        "number as a byte, in hex or octal, ...); write {name}, {name:d} or {name:.3f}");
  CHECK(
      error_of(head + "[program]\nheader = [\"(\u00e5)\"]\n") ==
      "m.toml:7:11: error: program.header: a template holds the byte 0xc3, no ASCII (a 7-bit link strips its "
      "top bit): a block is one line of printable text");
  CHECK(error_of(head + std::string(std::size_t{1} << 20, '#') + "\n") ==
        "m.toml:1:1: error: a machine file of 1048629 bytes: at most 1048576 (1 MB)");
  // A line of more than 4096 bytes (a dotted key of 200 000 parts overflowed toml++'s stack).
  std::string deep = "a";
  for (int i = 0; i < 3000; ++i) deep += ".a";
  CHECK(error_of(head + deep + " = 1\n") ==
        "m.toml:6:1: error: a line of 6005 bytes: a machine file's lines have at most 4096; break a long "
        "array over several lines");
}

TEST_CASE("validation: a template names only what is known where it is used", "[machines]") {
  // A file name is made once for all channels: there is no channel to name.
  CHECK(error_of(head + "[program]\nfile_name = \"{name}_{channel}\"\n") ==
        "m.toml:7:13: error: program.file_name: template \"{name}_{channel}\" names {channel}, "
        "which is not known there (it is given {program}, {name})");
  CHECK(error_of(head + "[program]\nprogram_line = \"O{program:04} T{tool}\"\n") ==
        "m.toml:7:16: error: program.program_line: template \"O{program:04} T{tool}\" names "
        "{tool}, which is not known there (it is given {program}, {name})");
  CHECK(error_of(head + "[program]\nfooter = [\"M9\", \"G50 S{max}\"]\n") ==
        "m.toml:7:17: error: program.footer: template \"G50 S{max}\" names {max}, which is not "
        "known there (it is given {program}, {name}, {channel})");
  // A tool call is not given the program's name: it would print the sample PART.
  CHECK(error_of(head + "[[channel]]\nnumber = 1\ntool_call = \"T{tool:02} ({name})\"\n" + xz) ==
        "m.toml:8:13: error: channel.tool_call: template \"T{tool:02} ({name})\" names {name}, "
        "which is not known there (it is given {channel}, {tool}, {offset})");
  CHECK(error_of(head + "[[spindle]]\nname = \"main\"\nclamp = \"G50 S{max} T{tool}\"\n") ==
        "m.toml:8:9: error: spindle.clamp: template \"G50 S{max} T{tool}\" names {tool}, which "
        "is not known there (it is given {channel}, {max}, {rpm})");
  CHECK(error_of(head + "[codes]\ndwell = \"G4 U{seconds} ({program})\"\n") ==
        "m.toml:7:9: error: codes.dwell: template \"G4 U{seconds} ({program})\" names {program}, "
        "which is not known there (it is given {channel}, {seconds}, {ms})");
  // The checker finds sections by the marker: it knows the channel and nothing else.
  CHECK(error_of(head + "[program]\nsection_marker = \"G109 L{channel} ({name})\"\n") ==
        "m.toml:7:18: error: program.section_marker: template \"G109 L{channel} ({name})\" "
        "names {name}, which is not known there (it is given {channel})");
  // Fixed blocks are given nothing.
  CHECK(error_of(head + "[codes]\nhome = [\"G28 U0 (T{tool})\"]\n") ==
        "m.toml:7:9: error: codes.home: template \"G28 U0 (T{tool})\" names {tool}, which "
        "is not known there (it is given no placeholder)");
  CHECK(error_of(head + "[codes]\ncoolant_on = [\"M8\", \"M{channel}\"]\n") ==
        "m.toml:7:21: error: codes.coolant_on: template \"M{channel}\" names {channel}, which is "
        "not known there (it is given no placeholder)");
  CHECK(error_of(head + "[program]\nend_code = \"M30 ({name})\"\n") ==
        "m.toml:7:12: error: program.end_code: template \"M30 ({name})\" names {name}, which "
        "is not known there (it is given no placeholder)");
  // A width taken from a placeholder is held to the same sets.
  CHECK(error_of(head + "[program]\nprogram_line = \"O{program:0{channel}}\"\n") ==
        "m.toml:7:16: error: program.program_line: template \"O{program:0{channel}}\" names "
        "{channel}, which is not known there (it is given {program}, {name})");
  // Where they are known, all are fine, and a literal brace is not a placeholder.
  CHECK(error_of(head +
                 "[program]\nfile_name = \"{name}-{program}\"\n"
                 "header = [\"({name} {program} {channel})\", \"{{tool}}\"]\n"
                 "section_marker = \"G109 L{channel}\"\n"
                 "[codes]\ndwell = \"G4 P{ms} (C{channel} {seconds})\"\n"
                 "[[spindle]]\nname = \"main\"\nclamp = \"G50 S{max} (S{rpm} C{channel})\"\n"
                 "[[channel]]\nnumber = 1\ntool_call = \"T{tool:02}{offset:02} (C{channel})\"\n" +
                 xz) == "(no error)");
}

TEST_CASE("fixed blocks are stored as the control reads them", "[machines]") {
  // A fixed block is formatted once at load: `{{` stands for a brace, in the file as on the
  // control.
  const machine m = parse_machine(head +
                                      "[program]\nend_code = \"M30 ({{END}})\"\n"
                                      "[codes]\nhome = [\"G28 U0 ({{HOME}})\", \"G28 W0\"]\n"
                                      "coolant_on = [\"M8 ({{A}})\"]\n" +
                                      two_channels,
                                  "m.toml");
  CHECK(m.program.end_code == "M30 ({END})");
  CHECK(m.codes.home == std::vector<std::string>{"G28 U0 ({HOME})", "G28 W0"});
  CHECK(m.codes.coolant_on == std::vector<std::string>{"M8 ({A})"});
}

// Every code the file names is held to the wait range (machines/code_overlap.hpp): the
// control would take it for a wait. The message names the key and the range, at the value.
namespace {
// Channels work on spindle "main": a file naming spindles must have it.
const std::string main_spindle = "[[spindle]]\nname = \"main\"\n";
const std::string lies =
    " lies in the wait range M100-M103 ([waits]); a program could not tell it from a wait";
}  // namespace

TEST_CASE("overlap: every spindle code inside the wait range is refused", "[machines][overlap]") {
  CHECK(error_of(head + "[[spindle]]\nname = \"sub\"\ncw = 103\n" + main_spindle + two_channels) ==
        "m.toml:8:6: error: spindle 'sub': cw M103" + lies);
  CHECK(error_of(head + "[[spindle]]\nname = \"sub\"\nccw = 102\n" + main_spindle + two_channels) ==
        "m.toml:8:7: error: spindle 'sub': ccw M102" + lies);
  CHECK(error_of(head + "[[spindle]]\nname = \"sub\"\nstop = 101\n" + main_spindle + two_channels) ==
        "m.toml:8:8: error: spindle 'sub': stop M101" + lies);
  CHECK(error_of(head + "[[spindle]]\nname = \"sub\"\nselect = 100\n" + main_spindle + two_channels) ==
        "m.toml:8:10: error: spindle 'sub': select M100" + lies);
  CHECK(error_of(head + "[[spindle]]\nname = \"main\"\nclamp = \"G50 S{max} M103\"\n" + two_channels) ==
        "m.toml:8:9: error: spindle 'main': clamp M103" + lies);
  // Codes outside the range, and the same codes in another address, are fine.
  CHECK(error_of(head + "[[spindle]]\nname = \"sub\"\ncw = 203\nccw = 97\nstop = 104\nselect = 902\n" +
                 main_spindle + two_channels) == "(no error)");
}

TEST_CASE("overlap: [codes] and the program's blocks", "[machines][overlap]") {
  CHECK(error_of(head + "[codes]\nprogram_stop = \"M101\"\n" + two_channels) ==
        "m.toml:7:16: error: codes.program_stop M101" + lies);
  CHECK(error_of(head + "[codes]\noptional_stop = \"M100\"\n" + two_channels) ==
        "m.toml:7:17: error: codes.optional_stop M100" + lies);
  CHECK(error_of(head + "[codes]\ncoolant_on = [\"M8\", \"M102\"]\n" + two_channels) ==
        "m.toml:7:21: error: codes.coolant_on M102" + lies);
  CHECK(error_of(head + "[codes]\ncoolant_off = \"M9 M103\"\n" + two_channels) ==
        "m.toml:7:15: error: codes.coolant_off M103" + lies);
  CHECK(error_of(head + "[codes]\nbalance_on = \"M100\"\n" + two_channels) ==
        "m.toml:7:14: error: codes.balance_on M100" + lies);
  CHECK(error_of(head + "[codes]\ndwell = \"G4 U{seconds} M101\"\n" + two_channels) ==
        "m.toml:7:9: error: codes.dwell M101" + lies);
  CHECK(error_of(head + "[program]\nend_code = \"M102\"\n" + two_channels) ==
        "m.toml:7:12: error: program.end_code M102" + lies);
  CHECK(error_of(head + "[program]\nheader = [\"G40\", \"G18 M101\"]\n" + two_channels) ==
        "m.toml:7:18: error: program.header M101" + lies);
  CHECK(error_of(head + "[program]\nfooter = [\"M9\", \"M5M100\"]\n" + two_channels) ==
        "m.toml:7:17: error: program.footer M100" + lies);
  CHECK(error_of(head + "[[channel]]\nnumber = 1\ntool_call = \"T{tool:02} M100\"\n" + xz) ==
        "m.toml:8:13: error: channel 1: tool_call M100" + lies);
}

TEST_CASE("overlap: what is not a wait word is not refused", "[machines][overlap]") {
  // Comments, placeholders, decimal codes, and wait numbers under another address.
  CHECK(error_of(head +
                 "[program]\nfooter = [\"M9 (M101)\", \"M98.1\", \"G4 P101\", \"DM100\"]\n"
                 "header = [\"({name} M{channel}01)\"]\n" +
                 two_channels) == "(no error)");
}

TEST_CASE("overlap: the step and the excluded codes decide what a wait code is", "[machines][overlap]") {
  const std::string stepped = "[machine]\nname = \"m\"\n[waits]\nfirst = 100\nlast = 110\nstep = 2\n";
  CHECK(error_of(stepped + "[[spindle]]\nname = \"sub\"\ncw = 101\n" + main_spindle + two_channels) ==
        "(no error)");
  CHECK(error_of(stepped + "[[spindle]]\nname = \"sub\"\ncw = 102\n" + main_spindle + two_channels) ==
        "m.toml:9:6: error: spindle 'sub': cw M102 lies in the wait range M100-M110 step 2 ([waits]); a "
        "program could not tell it from a wait");
  CHECK(error_of(stepped + "excluded = [102]\n[[spindle]]\nname = \"sub\"\ncw = 102\n" + main_spindle +
                 two_channels) == "(no error)");
  // A wait address other than M: M codes are never its words.
  CHECK(error_of("[machine]\nname = \"m\"\n[waits]\naddress = \"P\"\nfirst = 100\nlast = 103\n"
                 "[[spindle]]\nname = \"sub\"\ncw = 103\n" +
                 main_spindle + two_channels) == "(no error)");
}

TEST_CASE("overlap: a default code the range swallows is reported where it is left out",
          "[machines][overlap]") {
  // No [codes]: the default M9 is reported at [waits] (the first of the defaults found).
  CHECK(error_of("[machine]\nname = \"m\"\n[waits]\nfirst = 1\nlast = 9\n" + two_channels) ==
        "m.toml:3:1: error: codes.coolant_off M9 (the default) lies in the wait range M1-M9 ([waits]); a "
        "program could not tell it from a wait");
  // A spindle without codes: its default cw M3, at its table.
  CHECK(error_of("[machine]\nname = \"m\"\n[waits]\nfirst = 3\nlast = 5\n[[spindle]]\nname = \"main\"\n" +
                 two_channels) ==
        "m.toml:6:1: error: spindle 'main': cw M3 (the default) lies in the wait range M3-M5 ([waits]); a "
        "program could not tell it from a wait");
  // A range over M6 (a mill head's default tool call T.. M6): the tool change is no wait.
  CHECK(error_of("[machine]\nname = \"m\"\n[waits]\nfirst = 6\nlast = 7\n[[channel]]\nnumber = 1\n"
                 "kind = \"mill_head\"\n" +
                 xz) ==
        "m.toml:3:1: error: the waits take M6, which is the tool change: a wait code must have no other "
        "meaning");
}

TEST_CASE("overlap: the first offending value in the file is reported", "[machines][overlap]") {
  CHECK(error_of(head + "[[spindle]]\nname = \"sub\"\ncw = 103\n[codes]\nprogram_stop = \"M101\"\n" +
                 main_spindle + two_channels) == "m.toml:8:6: error: spindle 'sub': cw M103" + lies);
  CHECK(error_of(head + "[codes]\nprogram_stop = \"M101\"\n[[spindle]]\nname = \"sub\"\ncw = 103\n" +
                 main_spindle + two_channels) == "m.toml:7:16: error: codes.program_stop M101" + lies);
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
                 "step = 99999999\n" +
                 two_channels) == "(no error)");
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

TEST_CASE("a coolant kind is two blocks, on and off", "[machines]") {
  CHECK(error_of(head + "[codes]\ncoolant_mist = [\"M7\"]\n") ==
        "m.toml:7:16: error: codes.coolant_mist must be [on, off], two blocks, not 1");
  CHECK(error_of(head + "[codes]\ncoolant_through = \"M51\"\n") ==
        "m.toml:7:19: error: codes.coolant_through must be an array of strings, not a string");
}

TEST_CASE("validation: the part transfer", "[machines]") {
  const std::string sub = "[[spindle]]\nname = \"main\"\n[[spindle]]\nname = \"sub\"\n";
  CHECK(error_of(head + sub + two_channels + "[transfer]\nchannel = 3\n") ==
        "m.toml:17:11: error: transfer.channel 3 names no channel (the machine has 2)");
  CHECK(error_of(head + two_channels + "[transfer]\nchannel = 1\n") ==
        "m.toml:13:11: error: [transfer] needs a [[spindle]] named 'sub' to take the part");
  CHECK(error_of(head + sub + two_channels + "[transfer]\ngrip = [\"M68\"]\n") ==
        "m.toml:16:1: error: transfer.channel is required");
  CHECK(error_of(head + sub + two_channels + "[transfer]\nchannel = 1\ngrip = [\"M68\", \"M101\"]\n") ==
        "m.toml:18:16: error: transfer.grip M101 lies in the wait range M100-M103 ([waits]); a program could "
        "not tell it from a wait");
  CHECK(error_of(head + sub + two_channels + "[transfer]\nchannel = 1\nsync = true\n") ==
        "m.toml:18:1: error: unknown key 'transfer.sync'");
}

TEST_CASE("validation: the tool table", "[machines]") {
  CHECK(error_of(head + two_channels + "[[tool]]\nnumber = 5\nkind = \"mill\"\n") == "(no error)");
  CHECK(error_of(head + two_channels + "[[tool]]\nnumber = 5\nkind = \"bore\"\n") ==
        "m.toml:14:8: error: tool.kind must be turn, drill or mill, not 'bore'");
  CHECK(error_of(head + two_channels + "[[tool]]\nnumber = 5\nchannel = 3\nkind = \"mill\"\n") ==
        "m.toml:14:11: error: tool.channel 3 names no channel (the machine has 2)");
  CHECK(error_of(head + two_channels +
                 "[[tool]]\nnumber = 5\nkind = \"mill\"\n[[tool]]\nnumber = 5\nkind = \"turn\"\n") ==
        "m.toml:16:10: error: tool 5 is listed twice");
  CHECK(error_of(head + two_channels + "[[tool]]\nkind = \"mill\"\n") ==
        "m.toml:12:1: error: tool.number is required");
}

TEST_CASE("validation: bang waits", "[machines]") {
  const std::string bang = "[machine]\nname = \"m\"\n[waits]\nsyntax = \"bang\"\nfirst = 1\nlast = 99\n";
  CHECK(error_of(bang + two_channels) == "(no error)");
  CHECK(error_of(bang + "partners = \"path_numbers\"\n" + two_channels) ==
        "m.toml:7:12: error: waits.partners must be others with waits.syntax = \"bang\"");
  CHECK(error_of(head + "partners = \"others\"\n" + two_channels) ==
        "m.toml:6:12: error: waits.partners = others needs waits.syntax = \"bang\"");
  CHECK(error_of(head + "marker = \"!\"\n" + two_channels) ==
        "m.toml:6:10: error: waits.marker is read only with waits.syntax = \"bang\"");
  CHECK(error_of(bang + "marker = \"Q\"\n" + two_channels) ==
        "m.toml:7:10: error: waits.marker must be a sign that is no address, digit or comment, not 'Q'");
  CHECK(error_of(bang + "syntax = \"m\"\n") != "(no error)");
}

TEST_CASE("waits.fixed and waits.partner_list: Star-style waits", "[machines]") {
  using test::machine_head;
  using test::two_channels;
  const std::string p12 = "partners = \"path_numbers\"\n";
  CHECK(error_of(machine_head + p12 +
                 "partner_list = \"optional\"\n[[waits.fixed]]\ncode = 82\nchannels = [2, 1]\n" +
                 two_channels) == "(no error)");
  const machine m = parse_machine(
      machine_head + p12 + "partner_list = \"optional\"\n[[waits.fixed]]\ncode = 82\nchannels = [2, 1]\n" +
          two_channels,
      "m.toml");
  CHECK(m.waits.partners_optional);
  REQUIRE(m.waits.fixed.size() == 1);
  CHECK(m.waits.fixed[0].channels == std::vector<int>{1, 2});
  CHECK(m.waits.is_any_wait(82));
  CHECK_FALSE(m.waits.is_wait_code(82));  // never allocated by the post
  CHECK(
      error_of(machine_head + "partner_list = \"optional\"\n" + two_channels) ==
      "m.toml:6:16: error: waits.partner_list = \"optional\" needs waits.partners = path_numbers or binary");
  CHECK(error_of(machine_head + "partner_list = \"maybe\"\n" + two_channels) ==
        "m.toml:6:16: error: waits.partner_list must be required or optional, not 'maybe'");
  CHECK(error_of(machine_head + "[[waits.fixed]]\ncode = 101\nchannels = [1, 2]\n" + two_channels) ==
        "m.toml:7:8: error: waits.fixed code 101 lies in the wait range 100..103: a fixed wait is a code "
        "outside it");
  CHECK(error_of(machine_head + "[[waits.fixed]]\ncode = 82\nchannels = [1, 1]\n" + two_channels) ==
        "m.toml:8:12: error: waits.fixed channels must name at least two different channels");
  CHECK(error_of(machine_head + "[[waits.fixed]]\ncode = 82\nchannels = [1, 3]\n" + two_channels) ==
        "m.toml:3:1: error: waits.fixed code 82 names channel 3, which this machine does not have");
  // A fixed wait is a wait code like the range: no other code of the machine may be one.
  CHECK(error_of(machine_head + "[[waits.fixed]]\ncode = 8\nchannels = [1, 2]\n" + two_channels) ==
        "m.toml:3:1: error: codes.coolant_on M8 (the default) is a fixed wait ([[waits.fixed]]); a program "
        "could "
        "not tell it from a wait");
}

TEST_CASE("validation: mill/turn keys go in pairs and name known choices and index within travel",
          "[machines]") {
  // head is 5 lines: [machine], name, [waits], first, last.
  CHECK(
      error_of(head + "[[spindle]]\nname = \"main\"\nc_on = [\"M200\"]\n" + two_channels) ==
      "m.toml:8:8: error: spindle.c_on and spindle.c_off go together: a spindle held as a C axis must be let "
      "go again");
  CHECK(error_of(head + "[milling]\npolar_off = [\"G13.1\"]\n" + two_channels) ==
        "m.toml:7:13: error: milling.polar_on and milling.polar_off go together");
  CHECK(error_of(head + "[milling]\nface_milling = \"polar\"\n" + two_channels) ==
        "m.toml:7:16: error: milling.face_milling = \"polar\" needs milling.polar_on and polar_off");
  // Cylindrical interpolation: its size once, in the turned frame of cross holes.
  const std::string frame = "radial_frame_on = [\"G68\"]\nradial_frame_off = [\"G69\"]\n";
  CHECK(error_of(head + "[milling]\n" + frame +
                 "cylindrical_on = [\"G7.1 C40.\"]\ncylindrical_off = [\"G7.1 C0\"]\n" + two_channels) ==
        "m.toml:9:18: error: milling.cylindrical_on must hold the cylinder's size once: {radius} or "
        "{diameter}");
  CHECK(
      error_of(head + "[milling]\n" + frame +
               "cylindrical_on = [\"G7.1 C{rad}\"]\ncylindrical_off = [\"G7.1 C0\"]\n" + two_channels) ==
      "m.toml:9:18: error: milling.cylindrical_on: unknown placeholder in \"G7.1 C{rad}\" (it takes {radius} "
      "or {diameter})");
  CHECK(error_of(head +
                 "[milling]\ncylindrical_on = [\"G7.1 C{radius}\"]\ncylindrical_off = [\"G7.1 C0\"]\n" +
                 two_channels) ==
        "m.toml:7:18: error: milling.cylindrical_on needs milling.radial_frame_on: cylindrical interpolation "
        "is "
        "written in the turned frame of cross holes");
  CHECK(error_of(head + "[milling]\n" + frame + "cylindrical_on = [\"G7.1 C{radius}\"]\n" + two_channels) ==
        "m.toml:9:18: error: milling.cylindrical_on and milling.cylindrical_off go together");
  CHECK(error_of(head + "[milling]\nface_holes = \"c\"\n" + two_channels) ==
        "m.toml:7:14: error: milling.face_holes must be one of \"y_axis\", \"c_axis\", not \"c\"");
  CHECK(error_of(head + "[[channel]]\nnumber = 1\n" + test::xz_axes +
                 "[channel.head_index]\nmove = \"G0 G53\"\n") ==
        "m.toml:10:8: error: channel 1 has no axis B to index (channel.axis)");
  CHECK(error_of(
            head +
            "[[channel]]\nnumber = 1\naxis = [{address = \"X\"}, {address = \"Z\"}, {address = \"B\", min = "
            "-30, max = 210}]\n[channel.head_index]\nmove = \"G0 G53\"\nradial = 270\n") ==
        "m.toml:11:10: error: channel.head_index.radial = 270 is outside the travel of axis B");
  CHECK(error_of(
            head +
            "[[channel]]\nnumber = 1\naxis = [{address = \"X\"}, {address = \"Z\"}, {address = \"B\", min = "
            "-30, max = 210}]\n[channel.head_index]\nmove = \"G0 G53\"\naxial_sub = -180\n") ==
        "m.toml:11:13: error: channel.head_index.axial_sub = -180 is outside the travel of axis B");
}

TEST_CASE("validation: a dwell word reads the same on every decimal-point setting", "[machines]") {
  CHECK(error_of(head + "[codes]\ndwell = \"G4 U{ms}\"\n") ==
        "m.toml:7:9: error: codes.dwell \"G4 U{ms}\": U{ms} writes U2000 for 2 s, which a Fanuc reads as 2 s "
        "or "
        "2000 s by its decimal-point setting; write P{ms} (P is always milliseconds) or U{seconds} (written "
        "with "
        "its point)");
  CHECK(error_of(head + "[codes]\ndwell = \"G4 P{seconds}\"\n") ==
        "m.toml:7:9: error: codes.dwell \"G4 P{seconds}\": P{seconds} writes P2. for 2 s, but a Fanuc's P is "
        "milliseconds without a point; write P{ms}, or U{seconds} / X{seconds}");
  CHECK(error_of(head + "[codes]\ndwell = \"G4 X{seconds}\"\n" + two_channels) == "(no error)");
  CHECK(error_of(head + "[codes]\ndwell = \"G4 P{ms}\"\n" + two_channels) == "(no error)");
}

TEST_CASE("validation: a channel's offset call is a template of the tool call's placeholders", "[machines]") {
  CHECK(error_of(head + "[[channel]]\nnumber = 1\n" + xz + "offset_call = \"T{tool:02}{name}\"\n") ==
        "m.toml:9:15: error: channel.offset_call: template \"T{tool:02}{name}\" names {name}, which is not "
        "known "
        "there (it is given {channel}, {tool}, {offset})");
}

TEST_CASE("validation: the grip's last move onto the part is a feed with its own F", "[machines]") {
  // The sub spindle's chuck is open when it reaches the part: a rapid there (the old built-ins'
  // "G0 G53 B#500") crashes the jaws into it at the first error in the position.
  const std::string machine =
      test::machine_head + test::two_channels +
      "[[spindle]]\nname = \"main\"\n[[spindle]]\nname = \"sub\"\n[transfer]\nchannel = 1\n";
  CHECK(error_of(machine + "grip = [\"M169\", \"G0 G53 B#500\", \"M168\"]\n") ==
        "m.toml:18:8: error: transfer.grip brings the sub spindle onto the part with \"G0 G53 B#500\", a "
        "rapid: its "
        "chuck is open and the part is there; make the last move a feed with its own F (G1 ... F.. or a G31 "
        "torque skip), after a rapid to a position short of the part");
  CHECK(error_of(machine + "grip = [\"G0 G53 B#501\", \"G1 G53 B#500\"]\n") ==
        "m.toml:18:8: error: transfer.grip brings the sub spindle onto the part with \"G1 G53 B#500\", a "
        "feed with no "
        "F of its own: its chuck is open and the part is there; make the last move a feed with its own F (G1 "
        "... F.. or a G31 torque skip), after a rapid to a position short of the part");
  CHECK(error_of(machine + "grip = [\"G0 G53 B#501\", \"G98 G1 G53 B#500 F500.\", \"M168\"]\n") ==
        "(no error)");
  CHECK(error_of(machine + "grip = [\"G0 B#501\", \"M86\", \"G31 P99 G53 B#500 F300.\"]\n") == "(no error)");
  // On a Fanuc control G53 moves at rapid whatever the motion mode: the same feed is a rapid.
  std::string fanuc = machine;
  fanuc.replace(fanuc.find("name = \"m\"\n"), 11, "name = \"m\"\ncontrol = \"fanuc-0i-td\"\n");
  CHECK(
      error_of(fanuc + "grip = [\"G0 G53 B#501\", \"G98 G1 G53 B#500 F500.\", \"M168\"]\n") ==
      "m.toml:19:8: error: transfer.grip brings the sub spindle onto the part with \"G98 G1 G53 B#500 "
      "F500.\", "
      "a rapid on a Fanuc control (G53 moves at rapid traverse whatever the motion mode; G53.2 feeds in "
      "machine coordinates where the control has it): its chuck is open and the part is there; make the last "
      "move a feed with its own F (G1 ... F.. or a G31 torque skip), after a rapid to a position short of "
      "the "
      "part");
  CHECK(error_of(fanuc + "grip = [\"G0 G53 B#501\", \"G98 G1 G53.2 B#500 F500.\", \"M168\"]\n") ==
        "(no error)");
}

TEST_CASE("validation: a C-axis code is no spindle code, and side-cycle cross holes need their codes",
          "[machines]") {
  // The Fusion Doosan post's M35/M34 hold and free C, and its unique-M-code table gives them to
  // the live tool as well: the loader refuses the pair (head is 5 lines).
  const std::string spindles =
      "[[spindle]]\nname = \"main\"\nc_on = [\"M35\", \"G0 G28 H0.\"]\nc_off = [\"M34\"]\n"
      "[[spindle]]\nname = \"live\"\ncw = 33\nccw = 34\nstop = 35\n";
  CHECK(
      error_of(head + spindles + two_channels) ==
      "m.toml:8:8: error: spindle.c_on M35 is also the stop code of spindle 'live': a program could not tell "
      "the one from the other");
  CHECK(error_of(head +
                 "[[spindle]]\nname = \"main\"\nc_on = [\"M35\"]\nc_off = [\"M34\"]\nc_clamp = "
                 "\"M3 (CLAMP)\"\nc_unclamp = \"M90\"\n" +
                 two_channels) ==
        "m.toml:10:11: error: spindle.c_clamp M3 is also the cw code of spindle 'main': a program could not "
        "tell the one from the other");
  // M35 in a comment and M35.1 are not the code M35.
  CHECK(error_of(head +
                 "[[spindle]]\nname = \"main\"\nc_on = [\"M35.1 (NOT M35)\"]\nc_off = [\"M34\"]\n"
                 "[[spindle]]\nname = \"live\"\ncw = 33\nccw = 36\nstop = 35\n" +
                 two_channels) == "(no error)");
  CHECK(error_of(head + "[milling]\ncross_holes = \"side_cycle\"\n" + two_channels) ==
        "m.toml:7:15: error: milling.cross_holes = \"side_cycle\" needs cycles.side_drill_code (Fanuc G87): "
        "the holes are drilled with the lathe's side cycles");
  CHECK(error_of(head + "[milling]\ncross_holes = \"sideways\"\n" + two_channels) ==
        "m.toml:7:15: error: milling.cross_holes must be one of \"turned_frame\", \"side_cycle\", not "
        "\"sideways\"");
  const std::string side = "[cycles]\nside_drill_code = \"G87\"\n[milling]\ncross_holes = \"side_cycle\"\n";
  CHECK(
      error_of(head + side + "radial_frame_on = [\"G68\"]\nradial_frame_off = [\"G69\"]\n" + two_channels) ==
      "m.toml:10:19: error: milling.radial_frame_on is the turned frame of cross_holes = \"turned_frame\"; "
      "with \"side_cycle\" the holes are drilled along X without it");
  // With the side cycles, cylindrical interpolation needs no turned frame (the lathe's Z and C).
  CHECK(error_of(head + side +
                 "cylindrical_on = [\"G18 W0 H0\", \"G7.1 C{radius}\"]\ncylindrical_off = "
                 "[\"G7.1 C0\"]\n" +
                 two_channels) == "(no error)");
  CHECK(error_of(head + side + two_channels) == "(no error)");
}
