#pragma once
// An X3 primitive for CL numbers on top of std::from_chars: locale-free and correctly
// rounded (x3::double_ is not, boostorg/spirit#668). Accepts `95.`, `.9625`, `-0.000000`,
// `+1`, `1.5E-3`; refuses `inf`/`nan` and a number glued to a word (`1STPECK` is a word).
#include <charconv>
#include <cmath>

#include "parser/detail/config.hpp"
#include "parser/detail/lexical.hpp"
#include "support/ascii.hpp"

namespace twinpost::parser_detail {

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
    if (p == last || !(ascii::is_digit(*p) || *p == '.')) return false;
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
