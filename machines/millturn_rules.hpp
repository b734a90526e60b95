#pragma once
// Mill/turn on a lathe channel with a C axis: the workpiece spindle held as a C axis, polar
// interpolation, C-positioned holes and an indexing B head (docs/machines.md, "Mill/turn").
// Plain data, read by machines/machine_milling.cpp and the spindle and channel readers.
#include <optional>
#include <string>
#include <vector>

namespace twinpost {

/// A workpiece spindle that can be held as a C axis ([[spindle]] c_on, c_off, c_clamp,
/// c_unclamp). Empty `on`: it cannot, and live-tool work on it stops the post.
struct c_axis_codes {
  std::vector<std::string> on;   ///< the spindle becomes the C axis (Mazak M200: milling mode)
  std::vector<std::string> off;  ///< back to a turning spindle (Mazak M202)
  std::string clamp;             ///< holds C still for a hole (Mazak M210); "": none
  std::string unclamp;           ///< frees it again before C moves (Mazak M212)
  bool present() const { return !on.empty(); }
};

/// An indexing tool head on a channel ([channel.head_index]): the head turns to a fixed angle
/// for each tool, unclamped, moved in machine coordinates and clamped again (Integrex B head:
/// M108, G0 G53 B.., M107). The angles say where the tool points: `axial` along the spindle
/// axis (face work), `radial` across it (cross holes, OD milling), `turning` for turning tools.
struct head_index_rules {
  char address = 'B';
  std::string unclamp;  ///< before the move; "": none
  std::string move;     ///< the block the angle word is appended to ("G0 G53")
  std::string clamp;    ///< after the move; "": none
  std::optional<double> turning, axial, radial;
  /// The same for work on a spindle that faces the main one (`reverse_z`, the sub): the head
  /// turned to face it (Integrex B180 for axial work); none: such work stops the post.
  std::optional<double> turning_sub, axial_sub, radial_sub;
  /// Words put in the first move after the head is indexed: the tool length offset of a
  /// turning tool and of a live tool (Integrex: `G43 P1 H#3020`, `G43 H#3020`); "": none.
  std::string offset_turning, offset_live;
  bool present() const { return !move.empty(); }
};

/// [milling]: how a channel with a C axis posts live-tool work (docs/machines.md, "Mill/turn").
struct milling_rules {
  /// X in radius while the spindle is a C axis (Mazak G10.9 X0), and back in diameter (G10.9 X1).
  std::vector<std::string> radius_input, diameter_input;
  /// Polar interpolation on and off (G17 + G12.1, G13.1 + G18 on the Integrex).
  std::vector<std::string> polar_on, polar_off;
  /// The feed a CL rapid is written with inside polar interpolation on a control that takes
  /// no G0 there (mm/min, G1); 0: rapids are G0 (the Fusion Integrex post's useG0Polar).
  double polar_rapid_feed = 0;
  /// Off-centre milling with the tool along the spindle axis: "y_axis" (X Y Z words) or
  /// "polar" (polar interpolation, the Y of the CL as the C axis's linear value).
  std::string face_milling = "y_axis";
  /// Off-centre axial holes with a live tool: "y_axis" (X Y) or "c_axis" (C turns the hole
  /// onto the X axis: X is its radius).
  std::string face_holes = "y_axis";
  /// Cross (radial) holes: the frame turned so that the tool's axis is its Z, written after C
  /// is positioned (Integrex: `G68 X0. Y0. Z0. I0. J1. K0. R90.`, about Y by the head's
  /// radial angle) and cancelled after (`G69`). The holes are then drilled with the [cycles]
  /// codes in that frame: X is the part's -Z, Y its Y, Z the radius. Empty: cross holes stop
  /// the post.
  std::vector<std::string> radial_frame_on, radial_frame_off;
  /// How cross holes and the moves of a radial tool are written: "turned_frame" (the frame
  /// above, the [cycles] codes along its Z: Integrex) or "side_cycle" (C turned to the tool
  /// axis's angle and clamped, X the diameter along the tool, the [cycles] side codes: Fanuc
  /// G87/G88 as the Fusion "Doosan Mill/Turn" post writes them).
  std::string cross_holes = "turned_frame";
  /// Cylindrical interpolation for milling on the diameter with a radial tool, written inside
  /// the turned frame of cross holes (Integrex: `G17`, `G7.1 C{radius}`; off `G7.1 C0`, `G18`),
  /// or with cross_holes = "side_cycle" on the lathe's own axes: `G1 Z.. C<degrees>`, X the
  /// diameter (Fanuc: `G18 W0 H0`, `G7.1 C{radius}`; off `G7.1 C0`).
  /// One block of `cylindrical_on` holds `{radius}` (the cylinder's radius, mm) or `{diameter}`.
  /// Inside, a cut is `G1 X<the part's -Z> C<degrees> F..` with Z (the turned frame's) the
  /// tip's radius. Empty: a feed move with a radial tool stops the post.
  std::vector<std::string> cylindrical_on, cylindrical_off;
  bool given = false;  ///< the machine file has a [milling] table
  bool present() const { return given; }
};

}  // namespace twinpost
