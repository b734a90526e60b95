// Records that pick heads and channels and mark synchronisation points: HEAD, CHANNEL,
// CHANNL, CATIA SYNC, ICAM SYNCTR, MANUSpost $$UDE.
#include <catch2/catch.hpp>

#include "tests/parser_test_support.hpp"

using namespace twinpost;
using twinpost::test::events_of;
using twinpost::test::lines;
using twinpost::test::read_cl;

TEST_CASE("HEAD by number and by name", "[parser][channels]") {
  CHECK(events_of("HEAD/1\nHEAD/2\nHEAD/MAIN\nHEAD/SIDE\nHEAD/BOTH\nhead/main\n") ==
        lines{"1\thead head=1", "2\thead head=2", "3\thead head=MAIN", "4\thead head=SIDE",
              "5\thead head=BOTH", "6\thead head=MAIN"});
}

TEST_CASE("HEAD without a head is an error", "[parser][channels]") {
  auto r = read_cl("HEAD/UPPER\nHEAD/0\n", dialect::generic);
  CHECK(r.events.empty());
  CHECK(r.diagnostics ==
        "t.cl:1:6: error: HEAD needs a head number, MAIN, SIDE or BOTH\n"
        "HEAD/UPPER\n"
        "     ^\n"
        "t.cl:2:6: error: HEAD needs a head number, MAIN, SIDE or BOTH\n"
        "HEAD/0\n"
        "     ^\n");
}

TEST_CASE("CHANNEL,n (no slash) and CHANNL/n", "[parser][channels]") {
  CHECK(events_of("CHANNEL,2\nCHANNL/2\nCHANNEL,1\n") ==
        lines{"1\tchannel channel=2", "2\tchannel channel=2", "3\tchannel channel=1"});
  auto r = read_cl("CHANNEL\n", dialect::generic);
  CHECK(r.diagnostics ==
        "t.cl:1:1: error: CHANNEL needs a channel number\n"
        "CHANNEL\n"
        "^\n");
}

TEST_CASE("CATIA SYNC/k,c1,c2[,master] with its trailing comma", "[parser][channels]") {
  CHECK(events_of("SYNC/1,1,2,\nSYNC/1,2,1,\nSYNC/3,1,2,1\n", dialect::catia) ==
        lines{"1\tsync from=catia index=1 channels=1,2", "2\tsync from=catia index=1 channels=2,1",
              "3\tsync from=catia index=3 channels=1,2 master=1"});
  auto r = read_cl("SYNC/1,2\n", dialect::catia);
  CHECK(r.diagnostics ==
        "t.cl:1:6: error: SYNC needs a sync number and two channels\n"
        "SYNC/1,2\n"
        "     ^\n");
  // A number that is not whole, or beyond an int: read as one, it would pair with another sync
  // (1.5 as 1; 3000000000 and 4000000000 both as the largest int).
  CHECK(read_cl("SYNC/1.5,1,2\n", dialect::catia).diagnostics ==
        "t.cl:1:6: error: SYNC: 1.5 is no sync or channel number: a whole number up to 2147483647 is\n"
        "SYNC/1.5,1,2\n"
        "     ^\n");
  CHECK(read_cl("SYNC/3000000000,1,2\n", dialect::catia).diagnostics ==
        "t.cl:1:6: error: SYNC: 3000000000 is no sync or channel number: a whole number up to 2147483647 is\n"
        "SYNC/3000000000,1,2\n"
        "     ^\n");
  CHECK(read_cl("SYNCTR/NEXT,5,1.5\n", dialect::generic).diagnostics ==
        "t.cl:1:15: error: SYNCTR: 1.5 is no marker or channel number: a whole number up to 2147483647 is\n"
        "SYNCTR/NEXT,5,1.5\n"
        "              ^\n");
}

TEST_CASE("ICAM SYNCTR/NEXT leaves a marker left out to the router", "[parser][channels]") {
  // Each channel counts its own markers (channels/router): the parser cannot know which
  // channel a record is for, so it does not number them.
  CHECK(events_of("SYNCTR/NEXT\nSYNCTR/NEXT,5,1,2\nSYNCTR/NEXT\n") ==
        lines{"1\tsync from=icam index=next", "2\tsync from=icam index=5 channels=1,2",
              "3\tsync from=icam index=next"});
  CHECK(read_cl("SYNCTR/NEXT\nSYNCTR/NEXT,5,1,2\n", dialect::generic).json ==
        lines{"{\"line\":1,\"event\":\"sync\",\"from\":\"icam\",\"index\":\"next\"}",
              "{\"line\":2,\"event\":\"sync\",\"from\":\"icam\",\"index\":5,\"channels\":[1,2]}"});
  auto r = read_cl("SYNCTR/WAIT\n", dialect::generic);
  CHECK(r.diagnostics ==
        "t.cl:1:8: error: SYNCTR needs NEXT[,marker[,channels]]\n"
        "SYNCTR/WAIT\n"
        "       ^\n");
}

TEST_CASE("huge numbers in integer fields saturate instead of overflowing", "[parser][channels]") {
  // Regression: integer fields cast any double to int. (A tool number out of range is an
  // error now: tests/post_words_test.cpp; SYNCTR/NEXT after marker INT_MAX:
  // tests/router_test.cpp. A sync marker out of range is an error since attack 49: saturated,
  // two of them paired as one.)
  // An AUXFUN code out of range is an error (attack 68 L7), no longer saturated.
  CHECK(read_cl("AUXFUN/1e300\n", dialect::generic).diagnostics ==
        "t.cl:1:8: error: AUXFUN code 1e+300 is out of range\nAUXFUN/1e300\n       ^\n");
  CHECK(events_of("AUXFUN/99999\n") == lines{"1\tauxfun code=99999"});
  CHECK(
      read_cl("SYNCTR/NEXT,1e300\n", dialect::generic).diagnostics ==
      "t.cl:1:13: error: SYNCTR: 1e+300 is no marker or channel number: a whole number up to 2147483647 is\n"
      "SYNCTR/NEXT,1e300\n"
      "            ^\n");
}

TEST_CASE("a MANUSpost sync number too big for an int stays a UDE comment", "[parser][channels]") {
  // Regression: the digits were accumulated into an int without an overflow check.
  CHECK(events_of("$$UDE: MANUSPOST - SYNCHRONIZATION/SYNCHRONIZATION NUMBER=99999999999\n") ==
        lines{"1\tude text=\"UDE: MANUSPOST - SYNCHRONIZATION/SYNCHRONIZATION NUMBER=99999999999\""});
}

TEST_CASE("a two-channel CATIA program", "[parser][channels]") {
  CHECK(events_of("CHANNEL,1\n"
                  "LOADTL/1\n"
                  "GOTO/10,0,5\n"
                  "SYNC/1,1,2,\n"
                  "END\n"
                  "CHANNEL,2\n"
                  "LOADTL/11\n"
                  "SYNC/1,2,1,\n"
                  "GOTO/20,0,5\n"
                  "END\n",
                  dialect::catia) ==
        lines{"1\tchannel channel=1", "2\ttool tool=1 from=LOADTL", "3\tgoto x=10 y=0 z=5",
              "4\tsync from=catia index=1 channels=1,2", "5\tend word=END", "6\tchannel channel=2",
              "7\ttool tool=11 from=LOADTL", "8\tsync from=catia index=1 channels=2,1",
              "9\tgoto x=20 y=0 z=5", "10\tend word=END"});
}
