// The synchronisation checker and its report (check/sync_check.hpp,
// check/sync_report.hpp). Messages are asserted to the letter.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>

#include "check/sync_check.hpp"
#include "check/sync_report.hpp"
#include "file_test_support.hpp"
#include "machines/machine_loader.hpp"

using namespace twinpost;

namespace {

machine make_machine(int channels, int first, int last, partner_style partners, std::string marker = "",
                     std::string control = "fanuc-test") {
  machine m;
  m.name = "test";
  m.control = std::move(control);
  for (int c = 1; c <= channels; ++c) {
    m.channels.emplace_back();
    m.channels.back().number = c;
  }
  m.waits.first = first;
  m.waits.last = last;
  m.waits.partners = partners;
  m.program.section_marker = std::move(marker);
  return m;
}

/// Mazak-like twin head: M950-M997, one merged file with G109 L1 / G109 L2 sections.
machine mazak() { return make_machine(2, 950, 997, partner_style::none, "G109 L{channel}", "mazak-smoothx"); }
/// Fanuc 2-path: M100-M103, plain waits in both paths.
machine fanuc2() { return make_machine(2, 100, 103, partner_style::none); }
/// Fanuc 3-path: M100-M197, partners as path numbers (P12, P123).
machine fanuc3() { return make_machine(3, 100, 197, partner_style::path_numbers); }
/// Fanuc 3-path with parameter 8103#1: partners as a binary mask (P3, P7).
machine fanuc3_binary() { return make_machine(3, 100, 197, partner_style::binary); }

std::string check_text(const std::vector<nc_source>& files, const machine& m) {
  return format_sync_text(check_nc_files(files, m));
}

}  // namespace

TEST_CASE("sound 2-path programs pass with the exact summary", "[check]") {
  const sync_result r = check_nc_files({{"O1000_1.nc", "%\nO1000\nM100\nG0 X10.\nM101\nM102\nM30\n%\n"},
                                        {"O1000_2.nc", "%\nO1000\nM100\nM101\nT0202\nM102\nM30\n%\n"}},
                                       fanuc2());
  CHECK(r.ok);
  CHECK(r.paired == 6);
  REQUIRE(r.channels.size() == 2);
  CHECK(r.channels[1].file == "O1000_2.nc");
  CHECK(r.channels[1].waits == 3);
  CHECK(r.channels[1].paired == 3);
  CHECK(format_sync_text(r) == "check: 2 channels, 6 waits paired, 0 errors\n");
}

TEST_CASE("codes may be reused: pairing is by order", "[check]") {
  const std::string one = "M100\nM101\nM100\nM101\nM100\nM30\n";
  CHECK(check_text({{"a", one}, {"b", one}}, fanuc2()) == "check: 2 channels, 10 waits paired, 0 errors\n");
}

TEST_CASE("deadlock in Mazak syntax, one merged file", "[check]") {
  const std::string part =
      "%\n"
      "O1306(PART)\n"
      "G109 L1\n"
      "G0 X100. Z50.\n"
      "M951 (WAIT B)\n"
      "M950\n"
      "G109 L2\n"
      "M950\n"
      "M951\n"
      "M30\n"
      "%\n";
  const sync_result r = check_nc_files({{"part.eia", part}}, mazak());
  CHECK_FALSE(r.ok);
  CHECK(format_sync_text(r) ==
        "part.eia:5:1: error: deadlock: channel 1 waits on M951 at part.eia:5 while channel 2 "
        "waits on M950 at part.eia:8 (different codes)\n"
        "M951 (WAIT B)\n"
        "^\n"
        "check: 2 channels, 0 waits paired, 1 error\n");
}

TEST_CASE("deadlock in Fanuc syntax, split files", "[check]") {
  const std::string text = check_text(
      {{"O1000.nc", "O1000\nN10 M101\nN20 M100\nM30\n"}, {"O1000.P-2", "O1000\nN10 M100\nN20 M101\nM30\n"}},
      fanuc2());
  CHECK(text ==
        "O1000.nc:2:5: error: deadlock: channel 1 waits on M101 at O1000.nc:2 while channel 2 "
        "waits on M100 at O1000.P-2:2 (different codes, Fanuc PS0160)\n"
        "N10 M101\n"
        "    ^\n"
        "check: 2 channels, 0 waits paired, 1 error\n");
}

