// NX helical ramps (issue 24 item 3): CIRCLE/...,TIMES,n followed by a GOTO at another depth
// along the circle's axis is a helix of n turns, written as n helical G2/G3 blocks. The
// written words are read back and the tool tip is followed along each block as the control
// moves it (the plane's arc about I/J/K, the axis word reached at a constant pitch) and
// compared with the CL's helix at 72 points a turn.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "file_test_support.hpp"
#include "kinematics/forward.hpp"
#include "machines/machine_loader.hpp"
#include "post_test_jobs.hpp"
#include "support/diagnostics.hpp"

using namespace twinpost;

namespace {

struct p3 {
  double x = 0, y = 0, z = 0;
};

// The CL: a ramp at (cx, cy) of radius 5 from `top` down to `bottom` in `turns` turns, about
// the axis `axis` ("0,0,1" and the like); NX's CIRCLE: centre, axis, radius, tolerances,
// the tool's diameter and corner radius, then TIMES.
std::string helix_job(const std::string& axis, const p3& start, const p3& centre, const p3& end, int turns) {
  std::ostringstream cl;
  cl << "TOOL PATH/HELIX,TOOL,MILL-10\nTLDATA/MILL,10.0000,0.0000,75.0000,0.0000,0.0000\nLOAD/TOOL,2\n"
     << "SPINDL/RPM,3000,CLW\nRAPID\nGOTO/" << start.x << "," << start.y << "," << start.z + 8
     << ",0,0,1\nRAPID\nGOTO/" << start.x << "," << start.y << "," << start.z << "\nFEDRAT/MMPM,400\n"
     << "CIRCLE/" << centre.x << "," << centre.y << "," << centre.z << "," << axis
     << ",5.0000,0.0600,0.5000,10.0000,0.0000,TIMES," << turns << "\nGOTO/" << end.x << "," << end.y << ","
     << end.z << "\nEND-OF-PATH\n";
  return cl.str();
}

// Every G2/G3 block after the tool call, with the position it starts from (X Y Z modal).
struct nc_arc {
  p3 from, to, offset;  // offset: I J K, from the start to the centre
  bool cw = false;
  std::string text;
};

std::vector<nc_arc> arcs_of(const std::string& program) {
  std::istringstream in(program);
  std::string line;
  p3 at;
  std::vector<nc_arc> out;
  int motion = 0;
  while (std::getline(in, line)) {
    if (line.find(" M6") != std::string::npos) at = {};
    std::map<char, double> w;
    std::istringstream words(line);
    std::string word;
    while (words >> word) {
      if (word.size() < 2 || word[0] == '(' || word[0] == ';') break;
      w[word[0]] = std::stod(word.substr(1));
    }
    if (w.count('G')) {
      // the last G of the motion group on the line
      std::istringstream again(line);
      while (again >> word)
        if (word == "G0" || word == "G1" || word == "G2" || word == "G3") motion = word[1] - '0';
    }
    p3 to = at;
    if (w.count('X')) to.x = w['X'];
    if (w.count('Y')) to.y = w['Y'];
    if (w.count('Z')) to.z = w['Z'];
    if ((motion == 2 || motion == 3) && (w.count('I') || w.count('J') || w.count('K')))
      out.push_back({at, to, {w['I'], w['J'], w['K']}, motion == 2, line});
    at = to;
  }
  return out;
}

// The largest distance between the control's path through `arcs` (72 points a block) and the
// CL helix about `axis` (a unit vector along X, Y or Z) through `start` with centre `centre`,
// clockwise about the axis (NX), reaching `end` after `turns` full turns and, when `end` is
// elsewhere on the circle, the part turn on to it: one pitch over the whole sweep.
double worst_distance(const std::vector<nc_arc>& arcs, char axis, const p3& start, const p3& centre,
                      const p3& end, int turns) {
  // Plane coordinates (u, v) with axis = u x v, and the axis coordinate w.
  auto u = [&](const p3& p) { return axis == 'Z' ? p.x : axis == 'Y' ? p.z : p.y; };
  auto v = [&](const p3& p) { return axis == 'Z' ? p.y : axis == 'Y' ? p.x : p.z; };
  auto w = [&](const p3& p) { return axis == 'Z' ? p.z : axis == 'Y' ? p.y : p.x; };
  const double two_pi = 2 * std::numbers::pi;
  const double r = std::hypot(u(start) - u(centre), v(start) - v(centre));
  const double a0 = std::atan2(v(start) - v(centre), u(start) - u(centre));
  // The CL's sweep, clockwise: n turns and the clockwise angle from the start to the end.
  double part = a0 - std::atan2(v(end) - v(centre), u(end) - u(centre));
  while (part < -1e-12) part += two_pi;
  while (part >= two_pi - 1e-12) part -= two_pi;
  const double sweep = two_pi * turns + part;
  double worst = 0, done = 0;  // done: the CL angle the blocks before this one swept
  for (const nc_arc& a : arcs) {
    const p3 c{a.from.x + a.offset.x, a.from.y + a.offset.y, a.from.z + a.offset.z};
    const double rn = std::hypot(u(a.from) - u(c), v(a.from) - v(c));
    const double s0 = std::atan2(v(a.from) - v(c), u(a.from) - u(c));
    // The block's own sweep in its sense: a full turn when it ends where it starts in the plane.
    double block = (a.cw ? 1 : -1) * (s0 - std::atan2(v(a.to) - v(c), u(a.to) - u(c)));
    while (block <= 1e-9) block += two_pi;
    while (block > two_pi + 1e-9) block -= two_pi;
    for (int i = 0; i <= 72; ++i) {
      const double t = i / 72.0;
      // The control: the block's arc in its sense, the axis word reached linearly with the angle.
      const double ang = s0 + (a.cw ? -1 : 1) * block * t;
      const double nu = u(c) + rn * std::cos(ang), nv = v(c) + rn * std::sin(ang);
      const double nw = w(a.from) + (w(a.to) - w(a.from)) * t;
      // The CL helix at the same total angle: clockwise about the axis.
      const double phi = done + block * t;
      const double cu = u(centre) + r * std::cos(a0 - phi), cv = v(centre) + r * std::sin(a0 - phi);
      const double cw = w(start) + (w(end) - w(start)) * phi / sweep;
      worst =
          std::max(worst, std::sqrt((nu - cu) * (nu - cu) + (nv - cv) * (nv - cv) + (nw - cw) * (nw - cw)));
    }
    done += block;
  }
  // Every block together goes the CL's whole way round.
  return std::max(worst, std::abs(done - sweep) * r);
}

// LinuxCNC's rs274 as an independent reader of a G17 program (optional: empty when rs274 is
// not installed): the motion blocks of `program` (the length offset and the rotary words left
// out) run through `rs274 -g`, and each ARC_FEED of its canonical output turned back into an
// arc from the point the previous move ended at.
std::optional<std::vector<nc_arc>> rs274_arcs(const std::string& program, const std::string& dir) {
  if (std::system("command -v rs274 >/dev/null 2>&1") != 0) return std::nullopt;
  std::istringstream in(program);
  std::string line, kept = "G17 G21 G90\n";
  bool on = false;
  while (std::getline(in, line)) {
    on = on || line.find(" M6") != std::string::npos;
    if (!on || line.empty() || !(line[0] == 'G' || line[0] == 'X' || line[0] == 'Y' || line[0] == 'Z'))
      continue;
    if (line.starts_with("G91") || line.starts_with("G90") || line.starts_with("G49")) continue;
    std::istringstream words(line);
    std::string word;
    while (words >> word)
      if (word != "G43" && word != "G43.4" && word[0] != 'H' && word[0] != 'A' && word[0] != 'B' &&
          word[0] != 'C')
        kept += word + ' ';
    kept += '\n';
  }
  kept += "M2\n";
  const std::string ngc = dir + "/helix.ngc", canon = dir + "/helix.canon";
  std::ofstream(ngc) << kept;
  if (std::system(("rs274 -g " + ngc + " > " + canon + " 2>&1 < /dev/null").c_str()) != 0)
    return std::nullopt;
  std::ifstream out(canon);
  std::vector<nc_arc> arcs;
  p3 at;
  while (std::getline(out, line)) {
    const auto open = line.find('(');
    if (open == std::string::npos) continue;
    std::vector<double> v;
    std::istringstream args(line.substr(open + 1));
    for (std::string a; std::getline(args, a, ',');) v.push_back(std::strtod(a.c_str(), nullptr));
    if (line.find("STRAIGHT_") != std::string::npos && v.size() >= 3) {
      at = {v[0], v[1], v[2]};
    } else if (line.find("ARC_FEED") != std::string::npos && v.size() >= 6) {
      // first end, second end, first centre, second centre, rotation (-1: one turn clockwise), axis end
      const p3 to{v[0], v[1], v[5]};
      arcs.push_back({at, to, {v[2] - at.x, v[3] - at.y, 0}, v[4] < 0, line});
      CHECK(std::abs(v[4]) == 1);  // one turn a block
      at = to;
    }
  }
  return arcs;
}

test::posted post(const std::string& cl, const std::string& machine, const std::string& tag) {
  return test::post_in_fresh_dir(cl, load_machine(machine), "nxhelix-" + tag);
}

}  // namespace

