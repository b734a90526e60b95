#include "parser/record_parser.hpp"

#include <fmt/format.h>

#include "parser/detail/bad_number.hpp"
#include "parser/detail/grammar.hpp"
#include "support/ascii.hpp"

namespace twinpost {

namespace {

namespace x3 = boost::spirit::x3;

using ascii::is_blank;

// The token at `p` for a message: a run up to the next blank, comma or slash. Control and
// non-ASCII bytes are written as \xHH so that a message is always plain ASCII.
// With `one_byte` only the byte at `p` (an unexpected character is shown alone).
std::size_t token_end(std::string_view text, std::size_t p) {
  std::size_t e = p;
  while (e < text.size() && !is_blank(text[e]) && text[e] != ',' && text[e] != '/') ++e;
  return e;
}

std::string token_at(std::string_view text, std::size_t p, bool one_byte = false) {
  std::size_t e = one_byte ? p : token_end(text, p);
  if (e == p) e = p + 1;
  std::string out;
  for (unsigned char c : text.substr(p, e - p)) {
    if (c < 0x20 || c >= 0x7f)
      out += fmt::format("\\x{:02X}", c);
    else
      out += static_cast<char>(c);
  }
  return out;
}

bool run_grammar(std::string_view text, cl_record& out, std::size_t& stop) {
  out.clear();
  out.source = text;
  const char* first = text.data();
  const char* last = text.data() + text.size();
  bool ok = x3::parse(first, last, x3::with<parser_detail::record_tag>(out)[parser_detail::record_rule()]);
  stop = static_cast<std::size_t>(first - text.data());
  // A trailing empty argument (`CUTTER/...,102.,` or `RAPID/ `) carries nothing.
  while (!out.args.empty() && out.args.back().kind == arg_kind::empty) out.args.pop_back();
  return ok && first == last;
}

// Builds the message for a record the grammar stopped reading at `stop`.
record_error describe_stop(std::string_view text, const cl_record& rec, std::size_t stop) {
  std::size_t p = stop;
  while (p < text.size() && is_blank(text[p])) ++p;
  if (p >= text.size()) return {stop, "unexpected end of record"};
  std::string tok = token_at(text, p);
  if (rec.major.empty() && rec.kind == record_kind::statement)
    return {p, fmt::format("expected a major word, found '{}'", tok)};
  std::size_t major_end = rec.major_offset + rec.major.size();
  bool after_major_only =
      rec.kind == record_kind::statement && rec.args.empty() && text.find_first_of("/,", major_end) >= p;
  if (after_major_only) return {p, fmt::format("expected '/' after '{}', found '{}'", rec.major, tok)};
  if (auto message = detail::bad_number_message(text.substr(p, token_end(text, p) - p)))
    return {p, std::move(*message)};
  char c = text[p];
  if (ascii::is_alnum(c) || c == '_' || c == '.' || c == '-' || c == '+')
    return {p, fmt::format("expected ',' between arguments, found '{}'", tok)};
  return {p, fmt::format("unexpected '{}' in argument list", token_at(text, p, true))};
}

}  // namespace

bool parse_record_with_grammar(std::string_view text, cl_record& out, record_error& err) {
  std::size_t stop = 0;
  bool ok = run_grammar(text, out, stop);
  if (ok && out.kind == record_kind::comment && out.text.substr(0, 2) == "->") {
    // Creo's `$$->` pseudo-records carry data (CSYS, CUTTER, FEATNO, END).
    std::string_view comment_text = out.text;
    std::string_view body = comment_text.substr(2);
    std::size_t inner_stop = 0;
    if (run_grammar(body, out, inner_stop) && out.kind == record_kind::statement) {
      out.kind = record_kind::comment;  // still a comment, but one with a major and arguments
      out.data_comment = true;
      return true;
    }
    run_grammar(text, out, stop);  // not data after all: keep it a plain comment
    return true;
  }
  if (ok && out.kind == record_kind::coordinates) {
    for (const cl_arg& a : out.args) {
      if (a.kind == arg_kind::word) {
        if (auto message = detail::bad_number_message(a.word))
          err = {a.offset, std::move(*message)};
        else
          err = {a.offset, fmt::format("expected a number in a coordinate line, found '{}'", a.word)};
        return false;
      }
    }
  }
  if (ok) return true;
  err = describe_stop(text, out, stop);
  return false;
}

}  // namespace twinpost
