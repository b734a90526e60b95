// machining/channel_multiaxis: multi-axis output read back. Every block posted on a machine with
// a kinematic chain is taken through the forward transform (as a machinist's simulator would
// read the words) and held to the CL: each CL point is reached within the chain's tolerance,
// every point in between lies on the CL segment, and the tip of the joints as the control
// interpolates them stays within the chordal tolerance of the segment.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "file_test_support.hpp"
#include "kinematics/forward.hpp"
#include "kinematics/linearise.hpp"
#include "kinematics/vec3_ops.hpp"
#include "machines/machine_loader.hpp"
#include "post_test_jobs.hpp"

using namespace twinpost;

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

struct cl_point {
  kin::tool_pose pose;
  bool rapid = false;
};

// The GOTO points of a CL job (absolute, mm, i,j,k modal), and TLDATA/MILL's length. An NX
// MSYS turns them into the absolute frame's directions: x·X + y·Y + z·(X × Y), its two columns
// as NX describes them (the test's own reading, not the post's).
std::vector<cl_point> cl_points(const std::string& cl, double& length) {
  std::vector<cl_point> out;
  std::istringstream in(cl);
  vec3 axis{0, 0, 1};
  vec3 frame[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const auto turned = [&](const vec3& v) {
    return vec3{v.x * frame[0].x + v.y * frame[1].x + v.z * frame[2].x,
                v.x * frame[0].y + v.y * frame[1].y + v.z * frame[2].y,
                v.x * frame[0].z + v.y * frame[1].z + v.z * frame[2].z};
  };
  bool rapid = false;
  for (std::string line; std::getline(in, line);) {
    auto numbers = [&] {
      std::vector<double> v;
      std::string s = line.substr(line.find('/') + 1);
      for (char& c : s)
        if (c == ',') c = ' ';
      std::istringstream w(s);
      for (std::string t; w >> t;) {
        char* end = nullptr;
        const double d = std::strtod(t.c_str(), &end);
        if (end && *end == 0) v.push_back(d);
      }
      return v;
    };
    if (line.rfind("RAPID", 0) == 0) rapid = true;
    if (line.rfind("TLDATA/MILL", 0) == 0) length = numbers()[2];
    if (line.rfind("MSYS/", 0) == 0) {
      const std::vector<double> m = numbers();
      frame[0] = {m[3], m[4], m[5]};
      frame[1] = {m[6], m[7], m[8]};
      frame[2] = kin::cross(frame[0], frame[1]);
    }
    if (line.rfind("GOTO/", 0) != 0) continue;
    const std::vector<double> v = numbers();
    if (v.size() == 6) {
      const double n = std::sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5]);
      axis = {v[3] / n, v[4] / n, v[5] / n};
    }
    out.push_back({{turned({v[0], v[1], v[2]}), turned(axis)}, rapid});
    rapid = false;
  }
  return out;
}

// One motion block of the program: the words in force after it.
struct nc_point {
  kin::joint_values joints;
  vec3 ijk{0, 0, 1};
  bool rapid = false;
  std::string text;
  /// In a tilted working plane (G68.2 X0 Y0 Z0 I J K): its axes in the part frame; X Y Z are
  /// the tip in it.
  bool in_plane = false;
  vec3 frame[3];
  bool after_home = false;  ///< a reference return (G28) came between it and the point before
};

std::vector<nc_point> nc_points(const std::string& nc, const kinematic_chain& c) {
  std::vector<nc_point> out;
  std::map<char, double> words;
  bool rapid = true, started = false, in_plane = false, homed = false;
  vec3 frame[3];
  std::istringstream in(nc);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '(' || line[0] == ';' || line[0] == '%' || line[0] == 'O') continue;
    // Without a length code (pivot output) the points start after the tool call.
    if (offset_code(c).empty() && line.find(" M6") != std::string::npos) started = true;
    if (line.find("G28") != std::string::npos) {
      homed = true;
      continue;
    }
    if (line == "G53.1") continue;
    if (line.rfind("G68.2 X0. Y0. Z0. I", 0) == 0) {
      // Z-X-Z Euler angles: the plane's axes are Rz(I) Rx(J) Rz(K) applied to the part's.
      double e[3];
      REQUIRE(std::sscanf(line.c_str(), "G68.2 X0. Y0. Z0. I%lf J%lf K%lf", &e[0], &e[1], &e[2]) == 3);
      const vec3 basis[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
      for (int i = 0; i < 3; ++i)
        frame[i] = kin::rotate(kin::rotate(kin::rotate(basis[i], {0, 0, 1}, e[2]), {1, 0, 0}, e[1]),
                               {0, 0, 1}, e[0]);
      in_plane = true;
      words.clear();
      continue;
    }
    if (line == "G69") {
      in_plane = false;
      words.clear();
      continue;
    }
    bool moves = false;
    std::istringstream w(line);
    for (std::string t; w >> t;) {
      const char a = t[0];
      const double v = std::stod(t.substr(1));
      if (a == 'G' && (v == 0 || v == 1)) rapid = v == 0;
      if (a == 'G' && (v == 43 || v == 43.4 || v == 43.5)) started = true;
      if (std::string("XYZABCIJK").find(a) != std::string::npos) {
        words[a] = v;
        moves = true;
      }
    }
    if (!moves || !started) continue;
    nc_point p;
    p.rapid = rapid;
    p.text = line;
    p.after_home = homed;
    homed = false;
    p.joints.linear = {words[c.linear[0]], words[c.linear[1]], words[c.linear[2]]};
    if (c.output == multiaxis_output::pivot)
      p.joints.linear = kin::operator-(p.joints.linear, pivot_shift(c));
    for (std::size_t i = 0; i < c.rotaries.size(); ++i) p.joints.rotary[i] = words[c.rotaries[i].address];
    p.ijk = {words['I'], words['J'], words['K']};
    p.in_plane = in_plane;
    for (int i = 0; i < 3; ++i) p.frame[i] = frame[i];
    out.push_back(p);
  }
  return out;
}

// Where the words put the tool: the forward transform of the joints, or under tool-tip control
// the tip itself with the axis of the rotary values (G43.4) or I J K (G43.5).
kin::tool_pose pose_of(const kinematic_chain& c, const nc_point& p, double length) {
  if (p.in_plane) {
    const vec3& l = p.joints.linear;
    return {kin::operator+(kin::operator+(kin::operator*(l.x, p.frame[0]), kin::operator*(l.y, p.frame[1])),
                           kin::operator*(l.z, p.frame[2])),
            p.frame[2]};
  }
  switch (c.output) {
    case multiaxis_output::joints:
    case multiaxis_output::pivot: return kin::forward(c, p.joints, length);
    case multiaxis_output::tool_tip: return {p.joints.linear, kin::tool_axis(c, p.joints)};
    case multiaxis_output::vector: break;
  }
  return {p.joints.linear, p.ijk};
}

// How far the axis `a` is from the great circle arc between `a0` and `a1` (degrees).
double off_arc(const vec3& a, const vec3& a0, const vec3& a1) {
  return kin::angle_between(a0, a) + kin::angle_between(a, a1) - kin::angle_between(a0, a1);
}

struct round_trip {
  int cl_points = 0, blocks = 0, sub_points = 0;
  double worst_tip = 0, worst_axis = 0;  // at the CL points
  double worst_chord = 0;                // the joints' interpolation, from the segment
  double largest_swing = 0;              // degrees of one rotary axis between two CL points
  double uncut = 0;                      // the tip's worst deviation had a swing gone uncut
  int repositions = 0;                   // rapids on the way to a CL point (rotaries first, then X Y)
  int rapid_turns = 0;                   // rapids that turn a rotary axis
};

// Posts `cl` for `m` and reads every block back (see the file's comment).
round_trip read_back(const std::string& cl, const machine& m, const std::string& tag) {
  const test::posted p = test::post_in_fresh_dir(cl, m, tag);
  INFO(p.diagnostics);
  REQUIRE(p.ok);
  REQUIRE(p.files.size() == 1);
  const kinematic_chain& c = *m.chain(1);
  double length = 0;
  const std::vector<cl_point> cl_pts = cl_points(cl, length);
  const std::vector<nc_point> nc = nc_points(p.files.begin()->second, c);
  const double len = c.output == multiaxis_output::pivot ? c.programmed_length
                     : solves_joints(c)                  ? length
                                                         : 0;
  round_trip r;
  r.blocks = static_cast<int>(nc.size());
  std::size_t next = 0;  // the CL point the blocks are heading for
  kin::tool_pose at;     // the last CL point reached
  const nc_point* at_block = nullptr;
  const nc_point* prev = nullptr;
  for (const nc_point& b : nc) {
    INFO(b.text);
    const kin::tool_pose got = pose_of(c, b, len);
    // CL points the machine is already at write no block.
    while (next < cl_pts.size() && next > 0 && kin::distance(cl_pts[next].pose.tip, at.tip) < 1e-9 &&
           kin::angle_between(cl_pts[next].pose.axis, at.axis) < 1e-9)
      ++next;
    REQUIRE(next < cl_pts.size());
    const kin::tool_pose& target = cl_pts[next].pose;
    const double tip = kin::distance(got.tip, target.tip), axis = kin::angle_between(got.axis, target.axis);
    const bool feed = !b.rapid;
    if (b.rapid && prev && b.in_plane == prev->in_plane) {  // (G69 left the plane's words behind)
      // A rapid that turns a rotary axis moves no linear axis: the axes turn where the tool
      // stands clear (at the tool-change height, or the higher of two points), never on the
      // way down to the part (the Fusion posts' positionABC, then X Y, then Z).
      bool turns = false;
      for (std::size_t i = 0; i < c.rotaries.size(); ++i)
        turns = turns || std::abs(b.joints.rotary[i] - prev->joints.rotary[i]) > 1e-9;
      if (c.output == multiaxis_output::vector) turns = kin::angle_between(b.ijk, prev->ijk) > 1e-9;
      if (turns) {
        ++r.rapid_turns;
        CHECK(kin::distance(b.joints.linear, prev->joints.linear) < 1e-9);
        // Turning heads swing the tip about their pivot: it never passes below the higher of the
        // CL point the machine was at and the one the rapid goes to (the tool rises first).
        const bool heads = std::all_of(c.rotaries.begin(), c.rotaries.end(),
                                       [](const rotary_axis_def& a) { return a.kind == rotary_kind::head; });
        if (solves_joints(c) && heads && !b.after_home) {
          const auto up = [&](const kin::joint_values& j) { return kin::forward(c, j, len).tip.z; };
          const double top = std::max(at.tip.z, target.tip.z);
          for (int k = 1; k < 50; ++k)
            CHECK(up(kin::interpolate(c, prev->joints, b.joints, k / 50.0)) >= top - 0.002);
        }
      }
    }
    if (feed && prev && solves_joints(c)) {
      // The control interpolates the joints: the tip stays near the segment all the way.
      for (int k = 1; k < 50; ++k) {
        const kin::joint_values j = kin::interpolate(c, prev->joints, b.joints, k / 50.0);
        r.worst_chord = std::max(r.worst_chord,
                                 kin::distance_to_segment(kin::forward(c, j, len).tip, at.tip, target.tip));
      }
    }
    if (tip <= c.tolerance && axis <= c.angle_tolerance) {
      r.worst_tip = std::max(r.worst_tip, tip);
      r.worst_axis = std::max(r.worst_axis, axis);
      if (at_block && feed && solves_joints(c)) {
        for (std::size_t i = 0; i < c.rotaries.size(); ++i)
          r.largest_swing =
              std::max(r.largest_swing, std::abs(b.joints.rotary[i] - at_block->joints.rotary[i]));
        for (int k = 1; k < 50; ++k) {
          const kin::joint_values j = kin::interpolate(c, at_block->joints, b.joints, k / 50.0);
          r.uncut =
              std::max(r.uncut, kin::distance_to_segment(kin::forward(c, j, len).tip, at.tip, target.tip));
        }
      }
      at = target;
      at_block = &b;
      ++r.cl_points;
      ++next;
    } else if (b.rapid) {
      ++r.repositions;  // the rotaries alone, then X Y, before the rapid that reaches the point
    } else {
      // A point of a linearised move: on the segment towards the CL point.
      REQUIRE(feed);
      REQUIRE(next > 0);
      CHECK(kin::distance_to_segment(got.tip, at.tip, target.tip) <= c.tolerance);
      CHECK(off_arc(got.axis, at.axis, target.axis) <= c.angle_tolerance);
      ++r.sub_points;
    }
    prev = &b;
  }
  // Every CL point was reached (the last ones may repeat the point before them).
  while (next < cl_pts.size() && kin::distance(cl_pts[next].pose.tip, at.tip) < 1e-9 &&
         kin::angle_between(cl_pts[next].pose.axis, at.axis) < 1e-9)
    ++next;
  CHECK(next == cl_pts.size());
  return r;
}

