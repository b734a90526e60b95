// What a channel's blocks command of the spindles (analysis/spindle_state.hpp), read with
// the built-in machines' own codes.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "analysis/spindle_state.hpp"
#include "machines/machine_loader.hpp"

using namespace twinpost;

namespace {

const char* turn_name(spindle_turn t) {
  switch (t) {
    case spindle_turn::unknown: return "?";
    case spindle_turn::stopped: return "stop";
    case spindle_turn::cw: return "cw";
    case spindle_turn::ccw: return "ccw";
    case spindle_turn::held: return "held";
  }
  return "";
}
const char* mode_name(speed_mode m) {
  return m == speed_mode::css ? "css" : m == speed_mode::rpm ? "rpm" : "?";
}

// The changes of each block, one line per block: "spindle:turn,mode,speed,clamp@column".
std::string run(const machine& m, int channel, std::initializer_list<std::string_view> blocks) {
  channel_spindles s(m, channel);
  std::string out;
  for (std::string_view b : blocks) {
    std::string line;
    for (const spindle_change& c : s.apply(split_nc_words(b)))
      line += fmt::format("{}{}:{},{},{:g},{:g}@{}", line.empty() ? "" : " ",
                          m.spindles[static_cast<std::size_t>(c.spindle)].name, turn_name(c.after.turn),
                          mode_name(c.after.mode), c.after.speed, c.after.clamp, c.column);
    out += line + "\n";
  }
  out += fmt::format("current {}\n", m.spindles[static_cast<std::size_t>(s.current())].name);
  return out;
}

}  // namespace

TEST_CASE("spindle state: Fanuc 31i codes, clamp, CSS, rpm and the live and sub spindles", "[analysis]") {
  const machine m = load_machine("fanuc-31i-3path");
  CHECK(run(m, 1,
            {"G50 S2000", "G96 S200 M3", "G0 X50. Z2.", "G97 S1200 M33", "M37", "S300", "M105",
             "G97 S800 M103", "M5"}) ==
        "main:?,?,0,2000@5\n"
        "main:cw,css,200,2000@5\n"
        "\n"
        "live:cw,rpm,1200,0@5\n"
        "live:stop,rpm,1200,0@1\n"
        "live:stop,rpm,300,0@1\n"  // S goes to the last spindle turned: the live one
        "sub:stop,?,0,0@1\n"
        "sub:cw,rpm,800,0@5\n"
        "main:stop,css,200,2000@1\n"
        "current sub\n");
}

TEST_CASE("spindle state: Mazak select codes and the G92 S R clamp per spindle", "[analysis]") {
  const machine m = load_machine("integrex-i200st");
  CHECK(run(m, 2, {"G92 S3000 R1", "G92 S2500 R2", "M902", "G96 S150 M303", "M901", "S100 M204", "G97"}) ==
        "main:?,?,0,3000@5\n"
        "sub:?,?,0,2500@5\n"
        "\n"
        "sub:cw,css,150,2500@5\n"
        "\n"
        "main:ccw,css,100,3000@1\n"
        "main:ccw,rpm,0,3000@1\n"  // G97 without S: the rpm of that moment, unknown here
        "current main\n");
}

TEST_CASE("spindle state: rpm at a diameter, CSS held to the clamp and the spindle's limit", "[analysis]") {
  const machine m = load_machine("fanuc-31i-3path");  // main: max_rpm 4000
  channel_spindles s(m, 1);
  CHECK(s.rpm(50, false) == 0);  // not turning
  s.apply(split_nc_words("G50 S2500"));
  s.apply(split_nc_words("G96 S200 M3"));
  CHECK(s.rpm(50, false) == Approx(200 * 1000 / (M_PI * 50)));  // 1273.24 rpm
  CHECK(s.rpm(20, false) == 2500);                              // 3183 rpm clamped
  CHECK(s.rpm(0, false) == 2500);
  CHECK(s.rpm(2, true) == Approx(200 * 12 / (M_PI * 2)));  // ft/min at 2 in: 381.97 rpm
  s.apply(split_nc_words("G97 S5000"));
  CHECK(s.rpm(50, false) == 2500);  // the clamp holds in rpm mode too
}

TEST_CASE("spindle state: the Integrex main spindle held as the C axis (M200) and let go (M202)",
          "[analysis]") {
  const machine m = load_machine("integrex-i200st");
  CHECK(run(m, 1, {"G97 S800 M203", "M205", "M200", "G10.9 X0", "G97 S3000 M3", "M202"}) ==
        "main:cw,rpm,800,0@5\n"
        "main:stop,rpm,800,0@1\n"
        "main:held,rpm,800,0@1\n"
        "\n"
        "live:cw,rpm,3000,0@5\n"
        "main:stop,rpm,800,0@1\n"
        "current live\n");
}

TEST_CASE(
    "spindle state: the spindle a block selects takes the M-code the spindles share, wherever it stands",
    "[analysis]") {
  // Attack 67 H4: a twin-spindle lathe whose sub answers the main's M3/M4/M5, selected by its
  // work offset. `G55 G97 S500 M4` in one block reversed the main; the same words in two blocks
  // turned the sub.
  machine m = load_machine("fanuc-0itd-twin");
  m.spindles[1].cw = 3;
  m.spindles[1].ccw = 4;
  m.spindles[1].stop = 5;
  const std::string sub_ccw = "sub:ccw,rpm,500,0@";
  CHECK(run(m, 1, {"G55 G97 S500 M4"}) == sub_ccw + "9\ncurrent sub\n");
  CHECK(run(m, 1, {"G55", "G97 S500 M4"}) == "\n" + sub_ccw + "5\ncurrent sub\n");
  // A select code (the Integrex's M902) before or after the shared code in the block: the same.
  machine mz = load_machine("integrex-i200st");
  mz.spindles[1].cw = 203;
  mz.spindles[1].ccw = 204;
  mz.spindles[1].stop = 205;
  CHECK(run(mz, 1, {"S300 M203 M902"}) == "sub:cw,?,300,0@1\ncurrent sub\n");
  CHECK(run(mz, 1, {"S300 M902 M203"}) == "sub:cw,?,300,0@1\ncurrent sub\n");
}

TEST_CASE("spindle state: a work offset of two words selects its spindle", "[analysis]") {
  // Attack 67 H5: the sub's offset `G54.1 P2` (a Fanuc extended work offset) never selected it,
  // and the clamp after it went to the main.
  machine m = load_machine("fanuc-0itd-twin");
  m.spindles[1].work_offset = "G54.1 P2";
  CHECK(run(m, 1, {"G54.1 P2", "G50 S3000", "G54", "G50 S2000"}) ==
        "\nsub:?,?,0,3000@5\n\nmain:?,?,0,2000@5\ncurrent main\n");
}

TEST_CASE("spindle state: a macro call's words are its arguments", "[analysis]") {
  // Attack 68 M4: `G65 P9001 E2.` on a machine whose sub's work offset is E2 was read as
  // selecting the sub; an M3 there is an argument too.
  machine m = load_machine("fanuc-0itd-twin");
  m.spindles[0].work_offset = "E1";
  m.spindles[1].work_offset = "E2";
  CHECK(run(m, 1, {"G65 P9001 E2. M3 S500"}) == "\ncurrent main\n");
  CHECK(run(m, 1, {"E2", "S500"}) == "\nsub:?,?,500,0@1\ncurrent sub\n");  // (the offset alone selects)
}
