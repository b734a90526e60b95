// Machine definitions: the built-in machines, loading by name and path, the small look-ups
// and templates. The validation errors are in machine_validation_test.cpp.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "file_test_support.hpp"
#include "machine_test_support.hpp"
#include "machines/machine.hpp"
#include "machines/machine_loader.hpp"
#include "machines/name_template.hpp"

using namespace twinpost;

namespace {

const std::string& head = test::machine_head;
using test::two_channels;
const std::string& xz = test::xz_axes;

}  // namespace

TEST_CASE("a minimal machine loads with the documented defaults", "[machines]") {
  const machine m = parse_machine(head + two_channels, "m.toml");
  CHECK(m.name == "m");
  CHECK(m.source == "m.toml");
  CHECK(m.layout == layout_kind::split);
  CHECK(m.waits.address == 'M');
  CHECK(m.waits.step == 1);
  CHECK(m.waits.partners == partner_style::none);
  REQUIRE(m.channels.size() == 2);
  CHECK(m.channels[0].tool_call == "T{tool:02}{offset:02}");  // kind turret
  CHECK(m.channels[0].spindle == "main");
  CHECK(m.program.extension == ".nc");
  CHECK(m.program.program_line == "O{program:04} ({name})");
  CHECK(m.codes.dwell == "G4 U{seconds}");
  CHECK(m.limits.max_feed == 0);  // no limit
}

TEST_CASE("channels are sorted by number and a mill head defaults to an M6 tool call", "[machines]") {
  const machine m = parse_machine(
      head + "[[channel]]\nnumber = 2\nkind = \"mill_head\"\n" + xz + "[[channel]]\nnumber = 1\n" + xz,
      "m.toml");
  REQUIRE(m.channels.size() == 2);
  CHECK(m.channels[0].number == 1);
  CHECK(m.channels[1].number == 2);
  CHECK(m.channels[1].tool_call == "T{tool:02} M6");
}

TEST_CASE("built-in integrex-i200st", "[machines]") {
  const machine m = load_machine("integrex-i200st");
  CHECK(m.name == "integrex-i200st");
  CHECK(m.source == "machines/builtin/integrex-i200st.toml");
  CHECK(m.control == "mazak-smoothx");
  CHECK(m.layout == layout_kind::merged_appended);
  CHECK(m.program.section_marker == "G109 L{channel}");
  CHECK(m.program.extension == ".EIA");
  CHECK(format_template(m.program.program_line, {.program = 1000, .name = "PART"}) == "O1000(PART)");
  CHECK(m.program.end_code == "M30");
  CHECK(m.program.header.at(0) == "G21");
  CHECK(m.codes.feed_per_min == "G94");
  CHECK(m.codes.feed_per_rev == "G95");
  CHECK(m.codes.css == "G96");
  CHECK(m.codes.rpm == "G97");
  CHECK(m.waits.first == 950);
  CHECK(m.waits.last == 997);
  CHECK(m.waits.step == 1);
  CHECK(m.waits.reuse);
  CHECK(m.limits.max_feed == 20000);

  REQUIRE(m.channels.size() == 2);
  const channel_def& upper = m.channels[0];
  CHECK(upper.tool_call == "T{tool:02} M6");
  CHECK(m.channel_for_head(1) == &upper);
  CHECK(m.channel_for_head("MAIN") == &upper);
  const channel_def& lower = m.channels[1];
  CHECK(lower.tool_call == "T{tool:02}{offset:02}");
  CHECK(m.channel_for_head(2) == &lower);
  CHECK(m.channel_for_head("side") == &lower);
  REQUIRE(lower.axis('X'));
  CHECK(lower.axis('X')->diameter);
  CHECK(lower.axis('X')->mirror);
  CHECK_FALSE(upper.axis('X')->mirror);
  CHECK(lower.axis('Y') == nullptr);

  const spindle_def* main_sp = m.spindle("main");
  const spindle_def* sub_sp = m.spindle("sub");
  const spindle_def* live = m.spindle("live");
  REQUIRE(main_sp);
  REQUIRE(sub_sp);
  REQUIRE(live);
  CHECK((main_sp->cw == 203 && main_sp->ccw == 204 && main_sp->stop == 205));
  CHECK((sub_sp->cw == 303 && sub_sp->ccw == 304 && sub_sp->stop == 305));
  CHECK(main_sp->select == 901);
  CHECK(sub_sp->select == 902);
  CHECK(main_sp->clamp == "G92 S{max} R1");
  CHECK(sub_sp->clamp == "G92 S{max} R2");
  CHECK((live->cw == 3 && live->ccw == 4 && live->stop == 5));
  CHECK_FALSE(live->select);
  CHECK(m.spindle("tail") == nullptr);
  CHECK(m.channel_for_head(3) == nullptr);
  CHECK(m.channel_for_head("BOTH") == nullptr);
}

