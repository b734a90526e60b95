// Mill/turn on the Integrex upper head (machining/channel_millturn.cpp): the main spindle held as
// the C axis, polar interpolation, holes at C positions, cross holes in the turned frame, the
// B head indexed per tool. The sample job's head-1 program is read back here with a model of
// the control written from the Fusion Integrex post's block forms (docs/machines.md,
// "Mill/turn"), not from the writer: every tool position it finds must be a CL point.
#include <catch2/catch.hpp>

#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "file_test_support.hpp"
#include "kinematics/forward.hpp"
#include "machines/machine_loader.hpp"
#include "nc_words_test_support.hpp"
#include "post_test_jobs.hpp"
#include "support/vec3.hpp"

using namespace twinpost;

namespace {

test::posted post_on(const std::string& cl, const machine& m, const std::string& tag) {
  return test::post_in_fresh_dir(cl, m, "millturn-" + tag,
                                 [](const diagnostic& d) { return d.level == severity::error; });
}

std::string head1(const test::posted& p, const std::string& name) {
  if (!p.ok) return "(failed)\n" + p.diagnostics;
  const std::string& f = p.files.at(name);
  const std::size_t from = f.find("G109 L1"), to = f.find("G109 L2");
  return f.substr(from, to - from);
}

using test::has;
using test::word;

// The control as the Fusion Integrex post's blocks describe it: G10.9 X0/X1 radius or
// diameter, G12.1 with the Y value addressed as C (mm), G0 C.. turning the part (the point at
// angle C comes onto +X), G68 X0 Y0 Z0 I0 J1 K0 R90. turning the frame about Y (its Z along
// +X), G17 drilling cycles G81 X Y Z R along the frame's Z. Cylindrical interpolation as the
// Integrex shop program and Fanuc's manuals write it: G7.1 C<r> on, G7.1 C0 off, C in degrees
// turning the part inside it while X and Z stay the turned frame's. Returns the part-frame tool
// tips of the moves and the hole bottoms, in order (machine-coordinate G53 blocks are skipped,
// and leave their axes unknown: a move while X or Z is unknown, Y to the centre line before
// G12.1, is no tool tip).
std::vector<vec3> tips(const std::string& program) {
  std::vector<vec3> out;
  bool radius = false, polar = false, turned = false, cylinder = false, x_known = false, z_known = false;
  double c = 0, x = 0, y = 0, z = 0;
  const double deg = std::numbers::pi / 180;
  auto part = [&](double px, double py, double pz) {
    double wx = px, wy = py, wz = pz;
    if (turned) wx = pz, wy = py, wz = -px;  // work = Ry(90°) · program
    if (polar) return vec3{px, py, pz};
    return vec3{wx * std::cos(c * deg) - wy * std::sin(c * deg),
                wx * std::sin(c * deg) + wy * std::cos(c * deg), wz};
  };
  std::istringstream in(program);
  std::string b;
  while (std::getline(in, b)) {
    if (b.empty() || b[0] == '(') continue;
    if (has(b, "G53")) {
      bool gx = false, gz = false;
      (void)word(b, 'X', 0, &gx), (void)word(b, 'Z', 0, &gz);
      if (gx) x_known = false;
      if (gz) z_known = false;
      continue;
    }
    if (has(b, "G10.9")) {  // a mode, not a move
      radius = word(b, 'X', 1) == 0;
      continue;
    }
    if (has(b, "G12.1")) polar = true;
    if (has(b, "G13.1")) polar = false;
    if (has(b, "G68")) {  // the frame's centre and axis, not a move
      turned = true, x = y = z = 0;
      continue;
    }
    if (has(b, "G69")) turned = false;
    if (has(b, "G7.1")) {  // cylindrical interpolation on (C<radius>) or off (C0): a mode
      cylinder = word(b, 'C', 0) != 0;
      continue;
    }
    bool gx = false, gy = false, gz = false, gc = false;
    if (cylinder) c = word(b, 'C', c, &gc);  // in the mode C turns the part with the cut
    const double nx = word(b, 'X', x, &gx), nz = word(b, 'Z', z, &gz);
    const double ny = polar ? word(b, 'C', y, &gc) : word(b, 'Y', y, &gy);
    if (!polar && !turned && !(gx || gy || gz)) {
      bool cc = false;
      const double nc = word(b, 'C', c, &cc);
      if (cc) c = nc;
      continue;
    }
    if (!(gx || gy || gz || gc)) continue;
    x = radius || turned || polar ? nx : nx / 2, y = ny, z = nz;
    x_known = x_known || gx, z_known = z_known || gz;
    if (!(x_known && z_known)) continue;
    if (has(b, "G81")) {  // a hole: its bottom; the tool stays at the initial level
      out.push_back(part(x, y, z));
      continue;
    }
    out.push_back(part(x, y, z));
  }
  return out;
}

std::string text(const vec3& p) { return fmt::format("({:.3f}, {:.3f}, {:.3f})", p.x, p.y, p.z); }

}  // namespace

TEST_CASE("the mill/turn sample's head 1 reaches every CL point and hole bottom it should",
          "[post][millturn]") {
  const std::string cl =
      test::read_file(std::string(TWINPOST_SOURCE_DIR) + "/samples/millturn-flat-cross/job.cls");
  const test::posted p = post_on(cl, load_machine("integrex-i200st"), "sample");
  REQUIRE(p.ok);
  std::string seen;
  for (const vec3& t : tips(head1(p, "MILLTURN-FLAT-CROSS.EIA"))) seen += text(t) + "\n";
  // The CL points of head 1 in order: the flat's two passes (polar), the approach and the three
  // face holes (bottom 12 below each top), the cross holes (3 above the OD, bottom 15 deep
  // along -axis), the retracts. A point the model reads twice (the initial level before and
  // after a cycle) is listed twice. First, before G12.1, the flat's first point's radius at C0
  // and its height (the length offset's block: 47.17 = hypot(40, 25)).
  CHECK(seen ==
        "(47.170, 0.000, 5.000)\n"
        "(40.000, 25.000, 5.000)\n(40.000, 25.000, -8.000)\n(-40.000, 25.000, -8.000)\n(-40.000, 25.000, "
        "5.000)\n"
        "(-40.000, -25.000, 5.000)\n(-40.000, -25.000, -8.000)\n(40.000, -25.000, -8.000)\n"
        "(40.000, -25.000, 5.000)\n"
        "(20.000, 0.000, 10.000)\n(20.000, 0.000, 2.000)\n(20.000, 0.000, -12.000)\n(20.000, 0.000, 2.000)\n"
        "(-10.000, 17.321, 2.000)\n(-10.000, 17.321, -12.000)\n(-10.000, 17.321, 2.000)\n"
        "(-10.000, -17.321, 2.000)\n(-10.000, -17.321, -12.000)\n(-10.000, -17.321, 2.000)\n"
        "(-10.000, -17.321, 10.000)\n"
        "(40.000, 0.000, -20.000)\n(33.000, 0.000, -20.000)\n(15.000, 0.000, -20.000)\n(33.000, 0.000, "
        "-20.000)\n"
        "(0.000, 33.000, -20.000)\n(0.000, 15.000, -20.000)\n(0.000, 33.000, -20.000)\n(0.000, 40.000, "
        "-20.000)\n"
        "(0.000, 0.000, 100.000)\n");
}

