#pragma once
// A fast path for the commonest records: `MAJOR/number,number,...` (GOTO, FROM, CIRCLE,
// FEDRAT/250, ...), and bare `MAJOR`. It accepts a strict subset of the grammar's language
// and fills the record exactly as the X3 grammar would (same major, arguments, offsets);
// anything else — words, empty arguments, exponents, text records, comments — it leaves to
// the grammar. tests/parser_fast_path_test.cpp holds the two to the same result.
#include <string_view>

#include "parser/record.hpp"

namespace twinpost::parser_detail {

/// Fills `out` from `text` and returns true when `text` is a numeric statement; returns
/// false (with `out` in no particular state) when the grammar must read it.
bool parse_numeric_statement(std::string_view text, cl_record& out);

}  // namespace twinpost::parser_detail
