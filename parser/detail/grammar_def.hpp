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

const auto set_arg_offset = [](auto& ctx) {
  cl_record& r = x3::get<record_tag>(ctx);
  r.args.back().offset = static_cast<std::size_t>(x3::_attr(ctx).begin() - r.source.data());
};

const auto push_number = [](auto& ctx) {
  cl_record& r = x3::get<record_tag>(ctx);
  cl_arg a;
  a.kind = arg_kind::number;
  a.number = x3::_attr(ctx);
  r.args.push_back(a);
};
const auto push_word = [](auto& ctx) {
  cl_record& r = x3::get<record_tag>(ctx);
  cl_arg a;
  a.kind = arg_kind::word;
  a.word = view_of(x3::_attr(ctx));
  r.args.push_back(a);
};
const auto push_empty = [](auto& ctx) {
  x3::get<record_tag>(ctx).args.push_back(cl_arg{});
};
const auto set_major = [](auto& ctx) {
  cl_record& r = x3::get<record_tag>(ctx);
  r.major = view_of(x3::_attr(ctx));
  r.major_offset = static_cast<std::size_t>(r.major.data() - r.source.data());
};
const auto set_text_kind = [](auto& ctx) { x3::get<record_tag>(ctx).kind = record_kind::text; };
const auto set_coordinates_kind = [](auto& ctx) {
  x3::get<record_tag>(ctx).kind = record_kind::coordinates;
};
const auto set_comment = [](auto& ctx) {
  cl_record& r = x3::get<record_tag>(ctx);
  r.kind = record_kind::comment;
  r.major = {};
  r.args.clear();
  r.text = trimmed(view_of(x3::_attr(ctx)));
};
const auto set_text = [](auto& ctx) {
  x3::get<record_tag>(ctx).text = trimmed(view_of(x3::_attr(ctx)));
};

}  // namespace actions

const auto blanks = x3::omit[*x3::char_(" \t")];
const auto word_char = x3::alnum | x3::char_('_');
const auto boundary = !word_char;

// Words start with a letter, digit or '_' and may hold '-', '.', '#' (END-OF-PATH,
// MILL-20MM, 1STPECK, G98). A number is tried first, so "12.5" never becomes a word.
const auto word = x3::raw[word_char >> *(word_char | x3::char_("-.#"))];

// Records whose rest is free text, commas and slashes included.
struct text_major_symbols : x3::symbols<x3::unused_type> {
  text_major_symbols() {
    add("PARTNO")("PPRINT")("INSERT")("TPRINT")("OPFEATSTART")("OPFEATEND")("TOOL PATH")
        ("TITLES")("REMARK");
  }
};
const text_major_symbols text_majors;

const auto major_word =
    x3::raw[x3::alpha >> *(word_char | x3::char_('-'))];

const auto arg = blanks >>
                 x3::raw[cl_number[actions::push_number] | word[actions::push_word] |
                         x3::eps[actions::push_empty]][actions::set_arg_offset] >>
                 blanks;
const auto arg_list = arg % ',';

const auto comment = blanks >> x3::lit("$$") >> x3::raw[*x3::char_][actions::set_comment];

const auto coordinates = blanks >> &(x3::digit | x3::char_(".+-")) >>
                         x3::eps[actions::set_coordinates_kind] >> arg_list;

const auto text_record =
    blanks >> x3::raw[x3::no_case[text_majors] >> boundary][actions::set_major] >>
    x3::eps[actions::set_text_kind] >> blanks >> -x3::lit('/') >>
    x3::raw[*x3::char_][actions::set_text];

const auto statement = blanks >> major_word[actions::set_major] >> blanks >>
                       -((x3::lit('/') | x3::lit(',')) >> arg_list);

const record_type record = "record";
const auto record_def = comment | coordinates | text_record | statement;

BOOST_SPIRIT_DEFINE(record)

const record_type& record_rule() { return record; }

}  // namespace twinpost::parser_detail