std::string sample_job(const std::string& name) {
  return read_text(std::string(TWINPOST_SOURCE_DIR) + "/samples/" + name + "/job.cls");
}

}  // namespace

TEST_CASE("multi-axis: every block of the five-axis wall goes back to its CL point on the head/head mill",
          "[post][multiaxis]") {
  const machine m = load_machine("head-head-5axis");
  const round_trip r = read_back(sample_job("five-axis-wall"), m, "ma-hh");
  CHECK(r.cl_points == 13);
  CHECK(r.sub_points > 100);
  CHECK(r.worst_tip <= 0.005);
  CHECK(r.worst_axis <= 0.002);
  // The wall's tool axis swings by 30 degrees between two CL points; left uncut the tip
  // would leave the line by millimetres, cut it stays within the chordal tolerance (0.01 mm
  // and the words' rounding).
  CHECK(r.largest_swing == Approx(30).margin(1e-9));
  CHECK(r.uncut > 1.0);
  CHECK(r.worst_chord <= 0.01 + 0.005);
}

TEST_CASE("multi-axis: 3+2 work in tilted planes (G68.2) reads back to the CL on the head/head mill",
          "[post][multiaxis]") {
  const machine m = load_machine("head-head-5axis");
  const round_trip r = read_back(sample_job("three-plus-two"), m, "ma-32");
  CHECK(r.cl_points == 15);
  // X Y before Z at each plane's first point, and back to A0 B0: up to Z60 first, then the
  // head turns alone (docs/machines.md, the approach). G53.1 turned the head without A B words,
  // so the reader sees no rapid that turns one.
  CHECK(r.repositions == 4);
  CHECK(r.sub_points == 0);
  CHECK(r.worst_tip <= 0.001);
  CHECK(r.worst_axis <= 0.002);
  // A feed move that turns the tool inside a plane is refused: 3+2 keeps its axis. The cut is
  // looked at 4096 records ahead; one that kept its axis that long is taken for 3+2 work.
  std::string cl =
      "PARTNO T\nTLDATA/MILL,8,0,100,0,0\nMULTAX/ON\nLOADTL/1\nSPINDL/RPM,9000,CLW\n"
      "FEDRAT/MMPM,600\nRAPID\nGOTO/20,0,40,0.2588190,0,0.9659258\n";
  for (int i = 0; i < 4100; ++i) cl += i % 2 ? "GOTO/20,0,10,0.2588190,0,0.9659258\n" : "GOTO/21,0,10\n";
  cl += "GOTO/30,0,10,0,0,1\nFINI\n";
  const test::posted p = test::post_in_fresh_dir(cl, m, "ma-32b");
  CHECK(p.diagnostics ==
        "job.cls:4109:1: error: channel 1: the tool axis turns from (0.258819,0,0.965926) to (0,0,1) in a "
        "feed move inside a tilted working plane (G68.2): a 3+2 operation keeps its axis; give a RAPID to "
        "change it\n"
        "GOTO/30,0,10,0,0,1\n^\n"
        "job.cls:4110:1: warning: channel 1: the tool goes home straight from a feed move, with no retract "
        "in the CL: the home blocks move it as the machine file lists them, from where the feed left it; in "
        "a bore, a groove or under a shoulder it would run into the part: give the retract before GOHOME or "
        "the tool change\n"
        "FINI\n^\n");
  // A cut whose feed moves turn the tool after the RAPID is simultaneous work: no plane, the
  // rapid and the cut in joints (G93 on the turning move), as without `plane`.
  const test::posted s = test::post_in_fresh_dir(
      "PARTNO S\nTLDATA/MILL,8,0,100,0,0\nMULTAX/ON\nLOADTL/1\nSPINDL/RPM,9000,CLW\n"
      "FEDRAT/MMPM,600\nRAPID\nGOTO/20,0,40,0.2588190,0,0.9659258\n"
      "GOTO/20,0,10,0.2588190,0,0.9659258\nGOTO/30,0,10,0,0,1\nFINI\n",
      m, "ma-32s");
  INFO(s.diagnostics);
  REQUIRE(s.ok);
  CHECK(s.files.at("S.nc").find("G68.2") == std::string::npos);
  CHECK(s.files.at("S.nc").find("G93") != std::string::npos);
}

TEST_CASE("multi-axis: 3+2 work in tilted planes (G68.2) reads back to the CL on the trunnion",
          "[post][multiaxis][plane]") {
  // The same planes on the table/table machine: G53.1 turns the tables, X Y Z are the tip in
  // the plane; outside them G43.4 with A C.
  const machine m = load_machine("trunnion-5axis");
  const round_trip r = read_back(sample_job("three-plus-two"), m, "ma-32t");
  CHECK(r.cl_points == 15);
  CHECK(r.worst_tip <= 0.001);
  CHECK(r.worst_axis <= 0.002);
}

TEST_CASE("multi-axis: the trunnion's G43.4 blocks give back the CL tip and axis", "[post][multiaxis]") {
  const machine m = load_machine("trunnion-5axis");
  const round_trip r = read_back(sample_job("five-axis-wall"), m, "ma-tt");
  CHECK(r.cl_points == 13);
  // The control keeps the tip on the line; the one extra point is C turning from 135 to 180
  // at (40, 40), where the tool reached the pole in the cut, before it tilts to A10.
  CHECK(r.sub_points == 1);
  CHECK(r.worst_tip <= 0.0005);
  CHECK(r.worst_axis <= 0.002);
}

TEST_CASE("multi-axis: the trunnion in the vector form writes G43.5 with I J K to 6 decimals",
          "[post][multiaxis]") {
  const machine m = load_machine(std::string(TWINPOST_SOURCE_DIR) + "/tests/kin/trunnion-vector.toml");
  const round_trip r = read_back(sample_job("five-axis-wall"), m, "ma-tv");
  CHECK(r.cl_points == 13);
  CHECK(r.worst_axis <= 0.002);
  const test::posted p = test::post_in_fresh_dir(
      "PARTNO VEC\nMULTAX/ON\nLOADTL/4\nSPINDL/RPM,5000,CLW\nFEDRAT/MMPM,500\nRAPID\nGOTO/0,0,20,0,0,1\n"
      "GOTO/10,0,0,0.2588190,0,0.9659258\nGOTO/10,5,0,0.2588190,0,0.9659258\nFINI\n",
      m, "ma-tv2");
  REQUIRE(p.ok);
  CHECK(p.files.at("VEC.nc") ==
        "%\nO5002 (VEC)\nG21\nG90 G94 G17 G40 G49 G80\nG91 G28 Z0.\nG90\nT04 M6\nS5000 M3\n"
        "G0 A0. C0.\nG0 X0. Y0.\nG0 G43.5 H4 X0. Y0. Z20. I0. J0. K1.\n"
        "G1 X10. Z0. I0.258819 K0.965926 F500.\nY5.\nG91 G28 Z0.\nG90\nM9\nM5\nG49\nM30\n%\n");
}

TEST_CASE("multi-axis: the four-axis wrap on the A table, swings of 60 degrees cut to the tolerance",
          "[post][multiaxis]") {
  const machine m = load_machine("rotary-4axis");
  const round_trip r = read_back(sample_job("four-axis-wrap"), m, "ma-4x");
  CHECK(r.cl_points == 10);
  // A30 and back to A0 turn in rapids of their own at the higher point: G0 A30. at Z80 before
  // the rapid down to Z50; after the retract to Z60, G0 Z80. first and then G0 A0.
  CHECK(r.rapid_turns == 2);
  CHECK(r.repositions == 2);
  CHECK(r.largest_swing == Approx(60).margin(1e-9));
  CHECK(r.uncut > 1.0);
  CHECK(r.worst_chord <= 0.01 + 0.005);
  CHECK(r.worst_tip <= 0.005);
}

TEST_CASE("multi-axis: a head/table chain (B head over a C spindle) posts and reads back",
          "[post][multiaxis]") {
  machine m = load_machine(std::string(TWINPOST_SOURCE_DIR) + "/tests/kin/head-table.toml");
  // Its tolerance (0.001 mm) is finer than the words: B to 0.001 degree moves the tip 0.006 mm
  // at 350 mm from the pivot (the post would stop at the forward check, as it must).
  m.kinematics[0].tolerance = 0.01;
  // The wall's first half (tilts about Y: B with C at 0 or 180), then a radial cut round the
  // C axis with the tool tilted 30 degrees towards it.
  const std::string job =
      "PARTNO HEAD TABLE\nTLDATA/MILL,10,0,100,0,0\nMULTAX/ON\nLOADTL/1\nFEDRAT/MMPM,1000\nRAPID\n"
      "GOTO/0,0,50,0,0,1\nRAPID\nGOTO/-40,0,10,0,0,1\nGOTO/-40,0,-5,0,0,1\n"
      "GOTO/-20,0,-5,0.2588190,0,0.9659258\nGOTO/20,0,-5,-0.2588190,0,0.9659258\n"
      "GOTO/20,0,-5,0.5,0,0.8660254\nGOTO/0,20,-5,0,0.5,0.8660254\nGOTO/-20,0,-5,-0.5,0,0.8660254\n"
      "RAPID\nGOTO/-20,0,50,-0.5,0,0.8660254\nFINI\n";
  const round_trip r = read_back(job, m, "ma-ht");
  CHECK(r.cl_points == 9);
  CHECK(r.sub_points > 10);
  CHECK(r.worst_tip <= 0.005);
  CHECK(r.worst_chord <= 0.01 + 0.005);
}

namespace {

// A short job on `m`: a tool with a 100 mm length (unless `tldata` is empty), a rapid to
// (0,0,50) with the tool along Z, then `moves`.
test::posted post_moves(const machine& m, const std::string& moves, const std::string& tag,
                        const std::string& tldata = "TLDATA/MILL,10,0,100,0,0\n") {
  return test::post_in_fresh_dir("PARTNO MOVES\n" + tldata +
                                     "MULTAX/ON\nLOADTL/1\nSPINDL/RPM,5000,CLW\nFEDRAT/MMPM,500\n"
                                     "RAPID\nGOTO/0,0,50,0,0,1\n" +
                                     moves + "FINI\n",
                                 m, tag);
}

}  // namespace

