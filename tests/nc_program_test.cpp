// Reading NC programs into per-channel wait lists (check/nc_program.hpp).
#include <bit>
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <tuple>
#include <unistd.h>

#include <fmt/format.h>

#include "check/nc_program.hpp"
#include "file_test_support.hpp"
#include "machines/macro_variables.hpp"

using namespace twinpost;

namespace {

machine two_channels(int first, int last, std::string marker) {
  machine m;
  m.name = "test";
  m.channels.resize(2);
  m.channels[0].number = 1;
  m.channels[1].number = 2;
  m.waits.first = first;
  m.waits.last = last;
  m.program.section_marker = std::move(marker);
  return m;
}

machine mazak() { return two_channels(950, 997, "G109 L{channel}"); }
machine citizen() { return two_channels(600, 699, "${channel}"); }

std::string words_of(std::string_view line) {
  std::string out;
  for (const nc_word& w : split_nc_words(line)) {
    if (!out.empty()) out += ' ';
    out += w.address + std::string(w.value) + (w.expression ? "!" : "") + "@" + std::to_string(w.column);
  }
  return out;
}

std::string messages(const diagnostic_list& d) {
  std::string out;
  for (const diagnostic& x : d.all()) out += format_diagnostic(x);
  return out;
}

}  // namespace

TEST_CASE("split_nc_words reads words the way controls do", "[check]") {
  CHECK(words_of("N10 G0 X10. Z-1.5") == "N10@1 G0@5 X10.@8 Z-1.5@13");
  CHECK(words_of("M100P12") == "M100@1 P12@5");
  CHECK(words_of("m100 p12") == "M100@1 P12@6");
  CHECK(words_of("M 100") == "M100@1");
  CHECK(words_of("M3 M8 M100") == "M3@1 M8@4 M100@7");
  CHECK(words_of("(M100 WAIT) G0") == "G0@13");
  CHECK(words_of("G0 ; M100 after the end of block") == "G0@1");
  CHECK(words_of("/M100") == "M100@2");
  CHECK(words_of("/2 M100") == "M100@4");
  CHECK(words_of("%") == "");
  CHECK(words_of("  % M100") == "");
  CHECK(words_of("(unclosed M100") == "");
  CHECK(words_of("M#100 M[#1+2]") == "M#100!@1 M[#1+2]!@7");
  CHECK(words_of("IF [#1 EQ 0] GOTO 100") == "");
  CHECK(words_of("#100=5 M101") == "M101@8");
}

TEST_CASE("split files: file n is channel n, and comments hold no waits", "[check]") {
  const machine m = two_channels(100, 103, "");
  diagnostic_list d;
  const nc_programs p =
      read_nc_programs({{"a.nc", "%\nO1000 (PART M100)\nG0 X10.\nn20 m100 (wait)\nM101;\nM30\n%\n"},
                        {"b.nc", "%\r\nO1000\r\nM100\r\nG1 X1. F.2 (M101 IS NEXT)\r\nM101\r\n"}},
                       m, d);
  CHECK(messages(d) == "");
  REQUIRE(p.channels.size() == 2);
  const nc_channel_program& a = p.channels[0];
  CHECK(a.file == "a.nc");
  REQUIRE(a.waits.size() == 2);
  CHECK(a.waits[0].code == 100);
  CHECK(a.waits[0].channel == 1);
  CHECK(a.waits[0].where.line == 4);
  CHECK(a.waits[0].where.column == 5);
  CHECK(a.waits[0].where.source_line == "n20 m100 (wait)");
  CHECK(a.waits[1].where.line == 5);
  CHECK(a.end.line == 6);  // the M30 block
  CHECK(a.end.source_line == "M30");
  const nc_channel_program& b = p.channels[1];
  REQUIRE(b.waits.size() == 2);
  CHECK(b.waits[1].where.source_line == "M101");  // no CR left over
  CHECK(b.end.line == 5);                         // no end code: the last block
}

TEST_CASE("partner lists are recorded as written", "[check]") {
  machine m = two_channels(100, 199, "");
  m.channels.resize(3);
  m.channels[2].number = 3;
  m.waits.partners = partner_style::path_numbers;
  diagnostic_list d;
  const nc_programs p =
      read_nc_programs({{"1.nc", "M100P12\nM101 P1.5\n"}, {"2.nc", ""}, {"3.nc", "M102"}}, m, d);
  REQUIRE(p.channels[0].waits.size() == 2);
  const nc_wait& w = p.channels[0].waits[0];
  CHECK(w.has_partner_list);
  CHECK(w.partner_text == "12");
  CHECK(w.partners == std::vector<int>{1, 2});
  CHECK(w.partner_column == 5);
  CHECK_FALSE(p.channels[0].waits[1].partners_readable);
  CHECK_FALSE(p.channels[2].waits[0].has_partner_list);
  CHECK(p.channels[1].end.line == 0);  // an empty file has no program
}

