// Mill/turn on path 3 of the Fanuc 31i three-path built-in (machines/builtin/fanuc-31i-3path.toml,
// [milling]): the main spindle held as C with M35, polar interpolation with X in diameter, holes
// at C positions, cross holes with the lathe's side cycles G87/G88. The sample job's path-3
// program is read back with a model of the control written from the block forms of the Fusion
// "Doosan Mill/Turn with Fanuc 31i control" post (docs/machines.md, "Mill/turn"), not from the
// writer: every tool position it finds must be a CL point or a hole's bottom.
#include <catch2/catch.hpp>

#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "file_test_support.hpp"
#include "machines/machine_loader.hpp"
#include "nc_words_test_support.hpp"
#include "post_test_jobs.hpp"
#include "support/vec3.hpp"

using namespace twinpost;

namespace {

test::posted post_on(const std::string& cl, const std::string& tag) {
  return test::post_in_fresh_dir(cl, load_machine("fanuc-31i-3path"), "fanuc-millturn-" + tag,
                                 [](const diagnostic& d) { return d.level == severity::error; });
}

using test::has;
using test::word;

// The control as the Fusion Doosan post's blocks describe it: X always a diameter; G12.1 with
// the Y value addressed as C (radius); G0 C.. turning the part (the point at angle C comes onto
// +X), G28 H0. bringing C to 0; face cycles G83/G84 X Y Z drilling along Z to Z at (X/2, Y);
// side cycles G87/G88 X Z drilling along X to the radius X/2. G28 U/W (home) and the head's
// G0 B.. are no tool tips, and neither is a move while X or Z is unknown (after a home, until
// the program gives both: Y to the centre line before G12.1). Returns the part-frame tips of
// the moves and the hole bottoms.
std::vector<vec3> tips(const std::string& program) {
  std::vector<vec3> out;
  bool polar = false, x_known = false, z_known = false;
  double c = 0, x = 0, y = 0, z = 0;
  const double deg = std::numbers::pi / 180;
  auto part = [&](double px, double py, double pz) {
    if (polar) return vec3{px, py, pz};
    return vec3{px * std::cos(c * deg) - py * std::sin(c * deg),
                px * std::sin(c * deg) + py * std::cos(c * deg), pz};
  };
  std::istringstream in(program);
  std::string b;
  while (std::getline(in, b)) {
    if (b.empty() || b[0] == '(' || b[0] == '%' || b[0] == 'O') continue;
    if (has(b, "G28")) {
      if (word(b, 'H', 1) == 0) c = 0;
      bool gu = false, gw = false;
      (void)word(b, 'U', 0, &gu), (void)word(b, 'W', 0, &gw);
      if (gu) x_known = false;
      if (gw) z_known = false;
      continue;
    }
    if (has(b, "G12.1")) polar = true;
    if (has(b, "G13.1")) polar = false;
    bool gx = false, gy = false, gz = false, gc = false, gb = false;
    (void)word(b, 'B', 0, &gb);
    if (gb) continue;
    const double nx = word(b, 'X', x * 2, &gx) / 2, nz = word(b, 'Z', z, &gz);
    const double ny = polar ? word(b, 'C', y, &gc) : word(b, 'Y', y, &gy);
    if (!polar && !(gx || gy || gz)) {
      bool cc = false;
      const double nc = word(b, 'C', c, &cc);
      if (cc) c = nc;
      continue;
    }
    if (!(gx || gy || gz || gc)) continue;
    if (has(b, "G87") || has(b, "G88")) {  // along X at the hole's Z: the bottom; the tool stays
      out.push_back(part(nx, 0, nz));
      continue;
    }
    if (has(b, "G83") || has(b, "G84")) {  // along Z at (X, Y): the bottom; the tool stays
      out.push_back(part(nx, ny, nz));
      continue;
    }
    x = nx, y = ny, z = nz;
    x_known = x_known || gx, z_known = z_known || gz;
    if (x_known && z_known) out.push_back(part(x, y, z));
  }
  return out;
}

std::string text(const vec3& p) {
  return fmt::format("({:.3f}, {:.3f}, {:.3f})", p.x + 0.0, p.y + 0.0, p.z + 0.0);
}

}  // namespace

