// The lexical rules of CL text (cl-formats.md §2): comments, continuation, records without
// a slash, free text, numbers, words, blanks, line endings, encodings, long lines.
#include <catch2/catch.hpp>

#include <charconv>
#include <random>
#include <string>

#include "parser/detail/lexical.hpp"
#include "tests/parser_test_support.hpp"

using namespace twinpost;
using twinpost::test::events_of;
using twinpost::test::lines;
using twinpost::test::read_cl;

TEST_CASE("$$ starts a comment, on its own line or after data", "[parser][lexical]") {
  CHECK(events_of("$$ centerline data\n"
                  "GOTO/1,2,3 $$ trailing note\n"
                  "  $$OPERATION NAME : Pointage.1\n") ==
        lines{"1\tcomment text=\"centerline data\"", "2\tgoto x=1 y=2 z=3",
              "3\tcomment text=\"OPERATION NAME : Pointage.1\""});
}

TEST_CASE("$$-> data comments carry a major and arguments", "[parser][lexical]") {
  CHECK(events_of("$$-> MFGNO / MFG0004\n"
                  "$$-> CUTTER / 3.000000\n"
                  "$$-> FEATNO / 32\n"
                  "$$-> END / \n") ==
        lines{"1\tdata-comment text=\"MFGNO / MFG0004\"", "2\ttool-data from=\"$$-> CUTTER\" values=3",
              "3\tdata-comment text=\"FEATNO / 32\"", "4\tdata-comment text=END"});
}

TEST_CASE("$$-> lines continue with $ onto lines that do not start with $$", "[parser][lexical]") {
  CHECK(events_of("$$-> CSYS / 1.0000000000, 0.0000000000, 0.0000000000,  $\n"
                  "          10.0000000000, 0.0000000000, 1.0000000000,  $\n"
                  "          0.0000000000, 20.0000000000, 0.0000000000,  $\n"
                  "          0.0000000000, 1.0000000000, 30.0000000000\n"
                  "GOTO / 1, 2, 3\n") ==
        lines{"1\tcoordsys from=\"$$-> CSYS\" values=1,0,0,10,0,1,0,20,0,0,1,30", "5\tgoto x=1 y=2 z=3"});
}

TEST_CASE("a $$-> body that is not a record stays a plain comment", "[parser][lexical]") {
  CHECK(events_of("$$-> SETSTART / 1 2 3\n") == lines{"1\tcomment text=\"-> SETSTART / 1 2 3\""});
}

TEST_CASE("$$* is a header comment", "[parser][lexical]") {
  CHECK(events_of("$$*          Pro/CLfile  Version 8.0 - 8.0.3.0\n") ==
        lines{"1\theader text=\"Pro/CLfile  Version 8.0 - 8.0.3.0\""});
}

TEST_CASE("$$*CATIA0 and its three matrix rows make a coordinate system", "[parser][lexical]") {
  // The matrix event carries the header's line; it comes out once the third row is read.
  CHECK(events_of("$$*CATIA0\n"
                  "$$ Programme de fabrication.1\n"
                  "$$     1.00000     0.00000     0.00000  -220.00000\n"
                  "$$     0.00000     1.00000     0.00000  -170.00000\n"
                  "$$     0.00000     0.00000     1.00000    20.00000\n"
                  "PARTNO PART TO BE MACHINED\n") ==
        lines{"1\theader text=CATIA0", "2\tcomment text=\"Programme de fabrication.1\"",
              "3\tcomment text=\"1.00000     0.00000     0.00000  -220.00000\"",
              "4\tcomment text=\"0.00000     1.00000     0.00000  -170.00000\"",
              "1\tcoordsys from=$$*CATIA0 values=1,0,0,-220,0,1,0,-170,0,0,1,20",
              "5\tcomment text=\"0.00000     0.00000     1.00000    20.00000\"",
              "6\ttext major=PARTNO text=\"PART TO BE MACHINED\""});
}

TEST_CASE("$$*CATIA0 rows must hold four finite numbers", "[parser][lexical]") {
  // Regression: std::from_chars reads "nan" and "inf", which made a matrix of NaNs.
  CHECK(events_of("$$*CATIA0\n"
                  "$$ nan nan nan nan\n"
                  "$$ 1 0 0 0\n"
                  "$$ 0 1 0 0 0\n"
                  "$$ 0 1 0 0\n"
                  "$$ 0 0 1 5\n") ==
        lines{"1\theader text=CATIA0", "2\tcomment text=\"nan nan nan nan\"", "3\tcomment text=\"1 0 0 0\"",
              "4\tcomment text=\"0 1 0 0 0\"", "5\tcomment text=\"0 1 0 0\"",
              "1\tcoordsys from=$$*CATIA0 values=1,0,0,0,0,1,0,0,0,0,1,5", "6\tcomment text=\"0 0 1 5\""});
}