TEST_CASE("a live tool holds the main spindle as the C axis until a turning tool lets it go",
          "[post][millturn]") {
  const std::string cl =
      "PARTNO E\nHEAD/1\nTLDATA/MILL,8\nLOADTL/5\nSPINDL/RPM,3000,CLW\nFEDRAT/MMPM,300\nRAPID\n"
      "GOTO/10,5,2\nGOTO/10,5,-1\nCIRCLE/0,5,-1,0,0,1,10\nGOTO/-10,5,-1\nTLDATA/TURN,0.8\nLOADTL/1\n"
      "SPINDL/SMM,200,MAXRPM,2000,CLW\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/30,0,2\nFINI\n";
  const test::posted p = post_on(cl, load_machine("integrex-i200st"), "hold");
  // Polar interpolation for the axial end mill (X a radius, the CL's Y as C, arcs in I/J), off
  // before the reference return; turning mode (G10.9 X1, M202) before the turning spindle starts.
  // The tool change comes straight from the cut at Z-1: the end mill leaves along Z first, its
  // spindle still turning (review 64 H2, M4).
  CHECK(head1(p, "E.EIA") ==
        "G109 L1\nG21\nG0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG10.9 X1\nG0 G90 G53 X0. Y0.\nG0 G90 G53 "
        "Z0.\nT05 "
        "M6\nM901\nM200\n"
        "G10.9 X0\nG97 S3000 M3\nG94\nM108\nG0 G53 B0.\nM107\nG0 C0.\nG0 G43 H#3020 X11.18 Y0. Z2.\nG17 "
        "XC\nG12.1\nG0 X10. C5.\n"
        "G1 Z-1. F300.\nG3 X-10. C5. I-10. J0.\nG13.1\nG18\nG0 G90 G53 Z0.\nM5\nG0 G90 G53 X0. Y0.\nT01 M6\n"
        "M901\nG10.9 X1\nM202\nG92 S2000 R1\nG96 S200 M203\nG95\nM108\nG0 G53 B0.\nM107\nG0 G43 P1 H#3020 "
        "X60. Y0. "
        "Z2.\nM950\nM9\nM5\nM205\n"
        "M305\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM30\n");
}

TEST_CASE("the B head turns only at home: a cross hole after face work goes home first", "[post][millturn]") {
  const std::string cl =
      "PARTNO E\nHEAD/1\nTLDATA/DRILL,5,118\nLOADTL/12\nSPINDL/RPM,2000,CLW,LIVE\nRAPID\n"
      "GOTO/20,0,5,0,0,1\nRAPID\nGOTO/40,0,-10,1,0,0\nFINI\n";
  const test::posted p = post_on(cl, load_machine("integrex-i200st"), "index");
  CHECK(
      head1(p, "E.EIA") ==
      "G109 L1\nG21\nG0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG10.9 X1\nG0 G90 G53 X0. Y0.\nG0 G90 G53 "
      "Z0.\nT12 "
      "M6\nM901\nM200\n"
      "G10.9 X0\nG97 S2000 M3\nM108\nG0 G53 B0.\nM107\nG0 C0.\nG0 G43 H#3020 X20. Y0. Z5.\nG0 G90 G53 X0. "
      "Y0.\n"
      "G0 G90 G53 Z0.\nM108\nG0 G53 B90.\nM107\nM210\nG68 X0. Y0. Z0. I0. J1. K0. R90.\n"
      "G0 G43 H#3020 X10. Y0. Z40.\nM950\nG69\nM212\nG10.9 X1\nM202\nM9\nM5\nM205\nM305\nG0 G90 G53 X0. Y0.\n"
      "G0 G90 G53 Z0.\nM30\n");
}

TEST_CASE("face holes on a stepped face: the drill climbs to the higher plane before C turns",
          "[post][millturn]") {
  // Attack 50: C was turned to the next hole while the drill stood on the last one's R plane,
  // 13 mm below the next hole's top, then turned back to climb there and forward again, and
  // the second hole was drilled with C unclamped. Now: up, unclamp, turn, clamp, drill.
  const std::string cl =
      "PARTNO S\nHEAD/1\nTLDATA/DRILL,5,118\nLOADTL/12\nSPINDL/RPM,2500,CLW,LIVE\nRAPID\n"
      "GOTO/20,0,20,0,0,1\nCYCLE/DRILL,DEPTH,10,RAPTO,2,MMPM,150\nGOTO/20,0,-15\nGOTO/0,20,0\n"
      "GOTO/-20,0,-15\nCYCLE/OFF\nRAPID\nGOTO/-20,0,50\nSPINDL/OFF\nFINI\n";
  const test::posted p = post_on(cl, load_machine("integrex-i200st"), "stepped-holes");
  const std::string h = head1(p, "S.EIA");
  const std::size_t from = h.find("G98 G81");
  REQUIRE(from != std::string::npos);
  CHECK(h.substr(from) ==
        "G98 G81 X20. Y0. Z-25. R-13. F150.\nG80\nG18\nG0 Z-13.\nZ2.\nM212\nG0 C90.\nM210\nX20. Y0. Z2.\n"
        "G17\nG98 G81 X20. Y0. Z-10. R2. F150.\nG80\nG18\nG0 Z2.\nM212\nG0 C180.\nM210\nX20. Y0. Z2.\n"
        "Z-13.\nG17\nG98 G81 X20. Y0. Z-25. R-13. F150.\nG80\nG18\nG0 Z-13.\nZ50.\nM5\nM950\nM212\n"
        "G10.9 X1\nM202\nM9\nM205\nM305\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM30\n");
}

TEST_CASE("a cross hole on a machine without a turned frame, and a feed across the axis, stop the post",
          "[post][millturn]") {
  machine m = load_machine("integrex-i200st");
  m.milling.radial_frame_on.clear();
  m.milling.radial_frame_off.clear();
  const test::posted p = post_on(
      "PARTNO "
      "E\nHEAD/1\nTLDATA/DRILL,5,118\nLOADTL/12\nSPINDL/RPM,2000,CLW,LIVE\nRAPID\nGOTO/40,0,-10,1,0,0\n"
      "FINI\n",
      m, "no-frame");
  CHECK(p.diagnostics ==
        "job.cls:7:1: error: channel 1: a move with the tool across the spindle axis: machine "
        "'integrex-i200st' "
        "gives no frame for it (milling.radial_frame_on), so cross holes cannot be posted\n"
        "GOTO/40,0,-10,1,0,0\n^\n");
}

TEST_CASE("a tilted tool on the Integrex head goes to the chain: B and C unclamped and G43.4 H#3020",
          "[post][millturn]") {
  const std::string cl =
      "PARTNO E\nHEAD/1\nTLDATA/MILL,6\nLOADTL/14\nSPINDL/RPM,4000,CLW\nFEDRAT/MMPM,300\nMULTAX/ON\nRAPID\n"
      "GOTO/40,0,10,0.7071068,0,0.7071068\nGOTO/29,0,-1\nGOTO/0,29,-1,0,0.7071068,0.7071068\nRAPID\n"
      "GOTO/0,40,10\nFINI\n";
  const test::posted p = post_on(cl, load_machine("integrex-i200st"), "tilted");
  // B45 tilts the tool from +Z towards +X; C90 turns the point at +Y onto the head. X Y Z are
  // the tip in the part frame (tool-tip control), X in radius.
  CHECK(head1(p, "E.EIA") ==
        "G109 L1\nG21\nG0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG10.9 X1\nG0 G90 G53 X0. Y0.\nG0 G90 G53 "
        "Z0.\nT14 "
        "M6\nM901\nM200\n"
        "G10.9 X0\nG97 S4000 M3\nG94\nM108\nM212\nG0 B45. C0.\nG0 X40. Y0.\nG0 G43.4 H#3020 X40. Y0. Z10. "
        "B45. C0.\nG1 X29. Z-1. F300.\n"
        "X0. Y29. C90.\nG0 Y40. Z10.\nM950\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nG49\nG10.9 "
        "X1\nM202\nM9\nM5\nM205\nM305\nG0 G90 G53 X0. Y0.\n"
        "G0 G90 G53 Z0.\nM30\n");
}

