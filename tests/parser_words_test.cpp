// Non-motion events: tools, spindle, feed, coolant, cutter compensation, cycles, delays,
// M/G functions, text, units, machine, MULTAX, coordinate systems, program end, passthrough.
// Minor words are read by name: both argument orders must give the same event.
#include <catch2/catch.hpp>

#include "tests/parser_test_support.hpp"

using namespace twinpost;
using twinpost::test::events_of;
using twinpost::test::lines;
using twinpost::test::read_cl;

TEST_CASE("tool calls: LOADTL, LOAD/TOOL, SELECT/TOOL, TURRET", "[parser][words]") {
  CHECK(events_of("LOADTL/8\n"
                  "LOADTL/2,1\n"
                  "LOAD/TOOL,1,ADJUST,1\n"
                  "LOAD/TOOL,14\n"
                  "SELECT/TOOL,2\n"
                  "TURRET/5,6\n"
                  "TURRET/5,6,1.5,2.5\n") ==
        lines{"1\ttool tool=8 from=LOADTL", "2\ttool tool=2 offset=1 from=LOADTL",
              "3\ttool tool=1 offset=1 from=LOAD/TOOL", "4\ttool tool=14 from=LOAD/TOOL",
              "5\ttool-select tool=2 from=SELECT/TOOL", "6\ttool tool=5 offset=6 from=TURRET",
              "7\ttool tool=5 offset=6 from=TURRET"});
}

TEST_CASE("tool data: TLDATA and CUTTER kept as written", "[parser][words]") {
  CHECK(events_of("TLDATA/MILL,20.0000,0.0000,75.0000,0.0000,0.0000\n"
                  "CUTTER/3.,0,1.5,.62132,22.5,0,46.\n") ==
        lines{"1\ttool-data from=TLDATA words=MILL values=20,0,75,0,0",
              "2\ttool-data from=CUTTER values=3,0,1.5,0.62132,22.5,0,46"});
}

TEST_CASE("SPINDL in both orders", "[parser][words]") {
  CHECK(events_of("SPINDL/RPM,1000,CLW\n"
                  "SPINDL/12000,RPM,CLW\n"
                  "SPINDL / RPM, 9000.000000,  CCLW\n"
                  "SPINDL/ 2546.4790,RPM,CCLW\n"
                  "SPINDL/ 70.0000,RPM\n"
                  "SPINDL/1200\n") ==
        lines{"1\tspindle mode=rpm speed=1000 dir=cw", "2\tspindle mode=rpm speed=12000 dir=cw",
              "3\tspindle mode=rpm speed=9000 dir=ccw", "4\tspindle mode=rpm speed=2546.479 dir=ccw",
              "5\tspindle mode=rpm speed=70", "6\tspindle mode=rpm speed=1200"});
}

TEST_CASE("SPINDL constant surface speed with MAXRPM, in either place", "[parser][words]") {
  CHECK(events_of("SPINDL/SFM,300,MAXRPM,2000,CLW\n"
                  "SPINDL/SMM,200,CCLW,MAXRPM,3000\n"
                  "SPINDL/MAXRPM,4000,150,SMM,CLW\n") ==
        lines{"1\tspindle mode=sfm speed=300 dir=cw maxrpm=2000",
              "2\tspindle mode=smm speed=200 dir=ccw maxrpm=3000",
              "3\tspindle mode=smm speed=150 dir=cw maxrpm=4000"});
}

TEST_CASE("SPINDL OFF, ON, ORIENT, LOCK, RANGE", "[parser][words]") {
  CHECK(events_of("SPINDL/OFF\n"
                  "SPINDL/ON\n"
                  "SPINDL/ORIENT\n"
                  "SPINDL/ORIENT,90\n"
                  "SPINDL/LOCK\n"
                  "SPINDL/RPM,800,CLW,RANGE,2\n") ==
        lines{"1\tspindle mode=off", "2\tspindle mode=on", "3\tspindle mode=orient speed=0",
              "4\tspindle mode=orient speed=90", "5\tspindle mode=lock",
              "6\tspindle mode=rpm speed=800 dir=cw range=2"});
}

TEST_CASE("SPINDL names the spindle: MAIN, SUB (SIDE, OPPOS), LIVE", "[parser][words]") {
  CHECK(events_of("SPINDL/RPM,500,CLW,MAIN\n"
                  "SPINDL/SUB,RPM,600,CCLW\n"
                  "SPINDL/700,RPM,OPPOS\n"
                  "SPINDL/RPM,3000,CLW,LIVE\n") ==
        lines{"1\tspindle mode=rpm speed=500 dir=cw spindle=main",
              "2\tspindle mode=rpm speed=600 dir=ccw spindle=sub",
              "3\tspindle mode=rpm speed=700 spindle=sub",
              "4\tspindle mode=rpm speed=3000 dir=cw spindle=live"});
}