TEST_CASE("$$UDE: MANUSPOST synchronisation is a sync mark, and other UDEs stay comments",
          "[parser][lexical]") {
  CHECK(events_of("$$UDE: MANUSPOST - SYNCHRONIZATION/SYNCHRONIZATION NUMBER=1\n"
                  "$$UDE: MANUSPOST - SYNCHRONIZATION/SYNCHRONIZATION NUMBER= 12\n"
                  "$$UDE: MANUSPOST - COOLANT/MODE=FLOOD\n") ==
        lines{"1\tsync from=manus index=1", "2\tsync from=manus index=12",
              "3\tude text=\"UDE: MANUSPOST - COOLANT/MODE=FLOOD\""});
}

TEST_CASE("$ continues a record after a comma, with and without a blank", "[parser][lexical]") {
  CHECK(events_of("CYCLE / DEEP, DEPTH, 3.5, STEP, 1.0, MMPM, 50.0, CLEAR,$\n"
                  " 1.000000\n"
                  "GOTO / 4, 5,  $\n"
                  "6\n") ==
        lines{"1\tcycle type=DEEP DEPTH=3.5 STEP=1 MMPM=50 CLEAR=1", "3\tgoto x=4 y=5 z=6"});
}

TEST_CASE("CATIA continues with ,$ and the next line goes on with numbers", "[parser][lexical]") {
  CHECK(events_of("CUTTER/ 10.000000,  0.000000,  5.000000,  5.000000, 45.000000,$\n"
                  "         0.000000, 50.000000\n"
                  "TOOLNO/2,   10.000000\n") ==
        lines{"1\ttool-data from=CUTTER values=10,0,5,5,45,0,50", "3\tpassthrough major=TOOLNO args=2,10"});
}

TEST_CASE("Creo puts i,j,k of a 5-axis GOTO on a continuation line", "[parser][lexical]") {
  CHECK(events_of("MULTAX / ON\n"
                  "GOTO / 1.0, 2.0, 3.0,  $\n"
                  "       0.0, 0.0, 1.0\n") ==
        lines{"1\tmultax state=on", "2\tgoto x=1 y=2 z=3 i=0 j=0 k=1"});
}

TEST_CASE("records without a slash", "[parser][lexical]") {
  CHECK(events_of("PARTNO CORE_WORK\n"
                  "PPRINT NC_LATHE_MO_START_COMMENT BEGIN\n"
                  "RAPID\n"
                  "GOTO/1,2,3\n"
                  "MULTAX\n"
                  "CHANNEL,1\n"
                  "LOCAL_ORIGIN, 10, 20, 30\n"
                  "TOOL PATH/ZLEVEL_FOLLOW_CORE,TOOL,MILL-20MM\n"
                  "END-OF-PATH\n"
                  "END\n"
                  "FINI\n") ==
        lines{"1\ttext major=PARTNO text=CORE_WORK",
              "2\ttext major=PPRINT text=\"NC_LATHE_MO_START_COMMENT BEGIN\"", "4\tgoto x=1 y=2 z=3 rapid",
              "5\tmultax state=on", "6\tchannel channel=1", "7\tpassthrough major=LOCAL_ORIGIN args=10,20,30",
              "8\ttext major=\"TOOL PATH\" text=ZLEVEL_FOLLOW_CORE,TOOL,MILL-20MM", "9\tend word=END-OF-PATH",
              "10\tend word=END", "11\tend word=FINI"});
}

