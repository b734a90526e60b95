#include "parser/detail/fast_record.hpp"

#include <cstdint>
#include <cstring>

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

// The arguments of a numeric statement, from just after its '/' at `p` (the text starts at
// `begin` and ends at `end`): each number to `out.number(value, offset)` (false to give up), and
// at the end `out.done()` says whether what it took is complete.
template <class Out>
bool scan_numbers(const char* const begin, const char* p, const char* const end, Out& out) {
  for (bool first = true;; first = false) {
    while (p != end && blank(*p)) ++p;
    // Nothing after '/' is the grammar's to judge; nothing after a comma is a trailing
    // comma, which carries nothing (as in the grammar).
    if (p == end) return !first && out.done();
    const char* start = p;
    bool negative = false;
    if (*p == '+' || *p == '-') negative = *p++ == '-';
    // No digit or point (`inf`, a word, a sign alone) is no number to fast_decimal_in either.
    double value = 0;
    p = fast_decimal_in(begin, p, end, value);
    if (!p) return false;
    if (!out.number(negative ? -value : value, static_cast<std::size_t>(start - begin))) return false;
    if (p == end) return out.done();
    if (*p == ',') {  // the common case first: the next number follows at once
      ++p;
      continue;
    }
    if (is_word_char(*p)) return false;  // `1STPECK` is a word
    while (p != end && blank(*p)) ++p;
    if (p == end) return out.done();
    if (*p != ',') return false;
    ++p;
  }
}

// The one reading of a numeric statement, for both kinds of result: `Out` takes the major
// (`major(text, offset)`, false to give up) and the numbers (scan_numbers).
template <class Out>
bool scan_numeric_statement(std::string_view text, Out& out) {
  const char* const begin = text.data();
  const char* const end = begin + text.size();
  const char* p = begin;
  while (p != end && blank(*p)) ++p;
  if (p == end || !ascii::is_letter(*p)) return false;
  if (text_major_length(std::string_view(p, static_cast<std::size_t>(end - p))) != 0) return false;
  const char* major = p;
  while (p != end && major_chars.in[static_cast<unsigned char>(*p)]) ++p;
  if (!out.major(std::string_view(major, static_cast<std::size_t>(p - major)),
                 static_cast<std::size_t>(major - begin)))
    return false;
  while (p != end && blank(*p)) ++p;
  if (p == end) return out.done();  // a bare major: RAPID, FINI
  if (*p != '/') return false;
  return scan_numbers(begin, p + 1, end, out);
}

// The record as the grammar makes it.
struct record_out {
  std::string_view text;
  cl_record& r;
  bool major(std::string_view m, std::size_t offset) {
    r.clear();
    r.source = text;
    r.kind = record_kind::statement;
    r.major = m;
    r.major_offset = offset;
    r.numbers_only = true;
    return true;
  }
  bool number(double v, std::size_t offset) {
    cl_arg& a = r.args.emplace_back();
    a.kind = arg_kind::number;
    a.number = v;
    a.offset = offset;
    return true;
  }
  static bool done() { return true; }
};

// A GOTO of three or six numbers, nothing else.
struct goto_out {
  goto_statement& g;
  bool major(std::string_view m, std::size_t offset) {
    g.major = m;
    g.major_offset = offset;
    g.count = 0;
    return is_goto(m);
  }
  bool number(double v, std::size_t) {
    if (g.count == 6) return false;
    g.numbers[g.count++] = v;
    return true;
  }
  bool done() const { return g.count == 3 || g.count == 6; }
};
}  // namespace

bool parse_numeric_statement(std::string_view text, cl_record& out) {
  record_out o{text, out};
  return scan_numeric_statement(text, o);
}

bool parse_goto_statement(std::string_view text, goto_statement& out) {
  goto_out o{out};
  // Most GOTOs start the line as `GOTO/` (any case): its five bytes at once, then the numbers,
  // as scan_numeric_statement reads them after the same five bytes.
  if (text.size() >= 8) {
    // Byte strings, so that the masks fall on the same bytes in either byte order.
    std::uint64_t w = 0, want = 0, lower = 0, keep = 0;
    std::memcpy(&w, text.data(), 8);
    std::memcpy(&want, "goto/\0\0\0", 8);
    std::memcpy(&lower, "\x20\x20\x20\x20\0\0\0\0", 8);  // the case bit of the four letters
    std::memcpy(&keep, "\xff\xff\xff\xff\xff\0\0\0", 8);
    if (((w | lower) & keep) == want) {
      o.major(text.substr(0, 4), 0);
      return scan_numbers(text.data(), text.data() + 5, text.data() + text.size(), o);
    }
  }
  return scan_numeric_statement(text, o);
}

}  // namespace twinpost::parser_detail