TEST_CASE("unpaired wait in Mazak syntax", "[check]") {
  const std::string part =
      "G109 L1\n"
      "M950\n"
      "M951\n"
      "G109 L2\n"
      "M950\n"
      "G0 X10.\n";
  CHECK(check_text({{"p.eia", part}}, mazak()) ==
        "p.eia:3:1: error: wait M951 of channel 1 is never met: channel 2 ends at p.eia:6 "
        "without a matching wait\n"
        "M951\n"
        "^\n"
        "check: 2 channels, 2 waits paired, 1 error\n");
}

TEST_CASE("unpaired wait in Fanuc syntax", "[check]") {
  CHECK(check_text({{"a.nc", "M100\nM30\n"}, {"b.nc", "M100\nM101\nM30\n"}}, fanuc2()) ==
        "b.nc:2:1: error: wait M101 of channel 2 is never met: channel 1 ends at a.nc:2 "
        "without a matching wait\n"
        "M101\n"
        "^\n"
        "check: 2 channels, 2 waits paired, 1 error\n");
  CHECK(check_text({{"a.nc", "M100\n"}, {"b.nc", "(nothing)\n"}}, fanuc2()) ==
        "b.nc: error: no NC block in this file: channel 2 has no program\n"
        "a.nc:1:1: error: wait M100 of channel 1 is never met: channel 2 has no program\n"
        "M100\n"
        "^\n"
        "check: 2 channels, 0 waits paired, 2 errors\n");
}

TEST_CASE("comments holding wait codes are not waits", "[check]") {
  CHECK(check_text({{"a", "(M100 ON BOTH)\nM100\n; M101\n"}, {"b", "M100 (THEN M101)\n/ (M102)\n"}},
                   fanuc2()) == "check: 2 channels, 2 waits paired, 0 errors\n");
}

TEST_CASE("3 paths: glued and spaced partner lists pair", "[check]") {
  // The ncplot7py example: 1-2 meet at M250, 2-3 at M260, all three at M500.
  const machine m = make_machine(3, 200, 998, partner_style::path_numbers);
  const sync_result r = check_nc_files({{"1", "M250P12\nM500 P123\nM30\n"},
                                        {"2", "m250p12\nM260 P23\nM500P123\n"},
                                        {"3", "M260 P23\nM500 P123\n"}},
                                       m);
  CHECK(format_sync_text(r) == "check: 3 channels, 7 waits paired, 0 errors\n");
  CHECK(r.channels[1].paired == 3);
}

TEST_CASE("3 paths: partner list problems (PS0161)", "[check]") {
  const std::string text = check_text(
      {{"1.nc", "M100\nM101 P23\nM102 P14\nM103 P1\nM104 P112\nM105 P1.5\n"}, {"2.nc", ""}, {"3.nc", ""}},
      fanuc3());
  CHECK(text ==
        "2.nc: error: no NC block in this file: channel 2 has no program\n"
        "3.nc: error: no NC block in this file: channel 3 has no program\n"
        "1.nc:1:1: error: wait M100 has no partner list: with 3 channels every wait must name "
        "its partners (Fanuc PS0161)\nM100\n^\n"
        "1.nc:2:6: error: partner list P23 of wait M101 in channel 1 does not name channel 1 "
        "(Fanuc PS0161)\nM101 P23\n     ^\n"
        "1.nc:3:6: error: partner list P14 of wait M102 names channel 4, which this machine "
        "does not have (Fanuc PS0161)\nM102 P14\n     ^\n"
        "1.nc:4:6: error: partner list P1 of wait M103 names no channel but its own (Fanuc "
        "PS0161)\nM103 P1\n     ^\n"
        "1.nc:5:6: error: partner list P112 of wait M104 names channel 1 twice (Fanuc "
        "PS0161)\nM104 P112\n     ^\n"
        "1.nc:6:6: error: partner list P1.5 of wait M105 is not a list of channel numbers "
        "(Fanuc PS0161)\nM105 P1.5\n     ^\n"
        "1.nc:1:1: error: wait M100 of channel 1 is never met: channel 2 has no program; "
        "channel 3 has no program\nM100\n^\n"
        "check: 3 channels, 0 waits paired, 9 errors\n");
}