TEST_CASE("built-in fanuc-0itd-twin", "[machines]") {
  const machine m = load_machine("fanuc-0itd-twin");
  CHECK(m.name == "fanuc-0itd-twin");
  CHECK(m.layout == layout_kind::split);
  CHECK(m.program.extension == ".nc");
  CHECK(m.program.header == std::vector<std::string>{"G0 G18 G21 G40 G54 G80 G99"});
  CHECK(m.program.end_code == "M30");
  CHECK(m.codes.home == std::vector<std::string>{"G28 U0.", "G28 W0."});
  CHECK(m.codes.dwell == "G4 U{seconds}");
  CHECK(m.codes.feed_per_rev == "G99");
  CHECK(m.codes.feed_per_min == "G98");
  CHECK(m.waits.first == 100);
  CHECK(m.waits.last == 102);  // M103 is the Doosan sub spindle's CW
  CHECK(m.waits.reuse);
  CHECK(m.waits.partners == partner_style::none);
  REQUIRE(m.channels.size() == 2);
  for (const channel_def& c : m.channels) {
    CHECK(c.tool_call == "T{tool:02}{offset:02}");
    REQUIRE(c.axis('X'));
    CHECK(c.axis('X')->diameter);
  }
  CHECK_FALSE(m.channels[0].axis('X')->mirror);  // path 1: upper turret, X as in the CL
  CHECK(m.channels[1].axis('X')->mirror);        // path 2: lower turret, below the centre
  CHECK(m.channels[0].file_suffix == "_1");
  CHECK(m.channels[1].file_suffix == "_2");
  REQUIRE(m.spindle("main"));
  CHECK(m.spindle("main")->clamp == "G50 S{max}");
  // The Doosan sub-spindle codes; M203/M205 are spindle synchronisation there.
  REQUIRE(m.spindle("sub"));
  CHECK((m.spindle("sub")->cw == 103 && m.spindle("sub")->ccw == 104 && m.spindle("sub")->stop == 105));
}

TEST_CASE("built-in fanuc-31i-3path", "[machines]") {
  const machine m = load_machine("fanuc-31i-3path");
  CHECK(m.name == "fanuc-31i-3path");
  CHECK(m.layout == layout_kind::split);
  REQUIRE(m.channels.size() == 3);
  // The B head: M6 T0700 changes the tool, T0707 takes its offset (the Fusion Doosan post).
  CHECK(m.channels[2].tool_call == "M6 T{tool:02}00");
  CHECK(m.channels[2].offset_call == "T{tool:02}{offset:02}");
  CHECK(m.channel_for_head(3) == &m.channels[2]);
  CHECK(m.waits.first == 200);
  CHECK(m.waits.last == 299);
  // The Doosan codes of the range are never waits: synchronisation M203/M205/M213 and the
  // Y-axis interlock release M272/M273.
  CHECK(m.waits.excluded == std::vector<int>{203, 205, 213, 272, 273});
  CHECK_FALSE(m.waits.is_wait_code(203));
  CHECK(m.waits.is_wait_code(204));
  CHECK(m.waits.partners == partner_style::path_numbers);
  CHECK(m.waits.partner_address == 'P');
}