TEST_CASE("the Fanuc mill/turn sample's path 3 reaches every CL point and hole bottom it should",
          "[post][millturn]") {
  const std::string cl =
      test::read_file(std::string(TWINPOST_SOURCE_DIR) + "/samples/millturn-fanuc-3path/job.cls");
  const test::posted p = post_on(cl, "sample");
  REQUIRE(p.ok);
  std::string seen;
  for (const vec3& t : tips(p.files.at("MILLTURN-FANUC-3PATH_3.nc"))) seen += text(t) + "\n";
  // The CL points of path 3 in order: the flat's two passes (polar), the three face holes
  // (R plane 2 above the face, bottom 12 below it), their taps (R 3, bottom 9), the two cross
  // holes (R plane 3 above the 60 mm diameter, bottom 15 deep along the radius), the cross tap
  // at 0 degrees (bottom 12 deep), the park position. A point the model reads twice (the
  // initial level before and after a cycle) is listed twice.
  CHECK(seen ==
        "(40.000, 25.000, 5.000)\n(40.000, 25.000, -3.000)\n(-40.000, 25.000, -3.000)\n"
        "(-40.000, 25.000, 5.000)\n(-40.000, -25.000, 5.000)\n(-40.000, -25.000, -3.000)\n"
        "(40.000, -25.000, -3.000)\n(40.000, -25.000, 5.000)\n"
        "(20.000, 0.000, 10.000)\n(20.000, 0.000, 2.000)\n(20.000, 0.000, -12.000)\n(20.000, 0.000, 2.000)\n"
        "(-10.000, 17.321, 2.000)\n(-10.000, 17.321, -12.000)\n(-10.000, 17.321, 2.000)\n"
        "(-10.000, -17.321, 2.000)\n(-10.000, -17.321, -12.000)\n(-10.000, -17.321, 2.000)\n"
        "(20.000, 0.000, 10.000)\n(20.000, 0.000, 3.000)\n(20.000, 0.000, -9.000)\n(20.000, 0.000, 3.000)\n"
        "(-10.000, 17.321, 3.000)\n(-10.000, 17.321, -9.000)\n(-10.000, 17.321, 3.000)\n"
        "(-10.000, -17.321, 3.000)\n(-10.000, -17.321, -9.000)\n(-10.000, -17.321, 3.000)\n"
        "(40.000, 0.000, -20.000)\n(33.000, 0.000, -20.000)\n(15.000, 0.000, -20.000)\n"
        "(33.000, 0.000, -20.000)\n(0.000, 33.000, -20.000)\n(0.000, 15.000, -20.000)\n"
        "(0.000, 33.000, -20.000)\n(0.000, 40.000, -20.000)\n"
        "(40.000, 0.000, -20.000)\n(33.000, 0.000, -20.000)\n(18.000, 0.000, -20.000)\n"
        "(33.000, 0.000, -20.000)\n(40.000, 0.000, -20.000)\n"
        "(0.000, 0.000, 100.000)\n");
}

TEST_CASE("the Fanuc cross hole: C to the hole and clamped, G87 along X, R from the initial level",
          "[post][millturn]") {
  // A radial drill at 30 degrees on the 60 mm diameter, pecking 5 mm (Q in 0.001 mm).
  const test::posted p = post_on(
      "PARTNO E\nHEAD/3\nTLDATA/DRILL,6,118\nLOADTL/14\nSPINDL/RPM,2000,CLW,LIVE\nRAPID\n"
      "GOTO/43.30127,25,-20,0.8660254,0.5,0\nCYCLE/DEEP,DEPTH,15,STEP,5,RAPTO,3,MMPM,120\n"
      "GOTO/25.980762,15,-20\nCYCLE/OFF\nFINI\n",
      "cross-peck");
  REQUIRE(p.ok);
  const std::string& f = p.files.at("E_3.nc");
  CHECK(f.substr(f.find("M6 T14")) ==
        "M6 T1400\nT1414\nM35\nG0 G28 H0.\nG97 S2000 M33\nG0 B0.\nG0 C30.\nX100. Y0. Z-20.\nM89\nG98\nX66.\n"
        "G87 X30. Z-20. R0. Q5000 F120.\nG80\nG0 X66. Z-20.\nM200 P123\nM37\nM90\nM34\nM9\nG28 U0. V0.\n"
        "G28 W0.\nM30\n%\n");
}

