// Frames of the CL data (docs/records.md, "Frames"). NX writes MSYS/ox,oy,oz,xx,xy,xz,yx,yy,yz:
// the origin of the machine coordinate system (MCS) and the first two columns of the matrix
// that maps the CLSF's points from the MCS to the absolute frame, the third column their cross
// product (NX's CLSF description, as steptools/STEPNode examples/ParseNX.js quotes it). The
// points stay measured from the MCS origin (the work offset); its rotation turns them and their
// tool axes before the kinematics, so an MCS with Z down does not ask a 5-axis head for B180.
// SolidWorks CAM writes TRNTYP/WORLD with CSYS/ the 3x4 matrix of the operation's frame: its
// points and tool axes are in the world frame already (aamorim_Teste-Metrologia.apt: after
// CSYS/0,0,1,0,0,1,0,0,-1,0,0,0, whose Z is +X, every GOTO carries the axis 1,0,0 and the
// approach runs along X), so the post takes them as given and holds each move to the frame's Z.
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <variant>

#include "kinematics/vec3_ops.hpp"
#include "machining/channel_writer.hpp"

namespace twinpost {

using kin::operator*;
using kin::operator+;

namespace {

constexpr double rigid_tol = 1e-6;  // the CAMs write 6 or 7 decimals

// Why columns `x`, `y`, `z` are no rotation ("" when they are one, right-handed).
std::string not_rigid(const vec3& x, const vec3& y, const vec3& z) {
  // X and Y first: MSYS gives them, its Z is their cross product.
  const double lx = kin::norm(x), ly = kin::norm(y);
  if (std::abs(lx - 1) > rigid_tol || std::abs(ly - 1) > rigid_tol)
    return fmt::format("its X and Y axes are {:g} and {:g} long, not 1 (a scaled frame)", lx, ly);
  const double xy = kin::dot(x, y), yz = kin::dot(y, z), zx = kin::dot(z, x);
  if (std::abs(xy) > rigid_tol || std::abs(yz) > rigid_tol || std::abs(zx) > rigid_tol)
    return "its axes are not square to each other (a sheared frame)";
  const double lz = kin::norm(z);
  if (std::abs(lz - 1) > rigid_tol) return fmt::format("its Z axis is {:g} long, not 1 (a scaled frame)", lz);
  if (kin::dot(kin::cross(x, y), z) < 0) return "it is left-handed (a mirrored frame)";
  return "";
}

bool is_identity(const vec3& x, const vec3& y, const vec3& z) {
  return kin::distance(x, {1, 0, 0}) <= 1e-9 && kin::distance(y, {0, 1, 0}) <= 1e-9 &&
         kin::distance(z, {0, 0, 1}) <= 1e-9;
}

}  // namespace

void channel_writer::frame(const coordsys_event& c, int line) {
  const std::vector<double>& v = c.values;
  if (c.source == "MSYS") {
    if (v.size() != 9)
      return error(line,
                   fmt::format("MSYS/{}: NX writes 9 values (origin, the MCS's X and Y)", fmt::join(v, ",")));
    const vec3 x{v[3], v[4], v[5]}, y{v[6], v[7], v[8]};
    const vec3 z = kin::cross(x, y);
    const std::string why = not_rigid(x, y, z);
    if (!why.empty())
      return error(line, fmt::format("MSYS/{}: {}; only a rigid turn of the points is posted",
                                     fmt::join(v, ","), why));
    // One program has one work offset. A second MCS elsewhere (another setup face, a datum on
    // a boss) would be cut in the first one's offset: which offset the machinist gives it the
    // CL does not say. In the absolute frame the MCS may turn (3+2 setups about one origin).
    // Moves before the first MSYS were in the absolute frame: that is the first MCS then.
    if (!first_msys_ && cl_moved_) first_msys_ = std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0};
    if (!first_msys_) {
      first_msys_ = v;
      first_msys_line_ = line;
    } else {
      double moved = 0, turned = 0;
      for (std::size_t i = 0; i < 3; ++i) moved = std::max(moved, std::abs(v[i] - (*first_msys_)[i]));
      for (std::size_t i = 3; i < 9; ++i) turned = std::max(turned, std::abs(v[i] - (*first_msys_)[i]));
      if (moved > 1e-4 || (frame_ == cl_frame::mcs && turned > 1e-6))
        return error(
            line,
            fmt::format("MSYS/{}: a second MCS, {} {}: the program has one work "
                        "offset, and which offset the machinist gives this MCS the CL does not "
                        "say; post its operations as a job of their own{}",
                        fmt::join(v, ","), moved > 1e-4 ? "away from" : "turned from",
                        first_msys_line_ ? fmt::format("the one of line {}", first_msys_line_)
                                         : std::string("the absolute frame the job's first moves were in"),
                        moved > 1e-4 ? ""
                                     : " (or write the program in the absolute frame, "
                                       "[program] cl_frame = \"absolute\", where an MCS may turn)"));
    }
    // Written in the MCS ([program] cl_frame, post --cl-frame): the points as given; the work
    // offset is the MCS's origin, and where the MCS lies is the setup's business.
    if (frame_ == cl_frame::mcs) return;
    // The tool axis a move without one keeps is the CL's, in the CL's frame: the MCS's +Z
    // until a record gives another. Turned with the points, or a file that gives no axis
    // would be cut from below (the post's frame's +Z where the MCS's Z points down).
    if (!msys_) cl_axis_ = axis_;
    if (is_identity(x, y, z)) {
      // Back to the absolute frame: the axis in force is the CL's again, written on the next
      // move by the identity turn, which costs only the files that turn back.
      if (msys_) msys_ = std::array<vec3, 3>{x, y, z};
      return;
    }
    // A lathe's CL frame is its own (x the radius, z along the spindle): what a turned MCS means
    // there is not known (UNVERIFIED), so it is not guessed.
    if (std::abs(x_factor_) == 2.0)
      return error(line,
                   fmt::format("MSYS/{}: a turned MCS on a lathe channel (X in diameter), whose CL frame "
                               "is the lathe's own; twinpost turns the points of an MCS on a mill only",
                               fmt::join(v, ",")));
    // The holes of a cycle in force were read in the frame before (the cycle's levels with them).
    if (cycle_)
      return error(line,
                   fmt::format("MSYS/{} turns the MCS while CYCLE/{} (line {}) is in force: whether the "
                               "cycle's levels turn with the points is not known (UNVERIFIED); end the "
                               "cycle (CYCLE/OFF) before the MSYS",
                               fmt::join(v, ","), cycle_->type, cycle_line_));
    msys_ = std::array<vec3, 3>{x, y, z};
    msys_line_ = line;
    return;
  }
  // NX MSYS aside, Creo `$$-> CSYS` and CATIA's matrix describe the frame the points are
  // already in; SolidWorks' CSYS is the operation's frame with the points in the world's.
  if (c.source != "CSYS") return;
  if (v.size() != 12 && v.size() != 9)
    return error(line,
                 fmt::format("CSYS/{}: SolidWorks CAM writes 12 values (3 rows of a rotation and its origin)",
                             fmt::join(v, ",")));
  const std::size_t row = v.size() == 12 ? 4 : 3;
  // The rows of the matrix: its columns are the frame's axes in the world frame.
  const vec3 x{v[0], v[row], v[2 * row]}, y{v[1], v[row + 1], v[2 * row + 1]},
      z{v[2], v[row + 2], v[2 * row + 2]};
  const std::string why = not_rigid(x, y, z);
  if (!why.empty())
    return error(line, fmt::format("CSYS/{}: {}; only a rigid frame is posted", fmt::join(v, ","), why));
  if (row == 4 && (std::abs(v[3]) > 1e-4 || std::abs(v[7]) > 1e-4 || std::abs(v[11]) > 1e-4))
    return error(line,
                 fmt::format("CSYS/{}: a frame moved from the world origin; SolidWorks' points are in the "
                             "world frame (TRNTYP/WORLD), but whether they include the move is not "
                             "known (UNVERIFIED: no file seen), so it is not posted",
                             fmt::join(v, ",")));
  csys_refused_ = false;
  if (is_identity(x, y, z)) {
    csys_axis_.reset();
    return;
  }
  csys_axis_ = z;
  csys_line_ = line;
}

