#pragma once
// The fast path for numeric statements (parser/fast_record.cpp) against the X3 grammar: one
// comparison, used by the cl_reader fuzz target and by tests/parser_fast_path_test.cpp.
#include <cstring>
#include <string>
#include <string_view>

#include "parser/detail/fast_record.hpp"
#include "parser/record_parser.hpp"

namespace twinpost::fuzz {

/// "" when the fast path declines `text`, or reads it exactly as the grammar does (kind,
/// major and its offset, every argument's kind, offset and number to the bit); else what
/// differs: "grammar rejects: ...", "kind", "major", "argument count" or "argument N".
inline std::string fast_path_difference(std::string_view text) {
  cl_record fast, slow;
  if (!parser_detail::parse_numeric_statement(text, fast)) return {};
  record_error err;
  if (!parse_record_with_grammar(text, slow, err)) return "grammar rejects: " + err.message;
  if (fast.kind != slow.kind) return "kind";
  if (fast.major != slow.major || fast.major_offset != slow.major_offset) return "major";
  if (fast.args.size() != slow.args.size()) return "argument count";
  for (std::size_t i = 0; i < fast.args.size(); ++i) {
    const cl_arg& a = fast.args[i];
    const cl_arg& b = slow.args[i];
    // memcmp, not ==: -0 against 0 and the bits of every NaN count.
    if (a.kind != b.kind || a.offset != b.offset || std::memcmp(&a.number, &b.number, sizeof(double)) != 0)
      return "argument " + std::to_string(i);
  }
  return {};
}

}  // namespace twinpost::fuzz