TEST_CASE("the Integrex chain agrees with the mill/turn writer's B and C", "[post][millturn]") {
  // The mill/turn writer indexes B0 for a tool along Z and B90 across it, and turns C to the
  // angle of the tool axis (C = atan2(j, i)); the chain that takes tilted tools must give those
  // same axes by its forward transform, or a job mixing the two would turn C the wrong way.
  const machine m = load_machine("integrex-i200st");
  const kinematic_chain& c = *m.chain(1);
  REQUIRE(c.rotaries.size() == 2);
  std::string seen;
  for (const auto& [cdeg, bdeg] :
       {std::pair{0.0, 0.0}, {0.0, 90.0}, {90.0, 90.0}, {200.0, 90.0}, {120.0, 45.0}}) {
    kin::joint_values j;
    for (std::size_t i = 0; i < 2; ++i) j.rotary[i] = c.rotaries[i].address == 'C' ? cdeg : bdeg;
    const vec3 a = kin::tool_axis(c, j);
    seen +=
        fmt::format("C{:g} B{:g}: ({:.4f}, {:.4f}, {:.4f})\n", cdeg, bdeg, a.x + 0.0, a.y + 0.0, a.z + 0.0);
  }
  CHECK(seen ==
        "C0 B0: (0.0000, 0.0000, 1.0000)\n"
        "C0 B90: (1.0000, 0.0000, 0.0000)\n"
        "C90 B90: (0.0000, 1.0000, 0.0000)\n"
        "C200 B90: (-0.9397, -0.3420, 0.0000)\n"
        "C120 B45: (-0.3536, 0.6124, 0.7071)\n");
}

namespace {

// The GOTO points of a CL text in order (x, y, z), for the read-back below.
std::vector<vec3> cl_points(const std::string& cl) {
  std::vector<vec3> out;
  std::istringstream in(cl);
  std::string l;
  while (std::getline(in, l)) {
    if (l.rfind("GOTO/", 0) != 0) continue;
    std::istringstream f(l.substr(5));
    std::string v[3];
    for (std::string& s : v) std::getline(f, s, ',');
    out.push_back({std::stod(v[0]), std::stod(v[1]), std::stod(v[2])});
  }
  return out;
}

}  // namespace

TEST_CASE("the wrapped groove comes back to every CL point to the micron, on the cylinder of G7.1",
          "[post][millturn]") {
  const std::string cl =
      test::read_file(std::string(TWINPOST_SOURCE_DIR) + "/samples/millturn-wrap-groove/job.cls");
  const test::posted p = post_on(cl, load_machine("integrex-i200st"), "wrap");
  REQUIRE(p.ok);
  // The groove (OP10): its program up to the next operation, its CL points up to OP20's.
  const std::string all = head1(p, "MILLTURN-WRAP-GROOVE.EIA");
  const std::string program = all.substr(0, all.find("(OP20"));
  const std::vector<vec3> want = cl_points(cl.substr(0, cl.find("PPRINT OP20"))), got = tips(program);
  REQUIRE(got.size() == want.size());
  double worst = 0;
  std::string far;
  for (std::size_t i = 0; i < want.size(); ++i) {
    const double d = std::hypot(got[i].x - want[i].x, got[i].y - want[i].y, got[i].z - want[i].z);
    worst = std::max(worst, d);
    if (d > 0.001) far += fmt::format("point {}: {} for {}\n", i + 1, text(got[i]), text(want[i]));
  }
  CHECK(far == "");
  CHECK(worst < 0.001);
  // Every cut in the mode runs at the radius G7.1 was given (the tip's: F is the CL's feed at
  // the tip), and C runs on past 360 without a jump.
  std::istringstream in(program);
  std::string b, seen;
  double r = 0, z = 0, last_c = 0;
  bool on = false;
  while (std::getline(in, b)) {
    if (has(b, "G7.1")) {
      r = word(b, 'C', 0), on = r != 0;
      continue;
    }
    z = word(b, 'Z', z);
    if (!on || (" " + b).find(" C") == std::string::npos) continue;
    const double c = word(b, 'C', 0);
    if (std::abs(z - r) > 5e-4) seen += fmt::format("{}: at Z{} in G7.1 C{}\n", b, z, r);
    if (std::abs(c - last_c) > 30.0005) seen += fmt::format("{}: C jumps from {}\n", b, last_c);
    last_c = c;
  }
  CHECK(seen == "");
  CHECK(last_c == 390);
}

TEST_CASE("a cut on the diameter: plunge, G7.1 at the tip's radius, C on past 360, a new depth reopens it",
          "[post][millturn]") {
  const std::string cl =
      "PARTNO E\nHEAD/1\nTLDATA/MILL,6\nLOADTL/21\nSPINDL/RPM,3000,CLW\nFEDRAT/MMPM,200\nRAPID\n"
      "GOTO/21.6506351,-12.5,-10,0.8660254,-0.5,0\nGOTO/17.3205081,-10,-10\nGOTO/20,0,-10,1,0,0\n"
      "GOTO/17.3205081,10,-15,0.8660254,0.5,0\nGOTO/16.4544827,9.5,-15\nGOTO/19,0,-15,1,0,0\nGOTO/25,0,-15\n"
      "RAPID\nGOTO/30,0,-15\nFINI\n";
  const test::posted p = post_on(cl, load_machine("integrex-i200st"), "cylinder");
  // The plunge in the turned frame with C clamped; C unclamped before the mode; the cut at C330
  // + 30 = 360 and on to 390 (no wrap); the plunge to radius 19 inside, then the mode again at
  // 19; the retract inside; off before the rapid (no G0 in the mode).
  CHECK(head1(p, "E.EIA") ==
        "G109 L1\nG21\nG0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG10.9 X1\nG0 G90 G53 X0. Y0.\nG0 G90 G53 "
        "Z0.\nT21 M6\nM901\n"
        "M200\nG10.9 X0\nG97 S3000 M3\nG94\nM108\nG0 G53 B90.\nM107\nG0 C330.\nM210\n"
        "G68 X0. Y0. Z0. I0. J1. K0. R90.\nG0 G43 H#3020 X10. Y0. Z25.\nG1 Z20. F200.\nM212\nG17\nG7.1 C20.\n"
        "G1 C360.\nX15. C390.\nZ19.\nG7.1 C0\nG18\nG17\nG7.1 C19.\nG1 C360.\nZ25.\nG7.1 C0\nG18\nG0 Z30.\n"
        "M950\nG69\nG10.9 X1\nM202\nM9\nM5\nM205\nM305\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM30\n");
}

