// What a G code makes of its block's axis words (analysis/nc_codes.hpp), per G-code system and
// from the machine file's own cycle codes; and, through `check`, the rules that read it: a
// system-A lathe's G92 threading and G90 turning cycles are cuts to the spindle rules and
// sweeps to the interference rule (they were a coordinate setting and a rapid), a macro call's
// arguments no cut. Messages asserted to the letter.
#include <catch2/catch.hpp>

#include <string>

#include "analysis/nc_codes.hpp"
#include "analysis/shared_resources.hpp"
#include "check/sync_report.hpp"
#include "machines/machine_loader.hpp"

using namespace twinpost;

namespace {

std::string check(const machine& m, const std::string& one, const std::string& two) {
  return format_sync_text(check_nc_resources({{"A_1.nc", one}, {"A_2.nc", two}}, m));
}

const std::string head = "%\nO1000\nG0 G18 G21 G40 G54 G80 G99\n";

}  // namespace

TEST_CASE("nc codes: what a G code makes of its block's axis words, per G-code system", "[analysis]") {
  const machine twin = load_machine("fanuc-0itd-twin");  // a header without G90: system A
  const nc_codes a(twin, twin.channels[0]);
  CHECK(a.system() == gcode_system::a);
  CHECK(a.role(1) == axis_words::motion);
  CHECK(a.role(90) == axis_words::turning_cycle);
  CHECK(a.role(92) == axis_words::turning_cycle);
  CHECK(a.threads(92));
  CHECK_FALSE(a.threads(90));
  CHECK(a.role(71) == axis_words::repetitive_cycle);
  CHECK(a.role(76) == axis_words::repetitive_cycle);  // the machine's thread = "g76"
  CHECK(a.threads(76));
  CHECK(a.role(32) == axis_words::feed_move);
  CHECK(a.role(83) == axis_words::hole_cycle);
  CHECK(a.role(20) == axis_words::modal);  // the unit, in systems A and B
  CHECK(a.role(50) == axis_words::none);
  CHECK(a.role(65) == axis_words::none);
  CHECK(a.role(10.9) == axis_words::none);
  CHECK(a.role(28) == axis_words::reference);
  CHECK(a.role(29) == axis_words::reference);
  CHECK(a.role(53) == axis_words::machine);
  CHECK(a.role(54) == axis_words::modal);
  CHECK(a.role(54.1) == axis_words::modal);
  // The Integrex's header gives G90: system B. G92 sets coordinates (or, with S, clamps);
  // its box thread is G292 (thread = "g292"), a single cycle.
  const machine integrex = load_machine("integrex-i200st");
  const nc_codes b(integrex, integrex.channels[1]);
  CHECK(b.system() == gcode_system::b);
  CHECK(b.role(90) == axis_words::modal);
  CHECK(b.role(92) == axis_words::none);
  CHECK(b.role(78) == axis_words::turning_cycle);
  CHECK(b.role(292) == axis_words::turning_cycle);
  CHECK(b.threads(292));
  // A machining centre: G73, G74, G76 are drilling cycles, G92 a setting, G70-G76 no lathe's.
  const machine mill = load_machine("rotary-4axis");
  const nc_codes m(mill, mill.channels[0]);
  CHECK(m.system() == gcode_system::mill);
  CHECK(m.role(76) == axis_words::hole_cycle);
  CHECK_FALSE(m.threads(76));
  CHECK(m.role(71) == axis_words::modal);
  CHECK(m.role(92) == axis_words::none);
  CHECK(m.role(68.2) == axis_words::none);
  CHECK(m.role(84.2) == axis_words::hole_cycle);
  CHECK(m.role(43.4) == axis_words::modal);
}