TEST_CASE("multi-axis: a change of solution inside a cut stops the post at its GOTO", "[post][multiaxis]") {
  // The trunnion with A limited to -30..120: a tilt of 20 degrees towards +X and then -X can
  // keep C only with A at -20 or... A20 C90 then A-20 C90 is allowed; beyond -30 it needs A40
  // C-90 instead of A-40 C90: C turns half round while the tool cuts.
  machine m = load_machine("trunnion-5axis");
  m.kinematics[0].rotaries[0].min = -30;
  const test::posted p = post_moves(m,
                                    "GOTO/0,0,0,0.3420201,0,0.9396926\n"
                                    "GOTO/10,0,0,-0.6427876,0,0.7660444\n",
                                    "ma-flip");
  CHECK_FALSE(p.ok);
  CHECK(p.diagnostics ==
        "job.cls:10:1: error: channel 1: the rotary axes would change solution inside a cut, from A20 C90 to "
        "A40 "
        "C-90 (C turns 180 degrees while the tool cuts): retract, reposition with RAPID and re-engage\n"
        "GOTO/10,0,0,-0.6427876,0,0.7660444\n^\n");
  // As a rapid the same change is a reposition, and posts.
  CHECK(post_moves(m, "GOTO/0,0,0,0.3420201,0,0.9396926\nRAPID\nGOTO/10,0,0,-0.6427876,0,0.7660444\n",
                   "ma-flip2")
            .ok);
}

TEST_CASE("multi-axis: arcs and drilling cycles only with the rotary axes at 0", "[post][multiaxis]") {
  const machine m = load_machine("trunnion-5axis");
  // Back to the tool along Z, C stays at 90 (the pole keeps it): the arc is refused.
  const test::posted p = post_moves(m,
                                    "GOTO/0,0,0,0.2588190,0,0.9659258\nGOTO/0,0,0,0,0,1\n"
                                    "CIRCLE/0,10,0,0,0,1,10,0.06,0.5,10,0\nGOTO/10,10,0\n",
                                    "ma-arc");
  CHECK_FALSE(p.ok);
  CHECK(p.diagnostics ==
        "job.cls:12:1: error: channel 1: an arc or a drilling cycle with the tool axis (0,0,1) and the "
        "rotary axes "
        "at A0 C90: twinpost writes them only with the tool along Z, every table and every head that tilts "
        "the tool at 0 (a head about the tool's own axis may stand anywhere); output the move as GOTO points"
        "\nGOTO/10,10,0\n^\n");
  // With the axes at 0 the arc is the 3-axis one, after G94 where G93 was in force.
  const test::posted q = post_moves(load_machine("head-head-5axis"),
                                    "GOTO/0,0,0,0,0,1\nGOTO/10,0,0,0.0871557,0,0.9961947\nGOTO/20,0,0,0,0,1\n"
                                    "CIRCLE/20,10,0,0,0,1,10,0.06,0.5,10,0\nGOTO/30,10,0\n",
                                    "ma-arc2");
  INFO(q.diagnostics);
  REQUIRE(q.ok);
  // B swings to 5 degrees and back (8 sub-moves each way, G93), then G94 for the arc.
  CHECK(q.files.at("MOVES.nc") ==
        "%\nO5001 (MOVES)\nG21\nG90 G94 G17 G40 G49 G80\nG91 G28 Z0.\nG90\nG0 A0. B0.\nT01 M6\n"
        "G54\nS5000 M3\nG0 A0. B0.\nG0 X0. Y0.\nG0 G43 H1 X0. Y0. Z50. A0. B0.\nG1 Z0. F500.\n"
        "G93 G1 X5.613 Z-0.024 B0.625 F400.\nX11.226 Z-0.095 B1.25 F400.\n"
        "X16.838 Z-0.214 B1.875 F400.\nX22.448 Z-0.381 B2.5 F400.\nX28.056 Z-0.595 B3.125 F400.\n"
        "X33.661 Z-0.856 B3.75 F400.\nX39.264 Z-1.166 B4.375 F400.\nX44.862 Z-1.522 B5. F400.\n"
        "X41.764 Z-1.166 B4.375 F400.\nX38.661 Z-0.856 B3.75 F400.\nX35.556 Z-0.595 B3.125 F400.\n"
        "X32.448 Z-0.381 B2.5 F400.\nX29.338 Z-0.214 B1.875 F400.\nX26.226 Z-0.095 B1.25 F400.\n"
        "X23.113 Z-0.024 B0.625 F400.\nX20. Z0. B0. F400.\nG94\nG3 X30. Y10. I0. J10. F500.\n"
        "G91 G28 Z0.\nG90\nM9\nM5\nG49\nM30\n%\n");
}

TEST_CASE("multi-axis: the trunnion writes an arc centre 20 mm away (I J K in the axes' format)",
          "[post][multiaxis]") {
  // I J K were "1.6" on trunnion-5axis (the unit vector of G43.5), which refused J20.
  const test::posted p =
      post_moves(load_machine("trunnion-5axis"),
                 "GOTO/0,0,0\nCIRCLE/0,20,0,0,0,1,20,0.06,0.5,10,0\nGOTO/20,20,0\n", "ma-arc-trunnion");
  INFO(p.diagnostics);
  REQUIRE(p.ok);
  const std::string nc = p.files.at("MOVES.nc");
  CHECK(
      nc.substr(nc.find("G0 G43.4")) ==
      "G0 G43.4 H1 X0. Y0. Z50. A0. C0.\nG1 Z0. F500.\nG3 X20. Y20. I0. J20.\nG91 G28 Z0.\nG90\nM9\nM5\nG49\n"
      "M30\n%\n");
}

TEST_CASE("multi-axis: the tool length from TLDATA or the tool table, never guessed", "[post][multiaxis]") {
  machine m = load_machine("head-head-5axis");
  const std::string tilt = "GOTO/10,0,0,0.1736482,0,0.9848078\n";
  const test::posted none = post_moves(m, tilt, "ma-len0", "");
  // The rapid to GOTO/0,0,50 under the spindle's axis posts; the tilted feed move is refused.
  CHECK(
      none.diagnostics ==
      "job.cls:8:1: error: channel 1: tool 1 (LOADTL at line 3) has no length, and this move tilts it (B10): "
      "the joint values of machine 'head-head-5axis' then depend on it (a head turns the tool about its "
      "pivot); give TLDATA/MILL with the length, or length = ... under the tool's [[tool]] in the machine "
      "file\nGOTO/10,0,0,0.1736482,0,0.9848078\n^\n");
  // The table's length serves where the CL gives none; the same program as with TLDATA.
  tool_def t;
  t.number = 1;
  t.kind = "mill";
  t.length = 100;
  m.tools.push_back(t);
  const test::posted table = post_moves(m, tilt, "ma-len1", "");
  const test::posted cl = post_moves(load_machine("head-head-5axis"), tilt, "ma-len2");
  REQUIRE(table.ok);
  REQUIRE(cl.ok);
  CHECK(table.files == cl.files);
  // Both, and different: which tool is in the spindle?
  m.tools.back().length = 120;
  CHECK(post_moves(m, tilt, "ma-len3").diagnostics ==
        "job.cls:8:1: error: channel 1: tool 1 (LOADTL at line 4): the CL's TLDATA gives a length of 100 mm, "
        "machine 'head-head-5axis' lists 120 mm ([[tool]] length): which tool is in the spindle? "
        "([[kinematics]] tool_length = \"table\" or \"cl\" says which wins)\nGOTO/0,0,50,0,0,1\n^\n");
  // The machine file says which wins ([[kinematics]] tool_length): a warning, and the program of
  // that length (the table's 120 mm: as the table alone gives it; the CL's: as TLDATA alone).
  machine by_table = m;
  by_table.kinematics.front().tool_length = length_source::table;
  const test::posted t120 = post_moves(by_table, tilt, "ma-len4");
  REQUIRE(t120.ok);
  CHECK(t120.diagnostics ==
        "job.cls:8:1: warning: channel 1: tool 1 (LOADTL at line 4): the CL's TLDATA gives a length of 100 "
        "mm, machine 'head-head-5axis' lists 120 mm ([[tool]] length): the table's is used ([[kinematics]] "
        "tool_length = \"table\"); on a tilted head the tip lies where that length puts it\n"
        "GOTO/0,0,50,0,0,1\n^\n"
        "job.cls:10:1: warning: channel 1: the tool goes home straight from a feed move, with no retract in "
        "the CL: the home blocks move it as the machine file lists them, from where the feed left it; in a "
        "bore, a groove or under a shoulder it would run into the part: give the retract before GOHOME or "
        "the tool change\n"
        "FINI\n^\n");
  const test::posted only_table = post_moves(by_table, tilt, "ma-len5", "");
  REQUIRE(only_table.ok);
  CHECK(t120.files == only_table.files);
  CHECK(t120.files != cl.files);
  machine by_cl = m;
  by_cl.kinematics.front().tool_length = length_source::cl;
  const test::posted c100 = post_moves(by_cl, tilt, "ma-len6");
  REQUIRE(c100.ok);
  CHECK(c100.files == cl.files);
}

TEST_CASE("multi-axis: no feed per revolution and no 2-D compensation under a tilted tool",
          "[post][multiaxis]") {
  const machine m = load_machine("rotary-4axis");
  CHECK(post_moves(m, "FEDRAT/0.1,MMPR\nGOTO/0,0,0,0,0,1\nGOTO/0,10,0,0,0.5,0.8660254\n", "ma-rev")
            .diagnostics ==
        "job.cls:11:1: error: channel 1: a feed per revolution on a move that turns a rotary axis: "
        "inverse-time "
        "feed (G93) needs a feed per minute (FEDRAT/MMPM)\nGOTO/0,10,0,0,0.5,0.8660254\n^\n");
  CHECK(post_moves(m, "CUTCOM/LEFT\nGOTO/0,10,0,0,0.5,0.8660254\n", "ma-cc").diagnostics ==
        "job.cls:10:1: error: channel 1: cutter compensation (G41 D1) under the tool axis (0,0.5,0.866025): "
        "twinpost "
        "writes no 3-D compensation (G41.2/G42.2)\nGOTO/0,10,0,0,0.5,0.8660254\n^\n");
}

TEST_CASE("multi-axis: an inverse-time F past the control's format stops the post at its GOTO",
          "[post][multiaxis]") {
  // A turn of 0.01 degrees on the spot at 200000 mm/min: 1 / (0.01 / 200000) = 2e7 per minute,
  // past F's 6.3 (999999.999).
  const test::posted p =
      post_moves(load_machine("rotary-4axis"),
                 "FEDRAT/200000\nGOTO/0,0,0,0,0,1\nGOTO/0,0,0,0,0.0001745,0.99999998\n", "ma-f");
  CHECK_FALSE(p.ok);
  CHECK(
      p.diagnostics ==
      "job.cls:11:1: error: channel 1: F word 20003773.4648 does not fit the control's format (6.3: at most "
      "999999.999)\nGOTO/0,0,0,0,0.0001745,0.99999998\n^\n");
}