bool channel_writer::csys_axis_fits(const event& e) {
  const auto* m = std::get_if<motion_event>(&e.data);
  if (!m || m->kind != motion_kind::go_to) return true;
  const vec3 axis = m->axis ? *m->axis : axis_;
  if (kin::angle_between(axis, *csys_axis_) <= 1e-3) return true;
  if (csys_refused_) return false;
  csys_refused_ = true;
  line_ = e.line;
  column_ = e.column;
  error(e.line, fmt::format("a move under the tool axis ({:g},{:g},{:g}) while CSYS (line {}) turns the "
                            "operation's tool to ({:g},{:g},{:g}): SolidWorks CAM gives the points of a "
                            "turned CSYS in the world frame with the tool along its Z; a point under another "
                            "axis is in a frame twinpost cannot tell",
                            axis.x, axis.y, axis.z, csys_line_, csys_axis_->x, csys_axis_->y, csys_axis_->z));
  return false;
}

bool channel_writer::turn_to_msys(event& e) {
  const std::array<vec3, 3>& r = *msys_;
  const auto turn = [&](vec3& p) { p = p.x * r[0] + p.y * r[1] + p.z * r[2]; };
  return std::visit(
      [&](auto& d) {
        using T = std::decay_t<decltype(d)>;
        if constexpr (std::is_same_v<T, motion_event>) {
          turn(d.pos);
          if (d.axis) cl_axis_ = *d.axis;
          // The axis every move carries: the one in force, turned (the lookahead sees it too).
          d.axis = cl_axis_;
          turn(*d.axis);
        } else if constexpr (std::is_same_v<T, arc_event>) {
          turn(d.start);
          turn(d.end);
          turn(d.center);
          turn(d.normal);
        } else if constexpr (std::is_same_v<T, tool_axis_event>) {
          cl_axis_ = d.axis;
          turn(d.axis);
        } else if constexpr (std::is_same_v<T, cycle_event>) {
          if (d.type != "OFF" && d.type != "ON" && d.type != "INIT" && !is_identity(r[0], r[1], r[2])) {
            line_ = e.line;
            column_ = e.column;
            error(e.line,
                  fmt::format("CYCLE/{} under MSYS (line {}), which turns the MCS: whether the cycle's "
                              "levels turn with the points is not known (UNVERIFIED), so it is not "
                              "posted; give the holes as GOTO moves",
                              d.type, msys_line_));
            cycle_.reset();  // its holes are passed over, as after any refused cycle
            cycle_refused_ = true;
            return false;
          }
        }
        return true;
      },
      e.data);
}

}  // namespace twinpost