TEST_CASE("builtin_machines lists every built-in, sorted, with its description", "[machines]") {
  const std::vector<machine_summary> all = builtin_machines();
  REQUIRE(all.size() == 8);
  CHECK(all[0].name == "citizen-2system");
  CHECK(all[1].name == "fanuc-0itd-twin");
  CHECK(all[2].name == "fanuc-31i-3path");
  CHECK(all[3].name == "head-head-5axis");
  CHECK(all[4].name == "integrex-i200st");
  CHECK(all[5].name == "rotary-4axis");
  CHECK(all[6].name == "star-3path");
  CHECK(all[7].name == "trunnion-5axis");
  for (const machine_summary& s : all) CHECK_FALSE(s.description.empty());
}

TEST_CASE("load_machine reads a file, and names what it cannot read", "[machines]") {
  const std::filesystem::path dir = test::fresh_temp_dir("loader");
  const std::string path = (dir / "machine.toml").string();
  {
    std::ofstream out(path);
    out << head << two_channels;
  }
  CHECK(load_machine(path).source == path);
  std::filesystem::remove(path);
  CHECK_THROWS_WITH(load_machine(path), "cannot read machine file '" + path + "'");
  CHECK_THROWS_WITH(load_machine(dir.string()), "cannot read machine file '" + dir.string() + "'");
  std::filesystem::remove_all(dir);
  CHECK_THROWS_WITH(load_machine("integrex"),
                    "unknown machine 'integrex': no built-in machine and no "
                    "file of that name");
}

TEST_CASE("is_wait_code: range, step and excluded codes", "[machines]") {
  wait_rules w;
  w.first = 100;
  w.last = 110;
  w.step = 2;
  w.excluded = {104};
  CHECK(w.is_wait_code(100));
  CHECK(w.is_wait_code(102));
  CHECK_FALSE(w.is_wait_code(101));  // off the step grid
  CHECK_FALSE(w.is_wait_code(104));  // excluded
  CHECK(w.is_wait_code(110));
  CHECK_FALSE(w.is_wait_code(98));
  CHECK_FALSE(w.is_wait_code(112));
}

TEST_CASE("format_template formats the named placeholders", "[machines]") {
  template_args a;
  a.program = 42;
  a.name = "SHAFT";
  a.channel = 2;
  a.max = 3500;
  a.tool = 5;
  a.offset = 7;
  a.seconds = 0.5;
  a.ms = 500;
  a.rpm = 1200;
  CHECK(format_template("O{program:04}({name})", a) == "O0042(SHAFT)");
  CHECK(format_template("T{tool:02}{offset:02}", a) == "T0507");
  CHECK(format_template("G92 S{max} R{channel}", a) == "G92 S3500 R2");
  CHECK(format_template("G4 U{seconds} (P{ms}) S{rpm}", a) == "G4 U0.5 (P500) S1200");
  CHECK(format_template("{{literal}}", a) == "{literal}");
  // {seconds} always has its point (a Fanuc reads U1 as 1 ms with decimal-point input off),
  // rounded to the millisecond; a spec of the file's own is fmt's.
  for (const auto& [s, text] : std::vector<std::pair<double, std::string>>{
           {1, "U1."}, {2.25, "U2.25"}, {0.0004, "U0."}, {1.23456, "U1.235"}, {120, "U120."}}) {
    a.seconds = s;
    CHECK(format_template("U{seconds}", a) == text);
  }
  CHECK(format_template("U{seconds:.2f}", a) == "U120.00");
  CHECK_THROWS_AS(format_template("G50 S{}", a), fmt::format_error);
  CHECK_THROWS_AS(format_template("T{tol}", a), fmt::format_error);
}

TEST_CASE("a number of the machine file is finite", "[machines]") {
  // Attack 45: TOML's nan passed every comparison with a limit (a rotary max = nan wrote A150.
  // on a head that stops at 110, max_feed = nan switched the feed check off).
  CHECK(test::machine_error_of(test::machine_head + "[limits]\nmax_feed = nan\n" + test::two_channels) ==
        "m.toml:7:12: error: limits.max_feed must be a finite number, not nan");
  CHECK(test::machine_error_of(test::machine_head + "[limits]\nmax_feed = -inf\n" + test::two_channels) ==
        "m.toml:7:12: error: limits.max_feed must be a finite number, not -inf");
}

