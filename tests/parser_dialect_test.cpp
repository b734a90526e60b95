// Dialect detection from the head of a file, dialect names, and forcing a dialect.
#include <catch2/catch.hpp>

#include "parser/dialect.hpp"
#include "tests/parser_test_support.hpp"

using namespace twinpost;
using twinpost::test::read_cl;

TEST_CASE("each CAM family is told apart by its first bytes", "[parser][dialect]") {
  CHECK(detect_dialect("$$*          Pro/CLfile  Version 8.0 - 8.0.3.0\n$$-> MFGNO / MFG0004\n") ==
        dialect::creo);
  CHECK(detect_dialect("$$*          Pro/CLfile  Vers 1.0\n") == dialect::creo);
  CHECK(detect_dialect("$$ISO\nUNITS/MM\nTOOL PATH/ZLEVEL_FOLLOW_CORE,TOOL,MILL-20MM\n") == dialect::nx);
  CHECK(detect_dialect("$$ ----\n$$     CATIA APT VERSION 1.0\n") == dialect::catia);
  CHECK(detect_dialect("$$ Programme\n$$*CATIA0\n") == dialect::catia);
  CHECK(detect_dialect("PARTNO/1\nUNIT/MM\nINSERT/x\n") == dialect::solidworks);
  CHECK(detect_dialect("PARTNO/1\nUNIT/INCH\nLOAD/TOOL,2\n") == dialect::solidworks);
  CHECK(detect_dialect("PARTNO/1\nUNITS/INCHES\nLOADTL/2\n") == dialect::generic);
  CHECK(detect_dialect("UNITS/ MM \nBOX/ 0,0,0,1,1,1 \nOPFEATSTART/Drill1\n") == dialect::solidworks);
  CHECK(detect_dialect("LOAD/TOOL,14\nCSI_SET_FLUTE_LENGTH/16.\n") == dialect::solidworks);
  CHECK(detect_dialect("PPRINT/APTCL-SPEC,MAKINO-FF,1\n") == dialect::makino);
  CHECK(detect_dialect("PARTNO TEST\nGOTO/1,2,3\n") == dialect::generic);
  CHECK(detect_dialect("") == dialect::generic);
}

TEST_CASE("dialect names round-trip", "[parser][dialect]") {
  for (dialect d :
       {dialect::generic, dialect::creo, dialect::nx, dialect::catia, dialect::solidworks, dialect::makino})
    CHECK(dialect_from_name(dialect_name(d)) == d);
  CHECK(dialect_name(dialect::solidworks) == "solidworks");
  CHECK_FALSE(dialect_from_name("mastercam").has_value());
}

TEST_CASE("the reader detects the dialect unless one is forced", "[parser][dialect]") {
  const char* nx_text = "TOOL PATH/A,TOOL,B\nGOTO/10,0,0\nCIRCLE/0,0,0,0,0,1,10,0.06,0.5,20,0\nGOTO/0,10,0\n";
  auto detected = read_cl(nx_text);
  CHECK(detected.used == dialect::nx);
  CHECK(detected.events.at(2) == "4\tarc x=0 y=10 z=0 cx=0 cy=0 cz=0 i=0 j=0 k=1 r=10 dir=cw");
  auto forced = read_cl(nx_text, dialect::creo);
  CHECK(forced.used == dialect::creo);
  CHECK(forced.events.at(2) == "4\tarc x=0 y=10 z=0 cx=0 cy=0 cz=0 i=0 j=0 k=1 r=10 dir=ccw");
}

TEST_CASE("detection only looks at the head of the file", "[parser][dialect]") {
  std::string text(70 * 1024, '\n');  // 70 KiB of blank lines, then an NX marker
  text += "TOOL PATH/A,TOOL,B\n";
  auto r = read_cl(text);
  CHECK(r.used == dialect::generic);
  CHECK(r.events == test::lines{"71681\ttext major=\"TOOL PATH\" text=A,TOOL,B"});
}