TEST_CASE("NX helix in XY: one helical G2 a turn, the tip on the CL's helix", "[post][arc][nx]") {
  // Down from Z2 to Z-6 in 4 turns about +Z (NX: clockwise about the axis, G2), radius 5.
  const p3 start{30, 20, 2}, centre{25, 20, -6}, end{30, 20, -6};
  const std::string cl = helix_job("0,0,1", start, centre, end, 4);
  for (const char* machine : {"rotary-4axis", "trunnion-5axis", "head-head-5axis"}) {
    INFO(machine);
    const test::posted p = post(cl, machine, machine);
    REQUIRE(p.ok);
    const std::vector<nc_arc> arcs = arcs_of(p.files.begin()->second);
    REQUIRE(arcs.size() == 4);
    CHECK(arcs[0].text == "G2 X30. Y20. Z0. I-5. J0. F400.");
    CHECK(arcs[1].text == "G2 X30. Y20. Z-2. I-5. J0.");
    CHECK(arcs[2].text == "G2 X30. Y20. Z-4. I-5. J0.");
    CHECK(arcs[3].text == "G2 X30. Y20. Z-6. I-5. J0.");
    CHECK(worst_distance(arcs, 'Z', start, centre, end, 4) < 1e-9);
    // The same blocks as LinuxCNC reads them, where rs274 is installed.
    const std::string dir = test::fresh_temp_dir(std::string("nxhelix-rs274-") + machine);
    if (const auto read = rs274_arcs(p.files.begin()->second, dir)) {
      REQUIRE(read->size() == 4);
      CHECK(worst_distance(*read, 'Z', start, centre, end, 4) < 1e-6);
    } else {
      WARN("rs274 not installed: the helix is not read by LinuxCNC");
    }
    std::filesystem::remove_all(dir);
  }
}