TEST_CASE("multi-axis: a rotary word past the control's format stops the post at its GOTO",
          "[post][multiaxis]") {
  // B given one whole digit (1.3, at most 9.999): the feed move's sub-moves to B15 past B9.999
  // do not fit.
  machine m = load_machine("head-head-5axis");
  m.formats['B'] = {1, 3};
  const test::posted p = post_moves(m, "GOTO/0,0,0,0,0,1\nGOTO/10,0,0,0.2588190,0,0.9659258\n", "ma-b");
  CHECK_FALSE(p.ok);
  // Each sub-move past it is refused, with its own error (and the post writes no file).
  CHECK(p.diagnostics ==
        "job.cls:10:1: error: channel 1: B word 10.3124985519 does not fit the control's format (1.3: at "
        "most 9.999)\n"
        "GOTO/10,0,0,0.2588190,0,0.9659258\n^\n"
        "job.cls:10:1: error: channel 1: B word 10.7812484861 does not fit the control's format (1.3: at "
        "most 9.999)\n"
        "GOTO/10,0,0,0.2588190,0,0.9659258\n^\n"
        "job.cls:10:1: error: channel 1: B word 11.2499984203 does not fit the control's format (1.3: at "
        "most 9.999)\n"
        "GOTO/10,0,0,0.2588190,0,0.9659258\n^\n"
        "job.cls:10:1: error: channel 1: B word 11.7187483545 does not fit the control's format (1.3: at "
        "most 9.999)\n"
        "GOTO/10,0,0,0.2588190,0,0.9659258\n^\n"
        "job.cls:10:1: error: channel 1: B word 12.1874982886 does not fit the control's format (1.3: at "
        "most 9.999)\n"
        "GOTO/10,0,0,0.2588190,0,0.9659258\n^\n"
        "job.cls:10:1: error: channel 1: B word 12.6562482228 does not fit the control's format (1.3: at "
        "most 9.999)\n"
        "GOTO/10,0,0,0.2588190,0,0.9659258\n^\n"
        "job.cls:10:1: error: channel 1: B word 13.124998157 does not fit the control's format (1.3: at most "
        "9.999)\n"
        "GOTO/10,0,0,0.2588190,0,0.9659258\n^\n"
        "job.cls:10:1: error: channel 1: B word 13.5937480912 does not fit the control's format (1.3: at "
        "most 9.999)\n"
        "GOTO/10,0,0,0.2588190,0,0.9659258\n^\n"
        "job.cls:10:1: error: channel 1: B word 14.0624980254 does not fit the control's format (1.3: at "
        "most 9.999)\n"
        "GOTO/10,0,0,0.2588190,0,0.9659258\n^\n"
        "job.cls:10:1: error: channel 1: B word 14.5312479595 does not fit the control's format (1.3: at "
        "most 9.999)\n"
        "GOTO/10,0,0,0.2588190,0,0.9659258\n^\n"
        "job.cls:10:1: error: channel 1: B word 14.9999978937 does not fit the control's format (1.3: at "
        "most 9.999)\n"
        "GOTO/10,0,0,0.2588190,0,0.9659258\n^\n"
        "job.cls:11:1: warning: channel 1: the tool goes home straight from a feed move, with no retract in "
        "the CL: the home blocks move it as the machine file lists them, from where the feed left it; in a "
        "bore, a groove or under a shoulder it would run into the part: give the retract before GOHOME or "
        "the tool change\n"
        "FINI\n^\n");
}

TEST_CASE("multi-axis: a rapid onto the pole takes the outer angle of the first point off it",
          "[post][multiaxis]") {
  // B head over a C spindle: the tool along Z leaves C free. Tilting it towards -Y needs C90;
  // kept at C0 from the start, C would turn 90 degrees while the tool tilts in the cut. The
  // rapid is held until the tilted point is read, and goes to C90 (X-40 Y40: the part turned).
  const machine m = load_machine(std::string(TWINPOST_SOURCE_DIR) + "/tests/kin/head-table.toml");
  const test::posted p = test::post_in_fresh_dir(
      "PARTNO POLE\nTLDATA/MILL,10,0,100,0,0\nMULTAX/ON\nLOADTL/1\nFEDRAT/MMPM,1000\nRAPID\n"
      "GOTO/40,40,5,0,0,1\nGOTO/40,40,-5,0,0,1\nGOTO/40,40,-5,0,-0.1736482,0.9848078\nFINI\n",
      m, "ma-pole");
  INFO(p.diagnostics);
  REQUIRE(p.ok);
  CHECK(
      p.files.at("POLE.nc") ==
      "%\nO1000 (POLE)\nG28 U0.\nG28 W0.\nG0 B0.\nT01 M6\nG98\nG0 B0. C90.\nG0 X-40. Y40.\nG0 G43 H1 X-40. "
      "Y40. Z5. "
      "B0. C90.\n"
      "G1 Z-5. F1000.\n"
      "G93 G1 X-36.182 Z-5.075 B0.625 F1600.\nX-32.366 Z-5.192 B1.25 F1600.\nX-28.551 Z-5.351 B1.875 F1600.\n"
      "X-24.738 Z-5.551 B2.5 F1600.\nX-20.927 Z-5.793 B3.125 F1600.\nX-17.12 Z-6.076 B3.75 F1600.\n"
      "X-13.315 Z-6.401 B4.375 F1600.\nX-9.515 Z-6.768 B5. F1600.\nX-5.718 Z-7.175 B5.625 F1600.\n"
      "X-1.926 Z-7.625 B6.25 F1600.\nX1.86 Z-8.115 B6.875 F1600.\nX5.641 Z-8.647 B7.5 F1600.\n"
      "X9.416 Z-9.22 B8.125 F1600.\nX13.185 Z-9.834 B8.75 F1600.\nX16.947 Z-10.489 B9.375 F1600.\n"
      "X20.701 Z-11.186 B10. F1600.\nG98\nG28 U0.\nG28 W0.\nG49\nM30\n%\n");
}

TEST_CASE("multi-axis: the records held with a rapid on the pole keep their order, and others release it",
          "[post][multiaxis]") {
  // The trunnion: tilting the tool towards +X needs C90 (A about X tilts it in Y).
  const machine m = load_machine("trunnion-5axis");
  const std::string head =
      "PARTNO POLE\nTLDATA/MILL,10,0,100,0,0\nMULTAX/ON\nLOADTL/1\nFEDRAT/MMPM,1000\nRAPID\n"
      "GOTO/40,40,5,0,0,1\nPPRINT APPROACH\nSPINDL/RPM,5000,CLW\n";
  const std::string tail = "GOTO/40,40,-5,0,0,1\nGOTO/40,40,-5,0.1736482,0,0.9848078\nFINI\n";
  const std::string start = "%\nO5002 (POLE)\nG21\nG90 G94 G17 G40 G49 G80\nG91 G28 Z0.\nG90\nT01 M6\nG54\n";
  const std::string end = "G91 G28 Z0.\nG90\nM9\nM5\nG49\nM30\n%\n";  // out of the cut first
  // A comment and a spindle start are held with it: the rapid takes C90, they follow it.
  const test::posted held = test::post_in_fresh_dir(head + tail, m, "ma-pole-held");
  INFO(held.diagnostics);
  REQUIRE(held.ok);
  CHECK(held.files.at("POLE.nc") ==
        start +
            "G0 A0. C90.\nG0 X40. Y40.\nG0 G43.4 H1 X40. Y40. Z5. A0. C90.\n(APPROACH)\nS5000 M3\nG1 Z-5. "
            "F1000.\nA10.\n" +
            end);
  // A dwell is not held: the rapid goes out as it came (C0), and C turns at the bottom of
  // the plunge, where the tool reaches the pole, before the tilt.
  const test::posted released = test::post_in_fresh_dir(head + "DELAY/2\n" + tail, m, "ma-pole-released");
  INFO(released.diagnostics);
  REQUIRE(released.ok);
  CHECK(released.files.at("POLE.nc") ==
        start +
            "G0 A0. C0.\nG0 X40. Y40.\nG0 G43.4 H1 X40. Y40. Z5. A0. C0.\n(APPROACH)\nS5000 M3\nG4 "
            "P2000\nG1 Z-5. F1000.\nC90.\nA10.\n" +
            end);
  // A change of units releases it too: the rapid was given in millimetres (X40, not 40 inches).
  const test::posted units = test::post_in_fresh_dir(
      "PARTNO POLE\nTLDATA/MILL,10,0,100,0,0\nMULTAX/ON\nLOADTL/1\nFEDRAT/MMPM,1000\nSPINDL/RPM,5000,CLW\n"
      "RAPID\nGOTO/40,40,5,0,0,1\nUNITS/INCHES\nGOTO/1.5748,1.5748,-0.19685,0,0,1\n"
      "GOTO/1.5748,1.5748,-0.19685,0.1736482,0,0.9848078\nFINI\n",
      m, "ma-pole-units");
  INFO(units.diagnostics);
  REQUIRE(units.ok);
  CHECK(units.files.at("POLE.nc") == start +
                                         "S5000 M3\nG0 A0. C0.\nG0 X40. Y40.\nG0 G43.4 H1 X40. Y40. Z5. A0. "
                                         "C0.\nG1 Z-5. F1000.\nC90.\nA10.\n" +
                                         end);
}

TEST_CASE("multi-axis: a cut that reaches the pole turns the outer axis there before it leaves it",
          "[post][multiaxis]") {
  // The pole reached by a feed (B-10 to B0 at the bottom of the plunge): nothing to look
  // ahead from. C turns to 90 at the point, the tip held there in steps whose chord stays
  // within the tolerance (1 mm here, so that they are few: 8 of 11.25 degrees on the 56.6 mm
  // radius of (40, 40)), at the feed read as degrees per minute; then B tilts alone.
  machine m = load_machine(std::string(TWINPOST_SOURCE_DIR) + "/tests/kin/head-table.toml");
  m.kinematics[0].chordal_tolerance = 1.0;
  const test::posted p = test::post_in_fresh_dir(
      "PARTNO POLE\nTLDATA/MILL,10,0,100,0,0\nMULTAX/ON\nLOADTL/1\nFEDRAT/MMPM,1000\nRAPID\n"
      "GOTO/40,40,5,-0.1736482,0,0.9848078\nGOTO/40,40,-5,0,0,1\nGOTO/"
      "40,40,-5,0,-0.1736482,0.9848078\nFINI\n",
      m, "ma-pole-turn");
  INFO(p.diagnostics);
  REQUIRE(p.ok);
  CHECK(p.files.at("POLE.nc") ==
        "%\nO1000 (POLE)\nG28 U0.\nG28 W0.\nG0 B0.\nT01 M6\nG98\nG0 B-10. C0.\nG0 X-20.853 Y40.\n"
        "G0 G43 H1 X-20.853 Y40. Z0.551 B-10. C0.\n"
        "G93 G1 X40. Z-5. B0. F100.\nX31.428 Y47.035 C11.25 F88.889\nX21.648 Y52.263 C22.5 F88.889\n"
        "X11.036 Y55.482 C33.75 F88.889\nX0. Y56.569 C45. F88.889\nX-11.036 Y55.482 C56.25 F88.889\n"
        "X-21.648 Y52.263 C67.5 F88.889\nX-31.428 Y47.035 C78.75 F88.889\nX-40. Y40. C90. F88.889\n"
        "X-9.515 Z-6.768 B5. F200.\nX20.701 Z-11.186 B10. F200.\nG98\nG28 U0.\nG28 W0.\nG49\nM30\n%\n");
}

