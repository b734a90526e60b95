// Words held to the control's format (machines/word_format), tool numbers, program numbers,
// NX CIRCLE TIMES and truncated jobs, through the whole post.
#include <catch2/catch.hpp>

#include <filesystem>
#include <map>
#include <string>
#include <unistd.h>

#include "file_test_support.hpp"
#include "machines/machine_loader.hpp"
#include "post/post_job.hpp"
#include "post_test_jobs.hpp"

using namespace twinpost;

namespace {

using test::posted;

posted post_text(const std::string& cl, const machine& m, const std::string& tag) {
  // Without the two-channel machines' "no sync records" note.
  return test::post_in_fresh_dir(
      cl, m, "words-" + tag, [](const diagnostic& d) { return !d.message.starts_with("no sync records"); });
}

posted post_text(const std::string& cl, const std::string& machine_name, const std::string& tag) {
  return post_text(cl, load_machine(machine_name), tag);
}

const std::string head = "PARTNO W\nUNITS/MM\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nFEDRAT/0.2,MMPR\n";

}  // namespace

TEST_CASE("an axis word past the control's format stops the post at its record", "[post][words]") {
  posted z = post_text(head + "GOTO/29,0,1e308\nFINI\n", "fanuc-0itd-twin", "z");
  CHECK_FALSE(z.ok);
  CHECK(z.files.empty());
  CHECK(z.diagnostics ==
        "job.cls:6:1: error: channel 1: Z word 1e+308 does not fit the control's format (5.3: at most "
        "99999.999)\n"
        "GOTO/29,0,1e308\n^\n");
  // One past the largest word the control reads; the largest itself is fine.
  posted over = post_text(head + "GOTO/29,0,100000\nFINI\n", "fanuc-0itd-twin", "over");
  CHECK(over.diagnostics ==
        "job.cls:6:1: error: channel 1: Z word 100000 does not fit the control's format (5.3: at most "
        "99999.999)\n"
        "GOTO/29,0,100000\n^\n");
  // A value from inches: 3937.7 x 25.4 is 100017.57999999999 as a double; the message gives
  // it to 12 digits.
  posted inch = post_text(
      "PARTNO W\nUNITS/INCHES\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nFEDRAT/0.2,MMPR\n"
      "GOTO/1,0,3937.7\nFINI\n",
      "fanuc-0itd-twin", "inch");
  CHECK(inch.diagnostics ==
        "job.cls:6:1: error: channel 1: Z word 100017.58 does not fit the control's format (5.3: at most "
        "99999.999)\n"
        "GOTO/1,0,3937.7\n^\n");
  posted edge = post_text(head + "GOTO/29,0,-99999.999\nFINI\n", "fanuc-0itd-twin", "edge");
  CHECK(edge.ok);
  CHECK(edge.diagnostics == "");
  // X is a diameter: CL x = 1e308 is an infinite diameter, -1e308 keeps its sign.
  posted x = post_text(head + "GOTO/1e308,0,1\nGOTO/-1e308,0,1\nFINI\n", "fanuc-0itd-twin", "x");
  CHECK(
      x.diagnostics ==
      "job.cls:6:1: error: channel 1: X word inf does not fit the control's format (5.3: at most 99999.999)\n"
      "GOTO/1e308,0,1\n^\n"
      "job.cls:7:1: error: channel 1: X word -inf does not fit the control's format (5.3: at most "
      "99999.999)\n"
      "GOTO/-1e308,0,1\n^\n");
}