TEST_CASE("a code that would make the control read something else is refused at its key", "[machines]") {
  const auto error_of = [](const std::string& tables) {
    return test::machine_error_of(test::machine_head + tables + test::two_channels);
  };
  // The post writes X Y Z R F after the cycle code: a comment to the end of the line takes them.
  CHECK(error_of("[program]\ncomment_open = \";\"\n[cycles]\ndrill_code = \"G81 ;\"\n") ==
        "m.toml:9:14: error: cycles.drill_code \"G81 ;\": ';' makes a comment of the rest of the block: the "
        "words "
        "twinpost writes after this code would not be read (a comment to the end of the line belongs in a "
        "block of its own)");
  CHECK(error_of("[cycles]\ndrill_code = \"G81 (DRILL\"\n") ==
        "m.toml:7:14: error: cycles.drill_code \"G81 (DRILL\": '(' opens a comment that no ')' closes: the "
        "words "
        "after it would not be read");
  CHECK(error_of("[codes]\ncoolant_on = [\"M8\", \"M30\"]\n") ==
        "m.toml:7:21: error: codes.coolant_on \"M30\": M30 ends the program (M99 goes back to its start) "
        "there: only program.end_code and the footer may end it");
  // A comment that closes, a comment line of the header, the end codes where they belong, and
  // M98 and M300 (no end) are codes as given.
  CHECK(error_of("[program]\ncomment_open = \";\"\nheader = [\";PART ONE\", \"G90\"]\nfooter = "
                 "[\"M99\"]\nend_code = \"M02\"\n[cycles]\ndrill_code = "
                 "\"M98 M300 G81\"\n") == "(no error)");
  CHECK(error_of("[cycles]\ndrill_code = \"G81 (PECK 2)\"\n") == "(no error)");
  CHECK(error_of("[codes]\ncoolant_on = [\"M2=70 M8\"]\n") == "(no error)");  // Sinumerik: spindle 2's M70
  // Blanks inside a word are dropped, as a control reads it (attack 45: "M 30" passed).
  CHECK(
      error_of("[codes]\ndwell = \"G4 M 3 0\"\n") ==
      "m.toml:7:9: error: codes.dwell \"G4 M 3 0\": M30 ends the program (M99 goes back to its start) there: "
      "only program.end_code and the footer may end it");
  // A spindle code given as a number that is a stop, an end, a tool change or a call.
  CHECK(error_of("[[spindle]]\nname = \"main\"\ncw = 30\n") ==
        "m.toml:8:6: error: spindle 'main': cw M30 is the program's end, no spindle code");
  // A home or a code that leaves G91 in force: every later move would be an increment.
  CHECK(
      error_of("[codes]\nhome = [\"G91 G28 Z0.\"]\n") ==
      "m.toml:7:8: error: codes.home: its blocks leave G91 (incremental) in force, and the post writes every "
      "move after them as absolute positions: end them with G90");
  CHECK(error_of("[codes]\nhome = [\"G91 G28 Z0.\", \"G90\"]\n") == "(no error)");
  CHECK(
      error_of("[codes]\ndwell = \"G91 G4\"\n") ==
      "m.toml:7:9: error: codes.dwell \"G91 G4\": it leaves G91 (incremental) in force, and the post writes "
      "every move after it as absolute positions: end it with G90");
  // A ( is a comment on the control whatever the post's comments; ) opens none, ( closes none.
  CHECK(
      error_of("[program]\ncomment_open = \";\"\n[codes]\ndwell = \"G4 (X\"\n") ==
      "m.toml:9:9: error: codes.dwell \"G4 (X\": '(' opens a comment on the control that no ')' closes: the "
      "words after it would not be read");
  CHECK(
      error_of("[program]\ncomment_open = \"<\"\ncomment_close = \"(\"\n") ==
      "m.toml:8:17: error: program.comment_open may not be ) nor comment_close (: every control reads ( as a "
      "comment's start and ) as its end");
  // A cycle code that moves (attack 45: drill_code = "G0" rapided to the bottom).
  CHECK(
      error_of("[cycles]\ndrill_code = \"G0\"\n") ==
      "m.toml:7:14: error: cycles.drill_code \"G0\" holds G0, a motion code: the hole's words would move the "
      "tool to its bottom at that motion");
  CHECK(error_of("[program]\ncomment_open = \":\"\n") ==
        "m.toml:7:16: error: program.comment_open must be a character no block word uses, such as ( or ;");
}

