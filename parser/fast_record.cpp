#include "parser/detail/fast_record.hpp"

#include "parser/detail/lexical.hpp"
#include "support/ascii.hpp"

namespace twinpost::parser_detail {

namespace {
bool blank(char c) { return c == ' ' || c == '\t'; }

// The characters of a major word (word characters and '-', END-OF-PATH): one look-up each.
constexpr auto major_chars = [] {
  struct table {
    bool in[256] = {};
  } t;
  for (int c = 0; c < 256; ++c) t.in[c] = word_chars.in[c] || c == '-';
  return t;
}();
}  // namespace

bool parse_numeric_statement(std::string_view text, cl_record& out) {
  const char* const begin = text.data();
  const char* const end = begin + text.size();
  const char* p = begin;
  while (p != end && blank(*p)) ++p;
  if (p == end || !ascii::is_letter(*p)) return false;
  if (text_major_length(std::string_view(p, static_cast<std::size_t>(end - p))) != 0) return false;
  const char* major = p;
  while (p != end && major_chars.in[static_cast<unsigned char>(*p)]) ++p;
  out.clear();
  out.source = text;
  out.kind = record_kind::statement;
  out.major = std::string_view(major, static_cast<std::size_t>(p - major));
  out.major_offset = static_cast<std::size_t>(major - begin);
  out.numbers_only = true;
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
    // No digit or point (`inf`, a word, a sign alone) is no number to fast_decimal_in either.
    double value = 0;
    p = fast_decimal_in(begin, p, end, value);
    if (!p) return false;
    cl_arg& a = out.args.emplace_back();
    a.kind = arg_kind::number;
    a.number = negative ? -value : value;
    a.offset = static_cast<std::size_t>(start - begin);
    if (p == end) return true;
    if (*p == ',') {  // the common case first: the next number follows at once
      ++p;
      continue;
    }
    if (is_word_char(*p)) return false;  // `1STPECK` is a word
    while (p != end && blank(*p)) ++p;
    if (p == end) return true;
    if (*p != ',') return false;
    ++p;
  }
}

}  // namespace twinpost::parser_detail