TEST_CASE("F, S, T and dwell words are held to the control's format", "[post][words]") {
  posted f =
      post_text("PARTNO W\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nFEDRAT/1e308\nFINI\n", "fanuc-0itd-twin", "f");
  CHECK(f.diagnostics ==
        "job.cls:4:1: error: channel 1: F word 1e+308 does not fit the control's format (6.4: at most "
        "999999.9999)\nFEDRAT/1e308\n^\n");
  posted s =
      post_text("PARTNO W\nTURRET/1,1\nSPINDL/SMM,123456,MAXRPM,3000,CLW\nFINI\n", "fanuc-0itd-twin", "s");
  CHECK(s.diagnostics ==
        "job.cls:3:1: error: channel 1: S word 123456 does not fit the control's format (5: at most 99999)\n"
        "SPINDL/SMM,123456,MAXRPM,3000,CLW\n^\n");
  posted t = post_text("PARTNO W\nTURRET/100,1\nFINI\n", "fanuc-0itd-twin", "t");
  CHECK(t.diagnostics ==
        "job.cls:2:1: error: channel 1: T word 10001 does not fit the control's format (4: at most 9999)\n"
        "TURRET/100,1\n^\n");
  posted d = post_text(head + "DELAY/1e9\nFINI\n", "fanuc-0itd-twin", "d");
  CHECK(d.diagnostics ==
        "job.cls:6:1: error: channel 1: U word 1000000000 does not fit the control's format (5.3: at most "
        "99999.999)\n"
        "DELAY/1e9\n^\n");
  posted ms = post_text("PARTNO W\nTURRET/1,1\nDELAY/1e6\nFINI\n", "integrex-i200st", "ms");
  CHECK(ms.diagnostics ==
        "job.cls:3:1: error: channel 1: P word 1000000000 does not fit the control's format (8: at most "
        "99999999)\nDELAY/1e6\n^\n");
}

TEST_CASE("a feed per minute above limits.max_feed stops the post at its record", "[post][words]") {
  // fanuc-0itd-twin: max_feed = 10000 mm/min. The limit itself is fine.
  const std::string start = "PARTNO W\nTURRET/1,1\nSPINDL/RPM,1000,CLW\n";
  posted at = post_text(start + "FEDRAT/MMPM,10000\nGOTO/10,0,1\nFINI\n", "fanuc-0itd-twin", "feed-at");
  CHECK(at.ok);
  CHECK(at.diagnostics == "");
  posted over = post_text(start + "FEDRAT/MMPM,12000\nFINI\n", "fanuc-0itd-twin", "feed-over");
  CHECK_FALSE(over.ok);
  CHECK(over.files.empty());
  CHECK(over.diagnostics ==
        "job.cls:4:1: error: channel 1: feed 12000 mm/min exceeds the machine's limit of 10000 mm/min "
        "(limits.max_feed)\nFEDRAT/MMPM,12000\n^\n");
  // Inch feeds are held to it after conversion: 500 in/min is 12700 mm/min.
  posted inch = post_text(start + "FEDRAT/500,IPM\nFINI\n", "fanuc-0itd-twin", "feed-inch");
  CHECK(inch.diagnostics ==
        "job.cls:4:1: error: channel 1: feed 12700 mm/min exceeds the machine's limit of 10000 mm/min "
        "(limits.max_feed)\nFEDRAT/500,IPM\n^\n");
  // A feed per revolution depends on the speed and is not compared with it.
  posted rev = post_text(start + "FEDRAT/20000,MMPR\nGOTO/10,0,1\nFINI\n", "fanuc-0itd-twin", "feed-rev");
  CHECK(rev.diagnostics == "");
}

TEST_CASE("a tool number is a whole number, or an error at its argument", "[post][words]") {
  posted big = post_text("PARTNO W\nTURRET/1e308\nFINI\n", "fanuc-0itd-twin", "big");
  CHECK(big.diagnostics ==
        "job.cls:2:8: error: TURRET tool number 1e+308 is out of range\nTURRET/1e308\n       ^\n");
  posted half = post_text("PARTNO W\nLOADTL/2.5\nFINI\n", "fanuc-0itd-twin", "half");
  CHECK(half.diagnostics ==
        "job.cls:2:8: error: LOADTL tool number 2.5 is not a whole number\nLOADTL/2.5\n       ^\n");
  // An AUXFUN's code too (attack 68 L7: AUXFUN/2.5 was written M3, a spindle start).
  posted aux = post_text("PARTNO W\nAUXFUN/2.5\nFINI\n", "fanuc-0itd-twin", "aux-half");
  CHECK(aux.diagnostics ==
        "job.cls:2:8: error: AUXFUN code 2.5 is not a whole number\nAUXFUN/2.5\n       ^\n");
  posted offset = post_text("PARTNO W\nTURRET/1,-1\nFINI\n", "fanuc-0itd-twin", "offset");
  CHECK(offset.diagnostics ==
        "job.cls:2:10: error: TURRET offset number -1 is out of range\nTURRET/1,-1\n         ^\n");
}