TEST_CASE("free-text records keep , / [ ] : and blanks", "[parser][lexical]") {
  CHECK(events_of("PARTNO PART TO BE MACHINED\n"
                  "PARTNO / MFG0004\n"
                  "INSERT/[HOLDER=C40-M06EM2] 6MM CRB 2FL 19 LOC\n"
                  "TPRINT/T1 PointeurD10\n"
                  "OPFEATSTART/Drill1-Hole Group1 [Drill] [Sub2]\n"
                  "PPRINT/BEGIN-SECTION,DEFINE\n"
                  "PPRINT OPERATION : ROUGH, PASS 1/2 \n"
                  "OPFEATEND/Drill1-Hole Group1 [Drill] [Sub2]\n") ==
        lines{"1\ttext major=PARTNO text=\"PART TO BE MACHINED\"", "2\ttext major=PARTNO text=MFG0004",
              "3\ttext major=INSERT text=\"[HOLDER=C40-M06EM2] 6MM CRB 2FL 19 LOC\"",
              "4\ttext major=TPRINT text=\"T1 PointeurD10\"",
              "5\ttext major=OPFEATSTART text=\"Drill1-Hole Group1 [Drill] [Sub2]\"",
              "6\ttext major=PPRINT text=BEGIN-SECTION,DEFINE",
              "7\ttext major=PPRINT text=\"OPERATION : ROUGH, PASS 1/2\"",
              "8\ttext major=OPFEATEND text=\"Drill1-Hole Group1 [Drill] [Sub2]\""});
}

TEST_CASE("a word that only starts like a text major is a statement", "[parser][lexical]") {
  auto r = read_cl("PARTNOX/1\n", dialect::generic);
  CHECK(r.events == lines{"1\tpassthrough major=PARTNOX args=1 unknown"});
  CHECK(r.diagnostics ==
        "t.cl:1:1: warning: unknown major word 'PARTNOX' (a post stops here with an error)\n"
        "PARTNOX/1\n"
        "^\n");
}

TEST_CASE("numbers: trailing point, leading point, -0, exponent, plus sign", "[parser][lexical]") {
  CHECK(events_of("GOTO/95.,.9625,-0.000000\n"
                  "GOTO/1.5E-3,+2,2.0000000000\n"
                  "GOTO/-.5,1.E2,-12000\n") ==
        lines{"1\tgoto x=95 y=0.9625 z=0", "2\tgoto x=0.0015 y=2 z=2", "3\tgoto x=-0.5 y=100 z=-12000"});
}

TEST_CASE("numbers read exactly, on the fast path and past it", "[parser][lexical]") {
  // Up to 15 digits take the exact integer / power-of-ten path, longer ones from_chars:
  // either way the shortest round-trip form comes back.
  CHECK(events_of("GOTO/0.1,0.3,0.123456789012345\n"
                  "GOTO/123456789012345,1234567890123456,0.12345678901234567\n"
                  "GOTO/000000000000000012.5,-7.4675,1E-7\n") ==
        lines{"1\tgoto x=0.1 y=0.3 z=0.123456789012345",
              "2\tgoto x=123456789012345 y=1234567890123456 z=0.12345678901234566",
              "3\tgoto x=12.5 y=-7.4675 z=1e-07"});
}

TEST_CASE("fast_decimal reads eight digits at a time as from_chars reads them", "[parser][lexical]") {
  // Digit runs of every length on both sides of the point, ended by every kind of character or
  // by the end of the text at every distance (the eight-at-a-time read needs eight characters
  // left): the value and the end must be from_chars' for each.
  std::mt19937_64 rng(7);
  const std::string ends[] = {"", ",", " ", "x", "/", ":", "\x7f", "\xff", "0.5", ",1.25"};
  int compared = 0;
  for (int whole = 0; whole <= 15; ++whole)
    for (int frac = -1; whole + std::max(frac, 0) <= 16; ++frac)  // -1: no point at all
      for (const std::string& end : ends)
        for (int n = 0; n < 20; ++n) {
          std::string number;
          for (int i = 0; i < whole; ++i) number += static_cast<char>('0' + rng() % 10);
          if (frac >= 0) number += '.';
          for (int i = 0; i < frac; ++i) number += static_cast<char>('0' + rng() % 10);
          const std::string text = number + end;
          double fast = -1;
          const char* stop = parser_detail::fast_decimal(text.data(), text.data() + text.size(), fast);
          // The digits the number has, read from the text (an end of "0.5" adds to them).
          int digits = 0;
          std::size_t at = 0;
          while (at < text.size() && text[at] >= '0' && text[at] <= '9') ++digits, ++at;
          if (at < text.size() && text[at] == '.')
            for (++at; at < text.size() && text[at] >= '0' && text[at] <= '9'; ++at) ++digits;
          if (digits == 0 || digits > 15) {  // handed on: "." alone, or too long for the fast path
            CHECK(stop == nullptr);
            continue;
          }
          REQUIRE(stop != nullptr);
          double exact = -2;
          const auto r = std::from_chars(text.data(), text.data() + text.size(), exact);
          INFO(text);
          REQUIRE(r.ec == std::errc());
          // from_chars takes "1." and ".5" as the fast path does; an end of "0.5" continues the
          // digits for both, so compare where each stopped.
          REQUIRE(stop == r.ptr);
          REQUIRE(fast == exact);
          ++compared;
        }
  CHECK(compared > 20000);
}