TEST_CASE("SPINDL reports words it does not know", "[parser][words]") {
  auto r = read_cl("SPINDL/RPM,500,CLW,FAST\n", dialect::generic);
  CHECK(r.events == lines{"1\tspindle mode=rpm speed=500 dir=cw"});
  CHECK(r.diagnostics ==
        "t.cl:1:20: warning: word 'FAST' ignored in SPINDL\n"
        "SPINDL/RPM,500,CLW,FAST\n"
        "                   ^\n");
}

TEST_CASE("FEDRAT in both orders, per minute and per rev", "[parser][words]") {
  CHECK(events_of("FEDRAT/MMPM,250.0000\n"
                  "FEDRAT / 400.000000,  MMPM\n"
                  "FEDRAT/ 0.4000,MMPR\n"
                  "FEDRAT/IPM,30\n"
                  "FEDRAT/0.01,IPR\n") ==
        lines{"1\tfeed mode=per-minute value=250 units=mm", "2\tfeed mode=per-minute value=400 units=mm",
              "3\tfeed mode=per-rev value=0.4 units=mm", "4\tfeed mode=per-minute value=30 units=inch",
              "5\tfeed mode=per-rev value=0.01 units=inch"});
}

TEST_CASE("FEDRAT PERMIN, PERREV and bare values follow UNITS", "[parser][words]") {
  CHECK(events_of("FEDRAT/PERMIN,141\n"
                  "UNITS/INCHES\n"
                  "FEDRAT/PERMIN,10\n"
                  "FEDRAT/PERREV,0.005\n"
                  "FEDRAT/30\n"
                  "UNITS/MM\n"
                  "FEDRAT/30\n") == lines{"1\tfeed mode=per-minute value=141 units=mm", "2\tunits units=inch",
                                          "3\tfeed mode=per-minute value=10 units=inch",
                                          "4\tfeed mode=per-rev value=0.005 units=inch",
                                          "5\tfeed mode=per-minute value=30 units=inch", "6\tunits units=mm",
                                          "7\tfeed mode=per-minute value=30 units=mm"});
}

TEST_CASE("FEDRAT INVERS: inverse time", "[parser][words]") {
  CHECK(
      events_of("FEDRAT/INVERS,2.5\nFEDRAT/12.5,INVERS\n") ==
      lines{"1\tfeed mode=inverse-time value=2.5 units=mm", "2\tfeed mode=inverse-time value=12.5 units=mm"});
}

TEST_CASE("COOLNT modes and levels", "[parser][words]") {
  CHECK(events_of("COOLNT/ON\nCOOLNT/FLOOD\nCOOLNT/MIST,HIGH\nCOOLNT/THRU\nCOOLNT/OFF\nCOOLNT\n") ==
        lines{"1\tcoolant mode=ON", "2\tcoolant mode=FLOOD", "3\tcoolant mode=MIST level=HIGH",
              "4\tcoolant mode=THRU", "5\tcoolant mode=OFF", "6\tcoolant mode=ON"});
}

TEST_CASE("CUTCOM side, register and plane", "[parser][words]") {
  CHECK(events_of("CUTCOM/LEFT,XYPLAN\nCUTCOM/RIGHT,3\nCUTCOM/ ON \nCUTCOM/ LEFT \nCUTCOM/OFF\n") ==
        lines{"1\tcutcom side=LEFT plane=XYPLAN", "2\tcutcom side=RIGHT register=3", "3\tcutcom side=ON",
              "4\tcutcom side=LEFT", "5\tcutcom side=OFF"});
}

TEST_CASE("CYCLE keyword pairs, positional values and OFF", "[parser][words]") {
  CHECK(events_of("CYCLE/DRILL,RAPTO,3.0000,FEDTO,-33.0043,RTRCTO,4.0000,MANUAL,IPR,250.0000\n"
                  "CYCLE / DEEP, DEPTH, 3.5, STEP, 1.0, MMPM, 50.0, CLEAR, 1.0\n"
                  "CYCLE/DRILL,    3.000000,    5.000000\n"
                  "CYCLE/INIT\n"
                  "CYCLE/OFF\n") ==
        lines{"1\tcycle type=DRILL RAPTO=3 FEDTO=-33.0043 RTRCTO=4 IPR=250 words=MANUAL",
              "2\tcycle type=DEEP DEPTH=3.5 STEP=1 MMPM=50 CLEAR=1", "3\tcycle type=DRILL values=3,5",
              "4\tcycle type=INIT", "5\tcycle type=OFF"});
}

TEST_CASE("DELAY in seconds and revolutions", "[parser][words]") {
  CHECK(events_of("DELAY/2.5\nDELAY/3,REV\n") == lines{"1\tdelay seconds=2.5", "2\tdelay revolutions=3"});
  auto r = read_cl("DELAY\n", dialect::generic);
  CHECK(r.events.empty());
  CHECK(r.diagnostics ==
        "t.cl:1:1: error: DELAY needs a time\n"
        "DELAY\n"
        "^\n");
}

