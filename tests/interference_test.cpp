// Turret interference (analysis/interference.hpp): the geometry to the letter (swept box of an
// arc, a drill's envelope along Z, a mirrored lower turret), the machine-file keys, and the rule
// through check_nc_resources, its message asserted.
#include <catch2/catch.hpp>

#include <string>

#include "analysis/interference.hpp"
#include "analysis/shared_resources.hpp"
#include "analysis/timeline_report.hpp"
#include "check/sync_report.hpp"
#include "machines/machine_loader.hpp"
#include "machines/machine_search.hpp"
#include "support/errors.hpp"

using namespace twinpost;

namespace {

void same_box(const xz_box& b, double r0, double r1, double z0, double z1) {
  CHECK(b.r0 == Approx(r0).margin(1e-9));
  CHECK(b.r1 == Approx(r1).margin(1e-9));
  CHECK(b.z0 == Approx(z0).margin(1e-9));
  CHECK(b.z1 == Approx(z1).margin(1e-9));
}

std::string check(const machine& m, const std::string& one, const std::string& two) {
  return format_sync_text(check_nc_resources({{"A_1.nc", one}, {"A_2.nc", two}}, m));
}

}  // namespace

TEST_CASE("interference: the swept box of an arc takes the quadrant points it passes", "[analysis]") {
  // A quarter circle of radius 10 about (r 0, z 0), from (r 10, z 0) to (r 0, z 10): seen with Z
  // to the right and r up that is clockwise (G2); its box is the chord's.
  same_box(arc_box(10, 0, 0, 10, 0, 0, true), 0, 10, 0, 10);
  // The other way round (G3) it sweeps three quarters: through r -10 and z -10.
  same_box(arc_box(10, 0, 0, 10, 0, 0, false), -10, 10, -10, 10);
  // A half circle from (r 5, z 0) to (r 5, z 20) about (r 5, z 10): counter-clockwise it passes
  // below the centre (r -5), clockwise above it (r 15).
  same_box(arc_box(5, 0, 5, 20, 5, 10, false), -5, 5, 0, 20);
  same_box(arc_box(5, 0, 5, 20, 5, 10, true), 5, 15, 0, 20);
  // Given by R: the same quarter clockwise (R 10: about (0, 0)); R -10, the longer way about
  // (10, 10): through r 20 and z 20.
  same_box(arc_box_radius(10, 0, 0, 10, 10, true), 0, 10, 0, 10);
  same_box(arc_box_radius(10, 0, 0, 10, -10, true), 0, 20, 0, 20);
  // Counter-clockwise with R 10 the short arc is about (10, 10): its box is the chord's too.
  same_box(arc_box_radius(10, 0, 0, 10, 10, false), 0, 10, 0, 10);
  // Start and end in one point: the full circle.
  same_box(arc_box(3, 0, 3, 0, 0, 0, true), -3, 3, -3, 3);
}

TEST_CASE("interference: a drill's envelope along Z and a mirrored lower turret", "[analysis]") {
  interference_channel upper{1, 1, {{-2, 60, -5, 60}, {60, 260, -60, 160}}};
  interference_channel lower{2, -1, {{-2, 60, -5, 60}, {60, 260, -60, 160}}};
  // A drill feeding from Z1 to Z-25 on the axis: its tool box runs from 5 mm below the hole's
  // bottom to 60 mm above the start, the turret behind it.
  const xz_box drill_tip{0, 0, -25, 1};
  std::vector<xz_box> up = envelope_boxes(upper, drill_tip);
  REQUIRE(up.size() == 2);
  same_box(up[0], -2, 60, -30, 61);
  same_box(up[1], 60, 260, -85, 161);
  // The same on the lower turret: r mirrored about the axis, Z as it is.
  std::vector<xz_box> low = envelope_boxes(lower, drill_tip);
  REQUIRE(low.size() == 2);
  same_box(low[0], -60, 2, -30, 61);
  same_box(low[1], -260, -60, -85, 161);
  // An upper tool at X60 (r 30) is 26 mm from the lower drill's box: 30 - 2 - 2.
  const std::vector<xz_box> od = envelope_boxes(upper, {30, 30, -40, 2});
  CHECK(box_distance(od[0], low[0]) == Approx(26));
  CHECK(box_distance({0, 1, 0, 1}, {4, 5, 4, 5}) == Approx(std::hypot(3, 3)));
}

