#include "channels/wait_allocator.hpp"

#include <cstdint>
#include <string>

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

std::string partner_list(const std::vector<int>& channels, partner_style style) {
  switch (style) {
    case partner_style::none: return {};
    case partner_style::path_numbers: {
      std::string s;
      for (int c : channels) s += std::to_string(c);
      return s;
    }
    case partner_style::binary: {
      std::uint64_t mask = 0;  // channel 64 is the top bit: a signed mask would go negative
      for (int c : channels) mask |= std::uint64_t{1} << (c - 1);
      return std::to_string(mask);
    }
  }
  return {};
}

}  // namespace twinpost