TEST_CASE("NX helix in YZ and ZX: the axis word is X or Y", "[post][arc][nx]") {
  // About +X (G19): from X8 to X2 in 3 turns; about +Y (G18): from Y8 to Y-1 in 3 turns.
  {
    const p3 start{8, 10, 5}, centre{2, 10, 0}, end{2, 10, 5};
    const test::posted p = post(helix_job("1,0,0", start, centre, end, 3), "rotary-4axis", "yz");
    REQUIRE(p.ok);
    const std::vector<nc_arc> arcs = arcs_of(p.files.begin()->second);
    REQUIRE(arcs.size() == 3);
    CHECK(arcs[0].text == "G19 G2 X6. Y10. Z5. J0. K-5. F400.");
    CHECK(arcs[2].text == "G2 X2. Y10. Z5. J0. K-5.");
    CHECK(worst_distance(arcs, 'X', start, centre, end, 3) < 1e-9);
  }
  {
    const p3 start{10, 8, 5}, centre{10, -1, 0}, end{10, -1, 5};
    const test::posted p = post(helix_job("0,1,0", start, centre, end, 3), "trunnion-5axis", "zx");
    REQUIRE(p.ok);
    const std::vector<nc_arc> arcs = arcs_of(p.files.begin()->second);
    REQUIRE(arcs.size() == 3);
    CHECK(arcs[0].text == "G18 G2 X10. Y5. Z5. I0. K-5. F400.");
    CHECK(worst_distance(arcs, 'Y', start, centre, end, 3) < 1e-9);
  }
}