TEST_CASE("PARTNO gives the program number only when it fits the O format", "[post][words]") {
  posted p = post_text("PARTNO 99999999\nTURRET/1,1\nFINI\n", "fanuc-0itd-twin", "partno");
  CHECK(p.ok);
  CHECK(p.diagnostics ==
        "job.cls:1:1: warning: PARTNO 99999999 is not a program number of this control (format.O 4: 1 to "
        "9999); "
        "the program takes the machine's program_number 1000\nPARTNO 99999999\n^\n");
  REQUIRE(p.files.count("99999999_1.nc") == 1);
  CHECK(p.files.at("99999999_1.nc").starts_with("%\nO1000 (99999999)\n"));
  posted fits = post_text("PARTNO 1234\nTURRET/1,1\nFINI\n", "fanuc-0itd-twin", "fits");
  CHECK(fits.diagnostics == "");
  CHECK(fits.files.at("1234_1.nc").starts_with("%\nO1234 (1234)\n"));
  // Mazak EIA takes eight digits.
  posted mazak = post_text("PARTNO 99999999\nTURRET/1,1\nFINI\n", "integrex-i200st", "mazak");
  CHECK(mazak.diagnostics == "");
  CHECK(mazak.files.at("99999999.EIA").starts_with("%\nO99999999(99999999)\n"));
}