TEST_CASE("milling on the diameter refuses what cylindrical interpolation cannot do, by name",
          "[post][millturn]") {
  const std::string start =
      "PARTNO E\nHEAD/1\nTLDATA/MILL,6\nLOADTL/21\nSPINDL/RPM,3000,CLW\nFEDRAT/MMPM,200\nRAPID\n"
      "GOTO/25,0,-10,1,0,0\nGOTO/20,0,-10\n";
  auto fails = [&](const std::string& rest, const machine& m = load_machine("integrex-i200st")) {
    return post_on(start + rest + "FINI\n", m, "cylinder-errors").diagnostics;
  };
  CHECK(
      fails("GOTO/0,21,-10,0,1,0\n") ==
      "job.cls:10:1: error: channel 1: a cut across the spindle axis changes the tip's radius from 20 to 21 "
      "mm: cylindrical interpolation keeps the tip on one cylinder; only a plunge or a retract along the "
      "radius (C and Z still) may change it\nGOTO/0,21,-10,0,1,0\n^\n");
  CHECK(fails("CIRCLE/0,0,-10,0,0,1,20\nGOTO/0,20,-10,0,1,0\n") ==
        "job.cls:11:1: error: channel 1: a CIRCLE with the tool across the spindle axis: twinpost writes no "
        "arcs on the cylinder (G2/G3 in cylindrical interpolation); give the path as GOTO points\n"
        "GOTO/0,20,-10,0,1,0\n^\n");
  CHECK(
      fails("GOTO/-20,0,-10,-1,0,0\n") ==
      "job.cls:10:1: error: channel 1: a cut across the spindle axis turns the part 180 degrees in one move: "
      "which way round is not known; give points less than half a turn apart\nGOTO/-20,0,-10,-1,0,0\n^\n");
  CHECK(
      fails("GOTO/20,1,-10\n") ==
      "job.cls:10:1: error: channel 1: a feed move across the spindle axis to X 20 Y 1, which the tool axis "
      "(1,0,0) does not point at along the radius (1 mm beside it): cylindrical interpolation moves the "
      "tool along the radius through its point only\nGOTO/20,1,-10\n^\n");
  CHECK(fails("CUTCOM/LEFT\nGOTO/18,0,-10\n") ==
        "job.cls:11:1: error: channel 1: cutter compensation (G41) would start outside cylindrical "
        "interpolation, on a plunge: it must start and end inside the mode (Fanuc 15i-MA B-63324EN/03 §4): "
        "put CUTCOM after the plunge\nGOTO/18,0,-10\n^\n");
  CHECK(fails("GOTO/17.3205081,10,-15,0.8660254,0.5,0\nCUTCOM/LEFT\nGOTO/20,0,-20,1,0,0\nRAPID\nGOTO/"
              "30,0,-20\n") ==
        "job.cls:14:1: error: channel 1: cutter compensation is still on where cylindrical interpolation "
        "ends: it must start and end inside the mode (Fanuc 15i-MA B-63324EN/03 §4): give CUTCOM/OFF before "
        "the retract\nGOTO/30,0,-20\n^\n");
  CHECK(post_on("PARTNO E\nHEAD/1\nTLDATA/MILL,6\nLOADTL/21\nSPINDL/RPM,3000,CLW\nFEDRAT/MMPM,200\nRAPID\n"
                "GOTO/25,5,-10,1,0,0\nGOTO/20,0,-10\nFINI\n",
                load_machine("integrex-i200st"), "cylinder-start")
            .diagnostics ==
        "job.cls:9:1: error: channel 1: a feed move across the spindle axis from a point the tool was not "
        "taken to along its radius: start a cut on the diameter with a RAPID under the same tool axis\n"
        "GOTO/20,0,-10\n^\n");
  machine none = load_machine("integrex-i200st");
  none.milling.cylindrical_on.clear();
  none.milling.cylindrical_off.clear();
  CHECK(
      fails("", none) ==
      "job.cls:9:1: error: channel 1: a feed move with the tool across the spindle axis (milling on the "
      "diameter): machine 'integrex-i200st' gives no cylindrical interpolation (milling.cylindrical_on), so "
      "it cannot be posted\nGOTO/20,0,-10\n^\n");
  // The second spindle held as C (as a machine file could give it): its C turns the other way,
  // and twinpost does not write the mode there.
  machine sub = load_machine("integrex-i200st");
  for (spindle_def& s : sub.spindles)
    if (s.name == "sub") s.c_axis = {{"M300"}, {"M302"}, "M310", "M312"};
  CHECK(post_on("PARTNO E\nHEAD/1\nTLDATA/MILL,6\nLOADTL/21\nSPINDL/RPM,3000,CLW,SUB\nFEDRAT/MMPM,200\n"
                "RAPID\nGOTO/25,0,10,1,0,0\nGOTO/20,0,10\nFINI\n",
                sub, "cylinder-sub")
            .diagnostics ==
        "job.cls:9:1: error: channel 1: a feed move with the tool across the spindle axis on the sub "
        "spindle: twinpost writes cylindrical interpolation on the main spindle only (the second spindle's C "
        "turns the other way)\nGOTO/20,0,10\n^\n");
}

TEST_CASE(
    "a cross tap: the head at B90, C at the hole and clamped, the turned frame, G84.2 at the pitch in G95",
    "[post][millturn]") {
  const std::string cl =
      "PARTNO E\nHEAD/1\nTLDATA/DRILL,6,0\nLOADTL/23\nSPINDL/RPM,500,CLW,LIVE\nRAPID\n"
      "GOTO/0,35,-20,0,1,0\nCYCLE/TAP,DEPTH,10,RAPTO,3,PITCH,1\nGOTO/0,25,-20\nCYCLE/OFF\nRAPID\n"
      "GOTO/0,35,-20\nSPINDL/RPM,500,CCLW\nCYCLE/TAP,DEPTH,10,RAPTO,3,PITCH,1\nGOTO/-25,0,-30,-1,0,0\n"
      "CYCLE/OFF\nFINI\n";
  const test::posted p = post_on(cl, load_machine("integrex-i200st"), "cross-tap");
  // The live spindle taps (M3, then M4 for the left-hand tap: G84.3), feed per revolution at
  // the pitch (G95 F1.), the spindle's speed and feed mode (G94) again after each rigid tap; C
  // unclamped only to turn to the next hole (C180: the point at -X).
  CHECK(head1(p, "E.EIA") ==
        "G109 L1\nG21\nG0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG10.9 X1\nG0 G90 G53 X0. Y0.\nG0 G90 G53 "
        "Z0.\nT23 M6\nM901\n"
        "M200\nG10.9 X0\nG97 S500 M3\nM108\nG0 G53 B90.\nM107\nG0 C90.\nM210\n"
        "G68 X0. Y0. Z0. I0. J1. K0. R90.\nG0 G43 H#3020 X20. Y0. Z35.\nZ28.\nG95\nG17\n"
        "G98 G84.2 X20. Y0. Z15. R28. F1.\nG80\nG18\nG0 Z28.\nG97 S500 M3\nG94\nZ35.\nG97 S500 M4\nG69\n"
        "M212\nG0 C180.\nM210\nG68 X0. Y0. Z0. I0. J1. K0. R90.\nG0 X30. Y0. Z28.\nG95\nG17\n"
        "G98 G84.3 X30. Y0. Z15. R28. F1.\nG80\nG18\nG0 Z28.\nG97 S500 M4\nG94\nM950\nG69\nM212\nG10.9 X1\n"
        "M202\nM9\nM5\nM205\nM305\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM30\n");
  // A machine whose taps are written as moves (G32 with the spindle reversed) cannot tap with a
  // live tool: G32 follows the workpiece spindle.
  machine expanded = load_machine("integrex-i200st");
  expanded.cycles.tap = "expanded";
  expanded.cycles.sync_feed = "G32";
  CHECK(
      post_on(cl, expanded, "cross-tap-expanded").diagnostics ==
      "job.cls:9:1: error: channel 1: CYCLE/TAP with a live tool on machine 'integrex-i200st', whose tapping "
      "is written as moves ([cycles] tap = \"expanded\"): G32 follows the workpiece spindle, not the "
      "tool's; a live tap needs the control's tapping cycle\nGOTO/0,25,-20\n^\n"
      "job.cls:15:1: error: channel 1: CYCLE/TAP with a live tool on machine 'integrex-i200st', whose "
      "tapping is written as moves ([cycles] tap = \"expanded\"): G32 follows the workpiece spindle, not "
      "the tool's; a live tap needs the control's tapping cycle\nGOTO/-25,0,-30,-1,0,0\n^\n");
}

