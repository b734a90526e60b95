#pragma once
// Hands out wait codes from the machine's range, in turn: start, start+step, ... skipping
// excluded codes. A small range (Fanuc M100-M103) starts again at the beginning when the
// machine allows reuse; pairing is by order, so a reused code is still unambiguous.
#include <optional>

#include "machines/machine.hpp"

namespace twinpost {

class wait_allocator {
 public:
  explicit wait_allocator(const wait_rules& rules) : rules_(rules), next_(rules.first) {}

  /// The next code, or nothing when the range is used up and reuse is not allowed.
  std::optional<int> next();
  /// How many codes have been handed out.
  int handed_out() const { return count_; }

 private:
  const wait_rules& rules_;
  long long next_;  ///< may pass the end of an int: a range can end near INT_MAX
  int count_ = 0;
};

}  // namespace twinpost