TEST_CASE("3 paths: partners whose lists disagree (PS0160)", "[check]") {
  CHECK(check_text({{"1.nc", "M100 P123\n"}, {"2.nc", "M100 P123\n"}, {"3.nc", "M100 P13\n"}}, fanuc3()) ==
        "1.nc:1:1: error: deadlock: channel 1 waits on M100 P123 at 1.nc:1 while channel 3 "
        "waits on M100 P13 at 3.nc:1 (different partner lists, Fanuc PS0160)\n"
        "M100 P123\n^\n"
        "2.nc:1:1: error: deadlock: channel 2 waits at 2.nc:1 (M100 P123) for channel 3\n"
        "M100 P123\n^\n"
        "check: 3 channels, 0 waits paired, 2 errors\n");
}

TEST_CASE("3 paths: a cyclic deadlock names every stuck channel", "[check]") {
  CHECK(check_text({{"1.nc", "M100 P12\nM101 P13\n"},
                    {"2.nc", "M102 P23\nM100 P12\n"},
                    {"3.nc", "M101 P13\nM102 P23\n"}},
                   fanuc3()) ==
        "1.nc:1:1: error: deadlock: channel 1 waits at 1.nc:1 (M100 P12) for channel 2; "
        "channel 2 waits at 2.nc:1 (M102 P23) for channel 3; channel 3 waits at 3.nc:1 "
        "(M101 P13) for channel 1\n"
        "M100 P12\n^\n"
        "check: 3 channels, 0 waits paired, 1 error\n");
}

TEST_CASE("3 paths: a channel may wait while others meet", "[check]") {
  // Channel 1 waits for 2 at M100 while 2 first meets 3 at M101.
  CHECK(check_text({{"1", "M100 P12\n"}, {"2", "M101 P23\nM100 P12\n"}, {"3", "M101 P23\n"}}, fanuc3()) ==
        "check: 3 channels, 4 waits paired, 0 errors\n");
}

TEST_CASE("binary partner masks", "[check]") {
  CHECK(check_text({{"1", "M100 P3\nM101 P7\n"}, {"2", "M100 P3\nM101 P7\n"}, {"3", "M101P7\n"}},
                   fanuc3_binary()) == "check: 3 channels, 5 waits paired, 0 errors\n");
  CHECK(check_text({{"1", ""}, {"2", "M100 P5\n"}, {"3", ""}}, fanuc3_binary()) ==
        "1: error: no NC block in this file: channel 1 has no program\n"
        "3: error: no NC block in this file: channel 3 has no program\n"
        "2:1:6: error: partner list P5 of wait M100 in channel 2 does not name channel 2 "
        "(Fanuc PS0161)\nM100 P5\n     ^\n"
        "2:1:1: error: wait M100 P5 of channel 2 is never met: channel 1 has no program; "
        "channel 3 has no program\n"
        "M100 P5\n^\n"
        "check: 3 channels, 0 waits paired, 4 errors\n");
}

TEST_CASE("2 channels: a partner list where the machine takes none", "[check]") {
  CHECK(check_text({{"a", "M100 P12\n"}, {"b", "M100\n"}}, fanuc2()) ==
        "a:1:6: error: wait M100 P12 has a partner list, but this machine's waits take none\n"
        "M100 P12\n     ^\n"
        "check: 2 channels, 2 waits paired, 1 error\n");
}

