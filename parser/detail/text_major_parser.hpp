#pragma once
// An X3 primitive for the majors of free-text records (PARTNO, PPRINT, INSERT, ...):
// matched ASCII case-insensitively and only as a whole word. Written by hand because
// x3::no_case over a symbol table lower-cases bytes with std::tolower on a signed char,
// which asserts (and is undefined behaviour) on the ISO-8859-1 bytes CL files contain.
#include <string_view>

#include "parser/detail/config.hpp"
#include "parser/detail/lexical.hpp"

namespace twinpost::parser_detail {

struct text_major_parser : x3::parser<text_major_parser> {
  using attribute_type = x3::unused_type;
  static bool const has_attribute = false;

  template <class Iterator, class Context, class RContext, class Attribute>
  bool parse(Iterator& first, Iterator const& last, Context const&, RContext&, Attribute&) const {
    std::size_t n = text_major_length(std::string_view(first, static_cast<std::size_t>(last - first)));
    if (n == 0) return false;
    first += static_cast<std::ptrdiff_t>(n);
    return true;
  }
};

inline const text_major_parser text_major{};

}  // namespace twinpost::parser_detail
