// Threading and grooving in a post: each [cycles] form on each built-in (and on variants of
// the Fanuc 0i-TD file for the forms no built-in uses), the cycles compared with the team's
// own expansion of them, and every error message exactly.
#include <catch2/catch.hpp>

#include <cmath>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "machines/builtin_machines.hpp"
#include "machines/machine_loader.hpp"
#include "post_test_jobs.hpp"

using namespace twinpost;

namespace {

const std::string head = "PARTNO THR\nUNITS/MM\nTURRET/1,1\nSPINDL/RPM,800,CLW\nFEDRAT/0.2,MMPR\n";

// An M20x1.5 external thread, 25 mm long (the tool starts at X26 Z5), and a 7 mm wide groove.
const std::string thread_job =
    "RAPID\nGOTO/13,0,5\n"
    "CYCLE/THREAD,PITCH,1.5,DEPTH,0.92,FIRST,0.35,MINCUT,0.05,FINISH,0.05,SPRING,1,"
    "ANGLE,30\nGOTO/9.08,0,-20\nCYCLE/OFF\n";
const std::string groove_job =
    "RAPID\nGOTO/15,0,-25\nCYCLE/GROOVE,DEPTH,3,WIDTH,4,ZSTEP,2.5,RAPTO,1,MMPR,0.05\n"
    "GOTO/12,0,-25\nCYCLE/OFF\n";

// The Fanuc 0i-TD file with its thread form (and name) replaced.
machine variant(const std::string& thread, const std::string& groove = "g75") {
  for (const builtin_machine_file& f : builtin_machine_files()) {
    if (f.name != "fanuc-0itd-twin") continue;
    std::string text(f.toml);
    text.replace(text.find("thread = \"g76\""), 14, "thread = \"" + thread + "\"");
    text.replace(text.find("groove = \"g75\""), 14, "groove = \"" + groove + "\"");
    return parse_machine(text, "variant.toml");
  }
  throw std::runtime_error("no fanuc-0itd-twin");
}

// The first program's blocks after the spindle start, up to the wait before the footer.
std::string body(const machine& m, const std::string& cl, const std::string& tag) {
  const test::posted p = test::post_in_fresh_dir(head + cl + "FINI\n", m, "thread-" + tag);
  if (!p.ok) return p.diagnostics;
  std::istringstream in(p.files.begin()->second);
  std::string line, out;
  bool on = false;
  while (std::getline(in, line)) {
    if (on && (line.starts_with("M100") || line.starts_with("M200") || line.starts_with("M950"))) break;
    if (on) out += line + "\n";
    if (line.starts_with("G97 S800")) on = true;
  }
  return out;
}

std::string errors_of(const machine& m, const std::string& cl, const std::string& tag) {
  const test::posted p =
      test::post_in_fresh_dir(head + cl + "FINI\n", m, "thread-" + tag,
                              [](const diagnostic& d) { return d.level == severity::error; });
  return p.ok ? "(posted)" : p.diagnostics;
}

// The value of `address` in `block`, or NAN.
double word(const std::string& block, char address) {
  std::smatch m;
  const std::regex rx(std::string(1, address) + R"(([-+]?[0-9]*\.?[0-9]*))");
  for (auto it = std::sregex_iterator(block.begin(), block.end(), rx); it != std::sregex_iterator(); ++it)
    if (it->position() == 0 || block[it->position() - 1] == ' ') return std::stod((*it)[1]);
  return NAN;
}

std::vector<std::string> lines_starting(const std::string& text, const std::string& prefix) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);)
    if (l.starts_with(prefix)) out.push_back(l);
  return out;
}

}  // namespace

TEST_CASE("G76 two-block threading and G75 grooving on the Fanuc 0i-TD", "[post][thread]") {
  CHECK(body(load_machine("fanuc-0itd-twin"), thread_job + groove_job, "0i") ==
        ""
        "G0 X26. Z5.\n"
        "G76 P020060 Q50 R0.05\n"
        "G76 X18.16 Z-20. P920 Q350 F1.5\n"
        "G0 X30. Z-25.\n"
        "X26.\n"
        "G75 R0.\n"
        "G75 X18. Z-29. P4000 Q2500 F0.05\n");
}