TEST_CASE("Mazak merged file: common blocks, interleaved sections", "[check]") {
  diagnostic_list d;
  const nc_programs p = read_nc_programs({{"part.eia",
                                           "%\n"
                                           "O1306(PART)\n"      // 2: common
                                           "G109 L1 (UPPER)\n"  // 3
                                           "M950\n"             // 4
                                           "g109l2\n"           // 5
                                           "M950\n"             // 6
                                           "M951\n"             // 7
                                           "N100 G109 L1\n"     // 8
                                           "T0101\n"            // 9
                                           "M951\n"             // 10
                                           "M30\n"              // 11
                                           "%\n"}},
                                         mazak(), d);
  CHECK(messages(d) == "");
  REQUIRE(p.channels[0].waits.size() == 2);
  CHECK(p.channels[0].waits[0].where.line == 4);
  CHECK(p.channels[0].waits[1].where.line == 10);
  CHECK(p.channels[0].end.line == 11);
  REQUIRE(p.channels[1].waits.size() == 2);
  CHECK(p.channels[1].waits[1].where.line == 7);
  CHECK(p.channels[1].end.line == 7);  // its last block
  CHECK(p.channels[1].file == "part.eia");
}

TEST_CASE("a marker block may carry more words", "[check]") {
  diagnostic_list d;
  const nc_programs p = read_nc_programs({{"p.eia", "G109 L1 M950\nG109 L2\nM950\n"}}, mazak(), d);
  CHECK(messages(d) == "");
  REQUIRE(p.channels[0].waits.size() == 1);
  CHECK(p.channels[0].waits[0].where.column == 9);
  CHECK(p.channels[0].end.line == 1);
  CHECK(p.channels[1].waits.size() == 1);
}

TEST_CASE("Citizen merged file: $1, $2 and the $0 data section", "[check]") {
  diagnostic_list d;
  const nc_programs p = read_nc_programs({{"c.nc",
                                           "%\nO3162(PART)\n$1\nM600\nM02\n$2\nM600\nM602\n"
                                           "M99\n$0\nM601\n%\n"}},
                                         citizen(), d);
  CHECK(messages(d) ==
        "c.nc:11:1: warning: wait M601 lies outside every channel's section and is not "
        "checked\nM601\n^\n");
  CHECK(p.channels[0].waits.size() == 1);
  CHECK(p.channels[0].end.line == 5);
  REQUIRE(p.channels[1].waits.size() == 2);
  CHECK(p.channels[1].end.line == 9);
}

TEST_CASE("layout problems are reported", "[check]") {
  diagnostic_list d;
  read_nc_programs({{"a", ""}, {"b", ""}, {"c", ""}}, mazak(), d);
  CHECK(messages(d) ==
        "a: error: this machine has 2 channels but 3 files were given: give one file per "
        "channel, or one file with sections\n");

  diagnostic_list none;
  read_nc_programs({{"one.eia", "M950\n"}}, mazak(), none);
  CHECK(messages(none) ==
        "one.eia: error: no section marker (G109 L{channel}) in this file: this machine has 2 "
        "channels; give one file per channel, or one file with sections\n");

  diagnostic_list missing;
  read_nc_programs({{"m.eia", "G109 L1\nM950\nG109 L3\nM950\n"}}, mazak(), missing);
  CHECK(messages(missing) ==
        "m.eia:3:1: error: section marker G109 L3 opens a section for channel 3, which this "
        "machine does not have\n"
        "G109 L3\n^\n"
        "m.eia: error: no section for channel 2 (G109 L2) in this file\n");

  diagnostic_list unmarked;
  read_nc_programs({{"u.nc", "M100\n"}}, two_channels(100, 103, ""), unmarked);
  CHECK(messages(unmarked) ==
        "u.nc: error: this machine has 2 channels but one file was given, and its programs "
        "have no section markers: give one file per channel\n");
}

TEST_CASE("a marker of an unknown channel is named, and pointed at past its N number", "[check]") {
  diagnostic_list d;
  read_nc_programs({{"m.eia", "G109 L1\nM950\nG109 L2\nM950\n  N20 G109 L3\n$4\n"}}, mazak(), d);
  CHECK(messages(d) ==
        "m.eia:5:7: error: section marker G109 L3 opens a section for channel 3, which this "
        "machine does not have\n"
        "  N20 G109 L3\n      ^\n"
        "m.eia:6:1: error: section marker $4 opens a section for channel 4, which this machine "
        "does not have\n"
        "$4\n^\n");
}

