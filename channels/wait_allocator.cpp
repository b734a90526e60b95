#include "channels/wait_allocator.hpp"

#include <string>

namespace twinpost {

std::optional<int> wait_allocator::next() {
  for (int guard = 0; guard < 2; ++guard) {
    while (next_ <= rules_.last) {
      int code = next_;
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

std::string partner_list(const std::vector<int>& channels, partner_style style) {
  switch (style) {
    case partner_style::none: return {};
    case partner_style::path_numbers: {
      std::string s;
      for (int c : channels) s += std::to_string(c);
      return s;
    }
    case partner_style::binary: {
      long mask = 0;
      for (int c : channels) mask |= 1L << (c - 1);
      return std::to_string(mask);
    }
  }
  return {};
}

}  // namespace twinpost
