#pragma once
// A fast path for the commonest records: `MAJOR/number,number,...` (GOTO, FROM, CIRCLE,
// FEDRAT/250, ...), and bare `MAJOR`. It accepts a strict subset of the grammar's language
// and fills the record exactly as the X3 grammar would (same major, arguments, offsets);
// anything else — words, empty arguments, exponents, text records, comments — it leaves to
// the grammar. tests/parser_fast_path_test.cpp holds the two to the same result.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>

#include "parser/record.hpp"

namespace twinpost::parser_detail {

/// Fills `out` from `text` and returns true when `text` is a numeric statement; returns
/// false (with `out` in no particular state) when the grammar must read it.
bool parse_numeric_statement(std::string_view text, cl_record& out);

/// `major` is GOTO in any case: its four bytes with the case bit set are "goto" (of the
/// characters a major word has, only G or g gives g so, O or o gives o, T or t gives t).
inline bool is_goto(std::string_view major) {
  if (major.size() != 4) return false;
  std::uint32_t w = 0, want = 0;
  std::memcpy(&w, major.data(), 4);
  std::memcpy(&want, "goto", 4);
  return (w | 0x20202020u) == want;
}

/// A GOTO of three or six numbers (`GOTO/x,y,z` or `GOTO/x,y,z,i,j,k`) as parse_numeric_statement
/// reads it: the commonest record of a job, its numbers straight into an array.
struct goto_statement {
  double numbers[6];
  std::size_t count = 0;
  std::string_view major;  ///< as written (GOTO, goto)
  std::size_t major_offset = 0;
};

/// Fills `out` and returns true when `text` is such a GOTO, exactly where parse_numeric_statement
/// would make a statement GOTO of three or six numbers of it; false for anything else.
bool parse_goto_statement(std::string_view text, goto_statement& out);

}  // namespace twinpost::parser_detail