TEST_CASE("fast_decimal_in reads a number inside a text as fast_decimal reads it", "[parser][lexical]") {
  // The same numbers and ends as above, now behind 0 to 9 characters of text (the word loads
  // near the end read the eight bytes that end there when the text has them, else byte by
  // byte): the value and the end, or the handing on, must be fast_decimal's for each.
  std::mt19937_64 rng(8);
  const std::string ends[] = {"", ",", " ", "x", "e5", "E", "/", "\xff", "0.5", ",1.25", ".", ".7"};
  int compared = 0;
  for (int whole = 0; whole <= 16; ++whole)
    for (int frac = -1; whole + std::max(frac, 0) <= 17; ++frac)  // -1: no point at all
      for (const std::string& end : ends)
        for (std::size_t before = 0; before <= 9; ++before) {
          std::string number;
          for (int i = 0; i < whole; ++i) number += static_cast<char>('0' + rng() % 10);
          if (frac >= 0) number += '.';
          for (int i = 0; i < frac; ++i) number += static_cast<char>('0' + rng() % 10);
          const std::string text = std::string(before, 'G') + number + end;
          const char* first = text.data() + before;
          const char* last = text.data() + text.size();
          double old_value = -1, new_value = -2;
          const char* old_stop = parser_detail::fast_decimal(first, last, old_value);
          const char* new_stop = parser_detail::fast_decimal_in(text.data(), first, last, new_value);
          INFO(text << " at " << before);
          REQUIRE(new_stop == old_stop);
          if (old_stop) {
            REQUIRE(new_value == old_value);
            ++compared;
          }
        }
  CHECK(compared > 10000);
}

TEST_CASE("minus zero never prints as -0, in passthrough arguments either", "[parser][lexical]") {
  // Regression: passthrough and MACHIN arguments were printed with fmt's "{}" ("-0").
  CHECK(events_of("ROTABL/ -0.000000,BAXIS,TABLE,CCLW \n"
                  "MACHIN / MILL, -0.0\n") ==
        lines{"1\tpassthrough major=ROTABL args=0,BAXIS,TABLE,CCLW", "2\tmachin name=MILL args=0"});
}

TEST_CASE("words may start with digits and hold - . #", "[parser][lexical]") {
  CHECK(events_of("CYCLE/DEEP2,FEDTO,24.6205,1STPECK,5.,SUBPECK,2.,MMPM,670.56\n"
                  "TOOL PATH/DRILL,TOOL,MILL-20MM\n"
                  "CYCLE/DRILL,G98,AUTO\n") ==
        lines{"1\tcycle type=DEEP2 FEDTO=24.6205 1STPECK=5 SUBPECK=2 MMPM=670.56",
              "2\ttext major=\"TOOL PATH\" text=DRILL,TOOL,MILL-20MM", "3\tcycle type=DRILL words=G98,AUTO"});
}

TEST_CASE("trailing blanks and trailing commas are ignored", "[parser][lexical]") {
  CHECK(events_of("RAPID \n"
                  "GOTO/1,2,3   \t\n"
                  "SPINDL/RPM,1000,CLW \n"
                  "CUTTER/ 6.000000,0.000000,3.000000,1.802582,31.000000,0.000000,102.000000,\n"
                  "SYNC/1,1,2,\n"
                  "FINI \n") == lines{"2\tgoto x=1 y=2 z=3 rapid", "3\tspindle mode=rpm speed=1000 dir=cw",
                                      "4\ttool-data from=CUTTER values=6,0,3,1.802582,31,0,102",
                                      "5\tsync from=catia index=1 channels=1,2", "6\tend word=FINI"});
}

TEST_CASE("empty arguments keep their place", "[parser][lexical]") {
  auto r = read_cl("BOX/a,,b\n", dialect::generic);
  CHECK(r.events == lines{"1\tpassthrough major=BOX args=a,,b"});
  CHECK(r.diagnostics == "");
  // In a GOTO an empty slot is not a coordinate.
  r = read_cl("GOTO/1,,2,3\n", dialect::generic);
  CHECK(r.events.empty());
  CHECK(r.diagnostics ==
        "t.cl:1:6: error: GOTO takes 3 or 6 numbers (x,y,z[,i,j,k]), found 4 arguments\n"
        "GOTO/1,,2,3\n"
        "     ^\n");
}