TEST_CASE("waits after the end, two waits in a block, expressions", "[check]") {
  const machine m = two_channels(100, 103, "");
  diagnostic_list d;
  const nc_programs p = read_nc_programs({{"a.nc", "M100 M101\nM#1\nM30\nM102\n"}, {"b.nc", "M100\n"}}, m, d);
  CHECK(messages(d) ==
        "a.nc:1:6: error: two waits in one block (M100 and M101): a wait needs a block of its "
        "own\nM100 M101\n     ^\n"
        "a.nc:2:1: warning: M#1 is a variable or expression: a wait given so cannot be "
        "checked\nM#1\n^\n"
        "a.nc:4:1: warning: wait M102 comes after the end of channel 1's program at a.nc:3 "
        "and is not checked\nM102\n^\n");
  CHECK(p.channels[0].waits.size() == 1);
}

TEST_CASE("near waits: off-step codes and M-codes with partner lists", "[check]") {
  machine m = two_channels(100, 198, "");
  m.waits.step = 2;
  m.waits.excluded = {198};
  diagnostic_list d;
  const nc_programs p = read_nc_programs(
      {{"a.nc", "M101\nM250 P12\nM98 P1000\nG4 P12 M250\nM198 P12\nM100\n"}, {"b.nc", ""}}, m, d);
  REQUIRE(p.channels[0].waits.size() == 1);
  REQUIRE(p.channels[0].near_waits.size() == 2);
  CHECK(p.channels[0].near_waits[0].code == 101);
  CHECK(p.channels[0].near_waits[1].code == 250);
  CHECK(p.channels[0].near_waits[1].partner_text == "12");
}

TEST_CASE("streamed files: the last block survives the reader's buffer", "[check]") {
  // Two files of over two megabytes each (the reader takes one at a time), streamed from
  // disk, neither with an end code: each channel's end is its last block, named with its own
  // file and text, though the buffer it was read into has since been read over by the
  // blank lines that follow it.
  const std::string dir = test::fresh_temp_dir("nc-stream");
  auto write = [&](const std::string& name, const std::string& last) {
    std::string text = "O1000\nM100\n";
    for (int i = 0; text.size() < (1u << 20) + 5000; ++i) text += "G1 X" + std::to_string(i) + ". Z-1.\n";
    text += last + "\n";
    int lines = 0;  // the last block's line
    for (char c : text) lines += c == '\n';
    text.append((1u << 20) + 100, '\n');
    const std::string path = dir + "/" + name;
    REQUIRE(test::write_file(path, text));
    return std::pair{path, lines};
  };
  auto [a_path, a_lines] = write("stream_a.nc", "G0 X100. Z5.");
  auto [b_path, b_lines] = write("stream_b.nc", "G0 X200. Z9.");
  diagnostic_list d;
  const nc_programs p =
      read_nc_programs({{"a.nc", {}, a_path}, {"b.nc", {}, b_path}}, two_channels(100, 103, ""), d);
  CHECK(p.channels[0].end.file == "a.nc");
  CHECK(p.channels[0].end.line == a_lines);
  CHECK(p.channels[0].end.source_line == "G0 X100. Z5.");
  CHECK(p.channels[1].end.file == "b.nc");
  CHECK(p.channels[1].end.line == b_lines);
  CHECK(p.channels[1].end.source_line == "G0 X200. Z9.");
  CHECK(p.channels[0].waits.size() == 1);
  std::filesystem::remove_all(dir);
}

namespace {
// Everything the reader found, as one text to compare.
std::string summary(const nc_programs& p, const diagnostic_list& d) {
  std::string s;
  for (const nc_channel_program& c : p.channels) {
    s += "channel " + std::to_string(c.channel) + " end " + std::to_string(c.end.line) + ":" +
         std::to_string(c.end.column) + " [" + c.end.source_line + "]\n";
    for (const nc_wait& w : c.waits)
      s += " wait M" + std::to_string(w.code) + " P" + w.partner_text + " at " +
           std::to_string(w.where.line) + ":" + std::to_string(w.where.column) + " [" + w.where.source_line +
           "]\n";
    for (const nc_wait& w : c.near_waits)
      s += " near M" + std::to_string(w.code) + " at " + std::to_string(w.where.line) + "\n";
  }
  return s + messages(d);
}
}  // namespace