TEST_CASE("G92 boxes and expanded grooving on the Fanuc 31i", "[post][thread]") {
  CHECK(body(load_machine("fanuc-31i-3path"), thread_job + groove_job, "31i") ==
        ""
        "G0 X26. Z5.\n"
        "G92 X19.3 Z-20. F1.5\n"
        "G0 X26. Z4.916\n"
        "G92 X19.01 Z-20. F1.5\n"
        "G0 X26. Z4.852\n"
        "G92 X18.788 Z-20. F1.5\n"
        "G0 X26. Z4.798\n"
        "G92 X18.6 Z-20. F1.5\n"
        "G0 X26. Z4.75\n"
        "G92 X18.435 Z-20. F1.5\n"
        "G0 X26. Z4.707\n"
        "G92 X18.285 Z-20. F1.5\n"
        "G0 X26. Z4.7\n"
        "G92 X18.26 Z-20. F1.5\n"
        "G0 X26. Z4.671\n"
        "G92 X18.16 Z-20. F1.5\n"
        "G92 X18.16 Z-20. F1.5\n"
        "G0 X26. Z5.\n"
        "X30. Z-25.\n"
        "X26.\n"
        "G1 X18. F0.05\n"
        "G0 X26.\n"
        "Z-27.5\n"
        "G1 X18.\n"
        "G0 X26.\n"
        "Z-29.\n"
        "G1 X18.\n"
        "G0 X26.\n"
        "Z-25.\n");
}

TEST_CASE("G292 boxes on the Integrex", "[post][thread]") {
  machine integrex = load_machine("integrex-i200st");
  integrex.tools.push_back({1, 1, "turn"});  // the head's tool table: a turning tool
  integrex.channels[0].head_index = {};      // the thread only (the B head: post_millturn_test)
  const std::string b = body(integrex, thread_job, "mazak");
  CHECK(b.starts_with(
      "G95\nG0 X26. Y0. Z5.\nG292 X19.3 Z-20. F1.5\nG0 X26. Y0. Z4.916\nG292 X19.01 Z-20. F1.5\n"));
  CHECK(b.ends_with("G292 X18.16 Z-20. F1.5\nG292 X18.16 Z-20. F1.5\nG0 X26. Y0. Z5.\n"));
  CHECK(lines_starting(b, "G292").size() == 9);
}

TEST_CASE("G276 writes P and Q in mm, G32 writes passes, multi-start is cut as shifted starts",
          "[post][thread]") {
  const std::string two_starts =
      "RAPID\nGOTO/13,0,5\nCYCLE/THREAD,LEAD,3,STARTS,2,DEPTH,0.9,PASSES,3\n"
      "GOTO/9.1,0,-15\nCYCLE/OFF\n";
  CHECK(body(variant("g276"), two_starts, "g276") ==
        ""
        "G0 X26. Z5.\n"
        "G276 P010000 Q0. R0.\n"
        "G276 X18.2 Z-15. P0.9 Q0.52 F3.\n"
        "G0 X26. Z6.5\n"
        "G276 P010000 Q0. R0.\n"
        "G276 X18.2 Z-15. P0.9 Q0.52 F3.\n"
        "G0 X26. Z5.\n");
  CHECK(body(variant("g32"), two_starts, "g32") ==
        "G0 X26. Z5.\n"
        "X18.961\nG32 X18.961 Z-15. F3.\nG0 X26.\nZ5.\n"
        "X18.53\nG32 X18.53 Z-15. F3.\nG0 X26.\nZ5.\n"
        "X18.2\nG32 X18.2 Z-15. F3.\nG0 X26.\nZ5.\n"
        "X18.2\nG32 X18.2 Z-15. F3.\nG0 X26.\nZ5.\n"
        "Z6.5\n"
        "X18.961\nG32 X18.961 Z-15. F3.\nG0 X26.\nZ6.5\n"
        "X18.53\nG32 X18.53 Z-15. F3.\nG0 X26.\nZ6.5\n"
        "X18.2\nG32 X18.2 Z-15. F3.\nG0 X26.\nZ6.5\n"
        "X18.2\nG32 X18.2 Z-15. F3.\nG0 X26.\nZ6.5\n"
        "Z5.\n");
}