TEST_CASE("CRLF line endings", "[parser][lexical]") {
  auto r = read_cl("RAPID\r\nGOTO/1,2,$\r\n3\r\nGOTO/1 2\r\nFINI\r\n", dialect::generic);
  CHECK(r.events == lines{"2\tgoto x=1 y=2 z=3 rapid", "5\tend word=FINI"});
  // The source line in a diagnostic has no carriage return.
  CHECK(r.diagnostics ==
        "t.cl:4:8: error: expected ',' between arguments, found '2'\n"
        "GOTO/1 2\n"
        "       ^\n");
}

TEST_CASE("ISO-8859-1 bytes in comments: opaque, escaped in text and JSON", "[parser][lexical]") {
  auto r = read_cl(
      "$$     G\xe9n\xe9r\xe9 le jeudi\n$$ D\xe9"
      "but\n",
      dialect::catia);
  CHECK(r.diagnostics == "");
  CHECK(r.events ==
        lines{"1\tcomment text=\"G\\u00e9n\\u00e9r\\u00e9 le jeudi\"", "2\tcomment text=\"D\\u00e9but\""});
  CHECK(r.json == lines{"{\"line\":1,\"event\":\"comment\",\"text\":\"G\\u00e9n\\u00e9r\\u00e9 le jeudi\"}",
                        "{\"line\":2,\"event\":\"comment\",\"text\":\"D\\u00e9but\"}"});
}

TEST_CASE("ISO-8859-1 bytes outside comments are an error, not a crash", "[parser][lexical]") {
  // Regression: x3::alnum / x3::no_case called std::isalnum / std::tolower on a negative
  // char and failed Spirit's assertion (undefined behaviour in release builds).
  auto r = read_cl("GOTO/1,2,\xe9\n\xc9TAPE/1\nPPRINT \xe9t\xe9\nGOTO/4,5,6\n", dialect::generic);
  CHECK(r.events == lines{"3\ttext major=PPRINT text=\"\\u00e9t\\u00e9\"", "4\tgoto x=4 y=5 z=6"});
  CHECK(r.diagnostics ==
        "t.cl:1:10: error: unexpected '\\xE9' in argument list\n"
        "GOTO/1,2,\\xE9\n"
        "         ^\n"
        "t.cl:2:1: error: expected a major word, found '\\xC9TAPE'\n"
        "\\xC9TAPE/1\n"
        "^\n");
}

TEST_CASE("a line longer than the reader's chunk", "[parser][lexical]") {
  // Just under the record limit (max_record_bytes), many times the chunk.
  std::string text = "GOTO/1,2,3\nPPRINT ";
  text.append(60000, 'A');
  text += "\nGOTO/4,5,6\n";
  auto r = read_cl(text, dialect::generic, 4096);
  REQUIRE(r.events.size() == 3);
  CHECK(r.events[0] == "1\tgoto x=1 y=2 z=3");
  CHECK(r.events[1] == "2\ttext major=PPRINT text=" + std::string(60000, 'A'));
  CHECK(r.events[2] == "3\tgoto x=4 y=5 z=6");
  CHECK(r.diagnostics == "");
}

TEST_CASE("small chunks: every line crosses a refill", "[parser][lexical]") {
  const char* text =
      "$$-> CSYS / 1.0000000000, 0.0000000000, 0.0000000000,  $\n"
      "          10.0000000000, 0.0000000000, 1.0000000000,  $\n"
      "          0.0000000000, 20.0000000000, 0.0000000000,  $\n"
      "          0.0000000000, 1.0000000000, 30.0000000000\n"
      "GOTO / 7.4675, 5.8283, 1.8000\n"
      "       7.4675, 5.8717, 1.8000\n"
      "GOTO/1 2 3\n";
  auto r = read_cl(text, dialect::creo, 16);
  CHECK(r.events == lines{"1\tcoordsys from=\"$$-> CSYS\" values=1,0,0,10,0,1,0,20,0,0,1,30",
                          "5\tgoto x=7.4675 y=5.8283 z=1.8", "6\tgoto x=7.4675 y=5.8717 z=1.8 continued"});
  CHECK(r.diagnostics ==
        "t.cl:7:8: error: expected ',' between arguments, found '2'\n"
        "GOTO/1 2 3\n"
        "       ^\n");
}

