#include "machines/partner_list.hpp"

#include <charconv>
#include <cstdint>

namespace twinpost {

namespace {

// Only the digits 0-9: a sign or a point makes a different number on the control.
bool all_digits(std::string_view s) {
  if (s.empty()) return false;
  for (char c : s)
    if (c < '0' || c > '9') return false;
  return true;
}

}  // namespace

std::string partner_list(const std::vector<int>& channels, partner_style style) {
  switch (style) {
    case partner_style::none: return {};
    case partner_style::path_numbers:
    case partner_style::others: {  // the caller leaves the own channel out
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

bool decode_partner_list(std::string_view text, partner_style style, std::vector<int>& out) {
  out.clear();
  if (!all_digits(text)) return false;
  if (style != partner_style::binary) {
    for (char c : text) out.push_back(c - '0');
    return true;
  }
  std::uint64_t mask = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), mask);
  if (ec != std::errc() || end != text.data() + text.size()) return false;
  for (int bit = 0; bit < 64; ++bit)
    if ((mask >> bit) & 1U) out.push_back(bit + 1);
  return true;
}

}  // namespace twinpost