TEST_CASE("a tapered thread on the lower turret: R as start minus end radius", "[post][thread]") {
  const std::string taper =
      "HEAD/2\nTURRET/2,2\nSPINDL/RPM,600,CLW\nFEDRAT/100,MMPM\nRAPID\nGOTO/-15,0,5\n"
      "CYCLE/THREAD,PITCH,2,DEPTH,1.2,FIRST,0.5,TAPER,-0.5\nGOTO/-9,0,-15\nCYCLE/OFF\n";
  const test::posted p = test::post_in_fresh_dir(head + taper + "FINI\n", variant("g76"), "thread-taper");
  REQUIRE(p.ok);
  // Feed per minute in force: G99 for the cycle, G98 again after it.
  CHECK(p.files.at("THR_2.nc")
            .find("G98\nG0 X30. Z5.\nG99\nG76 P010000 Q0 R0.\nG76 X18. Z-15. R-0.5 P1200 Q500 "
                  "F2.\nG98\n") != std::string::npos);
}

TEST_CASE("THREAD/TURN passes are G32 moves at the lead, and the next feed move writes its F",
          "[post][thread]") {
  CHECK(body(load_machine("fanuc-0itd-twin"),
             "RAPID\nGOTO/13,0,5\nTHREAD/TURN,LEAD,1.5\nRAPID\nGOTO/12.7,0,5\nGOTO/12.7,0,-20\nRAPID\n"
             "GOTO/13,0,-20\nRAPID\nGOTO/13,0,5\nTHREAD/OFF\nGOTO/12,0,4\n",
             "turn") == "G0 X26. Z5.\nX25.4\nG32 Z-20. F1.5\nG0 X26.\nZ5.\nG1 X24. Z4. F0.2\n");
}

TEST_CASE("G76 and G92 cut the passes the G32 expansion writes", "[post][thread]") {
  // The team's model of G76 (Fanuc manual, constant chip area): pass k at Q * sqrt(k), no
  // cut below the minimum, up to P - R; then m finishing passes at P. The G32 expansion of
  // the same CL must cut exactly those depths, and the G92 boxes end where its passes end.
  const std::string g76 = body(variant("g76"), thread_job, "model-76");
  const std::string g32 = body(variant("g32"), thread_job, "model-32");
  const std::string g92 = body(variant("g92"), thread_job, "model-92");
  const auto first = lines_starting(g76, "G76 P"), second = lines_starting(g76, "G76 X");
  REQUIRE(first.size() == 1);
  REQUIRE(second.size() == 1);
  const std::string p1 = first[0].substr(first[0].find(" P") + 2, 6);
  const int finishing = std::stoi(p1.substr(0, 2));
  const double min_cut = word(first[0], 'Q') / 1000, allowance = word(first[0], 'R');
  const double root = word(second[0], 'X') / 2, height = word(second[0], 'P') / 1000,
               first_cut = word(second[0], 'Q') / 1000;
  std::vector<double> want;
  double d = 0;
  for (int k = 1; d < height - allowance - 1e-9; ++k) {
    d = std::min(std::max(first_cut * std::sqrt(double(k)), d + min_cut), height - allowance);
    want.push_back(root + height - d);
  }
  for (int k = 0; k < finishing; ++k) want.push_back(root);
  const auto passes = lines_starting(g32, "G32"), boxes = lines_starting(g92, "G92");
  REQUIRE(passes.size() == want.size());
  REQUIRE(boxes.size() == want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    CHECK(word(passes[i], 'X') / 2 == Approx(want[i]).margin(0.0006));
    CHECK(word(boxes[i], 'X') == word(passes[i], 'X'));
    CHECK(word(boxes[i], 'Z') == word(second[0], 'Z'));
  }
}