TEST_CASE("TIMES with the GOTO elsewhere on the circle: the turns, then the part turn, at one pitch",
          "[post][arc][nx]") {
  // A helical entry: two turns down about +Z and three quarters more (clockwise from +X to +Y),
  // 8 mm in 990 degrees: 2.909 mm a turn, 6.061 mm after two.
  const p3 start{30, 20, 2}, centre{25, 20, -6}, end{25, 25, -6};
  const std::string cl = helix_job("0,0,1", start, centre, end, 2);
  for (const char* machine : {"rotary-4axis", "head-head-5axis"}) {
    INFO(machine);
    const test::posted p = post(cl, machine, std::string("part-") + machine);
    REQUIRE(p.ok);
    const std::vector<nc_arc> arcs = arcs_of(p.files.begin()->second);
    REQUIRE(arcs.size() == 3);
    CHECK(arcs[0].text == "G2 X30. Y20. Z-0.909 I-5. J0. F400.");
    CHECK(arcs[1].text == "G2 X30. Y20. Z-3.818 I-5. J0.");
    CHECK(arcs[2].text == "G2 X25. Y25. Z-6. I-5. J0.");
    // Against the CL's helix; 0.0005 mm: the written axis words keep three decimals.
    CHECK(worst_distance(arcs, 'Z', start, centre, end, 2) < 5e-4);
    const std::string dir = test::fresh_temp_dir(std::string("nxhelix-part-rs274-") + machine);
    if (const auto read = rs274_arcs(p.files.begin()->second, dir)) {
      REQUIRE(read->size() == 3);
      CHECK(worst_distance(*read, 'Z', start, centre, end, 2) < 5e-4);
    } else {
      WARN("rs274 not installed: the helix is not read by LinuxCNC");
    }
    std::filesystem::remove_all(dir);
  }
  // An end within print rounding of the start is the start (review 45): no flat full circle at
  // the bottom, no extra turn; two turns at 4 mm.
  for (const double y : {19.9996, 20.0004}) {
    INFO(y);
    const test::posted p = post(helix_job("0,0,1", start, centre, {30, y, -6}, 2), "rotary-4axis", "near");
    REQUIRE(p.ok);
    const std::vector<nc_arc> arcs = arcs_of(p.files.begin()->second);
    REQUIRE(arcs.size() == 2);
    CHECK(arcs[0].text == "G2 X30. Y20. Z-2. I-5. J0. F400.");
    CHECK(arcs[1].text == "G2 X30. Y20. Z-6. I-5. J0.");
  }
  // Counter-clockwise about +X (G19, G3): one turn and a half from Y15 round to Y5, X down 6.
  const p3 s2{8, 15, 0}, c2{2, 10, 0}, e2{2, 5, 0};
  std::string ccw = helix_job("1,0,0", s2, c2, e2, 1);
  ccw.replace(ccw.find(",TIMES,"), 7, ",CCLW,TIMES,");
  const test::posted p = post(ccw, "rotary-4axis", "part-yz");
  REQUIRE(p.ok);
  const std::vector<nc_arc> arcs = arcs_of(p.files.begin()->second);
  REQUIRE(arcs.size() == 2);
  CHECK(arcs[0].text == "G19 G3 X4. Y15. Z0. J-5. K0. F400.");
  CHECK(arcs[1].text == "G3 X2. Y5. Z0. J-5. K0.");
}

