// Motion events: FROM, GOTO (3/6 values, modal tool axis), GODLTA, GOHOME, one-shot RAPID,
// CIRCLE in every shape and direction convention.
#include <catch2/catch.hpp>

#include "tests/parser_test_support.hpp"

using namespace twinpost;
using twinpost::test::events_of;
using twinpost::test::lines;
using twinpost::test::read_cl;

TEST_CASE("FROM and GOTO with 3 and 6 values", "[parser][motion]") {
  CHECK(events_of("FROM/0,0,50\n"
                  "GOTO/1,2,3\n"
                  "GOTO/4,5,6,0,0,1\n") ==
        lines{"1\tfrom x=0 y=0 z=50", "2\tgoto x=1 y=2 z=3", "3\tgoto x=4 y=5 z=6 i=0 j=0 k=1"});
}

TEST_CASE("NX tool axis is modal: written only when it changes", "[parser][motion]") {
  CHECK(events_of("FROM/0,0,40,0,0,1\n"
                  "GOTO/76.6078,112.6997,28.0000\n"
                  "GOTO/1,2,3,0.7071068,0,0.7071068\n"
                  "GOTO/4,5,6\n",
                  dialect::nx) == lines{"1\tfrom x=0 y=0 z=40 i=0 j=0 k=1",
                                        "2\tgoto x=76.6078 y=112.6997 z=28 i=0 j=0 k=1",
                                        "3\tgoto x=1 y=2 z=3 i=0.7071068 j=0 k=0.7071068",
                                        "4\tgoto x=4 y=5 z=6 i=0.7071068 j=0 k=0.7071068"});
}

TEST_CASE("TLAXIS sets the modal tool axis", "[parser][motion]") {
  CHECK(events_of("TLAXIS/ 0.000000,-1.000000,0.000000 \nGOTO/1,2,3\n") ==
        lines{"1\ttool-axis i=0 j=-1 k=0", "2\tgoto x=1 y=2 z=3 i=0 j=-1 k=0"});
}

TEST_CASE("GODLTA moves by a delta, or along the tool axis by one distance", "[parser][motion]") {
  CHECK(events_of("GOTO/10,10,10\n"
                  "GODLTA/1,2,-3\n"
                  "GODLTA/5\n"
                  "TLAXIS/1,0,0\n"
                  "GODLTA/-2\n") == lines{"1\tgoto x=10 y=10 z=10", "2\tgodlta x=11 y=12 z=7",
                                          "3\tgodlta x=11 y=12 z=12", "4\ttool-axis i=1 j=0 k=0",
                                          "5\tgodlta x=9 y=12 z=12 i=1 j=0 k=0"});
}

TEST_CASE("GOHOME with and without a point", "[parser][motion]") {
  // Without a point the event holds the current position (the channel decides where home is).
  CHECK(events_of("GOTO/1,2,3\nGOHOME/0,0,100\nGOHOME\n") ==
        lines{"1\tgoto x=1 y=2 z=3", "2\tgohome x=0 y=0 z=100", "3\tgohome x=0 y=0 z=100"});
}

TEST_CASE("RAPID applies to the next move only", "[parser][motion]") {
  CHECK(events_of("RAPID\n"
                  "GOTO/1,1,1\n"
                  "GOTO/2,2,2\n"
                  "RAPID/\n"
                  "FEDRAT/MMPM,250\n"
                  "GOTO/3,3,3\n"
                  "GOTO/4,4,4\n") == lines{"2\tgoto x=1 y=1 z=1 rapid", "3\tgoto x=2 y=2 z=2",
                                           "5\tfeed mode=per-minute value=250 units=mm",
                                           "6\tgoto x=3 y=3 z=3 rapid", "7\tgoto x=4 y=4 z=4"});
}

TEST_CASE("CIRCLE with 4 values: centre and radius", "[parser][motion]") {
  CHECK(events_of("GOTO/10,0,0\nCIRCLE/0,0,0,10\nGOTO/0,10,0\n") ==
        lines{"1\tgoto x=10 y=0 z=0", "3\tarc x=0 y=10 z=0 cx=0 cy=0 cz=0 i=0 j=0 k=1 r=10 dir=ccw"});
}

TEST_CASE("SolidWorks CIRCLE with 6 values: radius from the start point", "[parser][motion]") {
  // Start (3,4,7) over a circle about (0,0,0) with axis k: planar radius 5.
  CHECK(events_of("GOTO/3,4,7\nCIRCLE/0,0,0,0,0,1\nGOTO/-4,3,7\n", dialect::solidworks) ==
        lines{"1\tgoto x=3 y=4 z=7", "3\tarc x=-4 y=3 z=7 cx=0 cy=0 cz=0 i=0 j=0 k=1 r=5 dir=ccw"});
}