TEST_CASE("interference: the machine file gives envelopes and zones, checked", "[machines]") {
  const machine twin = load_machine("fanuc-0itd-twin");
  REQUIRE(twin.interference.channels.size() == 2);
  CHECK(twin.interference.clearance == 5);
  CHECK(twin.interference.channel(2)->side == -1);
  CHECK(load_machine("integrex-i200st").interference.channel(2)->side == -1);
  CHECK(load_machine("fanuc-31i-3path").interference.channels.size() == 3);
  CHECK(load_machine("citizen-2system").interference.channels.empty());
  // fanuc-0itd-twin without its [interference] (the last thing in its file), given others.
  std::string base = find_machine("fanuc-0itd-twin", {}).text;
  base = base.substr(0, base.find("# Turret interference"));
  auto fails = [&](const std::string& extra) -> std::string {
    try {
      (void)parse_machine(base + extra, "m.toml");
    } catch (const std::exception& e) {
      return e.what();
    }
    return "";
  };
  CHECK_THAT(fails("[interference]\n[[interference.channel]]\nchannel = 3\nboxes = [[0, 1, 0, 1]]\n"),
             Catch::Contains("interference.channel.channel 3 names no channel (the machine has 2)"));
  CHECK_THAT(fails("[interference]\n[[interference.channel]]\nchannel = 1\nboxes = [[1, 0, 0, 1]]\n"),
             Catch::Contains("a box needs r0 <= r1 and z0 <= z1"));
  CHECK_THAT(
      fails("[interference]\n[[interference.channel]]\nchannel = 1\nside = 2\nboxes = [[0, 1, 0, 1]]\n"),
      Catch::Contains("interference.channel.side must be 1 or -1, not 2"));
  CHECK_THAT(fails("[interference]\n[[interference.zone]]\nspindle = \"back\"\nbox = [0, 1, 0, 1]\n"),
             Catch::Contains("interference.zone.spindle 'back' names no [[spindle]]"));
  CHECK(fails("[interference]\nclearance = 3\n[[interference.zone]]\nspindle = \"main\"\nbox = [0, 80, -200, "
              "-150]\n")
            .empty());
}