TEST_CASE("2 paths with optional P: plain and P12 forms do not meet", "[check]") {
  const machine m = make_machine(2, 100, 103, partner_style::path_numbers);
  CHECK(check_text({{"a", "M100 P12\nM101\n"}, {"b", "M100 P12\nM101 P12\n"}}, m) ==
        "a:2:1: error: deadlock: channel 1 waits on M101 at a:2 while channel 2 waits on M101 "
        "P12 at b:2 (one with a partner list, one without, Fanuc PS0160)\n"
        "M101\n^\n"
        "check: 2 channels, 2 waits paired, 1 error\n");
}

TEST_CASE("M-codes that look like waits outside the range", "[check]") {
  machine m = fanuc3();
  m.waits.step = 2;
  CHECK(check_text({{"1", "M250 P12\nM101\nM98 P12\n"}, {"2", ""}, {"3", ""}}, m) ==
        "1:3:1: warning: M98 P12 calls a subprogram the checker does not read: waits in it are not checked\n"
        "M98 P12\n^\n"
        "2: error: no NC block in this file: channel 2 has no program\n"
        "3: error: no NC block in this file: channel 3 has no program\n"
        "1:1:1: error: M250 P12 looks like a wait, but M250 is not a wait code of this machine "
        "(M100-M197)\nM250 P12\n^\n"
        "1:2:1: warning: M101 lies in the wait range M100-M197 but off its step of 2: it is "
        "not checked as a wait\nM101\n^\n"
        "check: 3 channels, 0 waits paired, 3 errors, 2 warnings\n");
}

TEST_CASE("Mazak sections interleaved and repeated", "[check]") {
  const std::string part =
      "O1(P)\n"
      "G109 L2\nM950\n"
      "G109 L1\nM950\nM951\n"
      "G109 L2\nM951\nM952\n"
      "G109 L1\nM952\nM30\n";
  const sync_result r = check_nc_files({{"p.eia", part}}, mazak());
  CHECK(format_sync_text(r) == "check: 2 channels, 6 waits paired, 0 errors\n");
  CHECK(r.channels[0].waits == 3);
}

TEST_CASE("the JSON report", "[check]") {
  const sync_result r = check_nc_files({{"a \"1\".nc", "M100\nM101\n"}, {"b.nc", "M100\n"}}, fanuc2());
  CHECK(format_sync_json(r) ==
        "{\n"
        "  \"ok\": false,\n"
        "  \"channels\": [\n"
        "    {\"channel\": 1, \"file\": \"a \\\"1\\\".nc\", \"waits\": 2, \"paired\": 1},\n"
        "    {\"channel\": 2, \"file\": \"b.nc\", \"waits\": 1, \"paired\": 1}\n"
        "  ],\n"
        "  \"paired\": 2,\n"
        "  \"errors\": 1,\n"
        "  \"warnings\": 0,\n"
        "  \"problems\": [\n"
        "    {\"file\": \"a \\\"1\\\".nc\", \"line\": 2, \"column\": 1, \"severity\": \"error\", "
        "\"message\": \"wait M101 of channel 1 is never met: channel 2 ends at b.nc:1 without "
        "a matching wait\"}\n"
        "  ]\n"
        "}\n");
  const sync_result ok = check_nc_files({{"a", "M100\n"}, {"b", "M100\n"}}, fanuc2());
  CHECK(format_sync_json(ok) ==
        "{\n  \"ok\": true,\n  \"channels\": [\n"
        "    {\"channel\": 1, \"file\": \"a\", \"waits\": 1, \"paired\": 1},\n"
        "    {\"channel\": 2, \"file\": \"b\", \"waits\": 1, \"paired\": 1}\n"
        "  ],\n  \"paired\": 2,\n  \"errors\": 0,\n  \"warnings\": 0,\n  \"problems\": []\n}\n");
}

