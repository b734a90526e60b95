#pragma once
// The events one CL record makes, in a list whose slots are kept from record to record:
// clear() only forgets how many are in use, so a move written into a slot that held a move
// costs no construction or destruction (most records are moves).
#include <cstddef>
#include <vector>

#include "parser/events.hpp"

namespace twinpost {

class event_queue {
 public:
  void clear() { used_ = 0; }
  bool empty() const { return used_ == 0; }
  std::size_t size() const { return used_; }
  const event& operator[](std::size_t i) const { return slots_[i]; }
  event& operator[](std::size_t i) { return slots_[i]; }
  const event* begin() const { return slots_.data(); }
  const event* end() const { return slots_.data() + used_; }

  void push_back(event e) { next_slot() = std::move(e); }

  /// The next slot as a motion event of `line`, with its fields as some earlier move left
  /// them: the caller sets every one.
  motion_event& next_motion(int line) {
    event& e = next_slot();
    e.line = line;
    if (auto* m = std::get_if<motion_event>(&e.data)) return *m;
    return e.data.emplace<motion_event>();
  }

 private:
  event& next_slot() {
    if (used_ == slots_.size()) slots_.emplace_back();
    return slots_[used_++];
  }
  std::vector<event> slots_;
  std::size_t used_ = 0;
};

}  // namespace twinpost