TEST_CASE("AUXFUN and PREFUN", "[parser][words]") {
  CHECK(events_of("AUXFUN/8\nAUXFUN/100,2\nPREFUN/54\n") ==
        lines{"1\tauxfun code=8", "2\tauxfun code=100 values=2", "3\tprefun code=54"});
}

TEST_CASE("text records: PARTNO, PPRINT, INSERT", "[parser][words]") {
  CHECK(events_of(
            "PARTNO/1\nPPRINT/APTCL-SPEC,MAKINO-FF,1\nINSERT/M01\nINSERT/Stock Size X220. Y220. Z24.\n") ==
        lines{"1\ttext major=PARTNO text=1", "2\ttext major=PPRINT text=APTCL-SPEC,MAKINO-FF,1",
              "3\ttext major=INSERT text=M01", "4\ttext major=INSERT text=\"Stock Size X220. Y220. Z24.\""});
}

TEST_CASE("the JSON form of a text record", "[parser][words]") {
  auto r = read_cl("INSERT/[HOLDER=C40] \"6MM\" CRB\n", dialect::generic);
  CHECK(
      r.json ==
      lines{
          "{\"line\":1,\"event\":\"text\",\"major\":\"INSERT\",\"text\":\"[HOLDER=C40] \\\"6MM\\\" CRB\"}"});
}

TEST_CASE("UNITS and UNIT", "[parser][words]") {
  CHECK(events_of("UNITS/MM\nUNITS / INCHES\nUNIT/MM\nUNITS/ MM \n") ==
        lines{"1\tunits units=mm", "2\tunits units=inch", "3\tunits units=mm", "4\tunits units=mm"});
  auto r = read_cl("UNITS/FEET\n", dialect::generic);
  CHECK(r.events.empty());
  CHECK(r.diagnostics ==
        "t.cl:1:7: error: unknown units 'FEET'\n"
        "UNITS/FEET\n"
        "      ^\n");
}

TEST_CASE("MACHIN, MULTAX, MSYS, CSYS", "[parser][words]") {
  CHECK(events_of("MACHIN / UNCX01, 1\n"
                  "MULTAX / ON\n"
                  "MULTAX/OFF\n"
                  "MULTAX\n"
                  "MSYS/0.0,0.0,0.0,1.0,0.0,0.0,0.0,1.0,0.0\n"
                  "CSYS/1.,0,0,0,0,1.,0,0,0,0,1.,0\n") ==
        lines{"1\tmachin name=UNCX01 args=1", "2\tmultax state=on", "3\tmultax state=off",
              "4\tmultax state=on", "5\tcoordsys from=MSYS values=0,0,0,1,0,0,0,1,0",
              "6\tcoordsys from=CSYS values=1,0,0,0,0,1,0,0,0,0,1,0"});
}

TEST_CASE("program end: FINI, END, END-OF-PATH", "[parser][words]") {
  CHECK(events_of("END-OF-PATH\nEND\nFINI \n") ==
        lines{"1\tend word=END-OF-PATH", "2\tend word=END", "3\tend word=FINI"});
}

TEST_CASE("an unknown major word is passed through with a warning", "[parser][words]") {
  auto r = read_cl("FOO/1,BAR\nPAINT/COLOR,186\n", dialect::generic);
  CHECK(r.events ==
        lines{"1\tpassthrough major=FOO args=1,BAR unknown", "2\tpassthrough major=PAINT args=COLOR,186"});
  CHECK(r.diagnostics ==
        "t.cl:1:1: warning: unknown major word 'FOO' (a post stops here with an error)\n"
        "FOO/1,BAR\n"
        "^\n");
  CHECK(r.warnings == 1);
  CHECK(r.errors == 0);
}

TEST_CASE("the JSON form of motion and passthrough events", "[parser][words]") {
  auto r = read_cl("RAPID\nGOTO/1,-0.0,2.5\nFOO/1,BAR\n", dialect::generic);
  CHECK(
      r.json ==
      lines{"{\"line\":2,\"event\":\"goto\",\"x\":1,\"y\":0,\"z\":2.5,\"rapid\":true}",
            "{\"line\":3,\"event\":\"passthrough\",\"major\":\"FOO\",\"args\":\"1,BAR\",\"unknown\":true}"});
}

TEST_CASE("JSON has no inf: an overflowing move writes null", "[parser][words]") {
  // Regression: the JSON form printed `inf`, which is not JSON.
  auto r = read_cl("GOTO/1e308,0,0\nGODLTA/1e308,0,0\n", dialect::generic);
  CHECK(r.events == lines{"1\tgoto x=1e+308 y=0 z=0", "2\tgodlta x=inf y=0 z=0"});
  CHECK(r.json == lines{"{\"line\":1,\"event\":\"goto\",\"x\":1e+308,\"y\":0,\"z\":0}",
                        "{\"line\":2,\"event\":\"godlta\",\"x\":null,\"y\":0,\"z\":0}"});
}
