#pragma once
// The 5-axis look-ahead: the inverse kinematics and the linearisation of a channel's CL moves,
// worked out on a thread of their own a few batches of events ahead of the writer (the post's
// reader_thread runs look() between the reader and the post), so that the post's thread
// mostly writes.
//
// The look-ahead reads the events as the writer will, but it does not know the writer's state:
// it guesses it the way the writer's plain path goes (the move's pose from the CL point and
// tool axis in mm, the tool's length from the machine's [[tool]] table or the CL's TLDATA,
// the joints where its own previous move ended). Each result is kept with the exact inputs
// it was worked out from. The writer takes a result only when its own inputs are the same,
// bit for bit: the functions are pure, so the result is then the one it would have worked out
// itself, and the program is the same bytes. Where the guess was wrong (a turn at the pole, a
// move held for the pole, a tilted plane, the first move of a tool) the writer works the move
// out itself, as without the look-ahead.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "kinematics/chain.hpp"
#include "kinematics/inverse.hpp"
#include "kinematics/linearise.hpp"
#include "machines/machine.hpp"
#include "parser/events.hpp"

namespace twinpost {

class kin_lookahead {
 public:
  /// What was worked out for one move, and from what.
  struct solution {
    bool linearised = false;                   ///< linearise (else inverse)
    kin::tool_pose from, to;                   ///< from: linearised only
    kin::joint_values start;                   ///< the previous joints (from_joints)
    double length = 0, tolerance = 0;          ///< tolerance: linearised only
    double deviation = 0;                      ///< linearised: as kin::linearise_result's
    kin::ik_need need = kin::ik_need::joints;  ///< inverse only
    kin::ik_result ik;                         ///< inverse: the result
    std::uint32_t first = 0, count = 0;        ///< linearised: its points in notes::points
  };
  /// The results for one batch of events.
  struct notes {
    std::vector<std::int32_t> of_event;  ///< per event of the batch: its solution, -1: none
    std::vector<solution> solutions;
    std::vector<kin::joint_values> points;  ///< the linearised moves' points, one after another
    std::vector<double> fractions;          ///< and their fractions
    void clear() {
      of_event.clear();
      solutions.clear();
      points.clear();
      fractions.clear();
    }
  };

  /// For channel `channel` of `m`, which has a kinematic chain.
  kin_lookahead(const machine& m, int channel);

  /// The look-ahead's thread: works out the moves of `events`, the next ones of the job in
  /// order, into `out` (cleared first).
  void look(std::span<const event> events, notes& out);

  /// The post's thread: the event given out last is `index` of the batch whose notes are `n`
  /// (nullptr: none).
  void at(const notes* n, std::size_t index) {
    notes_ = n;
    index_ = index;
  }
  /// The post's thread: kin::inverse(plan of `c`, pose, length, previous, need) as worked out
  /// ahead for the current event, or nullptr when it was not worked out from these inputs.
  const kin::ik_result* inverse(const kinematic_chain* c, const kin::tool_pose& pose, double length,
                                const kin::joint_values& previous, kin::ik_need need) const;
  /// The post's thread: true, with `out` filled as kin::linearise would fill it, when the
  /// current event's move was linearised ahead from exactly these inputs.
  bool linearise(const kinematic_chain* c, const kin::tool_pose& from, const kin::joint_values& from_joints,
                 const kin::tool_pose& to, double length, double tolerance, kin::linearise_result& out) const;

 private:
  const solution* current() const;
  const machine& m_;
  int channel_;
  const kinematic_chain* chain_;
  kin::chain_plan plan_;
  // The writer's plain path, guessed (the look-ahead's thread only).
  double cl_mm_ = 1.0;
  vec3 axis_{0, 0, 1};
  std::optional<double> length_cl_, next_length_cl_;  // the CL's TLDATA length (mm)
  std::optional<double> table_length_;                // the [[tool]] length of the tool called
  bool after_call_ = false;                           // a TLDATA now describes the tool just called
  bool known_ = false;                                // the joints and pose of the last move are known
  kin::tool_pose pose_;
  kin::joint_values joints_;
  kin::linearise_result lin_;  // reused
  // The post's thread's.
  const notes* notes_ = nullptr;
  std::size_t index_ = 0;
};

}  // namespace twinpost
