#include "formats/sequence_numbers.hpp"

#include <fmt/format.h>
#include <limits>

namespace twinpost {

sequence_numbers::sequence_numbers(const program_format& p, const word_format& n)
    : start_(p.sequence_start), step_(p.sequence_step), max_(std::numeric_limits<long>::max()),
      next_(p.sequence_start), on_(p.sequence_start > 0),
      every_block_(p.sequence_numbers == sequence_mode::all) {
  if (n.whole > 0 && n.whole < 18) {
    max_ = 1;
    for (int i = 0; i < n.whole; ++i) max_ *= 10;
    --max_;
  }
}

std::string sequence_numbers::next(bool restart) {
  if (!on_ || (!every_block_ && !restart)) return {};
  if (next_ > max_) next_ = start_;
  std::string s = fmt::format("N{} ", next_);
  next_ += step_;
  return s;
}

}  // namespace twinpost
