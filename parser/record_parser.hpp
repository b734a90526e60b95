#pragma once
// The public face of the CL grammar: one logical record in, a cl_record out.
// No X3 type appears here; the grammar lives in parser/detail and parser/grammar.cpp.
#include <cstddef>
#include <string>
#include <string_view>

#include "parser/record.hpp"

namespace twinpost {

/// Where and why a record could not be read.
struct record_error {
  std::size_t offset = 0;  ///< offset in the logical record text
  std::string message;
};

/// Parses the logical record `text` into `out` (which keeps views into `text`).
/// `$$->` comments are parsed as data comments; a `$$->` body that does not parse stays a
/// plain comment. Returns false and fills `err` when the record is malformed.
bool parse_record(std::string_view text, cl_record& out, record_error& err);

/// The same through the X3 grammar alone, without the fast path for numeric statements
/// (tests and the fuzzer hold the two to the same result).
bool parse_record_with_grammar(std::string_view text, cl_record& out, record_error& err);

}  // namespace twinpost