TEST_CASE("cutter compensation on the diameter starts and ends inside cylindrical interpolation",
          "[post][millturn]") {
  const std::string cl =
      "PARTNO E\nHEAD/1\nTLDATA/MILL,6\nLOADTL/21\nSPINDL/RPM,3000,CLW\nFEDRAT/MMPM,200\nRAPID\n"
      "GOTO/25,0,-10,1,0,0\nGOTO/20,0,-10\nCUTCOM/LEFT\nGOTO/0,20,-10,0,1,0\nGOTO/-20,0,-10,-1,0,0\n"
      "CUTCOM/OFF\nGOTO/0,-20,-10,0,-1,0\nGOTO/0,-25,-10\nRAPID\nGOTO/0,-30,-10\nFINI\n";
  const test::posted p = post_on(cl, load_machine("integrex-i200st"), "cylinder-comp");
  const std::string h = head1(p, "E.EIA");
  CHECK(h.substr(h.find("G68"), h.find("M950") - h.find("G68")) ==
        "G68 X0. Y0. Z0. I0. J1. K0. R90.\nG0 G43 H#3020 X10. Y0. Z25.\nG1 Z20. F200.\nM212\nG17\nG7.1 C20.\n"
        "G41 G1 C90.\nC180.\nG40 C270.\nZ25.\nG7.1 C0\nG18\nG0 Z30.\n");
}

TEST_CASE("polar interpolation ends with cutter compensation cancelled", "[post][millturn]") {
  // Review 38: a CL that left CUTCOM/LEFT on at GOHOME kept `G41` through `G13.1` and the home
  // blocks. Compensation is taken off on a move before the mode ends: the CL's lead-out after
  // CUTCOM/OFF carries `G40`; a CUTCOM/OFF with no move after it (a `G40` alone would shift the
  // cutter by its radius at depth: review 38b P1) and one never given stop the post.
  const std::string cl =
      "PARTNO CC\nHEAD/1\nTLDATA/MILL,10,0,75\nLOADTL/14\nSPINDL/RPM,3000,CLW,MAIN\nFEDRAT/MMPM,300\n"
      "RAPID\nGOTO/40,0,10,0,0,1\nRAPID\nGOTO/40,0,-3\nCUTCOM/LEFT\nGOTO/30,0,-3\nGOTO/30,10,-3\n";
  const machine integrex = load_machine("integrex-i200st");
  const std::string h =
      head1(post_on(cl + "CUTCOM/OFF\nGOTO/30,20,-3\nGOHOME\nFINI\n", integrex, "polar-comp-out"), "CC.EIA");
  CHECK(h.substr(h.find("G41"), h.find("M950") - h.find("G41")) ==
        "G41 G1 X30. F300.\nC10.\nG40 C20.\nG13.1\nG18\nG0 G90 G53 Z0.\nG0 G90 G53 X0. Y0.\n");
  for (const auto& [end, why] :
       {std::pair{
            "CUTCOM/OFF\nGOHOME\nFINI\n",
            "polar interpolation ends with CUTCOM/OFF given and no move after it: the control takes the "
            "offset off on a move, and G40 alone would shift the cutter by its radius where it stands; "
            "give a lead-out move after CUTCOM/OFF\nGOHOME\n^\n"},
        {"GOHOME\nFINI\n",
         "polar interpolation ends with cutter compensation on (CUTCOM/LEFT or RIGHT without CUTCOM/OFF): it "
         "is cancelled with G40 in force; give CUTCOM/OFF and a lead-out move before GOHOME, the tool change "
         "or the end of the face milling\nGOHOME\n^\n"}}) {
    const test::posted p = post_on(cl + end, integrex, "polar-comp-left");
    CHECK_FALSE(p.ok);
    CHECK(p.files.empty());
    const std::string at = std::string(end).starts_with("CUTCOM") ? "15" : "14";
    CHECK(p.diagnostics == "job.cls:" + at + ":1: error: channel 1: " + why);
  }
}

TEST_CASE("the head's offset follows the spindle the tool cuts with, and a SPINDL after it stops the post",
          "[post][millturn]") {
  // Attack 69 H1: a centre drill whose SPINDL (the main spindle: the part turns) came after its
  // approach was written with the live tool's `G43 H#3020` left from the end mill before it.
  const std::string cl =
      "PARTNO H5\nHEAD/1\nTLDATA/MILL,10\nLOADTL/11\nSPINDL/RPM,3000,CLW,LIVE\nFEDRAT/MMPM,200\nRAPID\n"
      "GOTO/0,0,10,0,0,1\nGOTO/0,0,-1\nRAPID\nGOTO/0,0,10\nSPINDL/OFF\nTLDATA/DRILL,10,118\nLOADTL/12\n";
  const std::string drill = "FEDRAT/0.1,MMPR\nGOTO/0,0,-20\nRAPID\nGOTO/0,0,10\nSPINDL/OFF\nFINI\n";
  const machine integrex = load_machine("integrex-i200st");
  const std::string h = head1(
      post_on(cl + "SPINDL/RPM,800,CLW,MAIN\nRAPID\nGOTO/0,0,10,0,0,1\n" + drill, integrex, "offset-main"),
      "H5.EIA");
  CHECK(h.substr(h.find("T12 M6"), h.find("G1 Z-20.") - h.find("T12 M6")) ==
        "T12 M6\nM901\nG10.9 X1\nM202\nG97 S800 M203\nM108\nG0 G53 B0.\nM107\nG0 G43 P1 H#3020 X0. Y0. "
        "Z10.\nG95\n");
  const test::posted late =
      post_on(cl + "RAPID\nGOTO/0,0,10,0,0,1\nSPINDL/RPM,800,CLW,MAIN\n" + drill, integrex, "offset-late");
  CHECK(late.files.empty());
  CHECK(
      late.diagnostics ==
      "job.cls:17:1: error: channel 1: SPINDL turns the main spindle for this tool after its first move gave "
      "the head's offset for a live tool (`G43 H#3020`); the tool wants `G43 P1 H#3020`: give the SPINDL "
      "before the tool's first GOTO\nSPINDL/RPM,800,CLW,MAIN\n^\n");
}

TEST_CASE("a hole's cycle straight from a cut below its R level stops the post", "[post][millturn]") {
  // Review 38b P3: an end mill 3 mm deep, then CYCLE/DRILL with no retract: the post wrote
  // `G0 C0.` (the part turned under the cutter) and `X20. Y10. Z2.` from the cut.
  const std::string cl =
      "PARTNO PK\nHEAD/1\nTLDATA/MILL,10,0,75\nLOADTL/14\nSPINDL/RPM,3000,CLW,MAIN\nFEDRAT/MMPM,300\n"
      "RAPID\nGOTO/40,0,10,0,0,1\nRAPID\nGOTO/40,0,-3\nGOTO/30,0,-3\nGOTO/30,10,-3\n";
  const std::string hole =
      "CYCLE/DRILL,FEDTO,-10.0,RAPTO,2.0,MMPM,100\nGOTO/20,20,0\nCYCLE/OFF\nGOHOME\nFINI\n";
  const machine integrex = load_machine("integrex-i200st");
  const test::posted p = post_on(cl + hole, integrex, "hole-from-cut");
  CHECK(p.files.empty());
  CHECK(
      p.diagnostics ==
      "job.cls:14:1: error: channel 1: CYCLE/DRILL: the hole's cycle starts straight from a cut, 5 below its "
      "R level: the control would position it across the tool there, through the part; give the retract "
      "before the cycle\nGOTO/20,20,0\n^\n");
  // A feed out to the R level or above first (a CL's retract at feed): the cycle as usual.
  CHECK(post_on(cl + "GOTO/30,10,5\n" + hole, integrex, "hole-after-feed-out").ok);
}