TEST_CASE("many waits in three paths pair up", "[check]") {
  // 3 paths, 40000-60000 waits each, pairs 1-2 then 2-3 then all. (Its speed is the
  // benchmark's business, not a test's: see bench/.)
  std::string a, b, c;
  for (int i = 0; i < 20000; ++i) {
    a += "M100 P12\nM102 P123\n";
    b += "M100 P12\nM101 P23\nM102 P123\n";
    c += "M101 P23\nM102 P123\n";
  }
  const sync_result r = check_nc_files({{"1", a}, {"2", b}, {"3", c}}, fanuc3());
  CHECK(r.ok);
  CHECK(r.paired == 140000);
  REQUIRE(r.channels.size() == 3);
  CHECK(r.channels[1].waits == 60000);
  CHECK(r.channels[1].paired == 60000);
}

namespace {

struct check_job {
  const char* what;
  machine m;
  std::vector<nc_source> files;
};

// Sound programs: check_nc_files says all it has to say from its compact reading.
std::vector<check_job> sound_jobs() {
  return {
      {"sound, plain waits", fanuc2(), {{"a", "M100\nG0 X1.\nM101\nM30\n"}, {"b", "M100\nM101\nM30\n"}}},
      {"sound, partner lists",
       fanuc3(),
       {{"1", "M100 P12\nM102 P123\nM30\n"},
        {"2", "M100 P12\nM101 P23\nM102 P123\nM30\n"},
        {"3", "M101 P23\nM102 P123\nM30\n"}}},
      {"sound, merged", mazak(), {{"p", "G109 L1\nM950\nM30\nG109 L2\nM950\nM30\n"}}},
  };
}

// Every kind of finding: each must take check_nc_files from its compact reading to the full one.
std::vector<check_job> finding_jobs() {
  return {
      {"unpaired", fanuc2(), {{"a", "M100\nM101\nM30\n"}, {"b", "M100\nM30\n"}}},
      {"deadlock", fanuc2(), {{"a", "M100\nM101\nM30\n"}, {"b", "M101\nM100\nM30\n"}}},
      {"near wait", fanuc2(), {{"a", "M100\nM150 P12\nM30\n"}, {"b", "M100\nM30\n"}}},
      {"bad partner list", fanuc3(), {{"1", "M100 P14\nM30\n"}, {"2", "M100 P12\nM30\n"}, {"3", "M30\n"}}},
      {"no partner list on 3 paths", fanuc3(), {{"1", "M100\nM30\n"}, {"2", "M100\nM30\n"}, {"3", "M30\n"}}},
      {"reading problem", fanuc2(), {{"a", "M100 M101\nM30\n"}, {"b", "M100\nM30\n"}}},
      {"no markers", mazak(), {{"p", "M950\nM30\n"}}},
      {"empty program", fanuc2(), {{"a", "M100\nM30\n"}, {"b", "%\n(NONE)\n%\n"}}},
      {"empty section", mazak(), {{"p", "G109 L1\nM950\nM30\nG109 L2\n"}}},
  };
}

// Diagnostics one after the other, as `twinpost check` prints them.
std::string diagnostics_text(const std::vector<diagnostic>& ds) {
  std::string s;
  for (const diagnostic& d : ds) s += format_diagnostic(d) + "\n";
  return s;
}

// Per channel: its file, its waits and how many of them paired.
std::string channels_text(const sync_result& r) {
  std::string s;
  for (const channel_sync_summary& c : r.channels)
    s += std::to_string(c.channel) + " " + c.file + " " + std::to_string(c.waits) + " " +
         std::to_string(c.paired) + "\n";
  return s;
}

}  // namespace

// Two public ways to check the same files: check_nc_files (compact first: only simulation
// entries are kept) and check_sync over read_nc_programs (every wait kept). Neither is
// rebuilt here: each result comes from the library as a user gets it.
TEST_CASE("on sound programs the compact check says what the full reading says", "[check]") {
  for (const check_job& j : sound_jobs()) {
    INFO(j.what);
    diagnostic_list read;
    const sync_result full = check_sync(read_nc_programs(j.files, j.m, read), j.m);
    REQUIRE(read.all().empty());
    REQUIRE(full.diagnostics.empty());
    const sync_result compact = check_nc_files(j.files, j.m);
    CHECK(format_sync_text(compact) == format_sync_text(full));
    CHECK(format_sync_json(compact) == format_sync_json(full));
  }
}