TEST_CASE("CIRCLE with 7 values (Creo) and 11 values (NX)", "[parser][motion]") {
  CHECK(events_of("GOTO/10,0,0\n"
                  "CIRCLE/0,0,0,0,0,1,10\n"
                  "GOTO/0,10,0\n"
                  "CIRCLE/0,0,0,0,0,1,10,0.0600,0.5000,20.0000,0.0000\n"
                  "GOTO/-10,0,0\n") == lines{"1\tgoto x=10 y=0 z=0",
                                             "3\tarc x=0 y=10 z=0 cx=0 cy=0 cz=0 i=0 j=0 k=1 r=10 dir=ccw",
                                             "5\tarc x=-10 y=0 z=0 cx=0 cy=0 cz=0 i=0 j=0 k=1 r=10 dir=ccw"});
}

TEST_CASE("CIRCLE direction per dialect: the same numbers, Creo ccw, NX cw", "[parser][motion]") {
  const char* text =
      "GOTO/93.5102,109.6997,20.0000\n"
      "CIRCLE/90.0336,90.1120,20.0000,0.0000000,0.0000000,1.0000000,19.8938,0.0600,0.5000,20.0000,0.0000\n"
      "GOTO/102.0069,105.9992,20.0000\n";
  const std::string arc =
      "3\tarc x=102.0069 y=105.9992 z=20 cx=90.0336 cy=90.112 cz=20 i=0 j=0 k=1 r=19.8938";
  CHECK(events_of(text, dialect::creo).at(1) == arc + " dir=ccw");
  CHECK(events_of(text, dialect::solidworks).at(1) == arc + " dir=ccw");
  CHECK(events_of(text, dialect::catia).at(1) == arc + " dir=ccw");
  CHECK(events_of(text, dialect::generic).at(1) == arc + " dir=ccw");
  CHECK(events_of(text, dialect::nx).at(1) == arc + " dir=cw");
  CHECK(events_of(text, dialect::makino).at(1) == arc + " dir=cw");
}

TEST_CASE("an explicit CLOCKWISE / COUNTERCLOCKWISE word wins over the dialect", "[parser][motion]") {
  CHECK(events_of("GOTO/10,0,0\n"
                  "CIRCLE/ 0,0,0,0,0,1,10,CLOCKWISE \n"
                  "GOTO/0,10,0\n",
                  dialect::creo) ==
        lines{"1\tgoto x=10 y=0 z=0", "3\tarc x=0 y=10 z=0 cx=0 cy=0 cz=0 i=0 j=0 k=1 r=10 dir=cw"});
  CHECK(events_of("GOTO/10,0,0\n"
                  "CIRCLE/ 0,0,0,0,0,1,10,COUNTERCLOCKWISE \n"
                  "GOTO/0,10,0\n",
                  dialect::nx) ==
        lines{"1\tgoto x=10 y=0 z=0", "3\tarc x=0 y=10 z=0 cx=0 cy=0 cz=0 i=0 j=0 k=1 r=10 dir=ccw"});
}

TEST_CASE("the arc ends with its GOTO record, and the next GOTO is straight", "[parser][motion]") {
  CHECK(events_of("GOTO/10,0,0\n"
                  "CIRCLE/0,0,0,10\n"
                  "FEDRAT/100,MMPM\n"
                  "GOTO/0,10,0\n"
                  "GOTO/0,20,0\n") ==
        lines{"1\tgoto x=10 y=0 z=0", "3\tfeed mode=per-minute value=100 units=mm",
              "4\tarc x=0 y=10 z=0 cx=0 cy=0 cz=0 i=0 j=0 k=1 r=10 dir=ccw", "5\tgoto x=0 y=20 z=0"});
}

TEST_CASE("a CIRCLE with no end point is an error at the end of input", "[parser][motion]") {
  auto r = read_cl("GOTO/10,0,0\n  CIRCLE/0,0,0,10\nFINI\n", dialect::generic);
  CHECK(r.events == lines{"1\tgoto x=10 y=0 z=0", "3\tend word=FINI"});
  CHECK(r.diagnostics == "t.cl:2:3: error: CIRCLE has no end point\n");
}

TEST_CASE("CIRCLE with a wrong number of values", "[parser][motion]") {
  auto r = read_cl("CIRCLE/0,0,0,0,0\n", dialect::generic);
  CHECK(r.events.empty());
  CHECK(r.diagnostics ==
        "t.cl:1:8: error: CIRCLE takes 4, 6, 7 or 11 numbers, found 5\n"
        "CIRCLE/0,0,0,0,0\n"
        "       ^\n");
}