TEST_CASE("multi-axis: a chain with moves = \"tilted\" leaves the moves along Z to the 3-axis writer",
          "[post][multiaxis]") {
  // A mill/turn head (B over a C spindle): the plunge and the last moves stay the channel's
  // own; the tilt between goes through the chain, with G43 H and G93, then G98 again.
  machine m = load_machine(std::string(TWINPOST_SOURCE_DIR) + "/tests/kin/head-table.toml");
  m.kinematics[0].moves = multiaxis_moves::tilted;
  m.kinematics[0].tolerance = 0.01;
  // The channel's own moves take its length offset (without it the plunge ran at the gauge
  // line, and the comparison with the CL refuses it).
  m.channels[0].length_offset = "G43 H{offset:02}";
  const test::posted p = test::post_in_fresh_dir(
      "PARTNO TILTED\nTLDATA/MILL,10,0,100,0,0\nMULTAX/ON\nLOADTL/1\nFEDRAT/MMPM,1000\nRAPID\n"
      "GOTO/40,0,5,0,0,1\nGOTO/40,0,-5,0,0,1\nGOTO/30,0,-5,0.0348995,0,0.9993908\nGOTO/20,0,-5,0,0,1\nRAPID\n"
      "GOTO/20,0,20,0,0,1\nFINI\n",
      m, "ma-tilted");
  INFO(p.diagnostics);
  REQUIRE(p.ok);
  CHECK(p.files.at("TILTED.nc") ==
        "%\nO1000 (TILTED)\nG28 U0.\nG28 W0.\nG0 B0.\nT01 M6\nG98\nG0 G43 H01 X40. Y0. Z5.\nG1 Z-5. F1000.\n"
        "G93 G1 G43 H1 X40.554 Y0. Z-5.057 B0.5 C0. F400.\nX41.108 Z-5.141 B1. F400.\n"
        "X41.66 Z-5.251 B1.5 F400.\nX42.212 Z-5.388 B2. F400.\nX36.66 Z-5.251 B1.5 F400.\n"
        "X31.108 Z-5.141 B1. F400.\nX25.554 Z-5.057 B0.5 F400.\nX20. Z-5. B0. F400.\nG98\nG0 Z20.\n"
        "G28 U0.\nG28 W0.\nG49\nM30\n%\n");
}

TEST_CASE("multi-axis: a head machine posts a tool of unknown length while no head tilts it",
          "[post][multiaxis]") {
  // With both heads at 0 the linear words are the tip whatever the length (docs/kinematics.md,
  // "Frames and signs"): the program without a length is the one with any length.
  const machine m = load_machine("head-head-5axis");
  const std::string flat =
      "GOTO/10,0,-5\nGOTO/20,5,-5\nCIRCLE/20,15,-5,0,0,1,10,0.06,0.5,10,0\nGOTO/30,15,-5\nRAPID\n"
      "GOTO/30,15,50\n";
  const test::posted none = post_moves(m, flat, "ma-free0", "");
  const test::posted l100 = post_moves(m, flat, "ma-free1", "TLDATA/MILL,10,0,100,0,0\n");
  const test::posted l250 = post_moves(m, flat, "ma-free2", "TLDATA/MILL,10,0,250,0,0\n");
  INFO(none.diagnostics);
  REQUIRE(none.ok);
  REQUIRE(l100.ok);
  REQUIRE(l250.ok);
  CHECK(none.files == l100.files);
  CHECK(none.files == l250.files);
  const std::string nc = none.files.at("MOVES.nc");
  CHECK(nc.substr(nc.find("G0 G43")) ==
        "G0 G43 H1 X0. Y0. Z50. A0. B0.\nG1 X10. Z-5. F500.\nX20. Y5.\nG3 X30. Y15. I0. J10.\nG0 "
        "Z50.\nM9\nM5\nG91 G28 Z0.\nG90\nG49\nM30\n%\n");
  // A tilted feed move is refused once per tool, at the first; the moves under the spindle's
  // axis after it still post, and the next tool is judged afresh.
  const test::posted tilted = test::post_in_fresh_dir(
      "PARTNO MOVES\nMULTAX/ON\nLOADTL/1\nSPINDL/RPM,5000,CLW\nFEDRAT/MMPM,500\nRAPID\nGOTO/0,0,50,0,0,1\n"
      "GOTO/10,0,0,0.1736482,0,0.9848078\nGOTO/20,0,0,0,0.1736482,0.9848078\nGOTO/20,0,50,0,0,1\n"
      "LOADTL/2\nSPINDL/RPM,5000,CLW\nRAPID\nGOTO/0,0,50,0,0,1\nGOTO/0,10,0,0,-0.1736482,0.9848078\nFINI\n",
      m, "ma-free3");
  CHECK(
      tilted.diagnostics ==
      "job.cls:8:1: error: channel 1: tool 1 (LOADTL at line 3) has no length, and this move tilts it (B10): "
      "the joint values of machine 'head-head-5axis' then depend on it (a head turns the tool about its "
      "pivot); give TLDATA/MILL with the length, or length = ... under the tool's [[tool]] in the machine "
      "file\nGOTO/10,0,0,0.1736482,0,0.9848078\n^\n"
      "job.cls:15:1: error: channel 1: tool 2 (LOADTL at line 11) has no length, and this move tilts it "
      "(A10): "
      "the joint values of machine 'head-head-5axis' then depend on it (a head turns the tool about its "
      "pivot); give TLDATA/MILL with the length, or length = ... under the tool's [[tool]] in the machine "
      "file\nGOTO/0,10,0,0,-0.1736482,0.9848078\n^\n");
  // A head along the tool (the bridge mill's C over its B head) never tilts it: the cut that
  // leaves the pole turns C there and then tilts B; only B is the tilt the length matters for.
  const test::posted bridge = test::post_in_fresh_dir(
      "PARTNO BRIDGE\nMULTAX/ON\nLOADTL/1\nFEDRAT/MMPM,500\nRAPID\nGOTO/0,0,50,0,0,1\nGOTO/0,0,0,0,0,1\n"
      "GOTO/10,0,0,0,0.1736482,0.9848078\nFINI\n",
      load_machine(std::string(TWINPOST_SOURCE_DIR) + "/tests/oracle/linuxcnc/bridge.toml"), "ma-free4");
  CHECK(
      bridge.diagnostics ==
      "job.cls:8:1: error: channel 1: tool 1 (LOADTL at line 3) has no length, and this move tilts it (B10): "
      "the joint values of machine 'lcnc-5axiskins' then depend on it (a head turns the tool about its "
      "pivot); give TLDATA/MILL with the length, or length = ... under the tool's [[tool]] in the machine "
      "file\nGOTO/10,0,0,0,0.1736482,0.9848078\n^\n");
}

namespace {
// A built-in machine that writes NX MSYS points turned into the absolute frame
// ([program] cl_frame = "absolute"; the default writes them in the CL's MCS).
machine absolute(const std::string& name) {
  machine m = load_machine(name);
  m.program.frame = cl_frame::absolute;
  return m;
}
}  // namespace

TEST_CASE("frames: NX MSYS turns the points and tool axes before the kinematics",
          "[post][multiaxis][frames]") {
  // An MCS with Z down (its Y is the absolute -Y, so Z = X x Y = -Z): the CL's tool axis
  // (0,0,-1) is the absolute +Z, which the heads reach at 0, not at B180; the written blocks,
  // read back through the forward transform, are the CL points turned by MSYS.
  const std::string job =
      "PARTNO MSYS DOWN\nMSYS/0.0000,0.0000,0.0000,1.0000000,0.0000000,0.0000000,0.0000000,-1.0000000,"
      "0.0000000\nTLDATA/MILL,10,0,100,0,0\nMULTAX/ON\nLOADTL/1\nSPINDL/RPM,6000,CLW\nFEDRAT/MMPM,800\n"
      "RAPID\nGOTO/0,0,-50,0,0,-1\nGOTO/10,0,5\nGOTO/20,0,5,0.1736482,0,-0.9848078\nGOTO/20,10,5\nRAPID\n"
      "GOTO/20,10,-50,0,0,-1\nFINI\n";
  for (const char* name : {"head-head-5axis", "trunnion-5axis"}) {
    INFO(name);
    const machine m = absolute(name);
    const round_trip r = read_back(job, m, std::string("fr-msys-") + name);
    CHECK(r.cl_points == 5);
    CHECK(r.worst_tip <= m.chain(1)->tolerance);
    CHECK(r.worst_axis <= m.chain(1)->angle_tolerance);
  }
  // The sample (an arc and a tilt about X under the turned MCS) on the three mills.
  for (const char* name : {"head-head-5axis", "trunnion-5axis", "rotary-4axis"}) {
    INFO(name);
    const machine m = absolute(name);
    const round_trip r = read_back(sample_job("nx-msys-z-down"), m, std::string("fr-msys-sample-") + name);
    CHECK(r.cl_points == 9);
    CHECK(r.worst_tip <= m.chain(1)->tolerance);
    CHECK(r.worst_axis <= m.chain(1)->angle_tolerance);
  }
  const test::posted t = test::post_in_fresh_dir(job, absolute("trunnion-5axis"), "fr-msys-exact");
  REQUIRE(t.ok);
  const std::string nc = t.files.at("MSYS_DOWN.nc");
  CHECK(nc.substr(nc.find("T01")) ==
        "T01 M6\nG54\nS6000 M3\nG0 A0. C90.\nG0 X0. Y0.\nG0 G43.4 H1 X0. Y0. Z50. A0. C90.\nG1 X10. Z-5. "
        "F800.\n"
        "X20. A10.\nY-10.\nG0 Z50.\nG0 A0.\nM9\nM5\nG91 G28 Z0.\nG90\nG49\nM30\n%\n");
  // On a 3-axis mill the turned axis is along Z: the points post, turned.
  const test::posted flat = test::post_in_fresh_dir(
      "PARTNO MSYS FLAT\nMSYS/5,0,0,0,1,0,1,0,0\nLOADTL/1\nSPINDL/RPM,6000,CLW\nFEDRAT/MMPM,800\n"
      "RAPID\nGOTO/0,0,-50,0,0,-1\nGOTO/10,20,3\nFINI\n",
      absolute("rotary-4axis"), "fr-msys-flat");
  INFO(flat.diagnostics);
  REQUIRE(flat.ok);
  const std::string f = flat.files.at("MSYS_FLAT.nc");
  // X = (0,1,0), Y = (1,0,0): (10,20,3) is the absolute (20,10,-3); the origin (5,0,0) is where
  // the MCS sits in the model, and the work offset stays on it.
  CHECK(f.find("G1 X20. Y10. Z-3. F800.") != std::string::npos);
  // A file that gives no tool axis: the axis in force is the MCS's +Z, turned with the points
  // (here the absolute -Z, which the trunnion cannot reach; before, the points were turned and
  // the axis left at +Z, and the tool fed up into the cut from below).
  const std::string bare =
      "PARTNO BARE\nMSYS/0,0,0,1,0,0,0,-1,0\nTLDATA/MILL,10,0,100,0,0\nLOADTL/1\n"
      "SPINDL/RPM,6000,CLW\nRAPID\nGOTO/10,10,50\nFEDRAT/MMPM,800\nGOTO/10,10,-3\nFINI\n";
  CHECK(
      test::post_in_fresh_dir(bare, absolute("trunnion-5axis"), "fr-msys-bare",
                              [](const diagnostic& d) { return d.level == severity::error; })
          .diagnostics ==
      "job.cls:7:1: error: channel 1: machine 'trunnion-5axis' cannot reach this point: tool axis (0, 0, -1) "
      "needs A180 C0 (A beyond -120..120)\nGOTO/10,10,50\n^\n"
      "job.cls:9:1: error: channel 1: machine 'trunnion-5axis' cannot reach this point: tool axis (0, 0, -1) "
      "needs A180 C0 (A beyond -120..120)\nGOTO/10,10,-3\n^\n");
}