TEST_CASE("with a finding the check reports what the full reading finds", "[check]") {
  // check_nc_files reports reading problems first, then the findings (check/sync_check.hpp).
  for (const check_job& j : finding_jobs()) {
    INFO(j.what);
    diagnostic_list read;
    const sync_result full = check_sync(read_nc_programs(j.files, j.m, read), j.m);
    REQUIRE(!(read.all().empty() && full.diagnostics.empty()));  // the case has a finding
    const sync_result checked = check_nc_files(j.files, j.m);
    CHECK(diagnostics_text(checked.diagnostics) ==
          diagnostics_text(read.all()) + diagnostics_text(full.diagnostics));
    CHECK(channels_text(checked) == channels_text(full));
    CHECK(checked.paired == full.paired);
  }
}

TEST_CASE("a streamed file whose last line has no line end", "[check]") {
  // The last line is read into the reader's carry-over buffer; the channel's end must be
  // copied out of it before the buffer goes (ASan: use after scope). Short and long lines:
  // one fits in the string itself, the other lives on the heap.
  std::string dir = (std::filesystem::temp_directory_path() / "twinpost-noeol-XXXXXX").string();
  REQUIRE(::mkdtemp(dir.data()) != nullptr);
  REQUIRE(test::write_file(dir + "/a.nc", "M100\nG1 X10."));
  REQUIRE(test::write_file(dir + "/b.nc", "M100\nG1 X10. Z-5. F0.2 S1200 T0101"));
  REQUIRE(test::write_file(dir + "/c.nc", "M100\nM101\n"));
  diagnostic_list d;
  const nc_programs p =
      read_nc_programs({{"a.nc", {}, dir + "/a.nc"}, {"b.nc", {}, dir + "/b.nc"}}, fanuc2(), d);
  CHECK(p.channels[0].end.source_line == "G1 X10.");
  CHECK(p.channels[0].end.line == 2);
  CHECK(p.channels[1].end.source_line == "G1 X10. Z-5. F0.2 S1200 T0101");
  CHECK(p.channels[1].end.line == 2);
  CHECK(format_sync_text(
            check_nc_files({{"a.nc", {}, dir + "/a.nc"}, {"c.nc", {}, dir + "/c.nc"}}, fanuc2())) ==
        "c.nc:2:1: error: wait M101 of channel 2 is never met: channel 1 ends at a.nc:2 without "
        "a matching wait\n"
        "M101\n^\n"
        "check: 2 channels, 2 waits paired, 1 error\n");
  std::filesystem::remove_all(dir);
}

TEST_CASE("an empty program is an error that names its file", "[check]") {
  // No block at all, or only comments, '%' lines and blanks: the channel has no program.
  CHECK(check_text({{"a.nc", "M100\nM30\n"}, {"b.nc", "%\n(NOTHING M100)\n\n%\n"}}, fanuc2()) ==
        "b.nc: error: no NC block in this file: channel 2 has no program\n"
        "a.nc:1:1: error: wait M100 of channel 1 is never met: channel 2 has no program\n"
        "M100\n^\n"
        "check: 2 channels, 0 waits paired, 2 errors\n");
  // Nothing recognised in any file: each is named.
  CHECK(check_text({{"a.nc", ""}, {"b.nc", "hello world\n"}}, fanuc2()) ==
        "a.nc: error: no NC block in this file: channel 1 has no program\n"
        "b.nc: error: no NC block in this file: channel 2 has no program\n"
        "check: 2 channels, 0 waits paired, 2 errors\n");
  // A section that holds only its marker.
  CHECK(check_text({{"p.eia", "G109 L1\nM950\nG109 L2\n(EMPTY)\n"}}, mazak()) ==
        "p.eia:3:1: error: no NC block in the section for channel 2: channel 2 has no program\n"
        "G109 L2\n^\n"
        "p.eia:2:1: error: wait M950 of channel 1 is never met: channel 2 ends at p.eia:3 "
        "without a matching wait\n"
        "M950\n^\n"
        "check: 2 channels, 0 waits paired, 2 errors\n");
  // A long program is still looked at block by block until its first block.
  std::string dir = (std::filesystem::temp_directory_path() / "twinpost-empty-XXXXXX").string();
  REQUIRE(::mkdtemp(dir.data()) != nullptr);
  std::string text = "%\n";
  for (int i = 0; i < 100000; ++i) text += "hello world\n";
  REQUIRE(test::write_file(dir + "/a.nc", text + "G1 X1.\nhello\n"));
  REQUIRE(test::write_file(dir + "/b.nc", text));
  CHECK(check_text({{"a.nc", {}, dir + "/a.nc"}, {"b.nc", {}, dir + "/b.nc"}}, fanuc2()) ==
        "b.nc: error: no NC block in this file: channel 2 has no program\n"
        "check: 2 channels, 0 waits paired, 1 error\n");
  std::filesystem::remove_all(dir);
}

