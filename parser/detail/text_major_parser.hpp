#pragma once
// An X3 primitive for the majors of free-text records (PARTNO, PPRINT, INSERT, ...):
// matched ASCII case-insensitively and only as a whole word. Written by hand because
// x3::no_case over a symbol table lower-cases bytes with std::tolower on a signed char,
// which asserts (and is undefined behaviour) on the ISO-8859-1 bytes CL files contain.
#include <string_view>

#include "parser/detail/config.hpp"
#include "parser/detail/number_parser.hpp"

namespace twinpost::parser_detail {

struct text_major_parser : x3::parser<text_major_parser> {
  using attribute_type = x3::unused_type;
  static bool const has_attribute = false;

  static constexpr std::string_view words[] = {"PARTNO",      "PPRINT",    "INSERT",
                                               "TPRINT",      "OPFEATSTART", "OPFEATEND",
                                               "TOOL PATH",   "TITLES",    "REMARK"};

  template <class Iterator, class Context, class RContext, class Attribute>
  bool parse(Iterator& first, Iterator const& last, Context const&, RContext&, Attribute&) const {
    for (std::string_view w : words) {
      if (static_cast<std::size_t>(last - first) < w.size()) continue;
      bool same = true;
      for (std::size_t i = 0; i < w.size() && same; ++i) {
        char c = first[i];
        if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
        same = c == w[i];
      }
      if (!same) continue;
      Iterator end = first + static_cast<std::ptrdiff_t>(w.size());
      if (end != last && is_word_char(*end)) continue;  // PARTNOX is a statement
      first = end;
      return true;
    }
    return false;
  }
};

inline const text_major_parser text_major{};

}  // namespace twinpost::parser_detail