TEST_CASE("what the Fanuc side cycles cannot do stops the post, by name", "[post][millturn]") {
  const std::string tool = "PARTNO E\nHEAD/3\nTLDATA/DRILL,6,118\nLOADTL/14\nSPINDL/RPM,500,CLW,LIVE\n";
  // A cross hole beside its radial line: G87 drills through the centre only.
  test::posted p = post_on(tool +
                               "RAPID\nGOTO/40,5,-20,1,0,0\nCYCLE/DRILL,DEPTH,10,RAPTO,3,MMPM,100\n"
                               "GOTO/30,5,-20\nCYCLE/OFF\nFINI\n",
                           "beside");
  CHECK(
      p.diagnostics ==
      "job.cls:9:1: error: channel 3: a cross hole 5 mm beside its radial line: the side cycle (G87) drills "
      "along X through the spindle centre only\nGOTO/30,5,-20\n^\n");
  // A left-hand cross tap: that post writes no left-hand side tap.
  p = post_on(tool +
                  "RAPID\nGOTO/40,0,-20,1,0,0\nCYCLE/TAP,DEPTH,10,RAPTO,3,PITCH,1,LEFT\n"
                  "GOTO/30,0,-20\nCYCLE/OFF\nFINI\n",
              "left-tap");
  CHECK(
      p.diagnostics ==
      "job.cls:9:1: error: channel 3: CYCLE/TAP across the spindle axis: machine 'fanuc-31i-3path' gives no "
      "left-hand side tapping cycle (cycles.side_tap_code, right-hand only)\nGOTO/30,0,-20\n^\n");
  // A feed of the radial tool beside its radius: cylindrical interpolation cannot carry it.
  p = post_on(
      "PARTNO E\nHEAD/3\nTLDATA/MILL,6\nLOADTL/21\nSPINDL/RPM,3000,CLW\nFEDRAT/MMPM,200\n"
      "RAPID\nGOTO/30,0,-10,1,0,0\nGOTO/23,0,-10\nGOTO/23,5,-10\nFINI\n",
      "y-cut");
  CHECK(
      p.diagnostics ==
      "job.cls:10:1: error: channel 3: a feed move across the spindle axis to X 23 Y 5, which the tool axis "
      "(1,0,0) does not point at along the radius (5 mm beside it): cylindrical interpolation moves the "
      "tool along the radius through its point only\nGOTO/23,5,-10\n^\n");
  // Live-tool work on the sub spindle: it has no C-axis codes here (kept refusal).
  p = post_on(
      "PARTNO E\nHEAD/3\nSPINDL/SMM,100,MAXRPM,2000,CLW,SUB\nTLDATA/MILL,6\nLOADTL/21\n"
      "SPINDL/RPM,3000,CLW\nFEDRAT/MMPM,200\nRAPID\nGOTO/20,0,5,0,0,1\nFINI\n",
      "sub");
  CHECK(p.diagnostics ==
        "job.cls:6:1: error: channel 3: live-tool work on the sub spindle, which machine 'fanuc-31i-3path' "
        "cannot hold as a C axis (spindle.c_on): the part would be free to turn under the cutter\n"
        "SPINDL/RPM,3000,CLW\n^\n");
}

TEST_CASE("the Fanuc polar interpolation holds the radius to the X travel of the diameter axis",
          "[post][millturn]") {
  // X travel -50..600 in diameter: a point 310 from the centre (diameter 620) is outside it,
  // 290 (diameter 580) inside, whatever the X and C words of the plane are.
  const std::string job =
      "PARTNO E\nHEAD/3\nTLDATA/MILL,10\nLOADTL/7\nSPINDL/RPM,3000,CLW\nFEDRAT/200,MMPM\n"
      "GOTO/0,290,2,0,0,1\nGOTO/0,310,2\nFINI\n";
  const test::posted p = post_on(job, "polar-travel");
  CHECK(p.diagnostics ==
        "job.cls:8:1: error: channel 3: polar interpolation to a radius of 310. is outside channel 3's X "
        "travel (channel.axis max 600)\nGOTO/0,310,2\n^\n");
}

TEST_CASE("a cross hole the side codes cannot say is written as moves along X at its C position",
          "[post][millturn]") {
  // Pecks without a side peck code: each peck fed along X in diameter, out to the R plane and
  // back in to 0.5 above the last depth, as any expanded hole.
  machine m = load_machine("fanuc-31i-3path");
  m.cycles.side_peck_code.clear();
  const test::posted p = test::post_in_fresh_dir(
      "PARTNO E\nHEAD/3\nTLDATA/DRILL,6,118\nLOADTL/14\nSPINDL/RPM,2000,CLW,LIVE\nRAPID\n"
      "GOTO/0,40,-20,0,1,0\nCYCLE/DEEP,DEPTH,10,STEP,4,RAPTO,3,MMPM,120\nGOTO/0,30,-20\nCYCLE/OFF\nFINI\n",
      m, "fanuc-millturn-cross-pecks", [](const diagnostic& d) { return d.level == severity::error; });
  REQUIRE(p.ok);
  const std::string& f = p.files.at("E_3.nc");
  CHECK(f.substr(f.find("G0 B0."), f.find("M200") - f.find("G0 B0.")) ==
        "G0 B0.\nG0 C90.\nX80. Y0. Z-20.\nM89\nG98\nX66.\nG1 X58. F120.\nG0 X66.\nX59.\nG1 X50.\nG0 X66.\n"
        "X51.\nG1 X42.\nG0 X66.\nX43.\nG1 X40.\nG0 X66.\n");
}

