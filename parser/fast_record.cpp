#include "parser/detail/fast_record.hpp"

#include "parser/detail/lexical.hpp"
#include "support/ascii.hpp"

namespace twinpost::parser_detail {

namespace {
bool blank(char c) { return c == ' ' || c == '\t'; }
}  // namespace

bool parse_numeric_statement(std::string_view text, cl_record& out) {
  const char* const begin = text.data();
  const char* const end = begin + text.size();
  const char* p = begin;
  while (p != end && blank(*p)) ++p;
  if (p == end || !ascii::is_letter(*p)) return false;
  if (text_major_length(std::string_view(p, static_cast<std::size_t>(end - p))) != 0) return false;
  const char* major = p;
  while (p != end && (is_word_char(*p) || *p == '-')) ++p;
  out.clear();
  out.source = text;
  out.kind = record_kind::statement;
  out.major = std::string_view(major, static_cast<std::size_t>(p - major));
  out.major_offset = static_cast<std::size_t>(major - begin);
  while (p != end && blank(*p)) ++p;
  if (p == end) return true;  // a bare major: RAPID, FINI
  if (*p != '/') return false;
  ++p;
  for (bool first = true;; first = false) {
    while (p != end && blank(*p)) ++p;
    // Nothing after '/' is the grammar's to judge; nothing after a comma is a trailing
    // comma, which carries nothing (as in the grammar).
    if (p == end) return !first;
    const char* start = p;
    bool negative = false;
    if (*p == '+' || *p == '-') negative = *p++ == '-';
    if (p == end || !(ascii::is_digit(*p) || *p == '.')) return false;
    double value = 0;
    p = fast_decimal(p, end, value);
    if (!p || (p != end && is_word_char(*p))) return false;
    cl_arg& a = out.args.emplace_back();
    a.kind = arg_kind::number;
    a.number = negative ? -value : value;
    a.offset = static_cast<std::size_t>(start - begin);
    while (p != end && blank(*p)) ++p;
    if (p == end) return true;
    if (*p != ',') return false;
    ++p;
  }
}

}  // namespace twinpost::parser_detail