TEST_CASE("G75 cuts the plunges the expanded groove writes", "[post][thread]") {
  const std::string g75 = body(variant("g76", "g75"), groove_job, "g75");
  const std::string plunges = body(variant("g76", "expanded"), groove_job, "plunges");
  const auto cycle = lines_starting(g75, "G75 X");
  REQUIRE(cycle.size() == 1);
  // G75 from the start point (X26 Z-25): plunges Q apart toward the cycle's Z, each P deep.
  const double x_bottom = word(cycle[0], 'X'), z_end = word(cycle[0], 'Z'), step = word(cycle[0], 'Q') / 1000;
  const double depth = word(cycle[0], 'P') / 1000;
  std::vector<double> zs;
  for (double z = -25;; z -= step) {
    if (z <= z_end) {
      zs.push_back(z_end);
      break;
    }
    zs.push_back(z);
  }
  const auto feeds = lines_starting(plunges, "G1 X");
  REQUIRE(feeds.size() == zs.size());
  for (const std::string& f : feeds) CHECK(word(f, 'X') == x_bottom);
  CHECK(x_bottom == 18);
  CHECK(26 - 2 * depth == x_bottom);
  CHECK(plunges.find(
            "X26.\nG1 X18. F0.05\nG0 X26.\nZ-27.5\nG1 X18.\nG0 X26.\nZ-29.\nG1 X18.\nG0 X26.\nZ-25.\n") !=
        std::string::npos);
  CHECK(zs == std::vector<double>{-25, -27.5, -29});
}

