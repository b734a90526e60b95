#pragma once
// An X3 primitive for CL numbers on top of std::from_chars: locale-free and correctly
// rounded (x3::double_ is not, boostorg/spirit#668). Accepts `95.`, `.9625`, `-0.000000`,
// `+1`, `1.5E-3`; refuses `inf`/`nan` and a number glued to a word (`1STPECK` is a word).
#include <charconv>
#include <cmath>

#include "parser/detail/config.hpp"

namespace twinpost::parser_detail {

inline bool is_word_char(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
}

// The common CL number (`123.4567`, at most 15 digits, no exponent) without from_chars:
// the digits as an exact integer divided by an exact power of ten is one correctly rounded
// IEEE division (Clinger's fast path), so the value equals from_chars'. Returns the end of
// the number, or nullptr to hand the text to from_chars (exponents, long numbers, "." alone).
inline const char* fast_decimal(const char* p, const char* last, double& value) {
  static constexpr double pow10[] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8,
                                     1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
  unsigned long long mantissa = 0;
  int digits = 0, fraction = 0;
  while (p != last && *p >= '0' && *p <= '9') {
    mantissa = mantissa * 10 + static_cast<unsigned>(*p++ - '0');
    if (++digits > 15) return nullptr;
  }
  if (p != last && *p == '.') {
    ++p;
    while (p != last && *p >= '0' && *p <= '9') {
      mantissa = mantissa * 10 + static_cast<unsigned>(*p++ - '0');
      ++fraction;
      if (++digits > 15) return nullptr;
    }
  }
  if (digits == 0) return nullptr;
  if (p != last && (*p == 'e' || *p == 'E')) return nullptr;
  value = static_cast<double>(mantissa) / pow10[fraction];
  return p;
}

struct cl_number_parser : x3::parser<cl_number_parser> {
  using attribute_type = double;
  static bool const has_attribute = true;

  template <class Iterator, class Context, class RContext, class Attribute>
  bool parse(Iterator& first, Iterator const& last, Context const&, RContext&, Attribute& attr) const {
    const char* p = first;
    bool negative = false;
    if (p != last && (*p == '+' || *p == '-')) {
      negative = *p == '-';
      ++p;
    }
    // from_chars would take "inf" and "nan": insist on a digit or a point first.
    if (p == last || !((*p >= '0' && *p <= '9') || *p == '.')) return false;
    double value = 0;
    const char* end = fast_decimal(p, last, value);
    if (!end) {
      auto [q, ec] = std::from_chars(p, last, value);
      if (ec != std::errc() || !std::isfinite(value)) return false;
      end = q;
    }
    if (end != last && is_word_char(*end)) return false;
    first = end;
    x3::traits::move_to(negative ? -value : value, attr);
    return true;
  }
};

inline const cl_number_parser cl_number{};

}  // namespace twinpost::parser_detail
