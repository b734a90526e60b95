#include "machining/kin_lookahead.hpp"

#include <cmath>
#include <cstring>
#include <type_traits>
#include <variant>

#include "parser/cam_tool.hpp"

namespace twinpost {

namespace {

// Bit for bit: -0 is not 0 (atan2 tells them apart), and a NaN is itself.
template <class T>
bool same_bits(const T& a, const T& b) {
  static_assert(std::is_trivially_copyable_v<T>);
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

bool same_pose(const kin::tool_pose& a, const kin::tool_pose& b) {
  return same_bits(a.tip, b.tip) && same_bits(a.axis, b.axis);
}

bool same_joints(const kin::joint_values& a, const kin::joint_values& b) {
  return same_bits(a.linear, b.linear) && same_bits(a.rotary, b.rotary);
}

static_assert(sizeof(vec3) == 3 * sizeof(double) && sizeof(kin::joint_values) == 5 * sizeof(double),
              "compared as their doubles, with no padding");

}  // namespace

kin_lookahead::kin_lookahead(const machine& m, int channel)
    : m_(m), channel_(channel), chain_(m.chain(channel)), plan_(*chain_) {}

void kin_lookahead::look(std::span<const event> events, notes& out) {
  out.clear();
  out.of_event.assign(events.size(), -1);
  const kinematic_chain& c = *chain_;
  const bool joints = solves_joints(c);
  for (std::size_t i = 0; i < events.size(); ++i) {
    const event& e = events[i];
    const bool after_call = after_call_;  // as the writer
    after_call_ = after_call && keeps_tool_call_open(e);
    std::visit(
        [&](const auto& d) {
          using T = std::decay_t<decltype(d)>;
          if constexpr (std::is_same_v<T, motion_event>) {
            if (d.axis) axis_ = *d.axis;
            if (d.kind != motion_kind::go_to) {
              known_ = false;
              return;
            }
            const double len = std::sqrt(axis_.x * axis_.x + axis_.y * axis_.y + axis_.z * axis_.z);
            const kin::tool_pose pose{{d.pos.x * cl_mm_, d.pos.y * cl_mm_, d.pos.z * cl_mm_},
                                      len > 0 ? vec3{axis_.x / len, axis_.y / len, axis_.z / len} : axis_};
            const double length = !joints ? 0 : chosen_length(c, table_length_, length_cl_).value_or(0);
            solution s;
            s.start = joints_;
            s.length = length;
            s.to = pose;
            if (d.rapid || !joints || !known_) {
              s.need = joints ? kin::ik_need::joints : kin::ik_need::angles;
              s.ik = kin::inverse(plan_, pose, length, joints_, s.need);
              known_ = s.ik.ok();
              if (known_) joints_ = s.ik.joints;
            } else {
              s.linearised = true;
              s.from = pose_;
              s.tolerance = c.chordal_tolerance;
              kin::linearise(plan_, pose_, joints_, pose, length, s.tolerance, lin_);
              known_ = lin_.ok();
              if (known_) {
                s.first = static_cast<std::uint32_t>(out.points.size());
                s.count = static_cast<std::uint32_t>(lin_.points.size());
                out.points.insert(out.points.end(), lin_.points.begin(), lin_.points.end());
                out.fractions.insert(out.fractions.end(), lin_.fractions.begin(), lin_.fractions.end());
                s.deviation = lin_.deviation;
                joints_ = lin_.points.back();
              }
            }
            pose_ = pose;
            if (known_) {
              out.of_event[i] = static_cast<std::int32_t>(out.solutions.size());
              out.solutions.push_back(s);
            }
          } else if constexpr (std::is_same_v<T, tool_axis_event>) {
            axis_ = d.axis;
          } else if constexpr (std::is_same_v<T, units_event>) {
            cl_mm_ = d.units == unit_system::inch ? 25.4 : 1.0;
          } else if constexpr (std::is_same_v<T, tool_event>) {
            if (d.preselect) return;
            table_length_ = m_.tool_length(channel_, d.tool);
            length_cl_ = next_length_cl_;
            next_length_cl_.reset();
            after_call_ = true;
            known_ = false;  // the tool change moved the machine
          } else if constexpr (std::is_same_v<T, tool_data_event>) {
            if (const std::optional<double> cl = tldata_length(d))
              (after_call ? length_cl_ : next_length_cl_) = *cl * cl_mm_;
          } else if constexpr (std::is_same_v<T, feed_event> || std::is_same_v<T, spindle_event> ||
                               std::is_same_v<T, coolant_event> || std::is_same_v<T, comment_event> ||
                               std::is_same_v<T, text_event> || std::is_same_v<T, multax_event>) {
            // no move, and nothing of the writer's kinematic state
          } else {
            known_ = false;  // anything else may move the machine or change the frame: the next move is
                             // solved afresh
          }
        },
        e.data);
  }
}

const kin_lookahead::solution* kin_lookahead::current() const {
  if (!notes_ || index_ >= notes_->of_event.size()) return nullptr;
  const std::int32_t k = notes_->of_event[index_];
  return k < 0 ? nullptr : &notes_->solutions[static_cast<std::size_t>(k)];
}

const kin::ik_result* kin_lookahead::inverse(const kinematic_chain* c, const kin::tool_pose& pose,
                                             double length, const kin::joint_values& previous,
                                             kin::ik_need need) const {
  const solution* s = current();
  if (!s || s->linearised || c != chain_ || s->need != need || !same_bits(s->length, length) ||
      !same_pose(s->to, pose) || !same_joints(s->start, previous))
    return nullptr;
  return &s->ik;
}

bool kin_lookahead::linearise(const kinematic_chain* c, const kin::tool_pose& from,
                              const kin::joint_values& from_joints, const kin::tool_pose& to, double length,
                              double tolerance, kin::linearise_result& out) const {
  const solution* s = current();
  if (!s || !s->linearised || c != chain_ || !same_bits(s->length, length) ||
      !same_bits(s->tolerance, tolerance) || !same_pose(s->from, from) || !same_pose(s->to, to) ||
      !same_joints(s->start, from_joints))
    return false;
  out.error = kin::ik_error::none;
  out.message.clear();
  out.points.assign(notes_->points.begin() + s->first, notes_->points.begin() + s->first + s->count);
  out.fractions.assign(notes_->fractions.begin() + s->first, notes_->fractions.begin() + s->first + s->count);
  out.deviation = s->deviation;
  return true;
}

}  // namespace twinpost