TEST_CASE("milling on the diameter on the Fanuc: G7.1 on the lathe's Z and C, X the tip's diameter",
          "[post][millturn]") {
  // A plunge along the radius (C clamped), the cut on the cylinder of radius 23 (C unclamped,
  // G18 W0 H0, G7.1 C23.), a retract along the radius inside the mode, G7.1 C0 before the rapid.
  const test::posted p = post_on(
      "PARTNO E\nHEAD/3\nTLDATA/MILL,6\nLOADTL/21\nSPINDL/RPM,3000,CLW\nFEDRAT/MMPM,200\nRAPID\n"
      "GOTO/30,0,-10,1,0,0\nGOTO/23,0,-10\nGOTO/22.216294,5.952838,-12.5,0.9659258,0.258819,0\n"
      "GOTO/19.9185843,11.5,-15.0,0.8660254,0.5,0.0\nGOTO/25.9807621,15.0,-15.0\nRAPID\n"
      "GOTO/34.6410162,20.0,-15.0\nFINI\n",
      "wrap");
  REQUIRE(p.ok);
  const std::string& f = p.files.at("E_3.nc");
  CHECK(f.substr(f.find("G0 B0."), f.find("M200") - f.find("G0 B0.")) ==
        "G0 B0.\nG0 C0.\nX60. Y0. Z-10.\nM89\nG1 X46. F200.\nM90\nG18 W0 H0\nG7.1 C23.\nG1 Z-12.5 C15.\n"
        "Z-15. C30.\nX60.\nG7.1 C0\nG0 X80.\n");
}

TEST_CASE(
    "an offset change of the polar tool is made after a GOHOME and starts the mode again from Y0 and C0",
    "[post][millturn]") {
  // Review 54: `T1127` was written inside G12.1 (no offset change the control takes there), and
  // the Y the old offset stood at was kept. After a GOHOME (the mode off, the axes home) the
  // offset changes, and polar interpolation starts again from Y0 and C0.
  const std::string job =
      "PARTNO E\nUNITS/MM\nHEAD/3\nTLDATA/MILL,10.0\nLOADTL/11\nSPINDL/RPM,3000,CLW\nFEDRAT/MMPM,400\n"
      "RAPID\nGOTO/40,25,5,0,0,1\nGOTO/40,25,-3\nGOTO/-40,25,-3\nRAPID\nGOTO/-40,25,5\nGOHOME\nLOADTL/11,27\n"
      "RAPID\nGOTO/40,-25,5\nGOTO/40,-25,-3\nGOTO/-40,-25,-3\nEND\nFINI\n";
  const test::posted p = post_on(job, "polar-offset");
  INFO(p.diagnostics);
  REQUIRE(p.ok);
  CHECK(p.files.at("E_3.nc") ==
        "%\nO1000 (E)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0. V0.\nG28 W0.\nM6 T1100\nT1111\nM35\n"
        "G0 G28 H0.\nG97 S3000 M33\nG98\nG0 B-90.\nG0 Y0.\nG0 C0.\nG17\nG12.1\n"
        "G1 X80. C25. Z5. F1500.\nZ-3. F400.\nX-80.\nZ5. F1500.\nG13.1\nG18\nG28 U0. V0.\nG28 W0.\n"
        "T1127\nG0 Y0.\nG0 C0.\nG17\nG12.1\nG1 X80. C-25. Z5.\nZ-3. F400.\nX-80.\nG13.1\nG18\n"
        "G28 W0.\nM200 P123\nM37\nM34\nM9\nG28 U0. V0.\nM30\n%\n");
}

TEST_CASE("an offset change of the polar tool inside the mode is refused", "[post][millturn]") {
  // Reviews 55 and 56: leaving the mode for the offset change and starting it again turns C
  // back to 0 where the tool stands; with the cutter 3 mm into the face (or at a depth a helix
  // or a lead-in from outside reached) that turns the part round it.
  const std::string job =
      "PARTNO E\nUNITS/MM\nHEAD/3\nTLDATA/MILL,10.0\nLOADTL/11\nSPINDL/RPM,3000,CLW\nFEDRAT/MMPM,400\n"
      "RAPID\nGOTO/40,25,5,0,0,1\nGOTO/40,25,-3\nLOADTL/11,27\nRAPID\nGOTO/40,25,5\nEND\nFINI\n";
  const test::posted p = post_on(job, "polar-offset-low");
  CHECK_FALSE(p.ok);
  CHECK(
      p.diagnostics ==
      "job.cls:11:1: error: channel 3: LOADTL changes tool 11's offset inside polar interpolation: the "
      "control "
      "takes no offset change in the mode, and leaving it turns C back to 0 where the tool stands, which may "
      "turn the part round the cutter; give a GOHOME before the offset change\n"
      "LOADTL/11,27\n^\n");
}
