#include "channels/wait_allocator.hpp"

namespace twinpost {

std::optional<int> wait_allocator::next() {
  if (rules_.step < 1) return std::nullopt;  // no grid: the loader refuses it
  for (int guard = 0; guard < 2; ++guard) {
    while (next_ <= rules_.last) {
      const int code = static_cast<int>(next_);
      next_ += rules_.step;
      if (rules_.is_wait_code(code)) {
        ++count_;
        return code;
      }
    }
    if (!rules_.reuse || count_ == 0) return std::nullopt;
    next_ = rules_.first;  // start the range again
  }
  return std::nullopt;
}

}  // namespace twinpost