TEST_CASE("streamed and in-memory reading agree, runs of plain blocks included", "[check]") {
  // Split files of a few megabytes: plain blocks in long runs (read from disk, they are
  // counted, not visited, one by one), with waits, comments, blank and indented lines,
  // CR LF endings in one stretch and lines on the read boundaries. From disk and from
  // memory the reader must find the same.
  std::uint32_t seed = 12345;
  auto next = [&seed] { return seed = seed * 1664525u + 1013904223u; };
  auto program = [&](int waits_from) {
    std::string t = "%\nO0001 (T)\n";
    int wait = waits_from;
    while (t.size() < (3u << 20)) {
      switch (next() % 40) {
        case 0: t += "M" + std::to_string(100 + (wait++ % 100)) + "\n"; break;
        case 1: t += "(COMMENT M5)\n"; break;
        case 2: t += "\n"; break;
        case 3: t += "   G1 X1. Z2.\n"; break;
        case 4: t += "G0 X5.\r\n"; break;
        case 5: t += " \t \n"; break;
        default: t += "G1 X" + std::to_string(next() % 1000) + ". Z-" + std::to_string(next() % 97) + ".5\n";
      }
    }
    return t + "G1 X1. Z1.\n\n  \n";  // no end code: the last block ends the program
  };
  const std::string a = program(100), b = program(100);
  const std::filesystem::path tmp = test::fresh_temp_dir("nc-runs");
  auto put = [&](const std::string& name, const std::string& text) {
    const std::string path = (tmp / name).string();
    REQUIRE(test::write_file(path, text));
    return path;
  };
  const machine m = two_channels(100, 199, "");
  diagnostic_list from_disk, from_memory;
  const nc_programs disk =
      read_nc_programs({{"a.nc", {}, put("a.nc", a)}, {"b.nc", {}, put("b.nc", b)}}, m, from_disk);
  const nc_programs memory = read_nc_programs({{"a.nc", a}, {"b.nc", b}}, m, from_memory);
  std::filesystem::remove_all(tmp);
  REQUIRE(memory.channels[0].waits.size() > 1000);
  CHECK(memory.channels[0].end.source_line == "G1 X1. Z1.");
  CHECK(summary(disk, from_disk) == summary(memory, from_memory));
}

TEST_CASE("a line past 1 MiB ends the reading of its file, from disk and from memory", "[check]") {
  // A line without a line end (a file of NULs) would otherwise be held whole in memory.
  std::string dir = (std::filesystem::temp_directory_path() / "twinpost-longline-XXXXXX").string();
  REQUIRE(::mkdtemp(dir.data()) != nullptr);
  const std::string too_long = "M100\n" + std::string(2u << 20, '\0') + "\nM101\n";
  const std::string longest = "M100\n" + std::string(1u << 20, 'X') + "\nM101\n";
  REQUIRE(test::write_file(dir + "/long.nc", too_long));
  REQUIRE(test::write_file(dir + "/ok.nc", longest));
  const machine m = two_channels(100, 103, "");
  const std::string error =
      "a.nc:2:1048577: error: line 2 is longer than 1048576 bytes: no NC block is that long; "
      "the rest of the file is not read\n";
  diagnostic_list disk, memory, fits;
  const nc_programs p = read_nc_programs({{"a.nc", {}, dir + "/long.nc"}, {"b.nc", "M100\n"}}, m, disk);
  const nc_programs q = read_nc_programs({{"a.nc", too_long}, {"b.nc", "M100\n"}}, m, memory);
  const nc_programs r = read_nc_programs({{"a.nc", {}, dir + "/ok.nc"}, {"b.nc", "M100\n"}}, m, fits);
  std::filesystem::remove_all(dir);
  CHECK(messages(disk) == error);
  CHECK(messages(memory) == error);
  CHECK(p.channels[0].waits.size() == 1);
  CHECK(q.channels[0].waits.size() == 1);
  CHECK(messages(fits) == "");
  CHECK(r.channels[0].waits.size() == 2);
}

namespace {

/// Citizen/Mitsubishi waits `!<partners>L<n>` (waits.syntax = bang), `$n` sections.
machine bang_machine(int channels) {
  machine m;
  m.name = "bang";
  for (int c = 1; c <= channels; ++c) {
    m.channels.emplace_back();
    m.channels.back().number = c;
  }
  m.waits.syntax = wait_syntax::bang;
  m.waits.marker = '!';
  m.waits.address = 'L';
  m.waits.partners = partner_style::others;
  m.waits.first = 1;
  m.waits.last = 9999;
  m.program.section_marker = "${channel}";
  return m;
}

std::string waits_of(const nc_channel_program& p) {
  std::string out;
  for (const nc_wait& w : p.waits) {
    out += out.empty() ? "" : " ";
    out += fmt::format("L{}[{}]", w.code, w.partner_text);
    for (int c : w.partners) out += std::to_string(c);
    out += fmt::format("@{}:{}", w.where.line, w.where.column);
  }
  return out;
}

}  // namespace