TEST_CASE("frames: by default NX MSYS points are written in the CL's MCS", "[post][multiaxis][frames]") {
  // [program] cl_frame = "mcs" (the default): the work offset is the MCS's origin and the points
  // and tool axes go out as the CL gives them, whatever MSYS says of where the MCS lies.
  const std::string flat =
      "PARTNO MSYS FLAT\nMSYS/5,0,0,0,1,0,1,0,0\nLOADTL/1\nSPINDL/RPM,6000,CLW\n"
      "FEDRAT/MMPM,800\nRAPID\nGOTO/0,0,50,0,0,1\nGOTO/10,20,3\nFINI\n";
  const test::posted p = test::post_in_fresh_dir(flat, load_machine("rotary-4axis"), "fr-mcs-flat");
  INFO(p.diagnostics);
  REQUIRE(p.ok);
  CHECK(p.files.at("MSYS_FLAT.nc").find("G1 X10. Y20. Z3. F800.") != std::string::npos);
  // post --cl-frame absolute turns them for this post: (10,20,3) is the absolute (20,10,-3).
  // (Its tool axis is the MCS's -Z, the absolute +Z.)
  std::string turned = flat;
  turned.replace(turned.find("GOTO/0,0,50,0,0,1"), 17, "GOTO/0,0,-50,0,0,-1");
  const test::posted q = test::post_in_fresh_dir(turned, load_machine("rotary-4axis"), "fr-abs-flat", {}, {},
                                                 [](post_options& o) { o.frame = cl_frame::absolute; });
  REQUIRE(q.ok);
  CHECK(q.files.at("MSYS_FLAT.nc").find("G1 X20. Y10. Z-3. F800.") != std::string::npos);
  // On a lathe in the MCS: posted (turned, a lathe's MSYS is refused).
  const std::string lathe =
      "PARTNO L\nMSYS/0,0,0,1,0,0,0,-1,0\nTURRET/1,1\nSPINDL/RPM,1000,CLW\n"
      "FEDRAT/0.2,MMPR\nGOTO/20,0,0\nGOTO/20,0,-5\nFINI\n";
  CHECK(test::post_in_fresh_dir(lathe, load_machine("fanuc-0itd-twin"), "fr-mcs-lathe").ok);
}

TEST_CASE("frames: MSYS and CSYS that are not rigid, or whose meaning is not known, stop the post",
          "[post][frames]") {
  const machine mill = absolute("rotary-4axis");
  const std::string start = "LOADTL/1\nSPINDL/RPM,6000,CLW\nFEDRAT/MMPM,800\nRAPID\nGOTO/0,0,50\n";
  CHECK(test::post_in_fresh_dir("PARTNO F\nMSYS/0,0,0,2,0,0,0,1,0\n" + start + "FINI\n", mill, "fr-bad1")
            .diagnostics ==
        "job.cls:2:1: error: channel 1: MSYS/0,0,0,2,0,0,0,1,0: its X and Y axes are 2 and 1 long, not 1 (a "
        "scaled frame); only a rigid turn of the points is posted\nMSYS/0,0,0,2,0,0,0,1,0\n^\n");
  CHECK(test::post_in_fresh_dir("PARTNO F\nMSYS/0,0,0,1,0,0,0.6,0.8,0\n" + start + "FINI\n", mill, "fr-bad2")
            .diagnostics ==
        "job.cls:2:1: error: channel 1: MSYS/0,0,0,1,0,0,0.6,0.8,0: its axes are not square to each other (a "
        "sheared frame); only a rigid turn of the points is posted\nMSYS/0,0,0,1,0,0,0.6,0.8,0\n^\n");
  CHECK(test::post_in_fresh_dir("PARTNO F\nMSYS/0,0,0,1,0,0,0,-1,0\n" + start +
                                    "CYCLE/DRILL,RAPTO,3,FEDTO,-10,MMPM,100\nGOTO/0,0,0\nCYCLE/OFF\nFINI\n",
                                mill, "fr-bad3")
            .diagnostics ==
        "job.cls:8:1: error: channel 1: CYCLE/DRILL under MSYS (line 2), which turns the MCS: whether the "
        "cycle's "
        "levels turn with the points is not known (UNVERIFIED), so it is not posted; give the holes as GOTO "
        "moves\nCYCLE/DRILL,RAPTO,3,FEDTO,-10,MMPM,100\n^\n");
  // A lathe's CL frame is its own: a turned MCS there is not guessed at.
  CHECK(test::post_in_fresh_dir("PARTNO L\nMSYS/0,0,0,1,0,0,0,-1,0\nTURRET/1,1\nSPINDL/RPM,1000,CLW\n"
                                "FEDRAT/0.2,MMPR\nGOTO/20,0,0\nGOTO/20,0,-5\nFINI\n",
                                absolute("fanuc-0itd-twin"), "fr-lathe")
            .diagnostics ==
        "job.cls:2:1: error: channel 1: MSYS/0,0,0,1,0,0,0,-1,0: a turned MCS on a lathe channel (X in "
        "diameter), "
        "whose CL frame is the lathe's own; twinpost turns the points of an MCS on a mill only\n"
        "MSYS/0,0,0,1,0,0,0,-1,0\n^\n");
  CHECK(
      test::post_in_fresh_dir("PARTNO F\nCSYS/1,0,0,0,0,1,0,0,0,0,-1,0\n" + start + "FINI\n", mill, "fr-bad4")
          .diagnostics ==
      "job.cls:2:1: error: channel 1: CSYS/1,0,0,0,0,1,0,0,0,0,-1,0: it is left-handed (a mirrored frame); "
      "only a rigid frame is posted\nCSYS/1,0,0,0,0,1,0,0,0,0,-1,0\n^\n");
  CHECK(
      test::post_in_fresh_dir("PARTNO F\nCSYS/1,0,0,10,0,1,0,0,0,0,1,0\n" + start + "FINI\n", mill, "fr-bad5")
          .diagnostics ==
      "job.cls:2:1: error: channel 1: CSYS/1,0,0,10,0,1,0,0,0,0,1,0: a frame moved from the world origin; "
      "SolidWorks' points are in the world frame (TRNTYP/WORLD), but whether they include the move is not "
      "known (UNVERIFIED: no file seen), so it is not posted\nCSYS/1,0,0,10,0,1,0,0,0,0,1,0\n^\n");
}

TEST_CASE("frames: a turned SolidWorks CSYS posts its world points, each move along the frame's Z",
          "[post][multiaxis][frames]") {
  // As aamorim_Teste-Metrologia.apt: TRNTYP/WORLD, CSYS whose Z is +X, then GOTOs with the
  // axis 1,0,0 in the world frame, approaching along X.
  const machine m = load_machine("trunnion-5axis");
  const std::string head = "PARTNO SW\nMULTAX/ON\nLOADTL/1\nSPINDL/RPM,6000,CLW\nFEDRAT/MMPM,800\n";
  const std::string csys = "TRNTYP/WORLD,0,0,0\nCSYS/0,0,1.,0,0,1.,0,0,-1.,0,0,0\n";
  const std::string moves =
      "RAPID\nGOTO/250.,35.8375,-12.1625,1.,0,0\nGOTO/78.,35.8375,-12.1625,1.,0,0\n"
      "GOTO/78.,22.749812,-12.1625,1.,0,0\nFINI\n";
  const test::posted with = test::post_in_fresh_dir(head + csys + moves, m, "fr-csys1");
  const test::posted without = test::post_in_fresh_dir(head + moves, m, "fr-csys2");
  INFO(with.diagnostics);
  REQUIRE(with.ok);
  CHECK(with.files == without.files);
  const round_trip r = read_back(head + csys + moves, m, "fr-csys3");
  CHECK(r.cl_points == 3);
  // A move under another axis while the CSYS is in force: which frame is it in?
  CHECK(
      test::post_in_fresh_dir(head + csys +
                                  "RAPID\nGOTO/250.,35.8375,-12.1625,1.,0,0\nGOTO/78.,35,-12,0,0,1\n"
                                  "GOTO/78.,30,-12,0,0,1\nFINI\n",
                              m, "fr-csys4")
          .diagnostics ==
      "job.cls:10:1: error: channel 1: a move under the tool axis (0,0,1) while CSYS (line 7) turns the "
      "operation's tool to (1,0,0): SolidWorks CAM gives the points of a turned CSYS in the world frame with "
      "the tool along its Z; a point under another axis is in a frame twinpost cannot tell\n"
      "GOTO/78.,35,-12,0,0,1\n^\n");
}

TEST_CASE("frames: a tool axis of -Z on a machining centre without rotary axes is refused",
          "[post][multiaxis][frames]") {
  // The machine holds its tool pointing down: points written for a tool pointing up (an MCS with
  // Z down turned into the absolute frame, its implied axis with it) would be cut from below.
  machine m = load_machine(std::string(TWINPOST_SOURCE_DIR) + "/tests/kin/vmc3.toml");
  m.program.frame = cl_frame::absolute;
  const std::string bare =
      "PARTNO BARE\nMSYS/0,0,0,1,0,0,0,-1,0\nTLDATA/MILL,10,0,100,0,0\nLOADTL/1\n"
      "SPINDL/RPM,6000,CLW\nRAPID\nGOTO/10,10,-50\nFEDRAT/MMPM,800\nGOTO/10,10,2\nFINI\n";
  CHECK(test::post_in_fresh_dir(bare, m, "fr-vmc-up",
                                [](const diagnostic& d) { return d.level == severity::error; })
            .diagnostics ==
        "job.cls:7:1: error: channel 1: tool axis (0,0,-1) points the tool up, and machine 'vmc3' gives "
        "channel 1 "
        "no rotary axes to turn it: the points were written for a tool coming from below (is the CL's frame "
        "turned? NX MSYS: [program] cl_frame, post --cl-frame)\nGOTO/10,10,-50\n^\n");
  // In the MCS (the default) the same file is a tool along +Z, from above.
  m.program.frame = cl_frame::mcs;
  const test::posted p = test::post_in_fresh_dir(bare, m, "fr-vmc-mcs");
  INFO(p.diagnostics);
  CHECK(p.ok);
}

TEST_CASE("frames: a second MCS in one job, and an MCS turned under a cycle, stop the post",
          "[post][frames]") {
  auto errors = [](const std::string& cl, const machine& m, const std::string& tag) {
    return test::post_in_fresh_dir(cl, m, tag, [](const diagnostic& d) { return d.level == severity::error; })
        .diagnostics;
  };
  const std::string op =
      "LOADTL/1\nSPINDL/RPM,6000,CLW\nFEDRAT/MMPM,800\nRAPID\nGOTO/0,0,5,0,0,1\nGOTO/0,0,-1\n";
  // A datum on a boss at X50 Y50 Z40: its points would be cut in the first MCS's offset.
  const std::string boss =
      "PARTNO M\nMSYS/0,0,0,1,0,0,0,1,0\n" + op + "MSYS/50,50,40,1,0,0,0,1,0\n" + op + "FINI\n";
  for (const cl_frame f : {cl_frame::mcs, cl_frame::absolute}) {
    machine m = load_machine("trunnion-5axis");
    m.program.frame = f;
    CHECK(
        errors(boss, m, "fr-second") ==
        "job.cls:9:1: error: channel 1: MSYS/50,50,40,1,0,0,0,1,0: a second MCS, away from the one of line "
        "2: "
        "the program has one work offset, and which offset the machinist gives this MCS the CL does not say; "
        "post its operations as a job of their own\nMSYS/50,50,40,1,0,0,0,1,0\n^\n");
  }
  // A side face's MCS (turned, same origin): an error in the MCS, turned in the absolute frame.
  const std::string side =
      "PARTNO M\nMSYS/0,0,0,1,0,0,0,1,0\n" + op + "MSYS/0,0,0,1,0,0,0,0,1\n" + op + "FINI\n";
  CHECK(errors(side, load_machine("trunnion-5axis"), "fr-side") ==
        "job.cls:9:1: error: channel 1: MSYS/0,0,0,1,0,0,0,0,1: a second MCS, turned from the one of line 2: "
        "the "
        "program has one work offset, and which offset the machinist gives this MCS the CL does not say; "
        "post its "
        "operations as a job of their own (or write the program in the absolute frame, [program] cl_frame = "
        "\"absolute\", where an MCS may turn)\nMSYS/0,0,0,1,0,0,0,0,1\n^\n");
  CHECK(errors(side, absolute("trunnion-5axis"), "fr-side-abs").empty());
  // The holes of a cycle were read in the frame before the MSYS.
  CHECK(
      errors("PARTNO M\nLOADTL/1\nTLDATA/DRILL,8,0,75,118,40\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,20,0,0,1\n"
             "CYCLE/DRILL,FEDTO,-5,RAPTO,3,MMPM,100\nGOTO/0,0,0\nMSYS/0,0,0,1,0,0,0,0,1\nGOTO/10,0,0\n"
             "CYCLE/OFF\nFINI\n",
             absolute("trunnion-5axis"), "fr-cycle") ==
      "job.cls:9:1: error: channel 1: MSYS/0,0,0,1,0,0,0,0,1 turns the MCS while CYCLE/DRILL (line 7) is in "
      "force: whether the cycle's levels turn with the points is not known (UNVERIFIED); end the cycle "
      "(CYCLE/OFF) before the MSYS\nMSYS/0,0,0,1,0,0,0,0,1\n^\n");
}

