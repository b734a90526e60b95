#pragma once
// The public face of the CL grammar: one logical record in, a cl_record out.
// No X3 type appears here; the grammar lives in parser/detail and parser/grammar.cpp.
#include <cstddef>
#include <string>
#include <string_view>

#include "parser/detail/fast_record.hpp"
#include "parser/record.hpp"

namespace twinpost {

/// Where and why a record could not be read.
struct record_error {
  std::size_t offset = 0;  ///< offset in the logical record text
  std::string message;
};

/// The same as parse_record through the X3 grammar alone, without the fast path for numeric
/// statements (tests and the fuzzer hold the two to the same result).
bool parse_record_with_grammar(std::string_view text, cl_record& out, record_error& err);

/// Parses the logical record `text` into `out` (which keeps views into `text`).
/// `$$->` comments are parsed as data comments; a `$$->` body that does not parse stays a
/// plain comment. Returns false and fills `err` when the record is malformed.
/// Inline: most records of a long job are numeric statements (GOTO/x,y,z), read directly.
inline bool parse_record(std::string_view text, cl_record& out, record_error& err) {
  if (parser_detail::parse_numeric_statement(text, out)) return true;
  return parse_record_with_grammar(text, out, err);
}

}  // namespace twinpost