TEST_CASE("bang waits: !2L1 in $1 and !1L1 in $2, $0 is data", "[check]") {
  diagnostic_list d;
  const nc_programs p = read_nc_programs({{"p.CNC",
                                           "%\nO1(X)\n$1\nG50 Z0\n!2L1\nN10 !2 L2 (WAIT !2L3)\nM02\nM99\n"
                                           "$2\nT3131\n!1L1\n  !1L2;\nM02\n$0\nD\n#100=0000000012\n%\n"}},
                                         bang_machine(2), d);
  CHECK(messages(d) == "");
  REQUIRE(p.channels.size() == 2);
  CHECK(waits_of(p.channels[0]) == "L1[2]2@5:1 L2[2]2@6:5");
  CHECK(waits_of(p.channels[1]) == "L1[1]1@11:1 L2[1]1@12:3");
  CHECK(p.channels[0].end.line == 7);
  CHECK(p.channels[1].end.line == 13);
}

TEST_CASE("bang waits: three systems, partners together or each after its marker", "[check]") {
  diagnostic_list d;
  const nc_programs p =
      read_nc_programs({{"p.CNC", "$1\n!23L5\n$2\n!1!3L5\n$3\nG0 X1. !12L5\n"}}, bang_machine(3), d);
  CHECK(messages(d) == "");
  CHECK(waits_of(p.channels[0]) == "L5[23]23@2:1");
  CHECK(waits_of(p.channels[1]) == "L5[1!3]13@4:1");
  CHECK(waits_of(p.channels[2]) == "L5[12]12@6:8");
}

TEST_CASE("bang waits: a marker without a number, two waits in a block, L words", "[check]") {
  diagnostic_list d;
  const nc_programs p = read_nc_programs({{"p.CNC", "$1\n!2\nM98 P100 L2\n!2L1 !2L2\n!2L#100\n$2\n!1L1\n"}},
                                         bang_machine(2), d);
  CHECK(messages(d) ==
        "p.CNC:2:1: error: '!2' is no wait: a wait is !<partners>L<number>, e.g. !2L1\n!2\n^\n"
        "p.CNC:4:6: error: two waits in one block (!2L1 and !2L2): a wait needs a block of its own\n"
        "!2L1 !2L2\n     ^\n"
        "p.CNC:3:1: warning: M98 P100 calls a subprogram the checker does not read: waits in it are not "
        "checked\n"
        "M98 P100 L2\n^\n"
        "p.CNC:5:1: warning: !2L#100 is a variable or expression: a wait given so cannot be checked\n"
        "!2L#100\n^\n");
  // The repeat count L2 of M98 is no wait: only an L after the marker is.
  CHECK(waits_of(p.channels[0]) == "L1[2]2@4:1");
}

TEST_CASE("bang waits are not read on an M-code machine", "[check]") {
  diagnostic_list d;
  const nc_programs p = read_nc_programs({{"p.CNC", "$1\n!2L1\nM100\n$2\n!1L1\nM100\n"}},
                                         two_channels(100, 103, "${channel}"), d);
  CHECK(messages(d) == "");
  CHECK(p.channels[0].waits.size() == 1);
  CHECK(p.channels[0].waits[0].code == 100);
}

TEST_CASE("on_block hands over every block of a channel in program order", "[check]") {
  diagnostic_list d;
  std::string got;
  nc_read_options o;
  o.on_block = [&](const nc_block& b) {
    std::string words;
    for (const nc_word& w : b.words()) words += fmt::format(" {}={}", w.address, w.number);
    got += fmt::format("{}:{}:{}:{} [{}] {:x}\n", b.channel, b.file, b.line, b.text, words, b.letters());
  };
  o.on_wait = [&](const nc_wait& w) { got += fmt::format("wait {} at {}\n", w.code, w.where.line); };
  read_nc_programs({{"part.eia",
                     "%\n"
                     "O1306(PART)\n"
                     "G109 L1 (UPPER)\n"
                     "G0 X10.\n"
                     "M950\n"
                     "(comment only)\n"
                     "G109 L2\n"
                     "M950\n"
                     "M30\n"
                     "X1.\n"
                     "%\n"}},
                   mazak(), d, o);
  CHECK(messages(d) == "");
  CHECK(got ==
        "1:part.eia:4:G0 X10. [ G=0 X=10] 800040\n"
        "1:part.eia:5:M950 [ M=950] 1000\n"
        "wait 950 at 5\n"
        "2:part.eia:8:M950 [ M=950] 1000\n"
        "wait 950 at 8\n"
        "2:part.eia:9:M30 [ M=30] 1000\n");
}