TEST_CASE("TIMES: an end off the circle is refused, the same depth stays full circles", "[post][arc][nx]") {
  // An end off the circle is no arc at all, with or without TIMES.
  for (const int turns : {0, 2}) {
    std::string job = helix_job("0,0,1", {30, 20, 2}, {25, 20, -6}, {29, 20, -6}, turns);
    if (turns == 0) job.replace(job.find(",TIMES,0"), 8, "");  // a plain arc
    const test::posted wide = post(job, "rotary-4axis", "wide" + std::to_string(turns));
    CHECK_FALSE(wide.ok);
    CHECK(
        wide.diagnostics ==
        "job.cls:11:1: error: channel 1: the arc ends 4 mm from its centre (25, 20, -6) and starts 5 mm from "
        "it: no circle about that centre goes through both\nGOTO/29,20,-6\n^\n");
  }
  const test::posted flat =
      post(helix_job("0,0,1", {30, 20, 2}, {25, 20, 2}, {30, 20, 2}, 2), "rotary-4axis", "flat");
  REQUIRE(flat.ok);
  const std::vector<nc_arc> arcs = arcs_of(flat.files.begin()->second);
  REQUIRE(arcs.size() == 2);
  CHECK(arcs[0].text == "G2 X30. Y20. I-5. J0. F400.");
  CHECK(arcs[1].text == "G2 X30. Y20. I-5. J0.");
}

TEST_CASE("a helix in polar interpolation is refused", "[post][arc][nx]") {
  // The Integrex mills the face with the spindle held as C in polar interpolation (G12.1).
  const test::posted p =
      post(helix_job("0,0,1", {30, 20, 2}, {25, 20, -6}, {30, 20, -6}, 4), "integrex-i200st", "polar");
  CHECK_FALSE(p.ok);
  CHECK(p.diagnostics.find(
            "job.cls:11:1: error: channel 1: CIRCLE TIMES 4: a helix in polar interpolation "
            "(G12.1) is not written: helical interpolation in that mode is not verified; give the "
            "ramp as GOTO points\nGOTO/30,20,-6\n^\n") != std::string::npos);
}

TEST_CASE(
    "the C/A gantry's helical entry (samples/nx-ca-head): on the CL's helix through the forward transform",
    "[post][arc][nx]") {
  // POCKET_HELIX: from (128, 60, 1) about (120, 60) clockwise, TIMES,2, to (120, 68, -5). The
  // MCS is the work offset's origin (program.cl_frame = "mcs", the default): the CL's numbers go out.
  const machine m = load_machine(std::string(TWINPOST_SOURCE_DIR) + "/samples/nx-ca-head/gantry-ca.toml");
  const test::posted p = test::post_in_fresh_dir(
      test::read_file(std::string(TWINPOST_SOURCE_DIR) + "/samples/nx-ca-head/job.cls"), m, "nxhelix-ca");
  REQUIRE(p.ok);
  const std::string& nc = p.files.begin()->second;
  const std::vector<nc_arc> arcs = arcs_of(nc);
  REQUIRE(arcs.size() == 3);
  CHECK(arcs[2].text == "G2 X120. Y68. Z-5. I-8. J0.");
  // The heads stand at C0 A0 for the tool: the tip is where the forward transform puts it for the
  // written X Y Z with the table's 150 mm tool.
  CHECK(nc.find("G0 G43 H1 X128. Y60. Z50. C0. A0.\nZ1.\nG2 ") != std::string::npos);
  const kinematic_chain& c = *m.chain(1);
  for (const nc_arc& a : arcs) {
    const vec3 tip = kin::forward(c, {{a.to.x, a.to.y, a.to.z}, {0, 0}}, 150).tip;
    CHECK(std::abs(tip.x - a.to.x) + std::abs(tip.y - a.to.y) + std::abs(tip.z - a.to.z) < 1e-9);
  }
  CHECK(worst_distance(arcs, 'Z', {128, 60, 1}, {120, 60, -5}, {120, 68, -5}, 2) < 5e-4);
}