TEST_CASE("threading and grooving errors name the record", "[post][thread]") {
  const machine fanuc = load_machine("fanuc-0itd-twin");
  machine none = fanuc;
  none.cycles = {};
  CHECK(errors_of(none, thread_job, "none") ==
        "job.cls:8:1: error: channel 1: CYCLE/THREAD is not supported by the post: machine 'fanuc-0itd-twin' "
        "names "
        "no threading cycle ([cycles] thread in its file)\n"
        "CYCLE/THREAD,PITCH,1.5,DEPTH,0.92,FIRST,0.35,MINCUT,0.05,FINISH,0.05,SPRING,1,ANGLE,30\n^\n");
  CHECK(errors_of(none, groove_job, "none-groove")
            .starts_with("job.cls:8:1: error: channel 1: CYCLE/GROOVE is not supported by the post: machine "
                         "'fanuc-0itd-twin' names no grooving cycle ([cycles] groove in its file)\n"));
  CHECK(errors_of(none, "THREAD/TURN,LEAD,1.5\n", "none-turn")
            .starts_with("job.cls:6:1: error: channel 1: THREAD/TURN is not supported by the post: machine "
                         "'fanuc-0itd-twin' names no threading cycle ([cycles] thread in its file)\n"));
  CHECK(errors_of(fanuc, "SPINDL/SMM,120,MAXRPM,2000,CLW\n" + thread_job, "css") ==
        "job.cls:10:1: error: channel 1: CYCLE/THREAD under constant surface speed (G96): threading needs a "
        "constant spindle speed; give SPINDL/RPM before the thread\nGOTO/9.08,0,-20\n^\n");
  CHECK(errors_of(fanuc, "SPINDL/OFF\n" + thread_job, "stopped")
            .starts_with(
                "job.cls:10:1: error: channel 1: CYCLE/THREAD with the spindle stopped: threading needs "
                "the spindle turning (SPINDL/RPM)\n"));
  CHECK(errors_of(fanuc, "CYCLE/THREAD,PITCH,1.5,DEPTH,0.9,PASSES,4,HAND,1\nGOTO/9,0,-20\n", "word") ==
        "job.cls:6:1: error: channel 1: CYCLE/THREAD: HAND is not carried out by the post (it knows LEAD or "
        "PITCH, "
        "STARTS, DEPTH, FIRST or PASSES, MINCUT, FINISH, SPRING, ANGLE, TAPER and CHAMFR)\n"
        "CYCLE/THREAD,PITCH,1.5,DEPTH,0.9,PASSES,4,HAND,1\n^\n");
  CHECK(errors_of(load_machine("fanuc-31i-3path"), "CYCLE/THREAD,PITCH,1.5,DEPTH,0.9,PASSES,4,CHAMFR,1\n",
                  "chamfer")
            .starts_with(
                "job.cls:6:1: error: channel 1: CYCLE/THREAD: CHAMFR is not carried out by the g92 form of "
                "machine 'fanuc-31i-3path' (only G76/G276 write a thread pull-out)\n"));
  CHECK(errors_of(fanuc,
                  "RAPID\nGOTO/13,0,5\nCYCLE/THREAD,PITCH,1.5,DEPTH,0.9,PASSES,4,ANGLE,20\nGOTO/9,0,-20\n",
                  "angle")
            .starts_with(
                "job.cls:9:1: error: channel 1: CYCLE/THREAD: ANGLE 20 gives a tool angle of 40 degrees; the "
                "G76 P word takes 0, 29, 30, 55, 60 or 80\n"));
  CHECK(errors_of(fanuc, "RAPID\nGOTO/9.5,0,5\nCYCLE/THREAD,PITCH,1.5,DEPTH,0.9,PASSES,4\nGOTO/9,0,-20\n",
                  "inside")
            .starts_with(
                "job.cls:9:1: error: channel 1: CYCLE/THREAD: the start X 9.5 lies inside the thread (crest "
                "X 9.9): start the cycle clear of the thread\n"));
  CHECK(errors_of(fanuc, "RAPID\nGOTO/13,0,5\nCYCLE/THREAD,PITCH,1.5,DEPTH,0.9\nGOTO/9,0,-20\n", "first")
            .starts_with(
                "job.cls:9:1: error: channel 1: CYCLE/THREAD: it needs the first cut (FIRST) or the number "
                "of passes (PASSES)\n"));
  CHECK(errors_of(fanuc, "CYCLE/GROOVE,DEPTH,3,MMPR,0.05\nGOTO/12,0,-25\n", "rapto")
            .starts_with(
                "job.cls:7:1: error: channel 1: CYCLE/GROOVE needs RAPTO above 0: the plunges start that "
                "far above the surface\n"));
  CHECK(errors_of(fanuc, "CYCLE/GROOVE,DEPTH,3,STEP,1,RAPTO,1\nGOTO/12,0,-25\n", "peck")
            .starts_with(
                "job.cls:6:1: error: channel 1: CYCLE/GROOVE: STEP is not carried out by the post (it knows "
                "DEPTH or FEDTO, WIDTH, ZSTEP, RAPTO and MMPR or IPR)\n"));
  CHECK(errors_of(fanuc, "THREAD/TURN,LEAD,3,STARTS,2\n", "starts")
            .starts_with(
                "job.cls:6:1: error: channel 1: THREAD/TURN with STARTS 2: the CL passes cut one helix; post "
                "each start with CYCLE/THREAD (shifted starts) instead\n"));
  CHECK(errors_of(fanuc, "THREAD/FACE,LEAD,2\n", "face") ==
        "job.cls:6:8: error: THREAD/FACE,LEAD,2 is not supported by the post: it posts THREAD/TURN (with "
        "LEAD or "
        "PITCH) and THREAD/OFF\nTHREAD/FACE,LEAD,2\n       ^\n");
  CHECK(errors_of(fanuc, "THREAD/TURN\n", "nolead")
            .starts_with("job.cls:6:8: error: THREAD/TURN needs the lead (LEAD,l or PITCH,p)\n"));
  CHECK(
      errors_of(fanuc, "THREAD/TURN,LEAD,1.5\nCIRCLE/0,0,0,0,1,0,5\nGOTO/5,0,0\n", "arc")
          .starts_with("job.cls:8:1: error: channel 1: an arc while THREAD/TURN is on: a threading pass is a "
                       "straight G32 move\n"));
}

TEST_CASE("a [cycles] form the loader does not know is an error at its key", "[post][thread]") {
  std::string text;
  for (const builtin_machine_file& f : builtin_machine_files())
    if (f.name == "fanuc-0itd-twin") text = f.toml;
  REQUIRE(text.find("thread = \"") != std::string::npos);
  const std::size_t at = text.find("thread = \"");
  text.replace(at, text.find('\n', at) - at, "thread = \"g33\"");
  try {
    parse_machine(text, "m.toml");
    FAIL("loaded");
  } catch (const std::exception& e) {
    CHECK(std::string(e.what()).find(
              "cycles.thread must be one of \"g76\", \"g276\", \"g92\", \"g292\", \"g32\", not \"g33\"") !=
          std::string::npos);
  }
}