TEST_CASE("on_block sees every plain block of a streamed file, runs of them included", "[check]") {
  const std::string dir = test::fresh_temp_dir("on_block");
  const test::removed_at_end cleanup{dir};
  const std::string p1 = dir + "/A_1.nc", p2 = dir + "/A_2.nc";
  REQUIRE(test::write_file(p1, "%\nO1000\nG0 X10.\nG1 X5. F0.1\n\nG1 Z-3.\nM100\nG0 X20.\nM30\n%\n"));
  REQUIRE(test::write_file(p2, "%\nO1000\nG0 X30.\nM100\nM30\n%\n"));
  machine m = two_channels(100, 102, "");
  diagnostic_list d;
  std::string got;
  nc_read_options o;
  o.on_block = [&](const nc_block& b) {
    got += fmt::format("{}:{}:{}", b.channel, b.line, b.text);
    for (const nc_word& w : b.words()) got += fmt::format(" {}{}", w.address, w.number);
    got += '\n';
  };
  read_nc_programs({{"A_1.nc", {}, p1}, {"A_2.nc", {}, p2}}, m, d, o);
  CHECK(messages(d) == "");
  CHECK(got ==
        "1:2:O1000 O1000\n1:3:G0 X10. G0 X10\n1:4:G1 X5. F0.1 G1 X5 F0.1\n1:6:G1 Z-3. G1 Z-3\n"
        "1:7:M100 M100\n1:8:G0 X20. G0 X20\n1:9:M30 M30\n"
        "2:2:O1000 O1000\n2:3:G0 X30. G0 X30\n2:4:M100 M100\n2:5:M30 M30\n");
}

TEST_CASE("jumps, loops and calls the checker does not follow are reported, not passed over", "[check]") {
  diagnostic_list d;
  read_nc_programs({{"J_1.nc",
                     "O1000\n"
                     "N10 G0 X10.\n"
                     "M100\n"
                     "GOTO 10\n"
                     "IF [#1 GT 2] GOTO20 (RETRY)\n"
                     "WHILE [#2 LT 3] DO1\n"
                     "IF [#100 EQ 1] THEN M5\n"
                     "M100\n"
                     "END1\n"
                     "G65 P9010 A1.\n"
                     "m98p1234\n"
                     "(M98 P1 IN A COMMENT, GOTO 5)\n"
                     "M30\n"
                     "M98 P7\n"},
                    {"J_2.nc", "M100\nM30\n"}},
                   two_channels(100, 102, ""), d);
  CHECK(
      messages(d) ==
      "J_1.nc:4:1: warning: GOTO: the checker does not follow jumps; the waits are checked in the order they "
      "are "
      "written\nGOTO 10\n^\n"
      "J_1.nc:5:14: warning: GOTO: the checker does not follow jumps; the waits are checked in the order "
      "they are "
      "written\nIF [#1 GT 2] GOTO20 (RETRY)\n             ^\n"
      "J_1.nc:6:1: warning: WHILE loop: the checker reads its blocks once; waits in it are checked as if it "
      "ran "
      "once\nWHILE [#2 LT 3] DO1\n^\n"
      "J_1.nc:7:1: warning: IF ... THEN: the checker does not evaluate the condition; the codes after THEN "
      "are checked as if it held (a stop there counts as a stop, a wait as a wait)\nIF [#100 EQ 1] THEN "
      "M5\n^\n"
      "J_1.nc:10:1: warning: G65 P9010 calls a macro the checker does not read: waits in it are not checked\n"
      "G65 P9010 A1.\n^\n"
      "J_1.nc:11:1: warning: M98 P1234 calls a subprogram the checker does not read: waits in it are not "
      "checked\nm98p1234\n^\n");
}

// A word's value is a view into the split line: a temporary string would leave every word
// pointing into freed memory, so splitting one must not compile; a string that lives, a view
// and a literal split as before.
template <class S>
concept splittable = requires(S s) {
  split_nc_words(std::forward<S>(s));
};
static_assert(!splittable<std::string>, "a temporary std::string dies before its words");
static_assert(splittable<const std::string&> && splittable<std::string_view> && splittable<const char*>);

TEST_CASE("a word's value is a view into the split line", "[check]") {
  const std::string line = "G1 X-12.5 (X9) M#100";
  const std::vector<nc_word> words = split_nc_words(line);
  REQUIRE(words.size() == 3);
  CHECK(words[1].value == "-12.5");
  CHECK(words[1].value.data() == line.data() + 4);  // in the line, not a copy
  CHECK(words[2].value == "#100");
  CHECK(words[2].value.data() == line.data() + 16);
}

TEST_CASE("may_have says what letters() says, split or not", "[check]") {
  constexpr std::uint32_t gms = nc_letter('G') | nc_letter('M') | nc_letter('S');
  const std::string file = "p.nc";
  std::vector<nc_word> store;
  for (const std::string_view text :
       {"X10. Z5.", "G1 X10.", "x1 (MOVE) z2", "m3", "X1 s200", "(g) X1", "T0101"}) {
    INFO(text);
    for (const std::uint32_t mask :
         {gms, nc_letter('G'), nc_letter('S'), nc_letter('X'), gms | nc_letter('T')}) {
      const nc_block fresh(1, file, 1, text, store);
      const bool want = (nc_block(1, file, 1, text, store).letters() & mask) != 0;
      CHECK(fresh.may_have(mask) == want);  // not split: the G/M/S scan or the letters
      (void)fresh.words();
      CHECK(fresh.may_have(mask) == ((fresh.letters() & mask) != 0));  // split: exact
    }
  }
}