TEST_CASE("interference: the rule in check, concurrent and sequenced, to the letter", "[analysis]") {
  const machine twin = load_machine("fanuc-0itd-twin");
  const std::string head = "%\nO1000\nG0 G18 G21 G40 G54 G80 G99\n";
  const std::string face =
      head + "T0101\nG97 S1000 M3\nG0 X64. Z0.\nM100\nG1 X-1.6 F0.15\nG0 X100. Z100.\nM101\nM30\n%\n";
  const std::string drill = head + "T0505\nG0 X0. Z5.\nM100\nG1 Z-25. F0.08\nG0 Z50.\nM101\nM30\n%\n";
  CHECK(check(twin, face, drill) ==
        "A_1.nc:8:1: error: channel 1 (T0101 at X-1.6 Z0) may meet channel 2 (T0505 at X0 Z-25, A_2.nc:7) on "
        "the main spindle, between M100 (A_1.nc:7) and M101 (A_1.nc:10) of channel 1: 0.0 mm apart, 5 mm "
        "required; no wait orders the two blocks\n"
        "G1 X-1.6 F0.15\n^\n"
        "A_2.nc:7:1: note: channel 2 is here (T0505 at X0 Z-25)\n"
        "G1 Z-25. F0.08\n^\n"
        "check: 2 channels, 4 waits paired, 1 error\n");
  // An arc about the centre (G3 from X20 to ): its sweep reaches the drill as well.
  const std::string arc =
      head +
      "T0101\nG97 S1000 M3\nG0 X20. Z0.\nM100\nG3 X-1.6 Z-10.8 R10.8 F0.15\nG0 X100. Z100.\nM101\nM30\n%\n";
  CHECK_THAT(check(twin, arc, drill),
             Catch::Contains("A_1.nc:8:1: error: channel 1 (T0101 at X-1.6 Z-10.8)"));
  // Ordered by a wait: no finding.
  const std::string face_then =
      head + "T0101\nG97 S1000 M3\nG0 X64. Z0.\nM100\nG1 X-1.6 F0.15\nG0 X100. Z100.\nM102\nM101\nM30\n%\n";
  const std::string drill_after =
      head + "T0505\nG0 X0. Z5.\nM100\nM102\nG1 Z-25. F0.08\nG0 Z50.\nM101\nM30\n%\n";
  CHECK(check(twin, face_then, drill_after) == "check: 2 channels, 6 waits paired, 0 errors\n");
  // Concurrent, the tips 30 mm apart (26 mm between the envelopes): no finding; 8 mm apart
  // (4 mm between them, under the 5 mm clearance): the finding.
  const std::string od =
      head + "T0101\nG97 S1000 M3\nG0 X60. Z2.\nM100\nG1 Z-40. F0.15\nG0 X100. Z100.\nM101\nM30\n%\n";
  CHECK(check(twin, od, drill) == "check: 2 channels, 4 waits paired, 0 errors\n");
  const std::string near =
      head + "T0101\nG97 S1000 M3\nG0 X16. Z2.\nM100\nG1 Z-40. F0.15\nG0 X100. Z100.\nM101\nM30\n%\n";
  CHECK_THAT(check(twin, near, drill), Catch::Contains(": 4.0 mm apart, 5 mm required"));
  // Channel 1 in inches (G20): its positions are held to the envelopes in millimetres. X2.4
  // (r 30.48 mm) is clear of the drill; X0.64 (r 8.128 mm) is 4.1 mm from it. Read as
  // millimetres, both were 0.0 mm apart.
  const std::string head_inch = "%\nO1000\nG0 G18 G20 G40 G54 G80 G99\n";
  const std::string od_inch =
      head_inch + "T0101\nG97 S1000 M3\nG0 X2.4 Z0.08\nM100\nG1 Z-1.6 F0.006\nG0 X4. Z4.\nM101\nM30\n%\n";
  CHECK(check(twin, od_inch, drill) == "check: 2 channels, 4 waits paired, 0 errors\n");
  const std::string near_inch =
      head_inch + "T0101\nG97 S1000 M3\nG0 X0.64 Z0.08\nM100\nG1 Z-1.6 F0.006\nG0 X4. Z4.\nM101\nM30\n%\n";
  CHECK_THAT(check(twin, near_inch, drill), Catch::Contains(": 4.1 mm apart, 5 mm required"));
  // A machine without envelopes: the rule is off.
  CHECK(check(load_machine("citizen-2system"), face, drill).find("may meet") == std::string::npos);
}

TEST_CASE("interference: G91 moves are increments, read from the one modal state", "[analysis]") {
  // The Integrex's programs are in G-code system B (its header gives G90): G91 makes X and Z
  // increments (analysis/modal_state). The upper head faces from X64. to the centre with
  // `G91 G1 X-65.6` (to) while the lower turret's drill waits at X0 Z5 between the same
  // waits. Read as an absolute X-65.6 (as the rule did before it read the modal state) the
  // face ended 32.8 mm below the axis; it ends at the centre, on the drill.
  const machine integrex = load_machine("integrex-i200st");
  const std::string head = "%\nO1000\nG21\nG0 G90 G54 G97 G18\n";
  const auto face = [&](const std::string& feed) {
    return head + "T0101\nG97 S1000 M3\nG0 X64. Z0.\nM950\n" + feed + "\nG90 G0 X100. Z100.\nM951\nM30\n%\n";
  };
  const std::string drill = head + "T0505\nG0 X0. Z5.\nM950\nG0 X0. Z5.\nM951\nM30\n%\n";
  CHECK(check(integrex, face("G91 G1 X-65.6 F0.15"), drill) ==
        "A_1.nc:9:1: error: channel 1 (T0101 at X-1.6 Z0) may meet channel 2 (T0505 at X0 Z5, A_2.nc:8) on "
        "the main spindle, between M950 (A_1.nc:8) and M951 (A_1.nc:11) of channel 1: 0.0 mm apart, 5 mm "
        "required; no wait orders the two blocks\n"
        "G91 G1 X-65.6 F0.15\n^\n"
        "A_2.nc:8:1: note: channel 2 is here (T0505 at X0 Z5)\n"
        "G0 X0. Z5.\n^\n"
        "check: 2 channels, 4 waits paired, 1 error\n");
  // A pass that stays outside: `G91 G1 X-4.` ends at X60. (r 30), clear of the drill as X60. in
  // the concurrent case of the test above. Read as an absolute X-4. it crossed the axis: a
  // finding where there is none.
  CHECK(check(integrex, face("G91 G1 X-4. F0.15"), drill) == "check: 2 channels, 4 waits paired, 0 errors\n");
  // Increments from a place not known (after G28, in G91 throughout): not held, and said once
  // (review 41 H3: no word, where a rule that read them as positions had found a meeting).
  const std::string lost =
      head + "T0101\nG97 S1000 M3\nG91 G28 X0. Z0.\nM950\nG1 X-60. F0.15\nZ-5.\nM951\nM30\n%\n";
  CHECK(check(integrex, lost, drill) ==
        "A_1.nc:9:1: warning: channel 1: 2 blocks from here on move by increments from a place the "
        "interference "
        "rule does not know (the program's start, a reference return or a move in machine coordinates): not "
        "held to the other channels; give X and Z absolute first\n"
        "G1 X-60. F0.15\n^\n"
        "check: 2 channels, 4 waits paired, 0 errors, 1 warning\n");
}