TEST_CASE("nc codes: a system-A lathe's cycles cut, a macro call's arguments do not", "[analysis]") {
  const machine twin = load_machine("fanuc-0itd-twin");
  const std::string idle = head + "T0505\nG0 X100. Z5.\nM100\nM101\nM30\n%\n";
  // Path 1 cuts with no spindle started: the spindle rules name the cycle's block.
  auto unstarted = [&](const std::string& block) {
    return check(twin, head + "T0101\nG0 X20. Z5.\nM100\n" + block + "\nG0 X100. Z100.\nM101\nM30\n%\n",
                 idle);
  };
  CHECK(
      unstarted("G92 X14. Z-25. F1.5") ==
      "A_1.nc:7:1: error: channel 1 cuts with feed per revolution (G99) on the main spindle, but no channel "
      "is known to have started it before this block (a start in another channel counts only when a wait "
      "orders it before)\n"
      "G92 X14. Z-25. F1.5\n^\n"
      "check: 2 channels, 4 waits paired, 1 error\n");
  CHECK(
      unstarted("G90 X14. Z-25. F0.2") ==
      "A_1.nc:7:1: error: channel 1 cuts with feed per revolution (G99) on the main spindle, but no channel "
      "is known to have started it before this block (a start in another channel counts only when a wait "
      "orders it before)\n"
      "G90 X14. Z-25. F0.2\n^\n"
      "check: 2 channels, 4 waits paired, 1 error\n");
  // After a G1 the arguments of a macro call are no cut.
  CHECK(check(twin,
              head + "T0101\nG97 S800 M3\nG1 X20. Z5. F0.2\nM5\nM100\nG65 P9100 X14. Z-25.\nM101\nM30\n%\n",
              idle) ==
        "A_1.nc:9:1: warning: G65 P9100 calls a macro the checker does not read: waits in it are not "
        "checked\n"
        "G65 P9100 X14. Z-25.\n^\n"
        "check: 2 channels, 4 waits paired, 0 errors, 1 warning\n");
  // The threading cycle down to X4 at Z-25 while path 2 drills the centre to Z-25: the
  // interference rule sweeps the cycle's box (it was no move: no finding).
  const std::string drill = head + "T0505\nG0 X0. Z5.\nM100\nG1 Z-25. F0.08\nG0 Z50.\nM101\nM30\n%\n";
  CHECK(
      check(
          twin,
          head + "T0101\nG97 S1000 M3\nG0 X20. Z5.\nM100\nG92 X4. Z-25. F1.5\nG0 X100. Z100.\nM101\nM30\n%\n",
          drill) ==
      "A_1.nc:8:1: error: channel 1 (T0101 at X4 Z-25) may meet channel 2 (T0505 at X0 Z-25, A_2.nc:7) on "
      "the main spindle, between M100 (A_1.nc:7) and M101 (A_1.nc:10) of channel 1: 0.0 mm apart, 5 mm "
      "required; no wait orders the two blocks\n"
      "G92 X4. Z-25. F1.5\n^\n"
      "A_2.nc:7:1: note: channel 2 is here (T0505 at X0 Z-25)\n"
      "G1 Z-25. F0.08\n^\n"
      "check: 2 channels, 4 waits paired, 1 error\n");
  // The cycle returns to its start: from there a rapid to X100 is clear of the drill (before,
  // the tip was left at the cycle's end point).
  CHECK(check(twin,
              head + "T0101\nG97 S1000 M3\nG0 X60. Z5.\nG92 X40. Z-25. F1.5\nM100\nG0 X100.\nM101\nM30\n%\n",
              drill) == "check: 2 channels, 4 waits paired, 0 errors\n");
}

TEST_CASE("nc codes: a lathe cycle's next passes, and codes whose words are limits or a frame",
          "[analysis]") {
  // Attack 63 M6: `X28.7` after `G92 X29.2 Z-20. F1.5` is another pass of the thread; after an
  // M5 the spindle rules took it for no cut, and the interference rule swept it to the cycle's
  // start Z.
  const machine twin = load_machine("fanuc-0itd-twin");
  const std::string idle = head + "T0505\nG0 X200. Z100.\nM101\nM30\n%\n";
  CHECK(
      check(twin,
            head + "T0303\nG97 S800 M3\nG0 X32. Z5.\nG92 X29.2 Z-20. F1.5\nX28.7\nM5\nX28.4\nG0 "
                   "X100.\nM101\nM30\n%\n",
            idle) ==
      "A_1.nc:10:1: error: channel 1 cuts with feed per revolution (G99) on the main spindle, but channel 1 "
      "stops it at A_1.nc:9 (M5) and no start is known to come after that\n"
      "X28.4\n^\n"
      "check: 2 channels, 2 waits paired, 1 error\n");
  const std::string drill = head + "T0505\nG0 X0. Z5.\nM100\nG1 Z-30. F0.08\nG0 Z50.\nM101\nM30\n%\n";
  CHECK_THAT(
      check(twin,
            head + "T0101\nG96 S180 M3\nG0 X64. Z2.\nM100\nG90 X58. Z-40. F0.25\nX4.\nG0 X100. "
                   "Z100.\nM101\nM30\n%\n",
            drill),
      Catch::StartsWith("A_1.nc:9:1: error: channel 1 (T0101 at X4 Z-40) may meet channel 2 (T0505 at X0 "
                        "Z-30, A_2.nc:7) on the main spindle"));
  // Attack 63 M5: a stored stroke check's limits (G22 X Z I K) and a coordinate rotation's
  // centre (G68.1) are no move: path 2's tool stays at X200, far from path 1's facing cut.
  const std::string face =
      head + "T0101\nG96 S180 M3\nG0 X64. Z5.\nM100\nG0 W-5.\nG1 X-1.6 F0.15\nG0 X100. Z100.\nM101\nM30\n%\n";
  for (const char* block : {"G22 X0. Z-10. I300. K150.", "G68.1 X0. Z-10. R30."})
    CHECK(check(twin, face,
                head + "T0505\nG0 X200. Z100.\nM100\n" + block + "\nG0 X200. Z100.\nM101\nM30\n%\n") ==
          "check: 2 channels, 4 waits paired, 0 errors\n");
}