TEST_CASE("frames: an MSYS after the job has moved is a second MCS", "[post][frames]") {
  // The first operation's moves were in the absolute frame; an MCS 100 mm away after them.
  const std::string cl =
      "PARTNO M\nLOADTL/1\nSPINDL/RPM,6000,CLW\nFEDRAT/MMPM,800\nRAPID\nGOTO/0,0,5,0,0,1\n"
      "GOTO/0,0,-1\nMSYS/100,0,0,1,0,0,0,1,0\nGOTO/10,0,-1\nFINI\n";
  CHECK(test::post_in_fresh_dir(cl, load_machine("trunnion-5axis"), "fr-after-moves",
                                [](const diagnostic& d) { return d.level == severity::error; })
            .diagnostics ==
        "job.cls:8:1: error: channel 1: MSYS/100,0,0,1,0,0,0,1,0: a second MCS, away from the "
        "absolute frame the job's first moves were in: the program has one work offset, and which "
        "offset the machinist gives this MCS the CL does not say; post its operations as a job of "
        "their own\nMSYS/100,0,0,1,0,0,0,1,0\n^\n");
}

TEST_CASE("multi-axis: pivot output on the C/A gantry reads back to the CL through the forward transform",
          "[post][multiaxis]") {
  machine m = load_machine(std::string(TWINPOST_SOURCE_DIR) + "/samples/nx-ca-pivot/gantry-ca-pivot.toml");
  m.program.frame = cl_frame::absolute;  // as the sample's post.args
  const round_trip r = read_back(sample_job("nx-ca-pivot"), m, "ma-pivot");
  CHECK(r.cl_points == 9);
  CHECK(r.sub_points > 60);  // the corners turn C by 90 degrees, cut to the chordal tolerance
  CHECK(r.worst_tip <= 0.004);
  CHECK(r.worst_axis <= 0.002);
  CHECK(r.worst_chord <= 0.01 + 0.004);
  // The words themselves: no length offset, X Y Z the pivot 150 mm up the tilted tool from the
  // tip (the MCS turned 90 degrees: the CL's (-20,-30,2) leaning -Y is (30,-20,2) leaning +X).
  const test::posted p = test::post_in_fresh_dir(sample_job("nx-ca-pivot"), m, "ma-pivot-words");
  REQUIRE(p.ok);
  const std::string& nc = p.files.at("PROGRAM.nc");
  CHECK(nc.find("G43") == std::string::npos);
  CHECK(nc.find(
            "S6000 M3\nG0 C90. A0.\nG0 X30. Y-20.\nZ190.\nG0 A20.\nG0 X81.303\nZ142.954\nG1 Z132.954 F1000.\n"
            "Y20.\nG93 G1 X80.408 Y20.991 Z133.218 C90.945 A19.703 F4525.483\n") != std::string::npos);
}

TEST_CASE("multi-axis: pivot output refuses a tool of another length, or warns where the control makes it up",
          "[post][multiaxis]") {
  machine m = load_machine(std::string(TWINPOST_SOURCE_DIR) + "/samples/nx-ca-pivot/gantry-ca-pivot.toml");
  m.tools.clear();  // the CL's TLDATA alone
  const std::string job =
      "PARTNO PIVOT\nTLDATA/MILL,10,0,120,0,0\nMULTAX/ON\nLOADTL/1\nSPINDL/RPM,5000,CLW\n"
      "FEDRAT/MMPM,500\nRAPID\nGOTO/0,0,50,0,0,1\nGOTO/0,0,0,0,0,1\nFINI\n";
  const test::posted refused = test::post_in_fresh_dir(job, m, "ma-pivot-len");
  CHECK(!refused.ok);
  CHECK(refused.diagnostics ==
        "job.cls:8:1: error: channel 1: tool 1 (LOADTL at line 4) is 120 mm long (the CL's TLDATA), and "
        "machine "
        "'gantry-ca-pivot' writes the pivot for a 150 mm tool ([[kinematics]] programmed_length): its tip "
        "would "
        "be 30 mm off along the tool; post it with a tool of that length, or name the control's length code "
        "([[kinematics]] length_on) that makes up the difference\nGOTO/0,0,50,0,0,1\n^\n");
  // No length at all: even upright the written Z is the tip + 150 mm.
  std::string no_length = job;
  no_length.replace(no_length.find("TLDATA/MILL,10,0,120,0,0\n"), 25, "");
  CHECK(
      test::post_in_fresh_dir(no_length, m, "ma-pivot-nolen").diagnostics ==
      "job.cls:7:1: error: channel 1: tool 1 (LOADTL at line 3) has no length, and machine 'gantry-ca-pivot' "
      "writes every point for a 150 mm tool ([[kinematics]] programmed_length); give TLDATA/MILL with the "
      "length, or length = ... under the tool's [[tool]] in the machine file\nGOTO/0,0,50,0,0,1\n^\n");
  // The table says 150, the CL 120, and the table counts: said, and posted.
  m.tools =
      load_machine(std::string(TWINPOST_SOURCE_DIR) + "/samples/nx-ca-pivot/gantry-ca-pivot.toml").tools;
  m.kinematics[0].tool_length = length_source::table;
  const test::posted table_wins = test::post_in_fresh_dir(job, m, "ma-pivot-table");
  REQUIRE(table_wins.ok);
  CHECK(
      table_wins.diagnostics ==
      "job.cls:8:1: warning: channel 1: tool 1 (LOADTL at line 4): the CL's TLDATA gives a length of 120 mm, "
      "machine "
      "'gantry-ca-pivot' lists 150 mm ([[tool]] length): the table's is compared with the programmed 150 mm "
      "([[kinematics]] tool_length = \"table\")\n");
  m.tools.clear();
  m.kinematics[0].tool_length = length_source::agree;
  m.kinematics[0].length_on = "G43.1";
  const test::posted made_up = test::post_in_fresh_dir(job, m, "ma-pivot-len-on");
  INFO(made_up.diagnostics);
  REQUIRE(made_up.ok);
  CHECK(made_up.diagnostics.find("G43.1 H1 must make up -30 mm along the tool") != std::string::npos);
  CHECK(made_up.files.at("PIVOT.nc").find("G0 G43.1 H1 X0. Y0. Z200. C0. A0.\nG1 Z150. F500.\n") !=
        std::string::npos);
}

TEST_CASE("multi-axis: the C/A gantry writes C before A and semicolon comments, and drills with C turned",
          "[post][multiaxis]") {
  const machine m = load_machine(std::string(TWINPOST_SOURCE_DIR) + "/samples/nx-ca-head/gantry-ca.toml");
  // A cut leaning towards +X (C90 A15), back upright with C left at 90, then a hole with the
  // same tool: C about the tool's own axis leaves X Y Z the tip, so the canned cycle is written.
  const test::posted p = test::post_in_fresh_dir(
      "PARTNO LEAN\nTLDATA/MILL,12,0,150,0,0\nMULTAX/ON\nLOADTL/1\nPPRINT/LEAN (15 "
      "DEG)\nSPINDL/RPM,5000,CLW\nFEDRAT/MMPM,500\n"
      "RAPID\nGOTO/0,0,50,0.2588190,0,0.9659258\nGOTO/0,0,0,0.2588190,0,0.9659258\nRAPID\n"
      "GOTO/0,0,50,0,0,1\nCYCLE/DRILL,DEPTH,5,CLEAR,2,MMPM,100\nGOTO/20,0,0,0,0,1\nCYCLE/OFF\nFINI\n",
      m, "ma-ca-lean");
  INFO(p.diagnostics);
  REQUIRE(p.ok);
  const std::string& nc = p.files.at("LEAN.nc");
  // A comment runs from ';' to the end of the line, its parentheses blanked.
  CHECK(nc.find("\n;LEAN  15 DEG\n") != std::string::npos);
  // The tip 150 mm below the nose, the nose over X38.823 (150 sin 15): X Y Z the tip with the
  // heads at 0, C then A in every block. Back upright the tip would swing down 150 (1 - cos 15)
  // = 5.111 mm below where it stood (Z55.111, tilted at Z50): it rises that much first.
  CHECK(
      nc.find(
          "S5000 M3\nG0 C90. A15.\nG0 X38.823 Y0.\nG0 G43 H1 X38.823 Y0. Z44.889 C90. A15.\n"
          "G1 Z-5.111 F500.\nG0 Z50.\nG0 Z55.111\nG0 A0.\nG0 X0.\nZ50.\nX20.\nZ2.\nG98 G81 X20. Y0. Z-5. R2. "
          "F100.\nG80\n") != std::string::npos);
}

TEST_CASE("multi-axis: feed blocks faster than the control reads them are counted and named",
          "[post][multiaxis]") {
  machine m = load_machine(std::string(TWINPOST_SOURCE_DIR) + "/samples/nx-ca-pivot/gantry-ca-pivot.toml");
  m.program.frame = cl_frame::absolute;
  m.limits.blocks_per_second = 50;  // 20 ms a block: the sub-moves of the corners take 13.3 ms
  const test::posted p = test::post_in_fresh_dir(sample_job("nx-ca-pivot"), m, "ma-rate");
  REQUIRE(p.ok);
  const std::size_t out = p.diagnostics.find("out/PROGRAM.nc");  // the test's own folder before it
  REQUIRE(out != std::string::npos);
  CHECK(
      p.diagnostics.substr(out) ==
      "out/PROGRAM.nc:21:1: warning: channel 1: 128 feed blocks take less than the 20 ms a block the control "
      "reads (limits.blocks_per_second = 50); this one, the shortest, 13.3 ms at its feed: the control would "
      "slow the feed down there (a coarser chordal_tolerance or CAM tolerance gives fewer, longer blocks)\n"
      "G93 G1 X80.408 Y20.991 Z133.218 C90.945 A19.703 F4525.483\n^\n");
  m.limits.blocks_per_second = 70;  // 14.3 ms
  CHECK(test::post_in_fresh_dir(sample_job("nx-ca-pivot"), m, "ma-rate-70")
            .diagnostics.find("128 feed blocks") != std::string::npos);
  m.limits.blocks_per_second = 76;  // 13.16 ms a block, the sub-moves 60/4525.483 = 13.26 ms: none counted
  CHECK(test::post_in_fresh_dir(sample_job("nx-ca-pivot"), m, "ma-rate-76").diagnostics.empty());
}