TEST_CASE("a comment to the end of the line: a semicolon comment_open with no comment_close, or an empty one",
          "[machines]") {
  const auto program = [](const std::string& keys) {
    return parse_machine(test::machine_head + "[program]\n" + keys + test::two_channels, "m.toml").program;
  };
  CHECK(program("").comment_open == '(');
  CHECK(program("").comment_close == ')');
  CHECK(program("comment_open = \";\"\n").comment_close == '\n');
  CHECK(program("comment_open = \"<\"\ncomment_close = \"\"\n").comment_close == '\n');
  CHECK(program("comment_open = \"<\"\ncomment_close = \">\"\n").comment_close == '>');
  // A character of the block's own words, or a ( that does not close with ), is refused.
  const auto error_of = [](const std::string& keys) {
    return test::machine_error_of(test::machine_head + "[program]\n" + keys + test::two_channels);
  };
  CHECK(error_of("comment_open = \"X\"\n") ==
        "m.toml:7:16: error: program.comment_open must be a character no block word uses, such as ( or ;");
  CHECK(error_of("comment_open = \"%\"\ncomment_close = \";\"\n") ==
        "m.toml:7:16: error: program.comment_open must be a character no block word uses, such as ( or ;");
  CHECK(error_of("comment_open = \";\"\ncomment_close = \"1\"\n") ==
        "m.toml:8:17: error: program.comment_close must be a character no block word uses, such as ), or "
        "\"\" (to "
        "the end of the line)");
  CHECK(error_of("comment_open = \")\"\n") ==  // the default close: once a crash (attack 44)
        "m.toml:7:16: error: program.comment_close must differ from comment_open (')')");
  CHECK(error_of("comment_close = \"\"\n") ==
        "m.toml:7:17: error: program.comment_open = \"(\" is closed by \")\": a control reads a ( comment on "
        "until "
        "its )");
  CHECK(test::machine_error_of(test::machine_head +
                               "[program]\ncomment_open = \";\"\ncomment_close = \";\"\n" +
                               test::two_channels) ==
        "m.toml:8:17: error: program.comment_close must differ from comment_open (';')");
  CHECK(test::machine_error_of(test::machine_head + "[program]\ncomment_close = \"))\"\n" +
                               test::two_channels) ==
        "m.toml:7:17: error: program.comment_close must be one character, not '))'");
}

TEST_CASE("a coolant code that is an indexing head's clamp or unclamp code is refused", "[machines]") {
  // Attack 71 F6: the Integrex with coolant_through = ["M108", "M109"] (the Fanuc lathes' codes)
  // loaded, and every index of the B head (M108 unclamp, M107 clamp) turned the coolant on.
  std::string text =
      test::read_file(std::string(TWINPOST_SOURCE_DIR) + "/machines/builtin/integrex-i200st.toml");
  const std::string line = "coolant_through = [\"M51\", \"M163\"]";
  REQUIRE(text.find(line) != std::string::npos);
  const std::size_t at = text.find(line);
  text.replace(at, line.size(), "coolant_through = [\"M108\", \"M109\"]");
  CHECK(
      test::machine_error_of(text) ==
      "m.toml:89:19: error: codes.coolant_through \"M108\" holds M108, channel 1's head_index.unclamp code: "
      "the "
      "post writes it at every index of the head, where the control would turn the coolant on too; give the "
      "coolant a code of its own");
}
