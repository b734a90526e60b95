// Malformed records: the exact diagnostic (file:line:col, message, source line, caret), and
// reading goes on after it.
#include <catch2/catch.hpp>

#include "tests/parser_test_support.hpp"

using namespace twinpost;
using twinpost::test::lines;
using twinpost::test::read_cl;

TEST_CASE("blank-separated numbers", "[parser][errors]") {
  auto r = read_cl("CYCLE/ DRILL,G98,3.000000,46.927686 46.927686 DWELL,0.000000 \n", dialect::solidworks);
  CHECK(r.events.empty());
  CHECK(r.diagnostics ==
        "t.cl:1:37: error: expected ',' between arguments, found '46.927686'\n"
        "CYCLE/ DRILL,G98,3.000000,46.927686 46.927686 DWELL,0.000000 \n"
        "                                    ^\n");
  CHECK(r.errors == 1);
}

TEST_CASE("GOTO with 2 numbers", "[parser][errors]") {
  auto r = read_cl("GOTO / 1.0, 2.0\n", dialect::generic);
  CHECK(r.events.empty());
  CHECK(r.diagnostics ==
        "t.cl:1:8: error: GOTO takes 3 or 6 numbers (x,y,z[,i,j,k]), found 2 arguments\n"
        "GOTO / 1.0, 2.0\n"
        "       ^\n");
}

TEST_CASE("GOTO with a word", "[parser][errors]") {
  auto r = read_cl("GOTO/1,2,Z\n", dialect::generic);
  CHECK(r.diagnostics ==
        "t.cl:1:6: error: GOTO takes 3 or 6 numbers (x,y,z[,i,j,k]), found 3 arguments\n"
        "GOTO/1,2,Z\n"
        "     ^\n");
}

TEST_CASE("a coordinate line without a GOTO", "[parser][errors]") {
  auto r = read_cl("FEDRAT/MMPM,250\n   7.4675, 5.8717, 1.8000\n", dialect::generic);
  CHECK(r.events == lines{"1\tfeed mode=per-minute value=250 units=mm"});
  CHECK(r.diagnostics ==
        "t.cl:2:4: error: coordinate line without a preceding GOTO\n"
        "   7.4675, 5.8717, 1.8000\n"
        "   ^\n");
}

TEST_CASE("a coordinate line with 2 numbers or a word", "[parser][errors]") {
  auto r = read_cl("GOTO/1,2,3\n 4,5\n 4,5,X\n 7,8,9\n", dialect::generic);
  CHECK(r.events == lines{"1\tgoto x=1 y=2 z=3", "4\tgoto x=7 y=8 z=9 continued"});
  CHECK(r.diagnostics ==
        "t.cl:2:2: error: a GOTO point takes 3 or 6 numbers, found 2\n"
        " 4,5\n"
        " ^\n"
        "t.cl:3:6: error: expected a number in a coordinate line, found 'X'\n"
        " 4,5,X\n"
        "     ^\n");
}

TEST_CASE("GOTO 1,2,3 without a slash", "[parser][errors]") {
  auto r = read_cl("GOTO 1,2,3\n", dialect::generic);
  CHECK(r.events.empty());
  CHECK(r.diagnostics ==
        "t.cl:1:6: error: expected '/' after 'GOTO', found '1'\n"
        "GOTO 1,2,3\n"
        "     ^\n");
}

TEST_CASE("a bad character", "[parser][errors]") {
  auto r = read_cl("FEDRAT/250;MMPM\n@GOTO/1,2,3\n", dialect::generic);
  CHECK(r.events.empty());
  CHECK(r.diagnostics ==
        "t.cl:1:11: error: unexpected ';' in argument list\n"
        "FEDRAT/250;MMPM\n"
        "          ^\n"
        "t.cl:2:1: error: expected a major word, found '@GOTO'\n"
        "@GOTO/1,2,3\n"
        "^\n");
}

// (No backslash in a test's name: ctest passes the name to Catch as a filter, where a
// backslash is an escape and the filter then matches nothing.)
TEST_CASE("a control byte in a message and in the echoed line is written in hex", "[parser][errors]") {
  auto r = read_cl("GOTO/1,2,\x01\n", dialect::generic);
  CHECK(r.diagnostics ==
        "t.cl:1:10: error: unexpected '\\x01' in argument list\n"
        "GOTO/1,2,\\x01\n"
        "         ^\n");
}

TEST_CASE("the caret of an error in a continued record is on its physical line", "[parser][errors]") {
  auto r = read_cl("GOTO/1,2,$\n   3 4\n", dialect::generic);
  CHECK(r.diagnostics ==
        "t.cl:2:6: error: expected ',' between arguments, found '4'\n"
        "   3 4\n"
        "     ^\n");
}

TEST_CASE("the caret keeps tabs so that it lines up", "[parser][errors]") {
  auto r = read_cl("\tGOTO/1\t2,3\n", dialect::generic);
  CHECK(r.diagnostics ==
        "t.cl:1:9: error: expected ',' between arguments, found '2'\n"
        "\tGOTO/1\t2,3\n"
        "\t      \t^\n");
}

TEST_CASE("a record cut short by the end of input", "[parser][errors]") {
  // The continuation says more is coming: the job is cut off, and the record is dropped.
  auto r = read_cl("GOTO/1,2,$\n", dialect::generic);
  CHECK(r.diagnostics ==
        "t.cl:1:10: error: the file ends in a continued record ('$' at the end of the last line): "
        "the job is cut off\n"
        "GOTO/1,2,$\n"
        "         ^\n");
  CHECK(r.events.empty());
}

TEST_CASE("reading goes on after errors", "[parser][errors]") {
  auto r = read_cl(
      "LOADTL/1\n"
      "GOTO 1,2,3\n"
      "GOTO/1,2\n"
      "FEDRAT/1 2\n"
      "GOTO/4,5,6\n"
      "FINI\n",
      dialect::generic);
  CHECK(r.events == lines{"1\ttool tool=1 from=LOADTL", "5\tgoto x=4 y=5 z=6", "6\tend word=FINI"});
  CHECK(r.errors == 3);
}

TEST_CASE("coordinate lines after a malformed record are dropped, not joined to an older GOTO",
          "[parser][errors]") {
  // Regression: a record that did not parse left the previous GOTO open, so the points of a
  // malformed GOTO were silently added to the one before it.
  auto r = read_cl(
      "GOTO/1,2,3\n"
      "GOTO/4 5 6\n"
      "     7,8,9\n"
      "FEDRAT/1 2\n"
      "     7,8,9\n"
      "GOTO/1,1,1\n",
      dialect::generic);
  CHECK(r.events == lines{"1\tgoto x=1 y=2 z=3", "6\tgoto x=1 y=1 z=1"});
  CHECK(r.diagnostics ==
        "t.cl:2:8: error: expected ',' between arguments, found '5'\n"
        "GOTO/4 5 6\n"
        "       ^\n"
        "t.cl:4:10: error: expected ',' between arguments, found '2'\n"
        "FEDRAT/1 2\n"
        "         ^\n");
}

TEST_CASE("a malformed point inside a multi-point GOTO leaves the GOTO going", "[parser][errors]") {
  auto r = read_cl("GOTO/1,2,3\n 4 5 6\n 7,8,9\n", dialect::generic);
  CHECK(r.events == lines{"1\tgoto x=1 y=2 z=3", "3\tgoto x=7 y=8 z=9 continued"});
  CHECK(r.diagnostics ==
        "t.cl:2:4: error: expected ',' between arguments, found '5'\n"
        " 4 5 6\n"
        "   ^\n");
}