TEST_CASE("a machine with more channels than the checker holds is named", "[check]") {
  // A machine file refuses a 65th channel; one made in code is reported at its source.
  machine m = make_machine(65, 100, 197, partner_style::binary);
  std::vector<nc_source> files;
  for (int c = 1; c <= 65; ++c) files.push_back({std::to_string(c) + ".nc", "G0 X1.\nM30\n"});
  m.source = "big.toml";
  CHECK(check_text(files, m) ==
        "big.toml: error: machine 'test' has 65 channels: the checker handles at most 64\n"
        "check: 65 channels, 0 waits paired, 1 error\n");
  m.source.clear();
  CHECK(check_text(files, m) ==
        "1.nc: error: machine 'test' has 65 channels: the checker handles at most 64\n"
        "check: 65 channels, 0 waits paired, 1 error\n");
}

TEST_CASE("citizen-2system: Citizen waits are paired with their partners", "[check]") {
  const machine m = load_machine("citizen-2system");
  const std::string sound =
      "%\nO1(P)\n$1\nT0101\n!2L1\nG1 X1. F.02\n!2L2\nM02\n$2\nT3131\n!1L1\n!1L2\nM02\n$0\nD\n%\n";
  CHECK(check_text({{"p.CNC", sound}}, m) == "check: 2 channels, 4 waits paired, 0 errors\n");
  // A wrong number: both lines named.
  std::string wrong = sound;
  wrong.replace(wrong.find("!1L2"), 4, "!1L3");
  CHECK(check_text({{"p.CNC", wrong}}, m) ==
        "p.CNC:7:1: error: deadlock: channel 1 waits on !2L2 at p.CNC:7 while channel 2 waits on !1L3 at "
        "p.CNC:12 (different wait numbers)\n!2L2\n^\ncheck: 2 channels, 2 waits paired, 1 error\n");
  // A partner the machine does not have.
  std::string absent = sound;
  absent.replace(absent.find("!2L1"), 4, "!3L1");
  CHECK(check_text({{"p.CNC", absent}}, m)
            .starts_with("p.CNC:5:2: error: partner list 3 of wait !3L1 names channel 3, which this machine "
                         "does not have\n"));
  // A number outside the machine's range.
  std::string zero = sound;
  zero.replace(zero.find("!2L1"), 4, "!2L0");
  CHECK(check_text({{"p.CNC", zero}}, m)
            .starts_with(
                "p.CNC:5:1: error: !2L0 looks like a wait, but L0 is not a wait number of this machine "
                "(L1-L9999)\n"));
}

TEST_CASE("citizen-2system: a program without any !nLm wait is an error", "[check]") {
  const machine m = load_machine("citizen-2system");
  CHECK(check_text({{"p.CNC", "$1\nM100\nM02\n$2\nM100\nM02\n"}}, m) ==
        "p.CNC: error: no wait code of machine 'citizen-2system' (!<partners>L1-!<partners>L9999) in any of "
        "the 2 channels: nothing to check, and the channels would run with no synchronisation; is this the "
        "right machine?\ncheck: 2 channels, 0 waits paired, 1 error\n");
}