TEST_CASE("Pro/E multi-point GOTO: coordinate-only lines are further points", "[parser][lexical]") {
  CHECK(events_of("RAPID \n"
                  "GOTO / 7.4300, 5.8500, 1.8000\n"
                  "       7.4675, 5.8717, 1.8000\n"
                  "       7.4300, 5.8500, 1.9000\n"
                  "GOTO / 1, 1, 1\n") ==
        lines{"2\tgoto x=7.43 y=5.85 z=1.8 rapid", "3\tgoto x=7.4675 y=5.8717 z=1.8 rapid continued",
              "4\tgoto x=7.43 y=5.85 z=1.9 rapid continued", "5\tgoto x=1 y=1 z=1"});
}

TEST_CASE("Pro/E multi-point GOTO after CIRCLE: every point is on the arc", "[parser][lexical]") {
  CHECK(events_of("GOTO / 7.4300, 5.8500, 1.8000\n"
                  "CIRCLE / 7.4550, 5.8500, 1.8000,  $\n"
                  "0.0000, 0.0000, 1.0000,  0.0250\n"
                  "GOTO / 7.4675, 5.8283, 1.8000\n"
                  "       7.4675, 5.8717, 1.8000\n"
                  "       7.4300, 5.8500, 1.8000\n"
                  "GOTO / 7.4300, 5.8500, 1.3000\n",
                  dialect::creo) ==
        lines{"1\tgoto x=7.43 y=5.85 z=1.8",
              "4\tarc x=7.4675 y=5.8283 z=1.8 cx=7.455 cy=5.85 cz=1.8 i=0 j=0 k=1 r=0.025 dir=ccw",
              "5\tarc x=7.4675 y=5.8717 z=1.8 cx=7.455 cy=5.85 cz=1.8 i=0 j=0 k=1 r=0.025 dir=ccw continued",
              "6\tarc x=7.43 y=5.85 z=1.8 cx=7.455 cy=5.85 cz=1.8 i=0 j=0 k=1 r=0.025 dir=ccw continued",
              "7\tgoto x=7.43 y=5.85 z=1.3"});
}

TEST_CASE("a comment between the points of a multi-point GOTO does not end it", "[parser][lexical]") {
  CHECK(events_of("GOTO / 1, 2, 3\n"
                  "$$ next point\n"
                  "       4, 5, 6\n") ==
        lines{"1\tgoto x=1 y=2 z=3", "2\tcomment text=\"next point\"", "3\tgoto x=4 y=5 z=6 continued"});
}

TEST_CASE("words are case-insensitive", "[parser][lexical]") {
  CHECK(events_of("goto/1,2,3\n"
                  "Spindl/rpm,1000,clw\n"
                  "fedrat/mmpm,250\n"
                  "partno lower case\n"
                  "Circle/0,0,0,0,0,1,5,clockwise\n"
                  "goto/5,0,0\n"
                  "fini\n") ==
        lines{"1\tgoto x=1 y=2 z=3", "2\tspindle mode=rpm speed=1000 dir=cw",
              "3\tfeed mode=per-minute value=250 units=mm", "4\ttext major=PARTNO text=\"lower case\"",
              "6\tarc x=5 y=0 z=0 cx=0 cy=0 cz=0 i=0 j=0 k=1 r=5 dir=cw", "7\tend word=FINI"});
}

TEST_CASE("blanks anywhere in a record, tabs included", "[parser][lexical]") {
  CHECK(events_of("  GOTO  /   98.0,  100.0 ,\t120.0\n"
                  "\tFEDRAT / 5.000000,  IPM\n"
                  " CYCLE / OFF \n") ==
        lines{"1\tgoto x=98 y=100 z=120", "2\tfeed mode=per-minute value=5 units=inch", "3\tcycle type=OFF"});
}

TEST_CASE("blank lines and blank-only lines are skipped", "[parser][lexical]") {
  CHECK(events_of("\n   \n\t\nGOTO/1,2,3\n\n") == lines{"4\tgoto x=1 y=2 z=3"});
}

TEST_CASE("the last line needs no newline", "[parser][lexical]") {
  CHECK(events_of("GOTO/1,2,3\nFINI") == lines{"1\tgoto x=1 y=2 z=3", "2\tend word=FINI"});
}
