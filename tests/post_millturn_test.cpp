// Mill/turn on the Integrex upper head (formats/channel_millturn.cpp): the main spindle held as
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

double word(const std::string& block, char address, double fallback, bool* given = nullptr) {
  std::istringstream in(block);
  std::string w;
  while (in >> w)
    if (w[0] == address && w.size() > 1 &&
        (std::isdigit(static_cast<unsigned char>(w[1])) || w[1] == '-' || w[1] == '.')) {
      if (given) *given = true;
      return std::stod(w.substr(1));
    }
  if (given) *given = false;
  return fallback;
}

bool has(const std::string& block, const std::string& w) {
  return (" " + block + " ").find(" " + w + " ") != std::string::npos;
}

// The control as the Fusion Integrex post's blocks describe it: G10.9 X0/X1 radius or
// diameter, G12.1 with the Y value addressed as C (mm), G0 C.. turning the part (the point at
// angle C comes onto +X), G68 X0 Y0 Z0 I0 J1 K0 R90. turning the frame about Y (its Z along
// +X), G17 drilling cycles G81 X Y Z R along the frame's Z. Returns the part-frame tool tips of
// the moves and the hole bottoms, in order (machine-coordinate G53 blocks are skipped).
std::vector<vec3> tips(const std::string& program) {
  std::vector<vec3> out;
  bool radius = false, polar = false, turned = false;
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
    if (b.empty() || b[0] == '(' || has(b, "G53")) continue;
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
    bool gx = false, gy = false, gz = false, gc = false;
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
  // after a cycle) is listed twice.
  CHECK(seen ==
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
  CHECK(
      head1(p, "E.EIA") ==
      "G109 L1\nG21\nG0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG0 G90 G53 X0.\nG0 G90 G53 Z0.\nT05 M6\nM200\n"
      "G10.9 X0\nG97 S3000 M3\nG94\nM108\nG0 G53 B0.\nM107\nG0 C0.\nG17 XC\nG12.1\nG0 G43 H#3020 X10. C5. "
      "Z2.\n"
      "G1 Z-1. F300.\nG3 X-10. C5. I-10. J0.\nM5\nG13.1\nG18\nG0 G90 G53 X0.\nG0 G90 G53 Z0.\nT01 M6\n"
      "G10.9 X1\nM202\nM901\nG92 S2000 R1\nG96 S200 M203\nG95\nG0 G43 P1 H#3020 X60. Y0. "
      "Z2.\nM950\nM9\nM5\nM205\n"
      "M305\nG0 G90 G53 X0.\nG0 G90 G53 Z0.\nM30\n");
}

TEST_CASE("the B head turns only at home: a cross hole after face work goes home first", "[post][millturn]") {
  const std::string cl =
      "PARTNO E\nHEAD/1\nTLDATA/DRILL,5,118\nLOADTL/12\nSPINDL/RPM,2000,CLW,LIVE\nRAPID\n"
      "GOTO/20,0,5,0,0,1\nRAPID\nGOTO/40,0,-10,1,0,0\nFINI\n";
  const test::posted p = post_on(cl, load_machine("integrex-i200st"), "index");
  CHECK(
      head1(p, "E.EIA") ==
      "G109 L1\nG21\nG0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG0 G90 G53 X0.\nG0 G90 G53 Z0.\nT12 M6\nM200\n"
      "G10.9 X0\nG97 S2000 M3\nM108\nG0 G53 B0.\nM107\nG0 C0.\nG0 G43 H#3020 X20. Y0. Z5.\nG0 G90 G53 X0.\n"
      "G0 G90 G53 Z0.\nM108\nG0 G53 B90.\nM107\nM210\nG68 X0. Y0. Z0. I0. J1. K0. R90.\n"
      "G0 G43 H#3020 X10. Y0. Z40.\nM950\nG69\nM212\nG10.9 X1\nM202\nM9\nM5\nM205\nM305\nG0 G90 G53 X0.\n"
      "G0 G90 G53 Z0.\nM30\n");
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
  CHECK(
      head1(p, "E.EIA") ==
      "G109 L1\nG21\nG0 G90 G54 G97 G18\nG40 G49 G80 G67 G69\nG0 G90 G53 X0.\nG0 G90 G53 Z0.\nT14 M6\nM200\n"
      "G10.9 X0\nG97 S4000 M3\nG94\nM108\nM212\nG0 G43.4 H#3020 X40. Y0. Z10. B45. C0.\nG1 X29. Z-1. F300.\n"
      "X0. Y29. C90.\nG0 Y40. Z10.\nM950\nG49\nG10.9 X1\nM202\nM9\nM5\nM205\nM305\nG0 G90 G53 X0.\n"
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