TEST_CASE("interference: a drilling cycle's depth by increments, and a coordinate setting", "[analysis]") {
  // Attack 72 F1: `G83 X0. W-50. R-100.` from Z5. drills to Z-145. (R from the start, W from R);
  // the depth was lost and the turret at X3. Z-150. passed. F3: after `G50 X200. Z100.` the
  // tool stands there; its U/W moves were not placed, and the face to the centre passed.
  const machine twin = load_machine("fanuc-0itd-twin");
  const std::string head = "%\nO1000\nG0 G18 G21 G40 G54 G80 G99\n";
  const std::string deep =
      head + "T0101\nG97 S1000 M3\nG0 X30. Z-150.\nM101\nG1 X3. F0.15\nG0 X100.\nM102\nM100\nM30\n%\n";
  const std::string drill =
      head + "T0505\nG0 X0. Z5.\nM101\nG83 X0. W-50. R-100. F0.1\nG80\nG0 Z50.\nM102\nM100\nM30\n%\n";
  CHECK_THAT(
      check(twin, deep, drill),
      Catch::StartsWith("A_1.nc:8:1: error: channel 1 (T0101 at X3 Z-150) may meet channel 2 (T0505 at X0 "
                        "Z-145, A_2.nc:7) on the main spindle"));
  const std::string set = head +
                          "T0101\nG50 X200. Z100.\nG97 S1000 M3\nG0 U-136. W-100.\nM100\nG1 U-65.6 F0.15\n"
                          "G0 U40. W100.\nM101\nM100\nM30\n%\n";
  const std::string bore = head + "T0505\nG0 X0. Z5.\nM100\nG1 Z-25. F0.08\nG0 Z50.\nM101\nM100\nM30\n%\n";
  CHECK_THAT(
      check(twin, set, bore),
      Catch::StartsWith("A_1.nc:9:1: error: channel 1 (T0101 at X-1.6 Z0) may meet channel 2 (T0505 at X0 "
                        "Z-25, A_2.nc:7) on the main spindle"));
}