TEST_CASE("NX CIRCLE TIMES,n is posted as n full circles", "[post][words]") {
  const std::string job = head + "GOTO/20,0,0\nCIRCLE/10,0,0,0,1,0,10,0.06,0.5,4,0,TIMES,2\nGOTO/20,0,0\n";
  posted p = post_text(job + "GOTO/20,0,5\nFINI\n", "fanuc-0itd-twin", "times");
  CHECK(p.diagnostics == "");
  REQUIRE(p.files.count("W_1.nc") == 1);
  CHECK(p.files.at("W_1.nc") ==
        "%\nO1000 (W)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG97 S1000 M3\nG1 X40. Z0. "
        "F0.2\n"
        "G3 X40. Z0. I-10. K0.\nG3 X40. Z0. I-10. K0.\nG1 Z5.\nM100\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
  // A move that ends elsewhere on the circle: the turns, then the part turn on to it.
  posted off =
      post_text(head + "GOTO/20,0,0\nCIRCLE/10,0,0,0,1,0,10,0.06,0.5,4,0,TIMES,2\nGOTO/0,0,0\nFINI\n",
                "fanuc-0itd-twin", "times-off");
  REQUIRE(off.ok);
  CHECK(off.files.at("W_1.nc").find(
            "G1 X40. Z0. F0.2\nG3 X40. Z0. I-10. K0.\nG3 X40. Z0. I-10. K0.\nG3 X0. Z0. "
            "I-10. K0.\n") != std::string::npos);
  // A helix about Y (G18) needs a Y axis: the lathe has none.
  posted helix =
      post_text(head + "GOTO/20,0,0\nCIRCLE/10,0,0,0,1,0,10,0.06,0.5,4,0,TIMES,2\nGOTO/20,-4,0\nFINI\n",
                "fanuc-0itd-twin", "times-helix");
  CHECK(helix.diagnostics ==
        "job.cls:8:1: error: channel 1: Y -4 on a channel without a Y axis\nGOTO/20,-4,0\n^\n");
}

TEST_CASE("a post stops at a record it cannot carry out, and warns at a job cut off", "[post][words]") {
  posted foo = post_text(head + "FOO/1\nFINI\n", "fanuc-0itd-twin", "foo");
  CHECK_FALSE(foo.ok);
  CHECK(foo.files.empty());
  CHECK(foo.diagnostics ==
        "job.cls:6:1: error: unknown major word 'FOO': this record cannot be posted\nFOO/1\n^\n");
  posted cut = post_text(head + "GOTO/20,0,0\nGOTO/20,0,-5\n", "fanuc-0itd-twin", "cut");
  CHECK(cut.ok);
  CHECK(
      cut.diagnostics ==
      "job.cls:7:1: warning: the job ends without FINI or END after this GOTO record: is the file cut off?\n"
      "GOTO/20,0,-5\n^\n");
  posted dangling = post_text(head + "GOTO/20,0,0\nGOTO/20,$\n", "fanuc-0itd-twin", "dangling");
  CHECK_FALSE(dangling.ok);
  CHECK(dangling.diagnostics ==
        "job.cls:7:9: error: the file ends in a continued record ('$' at the end of the last line): the job "
        "is cut "
        "off\nGOTO/20,$\n        ^\n"
        "job.cls:6:1: warning: the job ends without FINI or END after this GOTO record: is the file cut "
        "off?\n");
}

TEST_CASE("a dwell template without an address letter still keeps its milliseconds in range",
          "[post][words]") {
  machine m = load_machine("fanuc-0itd-twin");
  m.codes.dwell = "G4 P=#{ms}";
  posted ok = post_text(head + "DELAY/1.5\nFINI\n", m, "dwell-ok");
  CHECK(ok.diagnostics == "");
  CHECK(ok.files.at("W_1.nc").find("\nG98 G4 P=#1500\nM100\n") != std::string::npos);
  posted big = post_text(head + "DELAY/1e7\nFINI\n", m, "dwell-big");
  CHECK(big.diagnostics ==
        "job.cls:6:1: error: channel 1: DELAY/10000000 is longer than any dwell the control "
        "takes\nDELAY/1e7\n^\n");
}

TEST_CASE("an AUXFUN whose code is a wait code stops the post at its record", "[post][words]") {
  // The control would take M200 for a wait of the 31i's range and stop the path there.
  posted wait = post_text(head + "GOTO/20,0,0\nAUXFUN/200\nFINI\n", "fanuc-31i-3path", "aux-wait");
  CHECK_FALSE(wait.ok);
  CHECK(wait.files.empty());
  CHECK(wait.diagnostics ==
        "job.cls:7:1: error: channel 1: AUXFUN/200 gives M200, a wait code of this machine (waits "
        "M200-M299): the control would take it for a wait\n"
        "AUXFUN/200\n^\n");
  // M203 is excluded from the range (Doosan spindle synchronisation), PREFUN/200 is a G code.
  posted sync =
      post_text(head + "GOTO/20,0,0\nAUXFUN/203\nPREFUN/200\nFINI\n", "fanuc-31i-3path", "aux-sync");
  CHECK(sync.ok);
  CHECK(sync.diagnostics == "");
  CHECK(sync.files.at("W_1.nc").find("\nM203\nG200\n") != std::string::npos);
  posted twin = post_text(head + "AUXFUN/102\nAUXFUN/103\nFINI\n", "fanuc-0itd-twin", "aux-twin");
  CHECK(twin.diagnostics ==
        "job.cls:6:1: error: channel 1: AUXFUN/102 gives M102, a wait code of this machine (waits "
        "M100-M102): the control would take it for a wait\n"
        "AUXFUN/102\n^\n");
}

TEST_CASE("an X word past the channel's X travel stops the post at its record", "[post][words]") {
  // The Integrex lower turret's X runs 0..260 (diameter): facing 0.8 mm past the centre would
  // drive it into its stop. The Fanuc turret's -10..460 takes the same cut.
  const std::string job =
      "PARTNO W\nUNITS/MM\nHEAD/2\nTURRET/1,1\nSPINDL/SMM,200,MAXRPM,2000,CLW\n"
      "FEDRAT/0.2,MMPR\nRAPID\nGOTO/-30,0,0\nGOTO/0.8,0,0\nFINI\n";
  const posted lower = post_text(job, "integrex-i200st", "travel-integrex");
  CHECK_FALSE(lower.ok);
  CHECK(lower.diagnostics ==
        "job.cls:9:1: error: channel 2: X-1.6 is outside channel 2's X travel 0..260 (channel.axis min/max)\n"
        "GOTO/0.8,0,0\n^\n");
  CHECK(post_text(job, "fanuc-0itd-twin", "travel-fanuc").ok);
}

TEST_CASE("a dwell of 1 s reads as 1 s whatever the control's decimal-point setting", "[post][words]") {
  // A Fanuc reads a dwell word without a point in its least increment (G4 U1 is 1 ms with
  // decimal-point programming off, the default): seconds always carry their point, and
  // milliseconds (P) are whole numbers, which no setting reads otherwise. Under feed per
  // revolution (the Fanuc lathes' G99) the dwell is written under G98, where it is seconds
  // whatever parameter 3405#1 says, and G99 comes back before the next move (not before a
  // second dwell, and not at the program's end: review 40). The Integrex's header sets no feed
  // mode (a control may keep the last program's G95): G94 with the first dwell, and it stays.
  const std::map<std::string, std::string> want = {
      {"fanuc-0itd-twin", "G98 G4 U1."},   {"fanuc-31i-3path", "G98 G4 U1."},
      {"integrex-i200st", "G94 G4 P1000"}, {"head-head-5axis", "G4 P1000"},
      {"rotary-4axis", "G4 P1000"},        {"trunnion-5axis", "G4 P1000"},
  };
  for (const auto& [name, block] : want) {
    INFO(name);
    posted p = post_text("PARTNO W\nLOADTL/1\nDELAY/1\nDELAY/2.25\nFINI\n", name, "dwell-" + name);
    CHECK(p.diagnostics == "");
    std::string all;
    for (const auto& [file, text] : p.files) all += text;
    const bool per_rev = block.starts_with("G98");
    CHECK(all.find("\n" + block + (per_rev ? "\nG4 U2.25\n" : "\nG4 P2250\n")) != std::string::npos);
    if (per_rev) {  // (no G99 before the end of the channel's program)
      const std::string& one = p.files.at("W_1.nc");
      CHECK(one.find("G99", one.find("G4 U2.25")) == std::string::npos);
    }
  }
  // A negative time is no dwell (attack 71 F7: `G4 U-1.` was written).
  posted negative = post_text("PARTNO W\nLOADTL/1\nDELAY/-1\nFINI\n", "fanuc-0itd-twin", "dwell-negative");
  CHECK(negative.diagnostics ==
        "job.cls:3:1: error: channel 1: DELAY/-1: a dwell of a negative time; give the seconds to wait\n"
        "DELAY/-1\n^\n");
  // Between two cuts under G99: the dwell under G98, then G99 and the next cut's F again.
  posted cut = post_text(
      "PARTNO W\nTURRET/1,1\nSPINDL/RPM,800,CLW\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/20,0,2\n"
      "GOTO/20,0,-10\nDELAY/2\nGOTO/21,0,-10\nFINI\n",
      "fanuc-0itd-twin", "dwell-cut");
  CHECK(cut.files.at("W_1.nc").find("\nG1 Z-10. F0.2\nG98 G4 U2.\nG99\nX42. F0.2\n") != std::string::npos);
  // An INSERT after the dwell is NC text that may feed: G99 comes back before it (review 41 H1:
  // G1 X41. Z-11. ran at F0.2 mm/min).
  posted insert = post_text(
      "PARTNO W\nTURRET/1,1\nSPINDL/RPM,800,CLW\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/20,0,2\n"
      "GOTO/20,0,-10\nDELAY/2\nINSERT/G1 X41. Z-11.\nGOTO/21,0,-12\nFINI\n",
      "fanuc-0itd-twin", "dwell-insert");
  CHECK(insert.files.at("W_1.nc").find(
            "\nG1 Z-10. F0.2\nG98 G4 U2.\nG99\nG1 X41. Z-11.\nG1 X42. Z-12. F0.2\n") != std::string::npos);
  // A FEDRAT per minute after the dwell: G98 stays, no G99 and G98 again (review 40).
  posted per_min = post_text(
      "PARTNO W\nTURRET/1,1\nSPINDL/RPM,800,CLW\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/20,0,2\n"
      "GOTO/20,0,-10\nDELAY/2\nFEDRAT/200,MMPM\nGOTO/21,0,-10\nFINI\n",
      "fanuc-0itd-twin", "dwell-per-min");
  CHECK(per_min.diagnostics == "");
  CHECK(per_min.files.at("W_1.nc").find("\nG1 Z-10. F0.2\nG98 G4 U2.\nX42. F200.\nM100\n") !=
        std::string::npos);
  // A time the word writes as none (U0., P0) is no dwell: left out, and said.
  posted none =
      post_text("PARTNO W\nLOADTL/1\nDELAY/0\nDELAY/0.0004\nFINI\n", "integrex-i200st", "dwell-none");
  CHECK(none.diagnostics ==
        "job.cls:3:1: warning: channel 1: DELAY/0: the dwell is written as no time (P0): left out\n"
        "DELAY/0\n^\n"
        "job.cls:4:1: warning: channel 1: DELAY/0.0004: the dwell is written as no time (P0): left out\n"
        "DELAY/0.0004\n^\n");
  for (const auto& [file, text] : none.files) CHECK(text.find("G4 P") == std::string::npos);
  // A machine file with no feed-per-minute code: the dwell stays under G99, and the self-check
  // says what to give (attack 71 F7).
  machine no_min = load_machine("fanuc-0itd-twin");
  no_min.codes.feed_per_min = "";
  posted stays = post_text(
      "PARTNO W\nTURRET/1,1\nSPINDL/RPM,800,CLW\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/20,0,2\n"
      "GOTO/20,0,-10\nDELAY/2\nGOTO/21,0,-10\nFINI\n",
      no_min, "dwell-no-min");
  CHECK(
      stays.diagnostics ==
      "job.cls:8:1: error: channel 1: the CL dwells 2 s here (DELAY), the program under G99 (`G4 U2.`): a "
      "control that counts a dwell in spindle revolutions under feed per revolution (Fanuc parameter 3405#1) "
      "waits 2 revolutions; the machine file gives no codes.feed_per_min to write the dwell under: give it "
      "(G98, G94)\nDELAY/2\n^\n");
  // A machine file's own template: {seconds} with no spec has its point; with a spec it is fmt's.
  machine m = load_machine("fanuc-0itd-twin");
  m.codes.dwell = "G4 X{seconds}";
  posted x = post_text("PARTNO W\nTURRET/1,1\nDELAY/3\nFINI\n", m, "dwell-x");
  CHECK(x.files.at("W_1.nc").find("\nG98 G4 X3.\nM100\n") != std::string::npos);
  m.codes.dwell = "G4 U{seconds:.1f}";
  posted spec = post_text("PARTNO W\nTURRET/1,1\nDELAY/3\nFINI\n", m, "dwell-spec");
  CHECK(spec.files.at("W_1.nc").find("\nG98 G4 U3.0\nM100\n") != std::string::npos);
}

TEST_CASE("a lathe arc that passes the centre line between its ends is warned about", "[post][words]") {
  // Attack 45: a three-quarter arc about X2 (diameter 4) of radius 10 reaches X-16 on the way to
  // its end at X4; only the end was checked.
  posted p = post_text(head + "GOTO/12,0,-20\nCIRCLE/2,0,-20,0,-1,0,10\nGOTO/2,0,-30\nFINI\n",
                       "fanuc-0itd-twin", "arc-centre");
  CHECK(p.diagnostics ==
        "job.cls:8:1: warning: channel 1: X-16. is past the spindle centre line (CL x = -8)\n"
        "GOTO/2,0,-30\n^\n");
}
