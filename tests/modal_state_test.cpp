// The reading's one modal state (analysis/modal_state.hpp): what each block's G codes leave in
// force per G-code system, and what the block's own codes did, block by block to the letter.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "analysis/modal_state.hpp"
#include "machines/machine_loader.hpp"

using namespace twinpost;

namespace {

// Feeds `lines` to channel 1 of `modes`, one block each, and returns the state after the last.
const channel_modes& feed(modal_states& modes, const std::vector<std::string>& lines) {
  static const std::string file = "A_1.nc";
  std::vector<nc_word> store;
  int line = 0;
  for (const std::string& text : lines) modes.block(nc_block(1, file, ++line, text, store));
  return modes.channel(1);
}

}  // namespace

TEST_CASE("modal state: a system-A lathe's single cycles, G80 and the drilling cycles", "[analysis]") {
  const machine twin = load_machine("fanuc-0itd-twin");  // a header without G90: system A
  modal_states modes(twin);
  const channel_modes& c = modes.channel(1);
  CHECK(c.motion == -1);
  CHECK_FALSE(c.inch);
  feed(modes, {"G0 G18 G21 G40 G54 G80 G99"});
  CHECK(c.motion == 0);
  CHECK(c.plane == 18);
  CHECK(c.feed == feed_kind::per_rev);
  CHECK(c.now.motion);
  CHECK(c.now.work_offset);
  CHECK(c.now.units);
  // G90 is the turning cycle in system A: modal until a motion code; G80 ends drilling cycles
  // only. G91 is no code of system A (an alarm; its increments are U and W): read as system B
  // reads it, and G90 does not end it.
  feed(modes, {"G90 X50. Z-20. F0.2"});
  CHECK(c.turning_cycle);
  CHECK(c.in_cycle());
  CHECK(c.now.cycle);
  CHECK_FALSE(c.incremental);
  feed(modes, {"X46.", "G80"});
  CHECK(c.turning_cycle);
  CHECK_FALSE(c.now.cycle);
  feed(modes, {"G91", "G90 X50. Z-20."});
  CHECK(c.incremental);
  // A drilling cycle ends at G80, and at a code of group 01 (G0-G3, the single cycles).
  feed(modes, {"G0 X0. Z5.", "G83 Z-20. R1. Q5000 F0.1"});
  CHECK(c.hole_cycle);
  CHECK_FALSE(c.turning_cycle);
  feed(modes, {"G80"});
  CHECK_FALSE(c.in_cycle());
  feed(modes, {"G83 Z-20. R1. Q5000 F0.1", "G90 X50. Z-20."});
  CHECK_FALSE(c.hole_cycle);
  CHECK(c.turning_cycle);
  // A block without a G word leaves the modes and did nothing itself.
  feed(modes, {"X44."});
  CHECK(c.turning_cycle);
  CHECK_FALSE(c.now.any);
  // A dwell, a reference return, a repetitive cycle, a coordinate setting (G50 with X Z; G92 is
  // the thread cycle in system A), the feed mode per minute, the inch.
  CHECK(feed(modes, {"G4 U1."}).now.no_move);
  CHECK(feed(modes, {"G28 U0."}).now.reference);
  CHECK(feed(modes, {"G71 U2. R0.5"}).now.once);
  CHECK(feed(modes, {"G50 X100. Z50."}).now.coordinate_setting);
  CHECK_FALSE(feed(modes, {"G92 X30. Z-20. F1.5"}).now.coordinate_setting);
  CHECK(c.turning_cycle);
  CHECK(feed(modes, {"G98"}).feed == feed_kind::per_minute);
  CHECK(feed(modes, {"G20"}).inch);
  CHECK(c.now.units);
  CHECK(feed(modes, {"G65 P9000 A1."}).now.data);
}

TEST_CASE("modal state: G90/G91 in system B, polar interpolation, the machine's work offsets", "[analysis]") {
  const machine integrex = load_machine("integrex-i200st");  // its header gives G90: system B
  modal_states modes(integrex);
  const channel_modes& c = feed(modes, {"G21", "G0 G90 G54 G97 G18", "G91 G1 X-4. F0.15"});
  CHECK(c.incremental);
  CHECK(c.motion == 1);
  CHECK_FALSE(c.turning_cycle);
  CHECK_FALSE(feed(modes, {"G90 G0 X100."}).incremental);
  CHECK(feed(modes, {"G17", "G12.1"}).polar);
  CHECK(c.now.polar);
  CHECK(c.plane == 17);
  CHECK_FALSE(feed(modes, {"G13.1"}).polar);
  CHECK(c.now.polar);
  CHECK(feed(modes, {"G54.1 P2"}).now.work_offset);
  CHECK_FALSE(feed(modes, {"G54.2 P1"}).now.work_offset);
  CHECK(feed(modes, {"G53 X0."}).now.machine);
}
