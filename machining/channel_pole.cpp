// Looking ahead at the pole: with the tool along the outer rotary axis (a trunnion's C, a
// head's outer axis) that axis's angle is free, and the inverse keeps the last one. When the
// tool then leaves the pole the outer axis must turn to the angle the new tool axis needs;
// turned in the cut it sweeps the tool round while it tilts. So a RAPID onto the pole is held,
// with what follows it on the pole, until the first point off it: the rapid then goes to that
// point's outer angle, and the axis turns on the way in, with the tool clear (docs/machines.md,
// "Multi-axis output").
#include <cmath>
#include <variant>

#include "kinematics/inverse.hpp"
#include "kinematics/vec3_ops.hpp"
#include "machining/channel_writer.hpp"

namespace twinpost {

namespace {
using kin::operator*;
constexpr std::size_t max_held = 64;  // records: a plunge and its comments, not a whole operation
}  // namespace

bool channel_writer::on_outer_pole(const vec3& axis) const {
  const kin::orientation_form f = kin::orientation_of(*chain_);
  if (f.outer < 0 || f.inner < 0) return false;
  const double len = kin::norm(axis);
  if (!(len > 0)) return false;
  return kin::norm(kin::cross(chain_->rotaries[f.outer].direction, (1 / len) * axis)) < 1e-9;
}

std::optional<double> channel_writer::pole_target(const vec3& pos, const vec3& axis) const {
  const kinematic_chain& c = *chain_;
  const bool joints = solves_joints(c);
  double length = 0;
  if (joints) {
    // The length as tool_length_known() will take it, without its errors (the move gives them).
    const std::optional<double> table = m_.tool_length(ch_.number, tool_);
    // Neither known: 0, as the move takes it while no head tilts the tool (tool_length_known);
    // a target that tilts it is refused by the move itself.
    if (length_known_)
      length = tool_length_;
    else if (lengths_differ(c, table, length_cl_) && c.tool_length == length_source::agree)
      return std::nullopt;
    else if (table || length_cl_)
      length = *chosen_length(c, table, length_cl_);
  }
  const double len = kin::norm(axis);
  const kin::tool_pose pose{{pos.x * cl_mm_, pos.y * cl_mm_, pos.z * cl_mm_}, (1 / len) * axis};
  const kin::ik_result ik =
      kin::inverse(c, pose, length, joints_, joints ? kin::ik_need::joints : kin::ik_need::angles);
  if (!ik.ok()) return std::nullopt;
  return ik.joints.rotary[kin::orientation_of(c).outer];
}

bool channel_writer::hold_for_pole(const event& e, bool both) {
  const auto* m = std::get_if<motion_event>(&e.data);
  if (held_.empty()) {
    const kinematic_chain& c = *chain_;
    if (!m || m->kind != motion_kind::go_to || !m->rapid || tool_ < 0 || cycle_ || cycle_refused_ ||
        threading_ || c.moves != multiaxis_moves::all || c.output == multiaxis_output::vector)
      return false;
    const vec3 axis = m->axis ? *m->axis : axis_;
    if (!on_outer_pole(axis)) return false;
    held_axis_ = axis;
    held_.push_back(held_of(e, both));
    return true;
  }
  if (m && m->kind == motion_kind::go_to) {
    const vec3 axis = m->axis ? *m->axis : held_axis_;
    if (!on_outer_pole(axis)) {
      release_held(pole_target(m->pos, axis));
      return false;
    }
    if (held_.size() < max_held) {
      held_axis_ = axis;
      held_.push_back(held_of(e, both));
      return true;
    }
  } else if ((std::holds_alternative<feed_event>(e.data) || std::holds_alternative<spindle_event>(e.data) ||
              std::holds_alternative<coolant_event>(e.data) ||
              std::holds_alternative<comment_event>(e.data) || std::holds_alternative<text_event>(e.data)) &&
             held_.size() < max_held) {
    // Records that change nothing the solve of the next point depends on (the tool, its
    // length, the chain's state): they are written after the rapid, in their order, as ever.
    held_.push_back(held_of(e, both));
    return true;
  }
  release_held(std::nullopt);
  return false;
}

void channel_writer::release_held(std::optional<double> outer) {
  // A wait, the units or the end: a cut held for the plane ends there as it stands.
  if (!plane_held_.empty()) release_plane_held(true);
  if (held_.empty()) return;
  std::vector<held_record> events;
  events.swap(held_);
  pole_hint_ = outer;
  for (const held_record& r : events) {
    held_source_ = r.source.empty() ? nullptr : &r.source;
    process_event(r.e, r.both);
  }
  held_source_ = nullptr;
  pole_hint_.reset();
  events.clear();
  held_.swap(events);  // keep the capacity for the next pole
}

}  // namespace twinpost