TEST_CASE("interference: live-tool work on the part in polar interpolation, in the spindle's frame",
          "[analysis]") {
  // Path 3 of the 31i mills across the face of the part in the main spindle with its live
  // spindle (M33) in polar interpolation, while path 2 parks a drill at X0 Z5 between the same
  // waits (issue 37, item 3): the live tool's sweeps are in the main spindle's frame, at their
  // distance from the axis (the X/C line through the centre comes to r 0).
  const machine three = load_machine("fanuc-31i-3path");
  const std::string head = "%\nO1000\nG0 G18 G21 G40 G54 G80 G99\n";
  const std::string idle = head + "M30\n%\n";
  const std::string park = head + "T0505\nM200 P23\nG0 X0. Z5.\nM201 P23\nM30\n%\n";
  const auto mill = [&](const std::string& c) {
    return head + "T1111 M6\nG0 B-90.\nM35\nG97 S3000 M33\nG98\nG17\nG12.1\nG1 X80. C" + c +
           " Z5. F1500.\nM200 P23\n" + "Z-1. F400.\nX-80.\nZ5.\nG13.1\nG18\nM201 P23\nM30\n%\n";
  };
  const auto check3 = [&](const std::string& three_nc) {
    return format_sync_text(
        check_nc_resources({{"A_1.nc", idle}, {"A_2.nc", park}, {"A_3.nc", three_nc}}, three));
  };
  CHECK(check3(mill("0.")) ==
        "A_2.nc:6:1: error: channel 2 (T0505 at X0 Z5) may meet channel 3 (T1111 at X-80 Z-1, A_3.nc:14) on "
        "the "
        "main spindle, between M200 (A_2.nc:5) and M201 (A_2.nc:7) of channel 2: 0.0 mm apart, 5 mm "
        "required; no "
        "wait orders the two blocks\n"
        "G0 X0. Z5.\n^\n"
        "A_3.nc:14:1: note: channel 3 is here (T1111 at X-80 Z-1)\n"
        "X-80.\n^\n"
        "check: 3 channels, 4 waits paired, 1 error\n");
  // The same pass 25 mm off the centre (C25.): the end mill keeps 25 mm from the axis, its
  // envelope 21 mm from the drill's.
  CHECK(check3(mill("25.")) == "check: 3 channels, 4 waits paired, 0 errors\n");
  // 5 mm off the centre: 1 mm between the envelopes.
  CHECK_THAT(check3(mill("5.")), Catch::Contains(": 1.0 mm apart, 5 mm required"));
}

TEST_CASE("interference: the timeline carries the conflicts and the page marks both lanes", "[analysis]") {
  const machine twin = load_machine("fanuc-0itd-twin");
  const std::string head = "%\nO1000\nG0 G18 G21 G40 G54 G80 G99\n";
  const std::string face =
      head + "T0101\nG97 S1000 M3\nG0 X64. Z0.\nM100\nG1 X-1.6 F0.15\nG0 X100. Z100.\nM101\nM30\n%\n";
  const std::string drill = head + "T0505\nG0 X0. Z5.\nM100\nG1 Z-25. F0.08\nG0 Z50.\nM101\nM30\n%\n";
  timeline_options o;
  o.keep_blocks = true;
  const timeline t = make_timeline({{"A_1.nc", face}, {"A_2.nc", drill}}, twin, o);
  REQUIRE(t.ok);
  REQUIRE(t.conflicts.size() == 2);
  CHECK(conflict_channel(t, t.conflicts[0]) == 1);
  CHECK(conflict_channel(t, t.conflicts[1]) == 2);
  CHECK_THAT(format_timeline_json(t), Catch::Contains("\"conflicts\":[{\"channel\":1,\"severity\":\"error\","
                                                      "\"file\":\"A_1.nc\",\"line\":8,"));
  const std::string page = timeline_page(t, "t");
  CHECK(page.find("<rect class=\"conflict\" data-channel=\"1\"") != std::string::npos);
  CHECK(page.find("<rect class=\"conflict\" data-channel=\"2\"") != std::string::npos);
  CHECK(page.find("<b>Turrets may meet</b>") != std::string::npos);
  // The picture of the two envelopes: the facing tool's sweep from X64 to X-1.6 (r 32 to -0.8),
  // its tool box 2 mm past it; the lower turret's drill mirrored below the axis.
  REQUIRE(t.meetings.size() == 1);
  const interference_meeting& g = t.meetings[0];
  CHECK(g.channel_a == 1);
  CHECK(g.channel_b == 2);
  CHECK(g.tip_a.r0 == Approx(-0.8));
  CHECK(g.tip_a.r1 == Approx(32));
  CHECK(g.envelope_a[0].r0 == Approx(-2.8));
  CHECK(g.envelope_b[0].r0 == Approx(-60));
  CHECK(g.envelope_b[0].r1 == Approx(2));
  CHECK(g.distance == 0);
  CHECK(page.find("<figure class=\"meeting\"><svg class=\"envelopes\"") != std::string::npos);
  CHECK(page.find("<title>channel 1: r -2.8..92, Z -5..60</title>") != std::string::npos);
  // A sound job: no conflicts, and no key for them in the data.
  const std::string od =
      head + "T0101\nG97 S1000 M3\nG0 X60. Z2.\nM100\nG1 Z-40. F0.15\nG0 X100. Z100.\nM101\nM30\n%\n";
  const timeline sound = make_timeline({{"A_1.nc", od}, {"A_2.nc", drill}}, twin, o);
  CHECK(sound.conflicts.empty());
  CHECK(format_timeline_json(sound).find("conflicts") == std::string::npos);
}