TEST_CASE("a '#' outside the comments is in the letters as nc_variable_bit, split or not", "[check]") {
  std::vector<nc_word> words;
  const std::string file = "p.nc";
  // Each line, whether the split sets the bit, and whether it uses a variable as macro_uses reads
  // it: the bit is never missing where macro_uses finds one (a comment's '#' is not one; after a
  // ';' the bit is set all the same, the ';' may stand in a comment a bracket's '(' opened).
  for (const auto& [text, bit, uses] : std::vector<std::tuple<std::string_view, bool, bool>>{
           {"#5221=-5.", true, true},
           {"G1 X#100 Z5.", true, true},
           {"G65 P9000 A[#1+2.]", true, true},
           {"IF [#1 EQ 0] GOTO 10", true, true},
           {"X[1+2] Z5.", false, false},
           {"G1 X10. (#5 IN A COMMENT)", false, false},
           {"G1 X10. ; #500=0", true, false},
           {"IF [1 EQ 1(]; )] THEN #501=1.", true, true},  // attack 70 F1
           {"G1 X[1(]; )#501=1. Z-5.", true, true},
           {"/ #5221=1.", true, true},
           {"%#1", true, true},
           {"G1 X10. Z5.", false, false}}) {
    INFO(text);
    CHECK(((split_nc_words(text, words) & nc_variable_bit) != 0) == bit);
    CHECK(!macro_uses(text).empty() == uses);
    // Not split, the letters are a superset: every '#', a comment's too.
    const nc_block b(1, file, 1, text, words);
    CHECK(((b.letters() & nc_variable_bit) != 0) == (text.find('#') != std::string_view::npos));
  }
}

TEST_CASE("the variable bit is never missing where macro_uses finds a variable", "[check]") {
  // Random lines of the pieces that open and close comments, brackets and variables (attack 70
  // fuzzed 20 M lines of characters to find `[..(..]..;..)..#n`).
  const std::vector<std::string_view> pieces = {"[", "]",       "(",  ")",   ";", "/",
                                                "%", "#501=1.", "#1", "X2.", " ", "IF"};
  std::uint64_t x = 0x9E3779B97F4A7C15ULL;
  std::vector<nc_word> words;
  for (int k = 0; k < 100000; ++k) {
    std::string line;
    x ^= x << 13, x ^= x >> 7, x ^= x << 17;
    const int length = 1 + static_cast<int>(x % 9);
    for (int c = 0; c < length; ++c) {
      x ^= x << 13, x ^= x >> 7, x ^= x << 17;
      line += pieces[x % pieces.size()];
    }
    INFO(line);
    if (!macro_uses(line).empty()) REQUIRE((split_nc_words(line, words) & nc_variable_bit) != 0);
  }
}

TEST_CASE("split_nc_words decodes each number once, as from_chars reads it", "[check]") {
  // Every value the splitter can hand over: signs, points, leading zeros, digit counts past
  // the exact path (15) and past 19, and what is no number.
  std::vector<std::string> values = {"0",
                                     "-0",
                                     "+0",
                                     "1",
                                     "1.",
                                     ".5",
                                     "-.5",
                                     "007",
                                     "0.0001",
                                     "-12.345",
                                     "100.",
                                     "99999999",
                                     "1.2.3",
                                     ".",
                                     "12.",
                                     "3.14159265358979",
                                     "123456789012345",
                                     "1234567890123456",
                                     "12345678901234567890123",
                                     "0.1234567890123456789"};
  std::uint64_t x = 88172645463325252ULL;  // xorshift: random digit strings of every length
  for (int k = 0; k < 20000; ++k) {
    x ^= x << 13, x ^= x >> 7, x ^= x << 17;
    std::string v = (x & 1) ? "-" : "";
    const int digits = 1 + static_cast<int>((x >> 1) % 22);
    const int point = static_cast<int>((x >> 8) % (digits + 2)) - 1;  // -1: none
    for (int d = 0; d < digits; ++d) {
      if (d == point) v += '.';
      v += static_cast<char>('0' + (x >> (12 + d % 40)) % 10);
    }
    values.push_back(v);
  }
  std::vector<nc_word> words;
  for (const std::string& v : values) {
    // Followed by a blank and a word, by a letter at once, and by the line's end: the number is
    // read eight characters at a time where it ends within them (the line's end included).
    for (const std::string& after : {std::string(" M3"), std::string("M3"), std::string()}) {
      INFO(v << " then '" << after << "'");
      const std::string line = "X" + v + after;  // lives while its words are read
      const std::uint32_t letters = split_nc_words(line, words);
      REQUIRE(words.size() == (after.empty() ? 1u : 2u));
      CHECK(words[0].value == v);
      double want = 0;
      const bool ok = nc_number(words[0].value, want);
      CHECK(words[0].numeric == ok);
      if (ok) {
        CHECK(std::bit_cast<std::uint64_t>(words[0].number) == std::bit_cast<std::uint64_t>(want));
        CHECK(words[0].point == (v.find('.') != std::string::npos));
      }
      if (after.empty()) {
        CHECK(letters == nc_letter('X'));
        continue;
      }
      CHECK(words[1].numeric);
      CHECK(words[1].number == 3);
      CHECK(letters == (nc_letter('X') | nc_letter('M')));
    }
  }
  split_nc_words("G1 X#100 Y[#1+2] (Z5) f200", words);
  REQUIRE(words.size() == 4);
  CHECK((words[1].numeric || words[2].numeric) == false);
  CHECK(words[3].address == 'F');
  CHECK(words[3].number == 200);
}

