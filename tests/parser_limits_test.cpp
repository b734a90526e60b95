// The reader under bad input: numbers that are none, records too long, jobs cut off, NX
// CIRCLE TIMES, and diagnostics that echo huge or binary lines.
#include <catch2/catch.hpp>

#include <string>

#include "parser_test_support.hpp"
#include "support/diagnostics.hpp"

using namespace twinpost;
using twinpost::test::lines;
using twinpost::test::read_cl;

namespace {

// Reads as `post` does (posting on), with a small chunk to cross buffer refills.
test::read_result read_posting(std::string_view text, std::size_t chunk = 1 << 20) {
  string_source src(text);
  cl_reader_options options;
  options.file_name = "t.cl";
  options.forced = dialect::generic;
  options.chunk_size = chunk;
  options.posting = true;
  return test::read_source(src, options);
}

}  // namespace

TEST_CASE("a number that is none is named at its column", "[parser][limits]") {
  CHECK(read_cl("GOTO/1e999,0,0\n", dialect::generic).diagnostics ==
        "t.cl:1:6: error: number out of range: '1e999'\nGOTO/1e999,0,0\n     ^\n");
  CHECK(read_cl("GOTO/1,nan,0\n", dialect::generic).diagnostics ==
        "t.cl:1:8: error: not a number: 'nan'\nGOTO/1,nan,0\n       ^\n");
  CHECK(read_cl("GOTO/1,2,INF\n", dialect::generic).diagnostics ==
        "t.cl:1:10: error: not a number: 'INF'\nGOTO/1,2,INF\n         ^\n");
  CHECK(read_cl("GOTO/29.0,1e,2.0\n", dialect::generic).diagnostics ==
        "t.cl:1:11: error: malformed number '1e'\nGOTO/29.0,1e,2.0\n          ^\n");
  // In a multi-point GOTO's coordinate line too; the record is dropped, reading goes on.
  auto r = read_cl("GOTO/1,2,3\n4,5,1e999\nGOTO/7,8,9\n", dialect::generic);
  CHECK(r.diagnostics == "t.cl:2:5: error: number out of range: '1e999'\n4,5,1e999\n    ^\n");
  // A sign is no word character: the grammar stops there, and the token is named alike.
  CHECK(read_cl("GOTO/-1e999,0,0\n", dialect::generic).diagnostics ==
        "t.cl:1:6: error: number out of range: '-1e999'\nGOTO/-1e999,0,0\n     ^\n");
  CHECK(read_cl("GOTO/1,-inf,0\n", dialect::generic).diagnostics ==
        "t.cl:1:8: error: not a number: '-inf'\nGOTO/1,-inf,0\n       ^\n");
  CHECK(r.events == lines{"1\tgoto x=1 y=2 z=3", "3\tgoto x=7 y=8 z=9"});
}

TEST_CASE("a job that does not end with FINI or END is reported when posting", "[parser][limits]") {
  auto cut = read_posting("PARTNO A\nGOTO/1,2,3\n  goto/4,5,6\n$$ a comment\n");
  CHECK(cut.diagnostics ==
        "t.cl:3:3: warning: the job ends without FINI or END after this GOTO record: is the file cut off?\n");
  CHECK(cut.events.size() == 4);
  CHECK(read_posting("PARTNO A\nGOTO/1,2,3\nFINI\n$$ after\n").diagnostics == "");
  CHECK(read_posting("GOTO/1,2,3\nEND\n").diagnostics == "");
  CHECK(read_posting("GOTO/1,2,3\nEND-OF-PATH").diagnostics == "");
  CHECK(read_posting("").diagnostics == "t.cl: warning: the job has no records\n");
  // parse (posting off) stays quiet about it.
  CHECK(read_cl("GOTO/1,2,3\n", dialect::generic).diagnostics == "");
}

TEST_CASE("a continuation at the end of the file is an error at that line", "[parser][limits]") {
  for (std::size_t chunk : {16, 1 << 20}) {
    auto r = read_posting("GOTO/1,2,3\nGOTO/4,$\n  5,$", chunk);
    CHECK(
        r.diagnostics ==
        "t.cl:3:5: error: the file ends in a continued record ('$' at the end of the last line): "
        "the job is cut off\n  5,$\n    ^\n"
        "t.cl:1:1: warning: the job ends without FINI or END after this GOTO record: is the file cut off?\n");
    CHECK(r.events == lines{"1\tgoto x=1 y=2 z=3"});
  }
}

TEST_CASE("a record longer than the limit is an error, and memory stays bounded", "[parser][limits]") {
  // A line of NUL bytes with no newline, then a sound job: only the start is kept.
  for (std::size_t chunk : {16, 4096, 1 << 20}) {
    std::string text(max_record_bytes * 3, '\0');
    text += "\nGOTO/1,2,3\nFINI\n";
    auto r = read_posting(text, chunk);
    INFO(chunk);
    CHECK(r.errors == 1);
    // The source line echoed is the line's start, NULs escaped and cut at 200 columns.
    std::string expected =
        "t.cl:1:1: error: record longer than 65536 bytes: not CL data (a line without a newline?); skipped\n";
    for (int i = 0; i < 200; ++i) expected += "\\x00";
    expected += "...\n^\n";
    CHECK(r.diagnostics == expected);
    CHECK(r.events == lines{"2\tgoto x=1 y=2 z=3", "3\tend word=FINI"});
  }
  // Joined by '$': too long as a whole, reported at the line that makes it so.
  std::string joined = "GOTO/1,$\n";
  for (int i = 0; i < 40000; ++i) joined += "$\n";
  joined += "2,3\nFINI\n";
  auto j = read_posting(joined);
  CHECK(j.diagnostics ==
        "t.cl:32765:1: error: record longer than 65536 bytes: not CL data (a line without a newline?); "
        "skipped\n$\n^\n");
  CHECK(j.events == lines{"40003\tend word=FINI"});
}