TEST_CASE("the B head faces the sub spindle for work there, or the post stops", "[post][millturn]") {
  // After M902 the Integrex head turns half a turn (B180) for a drill on the second spindle's
  // centre: at B0 it would point at the main spindle, the drill's back end towards the part.
  const std::string drill =
      "PARTNO D\nHEAD/1\nTLDATA/DRILL,8,118\nLOADTL/4\nSPINDL/RPM,700,CLW,SUB\nFEDRAT/0.1,MMPR\nRAPID\n"
      "GOTO/0,0,5\nGOTO/0,0,-10\nFINI\n";
  const test::posted p = post_on(drill, load_machine("integrex-i200st"), "sub-b180");
  INFO(p.diagnostics);
  CHECK(head1(p, "D.EIA") ==
        "G109 L1\nG21\nG0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG10.9 X1\nG0 G90 G53 X0. Y0.\n"
        "G0 G90 G53 Z0.\nT04 M6\nG55\nM902\nG97 S700 M303\nG95\nM108\nG0 G53 B180.\nM107\n"
        "G0 G43 P1 H#3020 X0. Y0. Z-5.\nG1 Z10. F0.1\nG0 Z-5.\nM950\nM9\nM5\nM205\nM305\n"
        "G0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM30\n");
  // A machine file that gives no angle for the sub: the post stops at the move.
  machine m = load_machine("integrex-i200st");
  m.channels[0].head_index.axial_sub.reset();
  const test::posted none = post_on(drill, m, "sub-none");
  CHECK_FALSE(none.ok);
  const std::string why =
      "error: channel 1: channel 1 indexes its B head for every tool, and channel.head_index.axial_sub is "
      "not "
      "given: where the axial tool must point on the sub spindle is unknown\n";
  CHECK(none.diagnostics ==
        "job.cls:8:1: " + why + "GOTO/0,0,5\n^\njob.cls:9:1: " + why + "GOTO/0,0,-10\n^\n");
  // The 31i's mill head (path 3): face work on the sub at B90 (the Fusion Doosan post's range
  // -45..90 there), turning tools across the axis at B0 as on the main spindle.
  const test::posted f = post_on(
      "PARTNO D\nHEAD/3\nTLDATA/DRILL,8,118\nLOADTL/4\nSPINDL/RPM,700,CLW,SUB\nFEDRAT/0.1,MMPR\nRAPID\n"
      "GOTO/0,0,5\nGOTO/0,0,-10\nTLDATA/TURN\nLOADTL/5\nSPINDL/RPM,900,CLW\nRAPID\nGOTO/20,0,2\nFINI\n",
      load_machine("fanuc-31i-3path"), "sub-31i");
  INFO(f.diagnostics);
  const std::string nc = f.files.at("D_3.nc");
  CHECK(nc.substr(nc.find("M6 T04")) ==
        "M6 T0400\nT0404\nG55\nG97 S700 M103\nG0 B90.\nG0 X0. Y0. Z-5.\nG1 Z10. F0.1\nG0 Z-5.\n"
        "G28 U0. V0.\nG28 W0.\nM6 T0500\nT0505\nG97 S900 M103\nG0 B0.\nG0 X40. Y0. Z-2.\n"
        "M200 P123\nM105\nM9\nG28 U0. V0.\nG28 W0.\nM30\n%\n");
}

TEST_CASE("the 31i's B head changes the tool with M6 T0700 and takes its offset with T0707",
          "[post][millturn]") {
  // The Fusion Doosan Mill/Turn (31i) post: the tool change carries offset 00, the offset comes
  // by the T code after it, as on the turrets; a new offset for the same tool is that T alone,
  // and the next move gives every axis again (the control applies the new offset to each axis
  // as it next moves).
  const test::posted p = post_on(
      "PARTNO E\nHEAD/3\nTLDATA/TURN\nLOADTL/7\nSPINDL/RPM,900,CLW\nFEDRAT/0.2,MMPR\nGOTO/20,0,2\n"
      "LOADTL/7,27\nGOTO/20,0,1\nFINI\n",
      load_machine("fanuc-31i-3path"), "31i-offset");
  INFO(p.diagnostics);
  const std::string nc = p.files.at("E_3.nc");
  CHECK(nc.substr(0, nc.find("M200")) ==
        "%\nO1000 (E)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0. V0.\nG28 W0.\nM6 T0700\nT0707\nG97 S900 M3\n"
        "G0 B0.\nG1 X40. Y0. Z2. F0.2\nT0727\nX40. Y0. Z1.\n");
}

TEST_CASE("a drill's rapid out of a hole and round to the next rises before C turns", "[post][millturn]") {
  // Attack 60 F4: two holes on the 40 mm pitch circle drilled with moves, the link fed at z 2,
  // then the CL's rapid straight up to z 10 over the second hole. The writer positions C for a
  // drill's rapid; turned first, at z 2, the part swept under the tip 2 mm over the face (and the
  // comparison with the CL refused the post). It rises first now.
  const std::string cl =
      "PARTNO L\nHEAD/1\nTLDATA/DRILL,5,118\nLOADTL/12\nSPINDL/RPM,2500,CLW,LIVE\nFEDRAT/MMPM,150\nRAPID\n"
      "GOTO/20,0,10,0,0,1\nRAPID\nGOTO/20,0,2\nGOTO/20,0,-10\nGOTO/20,0,2\nGOTO/-10,17.3205081,2\n"
      "GOTO/-10,17.3205081,-10\nGOTO/-10,17.3205081,2\nRAPID\nGOTO/-10,17.3205081,10\nSPINDL/OFF\nFINI\n";
  const test::posted p = post_on(cl, load_machine("integrex-i200st"), "rise");
  const std::string h = head1(p, "L.EIA");
  // C is clamped for the holes (M210 before the first feed) and unclamped to turn (review 61 B3).
  CHECK(h.find("Z2.\nM210\nG1 Z-10. F150.") != std::string::npos);
  CHECK(h.substr(h.find("G1 Z-10. F150.")) ==
        "G1 Z-10. F150.\nZ2.\nX-10. Y17.321\nZ-10.\nZ2.\nG0 Z10.\nM212\nG0 C120.\nX20. Y0. "
        "Z10.\nM5\nM950\nG10.9 X1\n"
        "M202\nM9\nM205\nM305\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM30\n");
}

TEST_CASE("a cycle's own feed ends at CYCLE/OFF: the FEDRAT in force before it is back", "[post][millturn]") {
  // Review 55 L3: an end mill drills two holes (CYCLE/DRILL ... MMPM,150), then mills a flat in
  // polar interpolation under the FEDRAT of 400 mm/min given before the cycle. The flat ran at
  // the drill's F150. (and the comparison with the CL refused the post).
  const std::string cl =
      "PARTNO F\nHEAD/1\nTLDATA/MILL,10\nLOADTL/11\nSPINDL/RPM,3000,CLW,LIVE\nFEDRAT/MMPM,400\nRAPID\n"
      "GOTO/20,0,10,0,0,1\nCYCLE/DRILL,DEPTH,5,RAPTO,2,MMPM,150\nGOTO/20,0,0\nGOTO/-10,17.3205081,0\n"
      "CYCLE/OFF\nRAPID\nGOTO/40,25,5\nGOTO/40,25,-3\nGOTO/-40,25,-3\nRAPID\nGOTO/-40,25,5\nSPINDL/"
      "OFF\nFINI\n";
  const test::posted p = post_on(cl, load_machine("integrex-i200st"), "cycle-feed");
  const std::string h = head1(p, "F.EIA");
  CHECK(
      h.substr(h.find("G0 X40. C25. Z5.")) ==
      "G0 X40. C25. Z5.\nG1 Z-3. F400.\nX-40.\nG0 Z5.\nM5\nM950\nG13.1\nG18\nG10.9 X1\nM202\nM9\nM205\nM305\n"
      "G0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM30\n");
}