TEST_CASE("arcs as the control reads their words: a tiny arc, a helix ending by its start, R from the points",
          "[post][arc]") {
  // Attack 45. A CIRCLE whose GOTO is 0.0004 mm round from its start: the same words, which a
  // control runs as a full 100 mm circle. The tool is there within a unit: no block.
  const std::string head =
      "PARTNO TINY\nLOADTL/1\nSPINDL/RPM,3000,CLW\nFEDRAT/MMPM,600\nRAPID\nGOTO/80,0,5,0,0,1\nGOTO/80,0,-5\n";
  const test::posted tiny = post(head + "CIRCLE/30,0,-5,0,0,1,50\nGOTO/80,0.0004,-5\nGOTO/80,10,-5\nFINI\n",
                                 "rotary-4axis", "tiny");
  INFO(tiny.diagnostics);
  REQUIRE(tiny.ok);
  CHECK(tiny.files.at("TINY.nc").find("G1 Z-5. F600.\nY10.\n") != std::string::npos);
  // A helix whose GOTO is 0.0001 mm from the start, the two either side of a rounding step: the
  // last turn ends on the start's words (Y25.001), not on a 0.001 mm arc that drops 4 mm.
  const test::posted near = post(
      helix_job("0,0,1", {36, 25.0006, 1}, {30, 25.0006, -7}, {36, 25.0005, -7}, 2), "rotary-4axis", "near");
  REQUIRE(near.ok);
  const std::vector<nc_arc> arcs = arcs_of(near.files.begin()->second);
  REQUIRE(arcs.size() == 2);
  CHECK(arcs[1].text == "G2 X36. Y25.001 Z-7. I-6. J0.");
  // A radius under one unit of the words is no arc.
  const test::posted zero =
      post(head + "CIRCLE/80,0,-5,0,0,1,0\nGOTO/80,0,-5\nFINI\n", "rotary-4axis", "zero");
  CHECK(zero.diagnostics ==
        "job.cls:9:1: error: channel 1: the arc's radius, 0 mm, is under one unit of the written words: give "
        "the "
        "move as a GOTO\nGOTO/80,0,-5\n^\n");
  // R is the radius the points lie on (50), not the record's (60).
  machine r = load_machine("rotary-4axis");
  r.program.arcs_ijk = false;
  const test::posted rf =
      test::post_in_fresh_dir(head + "CIRCLE/30,0,-5,0,0,1,60\nGOTO/30,50,-5\nFINI\n", r, "nxhelix-r");
  INFO(rf.diagnostics);
  REQUIRE(rf.ok);
  CHECK(rf.files.at("TINY.nc").find("G3 X30. Y50. R50.") != std::string::npos);
}

TEST_CASE("a CIRCLE whose GOTO turns the tool axis is refused at that GOTO", "[post][arc]") {
  // Attack 45: the arc was written upright and the 15 degree tilt moved into the next cut.
  const test::posted p = post(
      "PARTNO TILT\nLOADTL/1\nTLDATA/MILL,12,0,150,0,0\nSPINDL/RPM,3000,CLW\nFEDRAT/MMPM,600\nRAPID\n"
      "GOTO/80,0,5,0,0,1\nGOTO/80,0,-5\nCIRCLE/30,0,-5,0,0,1,50\nGOTO/30,50,-5,0.258819,0,0.9659258\nFINI\n",
      "head-head-5axis", "tilt");
  CHECK(
      p.diagnostics ==
      "job.cls:10:1: error: channel 1: the CIRCLE's GOTO turns the tool axis: an arc holds the tool's axis; "
      "give the move as GOTO points\nGOTO/30,50,-5,0.258819,0,0.9659258\n^\n");
}

TEST_CASE("cutter compensation does not start or end on an arc", "[post][arc]") {
  // Attack 45: G41 D2 G2 ... and G40 G2 ... were written (Fanuc PS0034).
  const std::string head =
      "PARTNO COMP\nLOADTL/2\nSPINDL/RPM,3000,CLW\nFEDRAT/MMPM,600\nRAPID\nGOTO/80,0,5,0,0,1\nGOTO/80,0,-5\n";
  CHECK(
      post(head + "CUTCOM/LEFT,2\nCIRCLE/30,0,-5,0,0,1,50\nGOTO/30,50,-5\nFINI\n", "rotary-4axis", "comp-on")
          .diagnostics ==
      "job.cls:10:1: error: channel 1: cutter compensation would start on an arc (G41 D2): the control "
      "starts "
      "and ends it on a straight move; give a straight lead-in or lead-out between the CUTCOM and the "
      "CIRCLE\nGOTO/30,50,-5\n^\n");
}
