#pragma once
// The CL record grammar: rule definitions. Included only by parser/grammar.cpp.
//
//   record     = comment | coordinates | text_record | statement
//   comment    = "$$" rest                       ($$->, $$*, $$UDE are sorted out later)
//   coordinates= &number arg_list                (Pro/E multi-point GOTO lines)
//   text_record= TEXT_MAJOR ['/'] rest           (PARTNO, PPRINT, INSERT, ...)
//   statement  = major [('/' | ',') arg_list]    (`GOTO/..`, `CHANNEL,1`, bare `RAPID`)
//   arg_list   = arg % ','      arg = number | word | (empty)
//
// The grammar stops where the text stops making sense; record_parser.cpp turns the stop
// position into a diagnostic. No expectation points: in Boost 1.74 they throw, and a
// malformed record must not cost an exception.
#include <string_view>

#include "parser/detail/grammar.hpp"
#include "parser/detail/number_parser.hpp"
#include "parser/detail/text_major_parser.hpp"

namespace twinpost::parser_detail {

namespace actions {

inline std::string_view view_of(const boost::iterator_range<iterator_type>& r) {
  return {r.begin(), static_cast<std::size_t>(r.end() - r.begin())};
}

inline std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// Offsets count from the start of the record text (r.source); _where is the matched range.
template <class Ctx>
std::size_t here(Ctx& ctx, const cl_record& r) {
  return static_cast<std::size_t>(x3::_where(ctx).begin() - r.source.data());
}

// Where the next argument starts (eps matches an empty range there).
const auto mark_arg = [](auto& ctx) {
  cl_record& r = x3::get<record_tag>(ctx);
  r.arg_start = here(ctx, r);
};
const auto push_number = [](auto& ctx) {
  cl_record& r = x3::get<record_tag>(ctx);
  cl_arg a;
  a.kind = arg_kind::number;
  a.number = x3::_attr(ctx);
  a.offset = r.arg_start;
  r.args.push_back(a);
};
const auto push_word = [](auto& ctx) {
  cl_record& r = x3::get<record_tag>(ctx);
  cl_arg a;
  a.kind = arg_kind::word;
  a.word = view_of(x3::_attr(ctx));
  a.offset = static_cast<std::size_t>(a.word.data() - r.source.data());
  r.args.push_back(a);
};
const auto push_empty = [](auto& ctx) {
  cl_record& r = x3::get<record_tag>(ctx);
  cl_arg a;
  a.offset = here(ctx, r);
  r.args.push_back(a);
};
const auto set_major = [](auto& ctx) {
  cl_record& r = x3::get<record_tag>(ctx);
  r.major = view_of(x3::_attr(ctx));
  r.major_offset = static_cast<std::size_t>(r.major.data() - r.source.data());
};
const auto set_text_kind = [](auto& ctx) { x3::get<record_tag>(ctx).kind = record_kind::text; };
const auto set_coordinates_kind = [](auto& ctx) { x3::get<record_tag>(ctx).kind = record_kind::coordinates; };
const auto set_comment = [](auto& ctx) {
  cl_record& r = x3::get<record_tag>(ctx);
  r.kind = record_kind::comment;
  r.major = {};
  r.args.clear();
  r.text = trimmed(view_of(x3::_attr(ctx)));
};
const auto set_text = [](auto& ctx) { x3::get<record_tag>(ctx).text = trimmed(view_of(x3::_attr(ctx))); };

}  // namespace actions

// Character classes are explicit ASCII sets, never x3::alnum/alpha/digit: those call
// std::isalnum on a plain (signed) char and assert on ISO-8859-1 bytes >= 0x80.
const auto blanks = x3::omit[*x3::char_(" \t")];
const auto digit = x3::char_("0-9");
const auto letter = x3::char_("A-Za-z");
const auto word_char = x3::char_("A-Za-z0-9_");

// Words start with a letter, digit or '_' and may hold '-', '.', '#' (END-OF-PATH,
// MILL-20MM, 1STPECK, G98). A number is tried first, so "12.5" never becomes a word.
const auto word = x3::raw[word_char >> *(word_char | x3::char_("-.#"))];

const auto major_word = x3::raw[letter >> *(word_char | x3::char_('-'))];

const auto arg =
    blanks >> x3::eps[actions::mark_arg] >>
    (cl_number[actions::push_number] | word[actions::push_word] | x3::eps[actions::push_empty]) >> blanks;
const auto arg_list = arg % ',';

const auto comment = blanks >> x3::lit("$$") >> x3::raw[*x3::char_][actions::set_comment];

const auto coordinates = blanks >>
                         &(digit | x3::char_(".+-")) >> x3::eps[actions::set_coordinates_kind] >> arg_list;

const auto text_record = blanks >> x3::raw[text_major][actions::set_major] >>
                         x3::eps[actions::set_text_kind] >> blanks >>
                         -x3::lit('/') >> x3::raw[*x3::char_][actions::set_text];

const auto statement = blanks >> major_word[actions::set_major] >> blanks >>
                       -((x3::lit('/') | x3::lit(',')) >> arg_list);

const record_type record = "record";
const auto record_def = comment | coordinates | text_record | statement;

BOOST_SPIRIT_DEFINE(record)

const record_type& record_rule() { return record; }

}  // namespace twinpost::parser_detail