TEST_CASE("multi-axis: an axis on its limit within the CL's print rounding is on it", "[post][multiaxis]") {
  // Review 45: B20 A-10 in NX's 7 decimals solves to B20.00000018 on head-head-5axis (B -20..20),
  // refused as beyond the limit though B20.000 is what the block says.
  const test::posted p = test::post_in_fresh_dir(
      "PARTNO LIMIT\nLOADTL/1\nTLDATA/MILL,10,0,100,0,0\nSPINDL/RPM,6000,CLW\nFEDRAT/MMPM,1000\nRAPID\n"
      "GOTO/0,0,60,0.3368241,0.1736482,0.9254166\nGOTO/0,0,50,0.3368241,0.1736482,0.9254166\nFINI\n",
      load_machine("head-head-5axis"), "ma-on-limit");
  INFO(p.diagnostics);
  REQUIRE(p.ok);
  CHECK(p.files.at("LIMIT.nc").find("G68.2 X0. Y0. Z0. I117.273 J22.269 K-117.273\n") != std::string::npos);
}

TEST_CASE(
    "multi-axis: a rapid that turns the head below the CAM's clearance turns it at the tool-change height",
    "[post][multiaxis]") {
  // Review 45: a slot at Z-5, a RAPID up to Z-3 and on to a point 10 degrees over: turned in
  // place at Z-3 the 150 mm tool's tip swung 26 mm sideways, 6 mm into the slot's end wall.
  // Neither end is as high as the approach came down from (Z50): home, turn, over, down.
  const machine m = load_machine(std::string(TWINPOST_SOURCE_DIR) + "/samples/nx-ca-head/gantry-ca.toml");
  const std::string slot =
      "PARTNO LOW\nTLDATA/MILL,12,0,150,0,0\nLOADTL/1\nSPINDL/RPM,6000,CLW\nFEDRAT/MMPM,1000\nRAPID\n"
      "GOTO/0,0,50,0,0,1\nRAPID\nGOTO/0,0,2\nGOTO/0,0,-5\nGOTO/20,0,-5\nRAPID\nGOTO/20,0,";
  const std::string tilt =
      "\nRAPID\nGOTO/25,0,-3,0.1736482,0,0.9848078\nGOTO/40,0,-5,0.1736482,0,0.9848078\nFINI\n";
  const test::posted low = test::post_in_fresh_dir(slot + "-3" + tilt, m, "ma-low-turn");
  INFO(low.diagnostics);
  REQUIRE(low.ok);
  CHECK(low.files.at("LOW.nc").find("X20.\nG0 Z-3.\nG91 G28 Z0.\nG90\nG49\nG0 C90. A10.\nG0 X51.047 Y0.\n"
                                    "G0 G43 H1 X51.047 Y0. Z-5.279 C90. A10.\n") != std::string::npos);
  // Up at the approach's height first: the head turns there, after rising by its dip.
  const test::posted clear = test::post_in_fresh_dir(slot + "50" + tilt, m, "ma-clear-turn");
  REQUIRE(clear.ok);
  CHECK(clear.files.at("LOW.nc").find("X20.\nG0 Z50.\nG0 A10.\nG0 X51.047\nZ-5.279\n") != std::string::npos);
}

TEST_CASE("multi-axis: a low head turn on a machine with no home blocks is refused", "[post][multiaxis]") {
  // Verify 46: with home = [] the fallback lifted nothing and turned the head at the cut's depth.
  machine m = load_machine(std::string(TWINPOST_SOURCE_DIR) + "/samples/nx-ca-head/gantry-ca.toml");
  m.codes.home.clear();
  const test::posted p = test::post_in_fresh_dir(
      "PARTNO LOW\nTLDATA/MILL,12,0,150,0,0\nLOADTL/1\nSPINDL/RPM,6000,CLW\nFEDRAT/MMPM,1000\nRAPID\n"
      "GOTO/0,0,50,0,0,1\nRAPID\nGOTO/0,0,2\nGOTO/0,0,-5\nGOTO/20,0,-5\nRAPID\nGOTO/20,0,-3\nRAPID\n"
      "GOTO/25,0,-3,0.1736482,0,0.9848078\nFINI\n",
      m, "ma-low-no-home");
  CHECK(
      p.diagnostics.find("job.cls:15:1: error: channel 1: the heads would turn below the CAM's clearance, "
                         "swinging the tip sideways, and the machine has no home blocks (codes.home) to lift "
                         "the tool first: give the rapid at the clearance\n") != std::string::npos);
  CHECK_FALSE(p.ok);
}

TEST_CASE("multi-axis: a low head turn whose home blocks cancel the control's own length offset is refused",
          "[post][multiaxis]") {
  // Verify 46: a Sinumerik-style gantry whose tool call gives the offset (`T1 D1 M6`, length_on
  // = "") and whose home is `SUPA G0 Z0 D0`: after the low turn's home the Z words were the
  // spindle nose's, the tip 150 mm below them.
  machine m = load_machine(std::string(TWINPOST_SOURCE_DIR) + "/samples/nx-ca-head/gantry-ca.toml");
  m.kinematics.at(0).length_on.clear();
  const std::string job =
      "PARTNO LOW\nTLDATA/MILL,12,0,150,0,0\nLOADTL/1\nSPINDL/RPM,6000,CLW\nFEDRAT/MMPM,1000\nRAPID\n"
      "GOTO/0,0,50,0,0,1\nRAPID\nGOTO/0,0,2\nGOTO/0,0,-5\nGOTO/20,0,-5\nRAPID\nGOTO/20,0,-3\nRAPID\n"
      "GOTO/25,0,-3,0.1736482,0,0.9848078\nFINI\n";
  for (const char* home : {"SUPA G0 Z0 D0", "G91 G28 Z0. G49", "G53 Z0 H00"}) {
    m.codes.home = {home};
    const test::posted p = test::post_in_fresh_dir(job, m, "ma-low-d0");
    CHECK(p.diagnostics.find(fmt::format(
              "job.cls:15:1: error: channel 1: the heads would turn below the CAM's clearance, swinging the "
              "tip sideways, and the home blocks that lift the tool first cancel the tool's length offset "
              "(\"{}\"), which the tool call gives on this machine (kinematics.length_on = \"\"): give the "
              "rapid at the clearance\n",
              home)) != std::string::npos);
    CHECK_FALSE(p.ok);
  }
  // A home that leaves the offset alone (a G28 return, which keeps G43 on a Fanuc) still turns
  // the head up there.
  m.codes.home = {"G91 G28 Z0.", "G90"};
  const test::posted up = test::post_in_fresh_dir(job, m, "ma-low-g28");
  INFO(up.diagnostics);
  REQUIRE(up.ok);
  CHECK(up.files.at("LOW.nc").find("X20.\nG0 Z-3.\nG91 G28 Z0.\nG90\nG0 A10.\nG0 X51.047 Y0.\nZ-5.279\n") !=
        std::string::npos);
}

TEST_CASE("multi-axis: GOHOME whose home blocks cancel the length offset gives it back, or is refused",
          "[post][multiaxis]") {
  // Attack 47: a GOHOME in the middle of an operation on gantry-ca with `G49` in its home
  // blocks; the plunge after it ran 150 mm low. With length_on = "G43" the next move gives
  // `G43 H1` again; with the control's own offset (length_on = "") the post has no code for it.
  machine m = load_machine(std::string(TWINPOST_SOURCE_DIR) + "/samples/nx-ca-head/gantry-ca.toml");
  m.codes.home = {"G91 G28 Z0.", "G90", "G49"};
  const std::string job =
      "PARTNO GOHOME\nTLDATA/MILL,12,0,150,0,0\nLOADTL/1\nSPINDL/RPM,6000,CLW\nFEDRAT/MMPM,1000\nRAPID\n"
      "GOTO/0,0,50,0,0,1\nGOTO/0,0,-5\nGOHOME\nRAPID\nGOTO/20,0,50\nGOTO/20,0,-5\nFINI\n";
  const test::posted g43 = test::post_in_fresh_dir(job, m, "ma-gohome-g43");
  INFO(g43.diagnostics);
  REQUIRE(g43.ok);
  CHECK(g43.files.at("GOHOME.nc")
            .find("G1 Z-5. F1000.\nG91 G28 Z0.\nG90\nG49\nG0 C0. A0.\nG0 X20. Y0.\n"
                  "G0 G43 H1 X20. Y0. Z50. C0. A0.\nG1 Z-5.\n") != std::string::npos);
  m.kinematics.at(0).length_on.clear();
  const test::posted own = test::post_in_fresh_dir(job, m, "ma-gohome-own");
  CHECK(own.diagnostics ==
        "job.cls:11:1: error: channel 1: the home blocks written before this move (GOHOME) cancel the tool's "
        "length offset, which the tool call gives on this machine (kinematics.length_on = \"\"): the move "
        "would "
        "run the tip a tool length low; call the tool again (LOADTL) after GOHOME\nGOTO/20,0,50\n^\n");
  CHECK_FALSE(own.ok);
}

TEST_CASE("multi-axis: a machine whose home cancels the control's own length offset is refused at load",
          "[machine][multiaxis]") {
  // Attack 48: with length_on = "" the tool call gives the offset, and the post goes home in
  // the middle of a tool (a 3+2 plane, a low head turn, GOHOME) with no code to give it back.
  std::string text = test::read_file(std::string(TWINPOST_SOURCE_DIR) + "/samples/nx-ca-head/gantry-ca.toml");
  const std::size_t home = text.find("\nhome = ");
  REQUIRE(home != std::string::npos);
  text.replace(home + 1, text.find('\n', home + 1) - home - 1, "home = [\"G91 G28 Z0.\", \"G90\", \"G49\"]");
  const std::size_t on = text.find("length_on = ");
  REQUIRE(on != std::string::npos);
  text.replace(on, text.find('\n', on) - on, "length_on = \"\"");
  try {
    (void)parse_machine(text, "g.toml");
    FAIL("loaded");
  } catch (const config_error& e) {
    CHECK(std::string(e.what()).find(
              "codes.home \"G49\" cancels the tool length offset, and kinematics.length_on "
              "is \"\": the post goes home in the middle of a tool (a 3+2 plane, a head "
              "turned low, GOHOME) and has no code to give the offset back; give "
              "kinematics.length_on (G43), or home blocks that keep the offset") != std::string::npos);
  }
}

TEST_CASE("multi-axis: a tool change straight from a cut leaves along Z only with the tool along Z",
          "[post][multiaxis]") {
  // Attack 65: with the head at 0 the end mill leaves its cut along Z before its spindle stops;
  // tilted 15 degrees, machine Z is not its axis: the machine's order, and the post says it.
  const std::string head =
      "PARTNO CUT\nTLDATA/MILL,10,0,100,0,0\nLOADTL/1\nSPINDL/RPM,8000,CLW\nFEDRAT/MMPM,1000\n"
      "RAPID\nGOTO/0,0,50,0,0,1\n";
  const machine m = load_machine("head-head-5axis");
  const test::posted upright = test::post_in_fresh_dir(
      head + "GOTO/0,0,-5,0,0,1\nTLDATA/MILL,8,0,100,0,0\nLOADTL/2\nRAPID\nGOTO/0,0,50,0,0,1\nFINI\n", m,
      "ma-cut-up", [](const diagnostic&) { return true; });
  INFO(upright.diagnostics);
  REQUIRE(upright.ok);
  CHECK(upright.files.at("CUT.nc").find("G1 Z-5. F1000.\nG91 G28 Z0.\nG90\nM5\nG49\nT02 M6\n") !=
        std::string::npos);
  const test::posted tilted =
      test::post_in_fresh_dir(head +
                                  "GOTO/0,0,-5,0.258819,0,0.965926\nTLDATA/MILL,8,0,100,0,0\nLOADTL/"
                                  "2\nRAPID\nGOTO/0,0,50,0,0,1\nFINI\n",
                              m, "ma-cut-tilted", [](const diagnostic&) { return true; });
  CHECK(tilted.diagnostics.find(
            "job.cls:10:1: warning: channel 1: the tool goes home straight from a feed move, "
            "with no retract in the CL") != std::string::npos);
}