TEST_CASE("interference: a static zone of the spindle, however the waits pair", "[analysis]") {
  // fanuc-0itd-twin with a chuck zone for this job: |r| up to 80 mm, Z -250 to -180.
  const machine twin =
      parse_machine(find_machine("fanuc-0itd-twin", {}).text +
                        "\n[[interference.zone]]\nspindle = \"main\"\nbox = [0.0, 80.0, -250.0, -180.0]\n",
                    "m.toml");
  const std::string head = "%\nO1000\nG0 G18 G21 G40 G54 G80 G99\n";
  // Turning at X60 to Z-172: the tool box reaches 5 mm past the tip towards the chuck, 3 mm from
  // it (the turret body, 90 mm and more from the axis, passes 10 mm outside the chuck's 80).
  const std::string near =
      head + "T0101\nG97 S1000 M3\nG0 X60. Z2.\nM100\nG1 Z-172. F0.2\nG0 X100. Z100.\nM101\nM30\n%\n";
  const std::string idle = head + "T0505\nM100\nM101\nM30\n%\n";
  CHECK(check(twin, near, idle) ==
        "A_1.nc:8:1: error: channel 1 (T0101 at X60 Z-172) comes within 3.0 mm of the main spindle's static "
        "zone "
        "[0, 80, -250, -180] (interference.zone), 5 mm required\n"
        "G1 Z-172. F0.2\n^\n"
        "check: 2 channels, 4 waits paired, 1 error\n");
  const std::string clear =
      head + "T0101\nG97 S1000 M3\nG0 X60. Z2.\nM100\nG1 Z-160. F0.2\nG0 X100. Z100.\nM101\nM30\n%\n";
  CHECK(check(twin, clear, idle) == "check: 2 channels, 4 waits paired, 0 errors\n");
}

TEST_CASE("interference: a work offset that is no G code moves a channel's work to its spindle",
          "[analysis][interference]") {
  // Attack 67 H6: the twin-turret lathe with work offsets `E1` (main) and `E2` (sub). Channel 2
  // stood in E2 and then worked in E1 from a block with no G, M or S: its drill on the main
  // spindle's axis was taken for the sub's, and the meeting with channel 1's facing tool missed.
  // The emulator takes E1 for the offset it is (no "no work offset in force").
  machine m = load_machine("fanuc-0itd-twin");
  m.spindles[0].work_offset = "E1";
  m.spindles[1].work_offset = "E2";
  const std::string one =
      "%\nO1000 (FACE)\nG0 G18 G21 G40 G80 G99\nE1\nT0101\nG50 S2500\nG96 S180 M3\nG0 X64. Z5.\nM100\n"
      "G0 W-5.\nG1 X-1.6 F0.15\nG0 W2.\nG0 X100. Z100.\nM101\nM5\nM30\n%\n";
  const std::string two =
      "%\nO2000 (DRILL)\nG0 G18 G21 G40 G80 G99\nT0505\nG0 E2 X100. Z50.\nM100\nE1\nX0. Z20.\n"
      "Z-25.\nZ50.\nM101\nM30\n%\n";
  CHECK(
      check(m, one, two) ==
      "A_1.nc:11:1: error: channel 1 (T0101 at X-1.6 Z0) may meet channel 2 (T0505 at X0 Z-25, A_2.nc:9) on "
      "the main spindle, between M100 (A_1.nc:9) and M101 (A_1.nc:14) of channel 1: 0.0 mm apart, 5 mm "
      "required; no wait orders the two blocks\nG1 X-1.6 F0.15\n^\n"
      "A_2.nc:9:1: note: channel 2 is here (T0505 at X0 Z-25)\nZ-25.\n^\n"
      "check: 2 channels, 4 waits paired, 1 error\n");
}