TEST_CASE("a home straight from a cut leaves along the tool first", "[post][millturn]") {
  // Review 61 A2: a drill fed to the bottom of its hole, then GOHOME with no retract in the CL.
  // The upper head's home is X and Y, then Z (the Fusion "Mazak Integrex i" post's order, which
  // counts on the CAM's retract): the drill went sideways through the part. From a cut the
  // block along the tool comes first now; after a rapid the machine's order stands.
  const std::string cl =
      "PARTNO H\nHEAD/1\nTLDATA/DRILL,6,118\nLOADTL/12\nSPINDL/RPM,2000,CLW,LIVE\n"
      "FEDRAT/MMPM,120\nRAPID\nGOTO/0,25,10,0,0,1\nRAPID\nGOTO/0,25,2\nGOTO/0,25,-10\n";
  const machine integrex = load_machine("integrex-i200st");
  const std::string h = head1(post_on(cl + "GOHOME\nFINI\n", integrex, "home-cut"), "H.EIA");
  CHECK(h.substr(h.find("G1 Z-10. F120.")) ==
        "G1 Z-10. F120.\nG0 G90 G53 Z0.\nG0 G90 G53 X0. Y0.\nM950\nM212\nG10.9 X1\nM202\nM9\nM5\nM205\nM305\n"
        "G0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM30\n");
  const std::string r =
      head1(post_on(cl + "RAPID\nGOTO/0,25,10\nGOHOME\nFINI\n", integrex, "home-rapid"), "H.EIA");
  CHECK(r.substr(r.find("G1 Z-10. F120.")) ==
        "G1 Z-10. F120.\nG0 Z10.\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM950\nM212\nG10.9 X1\nM202\nM9\nM5\n"
        "M205\nM305\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM30\n");  // Review 64 H1: a centre drill the part
                                                                   // turns against (the turning spindle,
                                                                   // M203) leaves
  // A cross drill (B90, the turned frame) at the bottom of its hole: X goes home alone first. The
  // upper head's home block moves Y with X (machine Y0 need not be the centre line): the drill
  // would be dragged sideways out of its hole (the thirty-fourth note's open item). Then the
  // whole block, and Z.
  const std::string cross =
      "PARTNO H\nHEAD/1\nTLDATA/DRILL,6,118\nLOADTL/12\nSPINDL/RPM,2000,CLW,LIVE\nFEDRAT/MMPM,120\nRAPID\n"
      "GOTO/40,0,-20,1,0,0\nRAPID\nGOTO/32,0,-20\nGOTO/20,0,-20\nGOHOME\nFINI\n";
  const std::string x = head1(post_on(cross, integrex, "home-cross"), "H.EIA");
  CHECK(x.substr(x.find("G1 Z20. F120.")) ==
        "G1 Z20. F120.\nG69\nG0 G90 G53 X0.\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM950\nM212\nG10.9 "
        "X1\nM202\nM9\n"
        "M5\nM205\nM305\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM30\n");
  // A CL that ends in the cut (FINI with no retract): out along the tool before the last wait
  // (the other head's footer may stop a spindle), the C axis let go and the spindle stopped, and
  // the footer leaves out the home block already written (review 37 H1: the footer's X0. Y0.
  // came first, the spindle stopped with the drill 30 mm deep).
  const std::string axial_end =
      "PARTNO H\nHEAD/1\nTLDATA/DRILL,10,118\nLOADTL/11\nSPINDL/RPM,1200,CLW\nFEDRAT/0.12,MMPR\nRAPID\n"
      "GOTO/0,0,5,0,0,1\nGOTO/0,0,-30\nFINI\n";
  const std::string ae = head1(post_on(axial_end, integrex, "end-axial"), "H.EIA");
  CHECK(ae.substr(ae.find("G1 Z-30. F0.12")) ==
        "G1 Z-30. F0.12\nG0 G90 G53 Z0.\nM950\nM9\nM5\nM205\nM305\nG0 G90 G53 X0. Y0.\nM30\n");
  std::string cross_end = cross;
  cross_end.replace(cross_end.find("GOHOME\n"), 7, "");
  const std::string xe = head1(post_on(cross_end, integrex, "end-cross"), "H.EIA");
  CHECK(xe.substr(xe.find("G1 Z20. F120.")) ==
        "G1 Z20. F120.\nG69\nG0 G90 G53 X0.\nM950\nM212\nG10.9 X1\nM202\nM9\nM5\nM205\nM305\n"
        "G0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM30\n");
  // Home blocks glued, in lower case or with a comment are read as the checker reads them
  // (attack 67 H7, M8: `G28U0.` went first from the hole, `G28 U0. (RETURN Z AND X)` came out
  // `G28 (RETURN Z`): the drill leaves along Z first, and a comment stays whole.
  const std::string lathe_drill =
      "PARTNO D\nHEAD/1\nTURRET/1,1\nTLDATA/DRILL,8.0,118.0,50.0\nSPINDL/RPM,1000,CLW\nFEDRAT/0.1,MMPR\n"
      "RAPID\nGOTO/0,0,5\nGOTO/0,0,-30\nTURRET/3,3\nRAPID\nGOTO/40,0,5\nFINI\n";
  for (const auto& [home, out] :
       {std::pair{std::vector<std::string>{"G28U0.", "G28W0."}, "G28W0.\nG28U0.\n"},
        {{"g28 u0.", "g28 w0."}, "g28 w0.\ng28 u0.\n"},
        {{"G28 U0. W0. (RETURN X AND Z)"}, "G28 W0. (RETURN X AND Z)\nG28 U0. W0. (RETURN X AND Z)\n"}}) {
    machine twin = load_machine("fanuc-0itd-twin");
    twin.codes.home = home;
    const test::posted p = post_on(lathe_drill, twin, "home-glued");
    INFO(p.diagnostics);
    REQUIRE(p.ok);
    const std::string& f = p.files.at("D_1.nc");
    CHECK(f.substr(f.find("G1 Z-30. F0.1\n"), 14 + std::string(out).size()) ==
          "G1 Z-30. F0.1\n" + std::string(out));
  }
  // along Z too. On the second spindle (Z reversed) Z's home lies beyond its face, deeper into
  // its part, and the head's home moves X and Y first: the drill goes back along its axis to the
  // level of its last rapid, in the work frame (review 37 H2: it went X Y first from 30 deep,
  // with a warning only), then home as after a retract.
  const std::string centre =
      "PARTNO H\nHEAD/1\nTLDATA/DRILL,10,118\nLOADTL/11\nSPINDL/RPM,1200,CLW\n"
      "FEDRAT/0.12,MMPR\nRAPID\nGOTO/0,0,5,0,0,1\nGOTO/0,0,-30\nGOHOME\nFINI\n";
  const std::string c = head1(post_on(centre, integrex, "home-centre"), "H.EIA");
  CHECK(c.find("G1 Z-30. F0.12\nG0 G90 G53 Z0.\nG0 G90 G53 X0. Y0.\n") != std::string::npos);
  std::string on_sub = centre;
  on_sub.replace(on_sub.find("SPINDL/RPM,1200,CLW"), 19, "SPINDL/RPM,1200,CLW,SUB");
  const std::string sh = head1(post_on(on_sub, integrex, "home-centre-sub"), "H.EIA");
  CHECK(sh.substr(sh.find("G1 Z30. F0.12")) ==
        "G1 Z30. F0.12\nG0 Z-5.\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM950\nM9\nM5\nM205\nM305\n"
        "G0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM30\n");
  // `on_sub` with its first `from` replaced by `to`, posted: the upper head's program from the
  // block `at` on.
  auto sub_edit = [&](const std::string& from, const std::string& to, const std::string& tag,
                      const std::string& at) {
    std::string job = on_sub;
    job.replace(job.find(from), from.size(), to);
    const std::string h = head1(post_on(job, integrex, tag), "H.EIA");
    return h.substr(h.find(at));
  };
  // The same at the end of the CL (no GOHOME), and at a tool change.
  CHECK(sub_edit("GOHOME\n", "", "end-centre-sub", "G1 Z30. F0.12") ==
        "G1 Z30. F0.12\nG0 Z-5.\nM950\nM9\nM5\nM205\nM305\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM30\n");
  CHECK(sub_edit("GOHOME\n", "TLDATA/DRILL,8,118\nLOADTL/14\nRAPID\nGOTO/0,0,5\n", "tc-centre-sub",
                 "G1 Z30. F0.12")
            .substr(0, 73) ==
        "G1 Z30. F0.12\nG0 Z-5.\nM305\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nT14 M6\nM902\n");
  // The most retracted level of the tool's rapids, not the last (review 38 H1: an expanded
  // peck's rapid back into the hole, 0.5 above its last depth, was taken for the way out).
  CHECK(sub_edit("GOTO/0,0,-30\n", "GOTO/0,0,-10\nRAPID\nGOTO/0,0,2\nRAPID\nGOTO/0,0,-9.5\nGOTO/0,0,-30\n",
                 "peck-centre-sub", "Z9.5") ==
        "Z9.5\nG1 Z30.\nG0 Z-5.\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM950\nM9\n"
        "M5\nM205\nM305\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM30\n");
  // Only a rapid above the point the tool stands at counts (attack 69 M2: the tool change's
  // rapid 400 out at X200 sent the drill 400 mm along the centre line towards the main spindle).
  CHECK(sub_edit("RAPID\nGOTO/0,0,5,0,0,1\n", "RAPID\nGOTO/200,0,400,0,0,1\nRAPID\nGOTO/0,0,5\n",
                 "far-centre-sub", "G1 Z30. F0.12")
            .substr(0, 41) == "G1 Z30. F0.12\nG0 Z-5.\nG0 G90 G53 X0. Y0.\n");
  // Fed back out to that level (a reamer's way out): no retract to add (review 38 M5: refused).
  CHECK(sub_edit("GOTO/0,0,-30\n", "GOTO/0,0,-30\nGOTO/0,0,5\n", "ream-centre-sub", "G1 Z30. F0.12") ==
        "G1 Z30. F0.12\nZ-5.\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM950\nM9\n"
        "M5\nM205\nM305\nG0 G90 G53 X0. Y0.\nG0 G90 G53 Z0.\nM30\n");
  // With no rapid of the tool to go back to, the post cannot know a way out: an error.
  std::string no_rapid = on_sub;
  no_rapid.replace(no_rapid.find("RAPID\n"), 6, "");
  const test::posted nr = test::post_in_fresh_dir(no_rapid, integrex, "millturn-home-centre-sub-norapid",
                                                  [](const diagnostic&) { return true; });
  CHECK_FALSE(nr.ok);
  CHECK(nr.files.empty());
  CHECK(nr.diagnostics ==
        "job.cls:9:1: error: channel 1: the tool is left in a cut on the sub spindle, which faces the main "
        "one, with no retract in the CL and no rapid of this tool above that point on that spindle to go "
        "back to: its home blocks would move it across its hole, then towards that spindle; give the retract "
        "before GOHOME, the tool change or the end\n"
        "GOHOME\n^\n");
}