namespace {

// What a reading hands on, as text: every block and wait in the order they came, per channel
// (channels read one after the other or interleaved give the same), the programs' ends and
// the reading's problems.
struct reading_log {
  std::vector<std::string> per_channel[2];
  nc_read_options options() {
    nc_read_options o;
    o.on_block = [this](const nc_block& b) {
      std::string words;
      for (const nc_word& w : b.words()) words += fmt::format(" {}{}", w.address, w.value);
      per_channel[b.channel - 1].push_back(fmt::format("{}:{} '{}'{}", b.file, b.line, b.text, words));
    };
    o.on_wait = [this](const nc_wait& w) {
      per_channel[w.channel - 1].push_back(
          fmt::format("wait M{} at {}:{}:{}", w.code, w.where.file, w.where.line, w.where.column));
    };
    return o;
  }
};

std::string ends_and_problems(const nc_programs& p, const diagnostic_list& d) {
  std::string s;
  for (const nc_channel_program& c : p.channels)
    s += fmt::format("channel {} in {} ends at {}:{} '{}'\n", c.channel, c.file, c.end.file, c.end.line,
                     c.end.source_line);
  for (const diagnostic& x : d.all()) s += fmt::format("{}:{}:{}: {}\n", x.file, x.line, x.column, x.message);
  return s;
}

}  // namespace

TEST_CASE("nc_stream_reader: two programs fed in interleaved pieces cut anywhere read as their files") {
  const machine m = two_channels(100, 199, "");
  // CR LF, a lone CR, a byte order mark, a comment, a last line without its line end.
  const std::string one = "%\r\nO1000 (FIRST)\r\nG0 X10. Z5.\r\nM100\r\nG1 X5. F0.2\rG0 X20.\r\nM30\r\n%";
  const std::string two = "\xEF\xBB\xBF%\nO2000\nG0 X20. Z1.\n\nM100\nG1 Z-5. F0.1\nM30\n%\n";
  std::vector<nc_source> files = {{"one.nc", one}, {"two.nc", two}};
  reading_log whole;
  diagnostic_list whole_problems;
  const nc_programs expected = read_nc_programs(files, m, whole_problems, whole.options());
  REQUIRE(whole.per_channel[0].size() == 7);  // 6 blocks (not '%') and the wait
  REQUIRE(whole.per_channel[0][1] == "one.nc:3 'G0 X10. Z5.' G0 X10. Z5.");
  REQUIRE(whole.per_channel[1][3] == "wait M100 at two.nc:5:1");
  for (std::size_t cut = 1; cut <= 9; ++cut) {
    CAPTURE(cut);
    reading_log pieces;
    diagnostic_list problems;
    nc_stream_reader r(m, problems, pieces.options());
    r.open(2, "two.nc");
    r.open(1, "one.nc");
    // Channel 2 first, then the two in turns: a piece of `cut` bytes each (a copy, with the
    // NUL the reader asks for after it).
    std::size_t at[2] = {0, 0};
    const std::string* text[2] = {&one, &two};
    for (int turn = 1; at[0] < one.size() || at[1] < two.size(); turn ^= 1) {
      if (at[turn] >= text[turn]->size()) continue;
      const std::string piece = text[turn]->substr(at[turn], cut);
      r.feed(turn + 1, piece);
      at[turn] += piece.size();
    }
    const nc_programs got = r.finish();
    CHECK(pieces.per_channel[0] == whole.per_channel[0]);
    CHECK(pieces.per_channel[1] == whole.per_channel[1]);
    CHECK(ends_and_problems(got, problems) == ends_and_problems(expected, whole_problems));
  }
}
