#pragma once
// A channel's kinematic chain as data ([[kinematics]] of a machine file, read by
// machines/machine_kinematics.cpp): the linear axes, then up to two rotary axes, each a head
// or a table. Plain structs; the geometry that uses them is kinematics/ (docs/kinematics.md
// gives the frames and signs).
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "support/vec3.hpp"

namespace twinpost {

/// What a rotary axis turns: the tool (a head, carried by the linear axes) or the workpiece
/// (a table, carrying the part).
enum class rotary_kind { head, table };

/// How a rotary axis without limits counts its turns.
enum class rotary_rollover {
  absolute,  ///< multi-turn: the value goes on past 360 (and below 0); a move is value - previous
  shortest,  ///< the control reads the value modulo 360 and turns the shorter way: values 0 <= v < 360
};

/// The tilt sign to take when the two solutions of an orientation differ in it.
enum class preferred_sign { none, positive, negative };

/// One rotary axis. A positive value turns the moving member (the head with the tool, or the
/// table with the part) right-handed about `direction`, through `point`.
struct rotary_axis_def {
  char address = 'B';
  rotary_kind kind = rotary_kind::head;
  /// Unit direction of the axis at the home pose (every rotary axis at 0), in the machine
  /// frame (the axes X, Y, Z of the linear axes).
  vec3 direction{0, 1, 0};
  /// A point on the axis at the home pose. A table: in the part frame (the CL's frame, the
  /// same as the machine frame with every table at 0), so the table's rotation centre
  /// measured from the work zero. A head: measured from the gauge point (the spindle nose,
  /// where the tool length starts) with every linear axis and rotary at 0; the pivot length
  /// is its distance along the tool direction.
  vec3 point{};
  /// Travel limits in degrees; both absent: the axis is continuous.
  std::optional<double> min, max;
  rotary_rollover rollover = rotary_rollover::absolute;
  preferred_sign prefer = preferred_sign::none;
  bool continuous() const { return !min && !max; }
};

/// How the post writes a channel's multi-axis moves (docs/machines.md, "Multi-axis output").
enum class multiaxis_output {
  joints,    ///< full inverse kinematics: X Y Z and the rotary values, linearised, G93 on rotary moves
  tool_tip,  ///< tool-tip control (G43.4 H..): X Y Z the tip in the part frame, with the rotary values
  vector,    ///< tool-tip control with the tool axis (G43.5 H.. I J K): X Y Z the tip, I J K the axis
  pivot,     ///< no tool-tip control: X Y Z the head's pivot in the part frame for a fixed programmed
             ///< tool length, with the rotary values, linearised, G93 on rotary moves
};

/// The order of the rotary words in a block.
enum class rotary_word_order : unsigned char {
  address,  ///< by address (A, B, C), as most controls list them
  chain,    ///< as the [[kinematics.rotary]] tables list them (C before A on a C/A head)
};

/// Which GOTOs of the channel the multi-axis writer takes.
/// Whose tool length joints output uses when the CL's TLDATA and the machine's [[tool]] length
/// differ: none (`agree`: the post stops), the tool table's, or the CL's (docs/machines.md).
enum class length_source : unsigned char { agree, table, cl };

enum class multiaxis_moves {
  all,     ///< every move (a 5-axis mill: the length offset and rotary words from the first)
  tilted,  ///< only under a tool axis off the tool direction, or with a rotary axis off 0 (a
           ///< mill/turn head: turning moves stay the lathe's)
};

/// The kinematic chain of one channel.
struct kinematic_chain {
  int channel = 1;  ///< the channel it describes
  /// The addresses of the linear axes along the machine frame's x, y and z ("X", "Y", "Z").
  std::string linear = "XYZ";
  /// The rotary axes in chain order: a table before the table it carries, a head before the
  /// head it carries. At most two.
  std::vector<rotary_axis_def> rotaries;
  /// The tool direction (from the tip towards the spindle) at the home pose.
  vec3 tool_direction{0, 0, 1};
  /// Every inverse is checked by the forward transform to these: tip (mm) and axis (degrees).
  double tolerance = 0.001;
  double angle_tolerance = 0.001;
  /// How the post writes the channel's moves under a tool axis not along Z.
  multiaxis_output output = multiaxis_output::joints;
  multiaxis_moves moves = multiaxis_moves::all;
  rotary_word_order rotary_order = rotary_word_order::address;
  /// Pivot output: the tool length (mm) every point is written for, whatever the tool, and the
  /// pivot, where the heads' axes cross on the tool's axis (from the gauge point, home pose).
  double programmed_length = 0;
  vec3 pivot_point{};
  /// [[kinematics]] tool_length: which length wins when TLDATA and [[tool]] differ.
  length_source tool_length = length_source::agree;
  /// The code that turns tool-tip control on (G43.4 or G43.5, written with H and the tool's
  /// offset) and the one that cancels it (and the length offset of joints output).
  std::string tool_tip_on = "G43.4", tool_tip_off = "G49";
  /// The code of the length offset in joints output, written with H (G43).
  std::string length_on = "G43";
  /// Joints output: the inverse-time feed code of moves that turn a rotary axis (G93); the
  /// machine's codes.feed_per_min (G94) ends it.
  std::string inverse_time = "G93";
  /// Joints output: the chordal tolerance (mm) the tip of each sub-move keeps from the CL
  /// segment (kin::linearise).
  double chordal_tolerance = 0.01;
  /// 3+2 work: the tilted working plane code (G68.2, with Z-X-Z Euler angles I J K), "" for
  /// none; the code that turns the rotary axes to it (G53.1) and the one that cancels it (G69).
  std::string plane, plane_index = "G53.1", plane_off = "G69";
};

/// Whether the post solves the joints itself (joints and pivot output) rather than leaving the
/// tip to the control's tool-tip control.
inline bool solves_joints(const kinematic_chain& c) {
  return c.output == multiaxis_output::joints || c.output == multiaxis_output::pivot;
}

/// The code that turns the channel's length offset on: joints and pivot output's `length_on`,
/// tool-tip control's `tool_tip_on`.
inline const std::string& offset_code(const kinematic_chain& c) {
  return solves_joints(c) ? c.length_on : c.tool_tip_on;
}

/// Pivot output: the pivot's place from the linear values (the tip at the home pose, kinematics.md):
/// the programmed length up the tool direction to the gauge point, then the pivot from there.
inline vec3 pivot_shift(const kinematic_chain& c) {
  const vec3& t = c.tool_direction;
  const double l = c.programmed_length;
  return {t.x * l + c.pivot_point.x, t.y * l + c.pivot_point.y, t.z * l + c.pivot_point.z};
}

/// The rotary axes' indices in the order their words are written.
inline std::array<std::size_t, 2> rotary_words(const kinematic_chain& c) {
  std::array<std::size_t, 2> order{0, 1};
  if (c.rotary_order == rotary_word_order::address && c.rotaries.size() == 2 &&
      c.rotaries[1].address < c.rotaries[0].address)
    std::swap(order[0], order[1]);
  return order;
}

/// Whether the CL's and the table's tool lengths (mm) differ beyond the chain's tolerance.
inline bool lengths_differ(const kinematic_chain& c, std::optional<double> table, std::optional<double> cl) {
  return table && cl && std::abs(*table - *cl) > c.tolerance;
}

/// The tool length joints output uses: whichever of the table's and the CL's is given; both
/// given and differing, the one `tool_length` names (under `agree` the table's, for a caller
/// that has refused the tool already). Pivot output: the programmed length, whatever the tool.
inline std::optional<double> chosen_length(const kinematic_chain& c, std::optional<double> table,
                                           std::optional<double> cl) {
  if (c.output == multiaxis_output::pivot) return c.programmed_length;
  if (table && cl) return c.tool_length == length_source::cl ? cl : table;
  return table ? table : cl;
}

}  // namespace twinpost