TEST_CASE("live work on the main spindle, then a tool on the sub: the main's C axis let go first",
          "[post][millturn]") {
  // Review 64 M7: the main spindle held as the C axis (M200, clamped M210) for a live drill, then
  // a turning tool on the second spindle: M212 and M202 never came, and the second spindle's
  // empty unclamp code was written as an empty block after M902.
  const std::string cl =
      "PARTNO S\nHEAD/1\nTLDATA/DRILL,5,118\nLOADTL/12\nSPINDL/RPM,2500,CLW,LIVE\nFEDRAT/MMPM,150\nRAPID\n"
      "GOTO/20,0,10,0,0,1\nGOTO/20,0,-12\nRAPID\nGOTO/20,0,10\nTLDATA/TURN,0.8\nLOADTL/1\n"
      "SPINDL/SMM,180,MAXRPM,3000,CLW,SUB\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/30,0,5,0,0,1\nGOTO/25,0,2\n"
      "GOTO/25,0,-30\nRAPID\nGOTO/30,0,5\nFINI\n";
  const std::string h = head1(post_on(cl, load_machine("integrex-i200st"), "sub-after-c"), "S.EIA");
  CHECK(h.find("T01 M6\nM212\nG10.9 X1\nM202\nG55\nM902\nG92 S3000 R2\nG96 S180 M303\n") !=
        std::string::npos);
  CHECK(h.find("\n\n") == std::string::npos);
}

TEST_CASE("an axial drill after a tilted end mill is indexed at home, not in its first cut",
          "[post][millturn]") {
  // Review 64: the rotary axes the tilted tool left (B45 under G43.4) sent the drill's approach
  // through the chain (G43.4 with B0 C0, no clamp), and its first cut went home to index the
  // head; the comparison refused it ("the program moves in rapid" inside the feed).
  const std::string cl =
      "PARTNO T\nHEAD/1\nTLDATA/MILL,6\nLOADTL/11\nSPINDL/RPM,3000,CLW\nFEDRAT/MMPM,400\nRAPID\n"
      "GOTO/40,0,30,0.7071068,0,0.7071068\nGOTO/25,0,5,0.7071068,0,0.7071068\nGOTO/"
      "20,0,0,0.7071068,0,0.7071068\n"
      "RAPID\nGOTO/40,0,30,0.7071068,0,0.7071068\nTLDATA/DRILL,5,118\nLOADTL/12\nSPINDL/RPM,2500,CLW,LIVE\n"
      "FEDRAT/MMPM,150\nRAPID\nGOTO/20,0,10,0,0,1\nGOTO/20,0,-12\nRAPID\nGOTO/20,0,10\nFINI\n";
  const test::posted p = post_on(cl, load_machine("integrex-i200st"), "tilt-then-axial");
  const std::string h = head1(p, "T.EIA");
  CHECK(
      h.find("T12 M6\nM901\nG97 S2500 M3\nM108\nG0 G53 B0.\nM107\nG0 C0.\nG0 G43 H#3020 X20. Y0. Z10.\nM210\n"
             "G1 Z-12. F150.\nG0 Z10.\n") != std::string::npos);
}

TEST_CASE("a drill on the centre line with its axis pointing away from the part stops the post",
          "[post][millturn]") {
  // Attack 65: TLDATA/DRILL with the tool axis (0,0,-1) on the main spindle posted: the drill
  // would point away from the part it drills towards the chuck.
  const test::posted p = test::post_in_fresh_dir(
      "PARTNO "
      "D\nTLDATA/DRILL,10,118\nLOADTL/5\nSPINDL/RPM,1000,CLW\nFEDRAT/0.1,MMPR\nRAPID\nGOTO/0,0,5,0,0,-1\n"
      "GOTO/0,0,-20\nFINI\n",
      load_machine("fanuc-0itd-twin"), "drill-away",
      [](const diagnostic& d) { return d.level == severity::error; });
  CHECK_FALSE(p.ok);
  CHECK(p.diagnostics ==
        "job.cls:8:1: error: channel 1: tool 5 is a drill on the centre line of the main spindle with the "
        "tool axis "
        "(0,0,-1): it would point away from the part, which it drills towards the chuck (axis (0,0,1))\n"
        "GOTO/0,0,-20\n^\n");
}