TEST_CASE("an unknown major word: a warning when parsing, an error when posting", "[parser][limits]") {
  auto p = read_posting("FOO/1\nFINI\n");
  CHECK(p.diagnostics ==
        "t.cl:1:1: error: unknown major word 'FOO': this record cannot be posted\nFOO/1\n^\n");
  CHECK(p.events == lines{"2\tend word=FINI"});
}

TEST_CASE("NX CIRCLE ... TIMES,n carries its turns", "[parser][limits]") {
  auto r = read_cl("FROM/10,0,0\nCIRCLE/0,0,0,0,0,1,10,0.06,0.5,4,0,TIMES,3\nGOTO/10,0,0\n", dialect::nx);
  CHECK(r.diagnostics == "");
  CHECK(r.events ==
        lines{"1\tfrom x=10 y=0 z=0", "3\tarc x=10 y=0 z=0 cx=0 cy=0 cz=0 i=0 j=0 k=1 r=10 dir=cw turns=3"});
  CHECK(read_cl("CIRCLE/0,0,0,0,0,1,10,0.06,0.5,4,0,TIMES,2.5\n", dialect::nx).diagnostics ==
        "t.cl:1:42: error: CIRCLE TIMES 2.5 is not a whole number of turns from 1 to 100\n"
        "CIRCLE/0,0,0,0,0,1,10,0.06,0.5,4,0,TIMES,2.5\n"
        "                                         ^\n");
}

TEST_CASE("a word given twice with two values is an error at the second", "[parser][limits]") {
  // Attack 45: TIMES,2,TIMES,3 posted three turns, FEDTO,-10 ... FEDTO,-200 drilled to -10.
  CHECK(read_cl("CIRCLE/0,0,0,0,0,1,10,0.06,0.5,4,0,TIMES,2,TIMES,3\n", dialect::nx).diagnostics ==
        "t.cl:1:44: error: CIRCLE TIMES is given twice, 2 and 3: which one is meant is not known\n"
        "CIRCLE/0,0,0,0,0,1,10,0.06,0.5,4,0,TIMES,2,TIMES,3\n"
        "                                           ^\n");
  CHECK(read_cl("CYCLE/DRILL,FEDTO,-10,RAPTO,3,FEDTO,-200\n", dialect::nx).diagnostics ==
        "t.cl:1:31: error: CYCLE/DRILL: FEDTO is given twice, -10 and -200: which one is meant is not known\n"
        "CYCLE/DRILL,FEDTO,-10,RAPTO,3,FEDTO,-200\n"
        "                              ^\n");
  CHECK(read_cl("CYCLE/DRILL,FEDTO,-10,FEDTO,-10\n", dialect::nx).diagnostics.empty());
}

TEST_CASE("a diagnostic echoes at most 200 columns of its line, binary bytes escaped", "[parser][limits]") {
  std::string source(1000, 'A');
  source[299] = '\0';
  source[298] = '\xE9';
  diagnostic d{severity::error, "t.cl", 1, 300, "m", source};
  const std::string out = format_diagnostic(d);
  std::string expected = "t.cl:1:300: error: m\n...";
  expected.append(99, 'A');
  expected += "\\xE9\\x00";
  expected.append(99, 'A');
  expected += "...\n";
  expected.append(3 + 99 + 4, ' ');
  expected += "^\n";
  CHECK(out == expected);
  // Short lines print as they are, tabs kept under the caret.
  d.column = 3;
  d.source_line = "\tX\x01Y";
  CHECK(format_diagnostic(d) == "t.cl:1:3: error: m\n\tX\\x01Y\n\t ^\n");
}

TEST_CASE("a diagnostic's file name and message reach the terminal without control sequences",
          "[diagnostics]") {
  diagnostic d;
  d.file = "e\x1b[2Jv.lua";
  d.line = 2;
  // C0, DEL, a UTF-8 C1 control (U+009B, CSI), a bare 0x9B and a cut UTF-8 sequence are escaped;
  // valid UTF-8 (the section sign, an o umlaut) stays.
  d.message = std::string("a\x07") + "\x7f" + "\xc2\x9b" + "1m \x9b" + "31m \xc2\xa7" + "4 \xc3\xb6 \xe2\x82";
  CHECK(format_diagnostic(d) ==
        "e\\x1b[2Jv.lua:2: error: a\\x07\\x7f\\xc2\\x9b1m \\x9b31m \xc2\xa7"
        "4 \xc3\xb6 \\xe2\\x82\n");
  // A message is cut at 4 096 bytes.
  d.message = std::string(5000, 'x');
  CHECK(format_diagnostic(d) ==
        "e\\x1b[2Jv.lua:2: error: " + std::string(4096, 'x') + "... (5000 bytes in all)\n");
}
