#pragma once
// X3 configuration shared by the grammar definition and its one instantiation unit.
// Only parser/detail and parser/grammar.cpp / record_parser.cpp include this.
#include <boost/spirit/home/x3.hpp>

#include "parser/record.hpp"

namespace twinpost::parser_detail {
namespace x3 = boost::spirit::x3;

/// Tag under which the record being filled is reachable from semantic actions.
struct record_tag;

/// Contiguous input: number parsing hands the iterator straight to std::from_chars.
using iterator_type = const char*;

/// The context that `x3::with<record_tag>(record)[...]` builds for a plain x3::parse. If you
/// get "undefined reference to parse_rule", the call site's context no longer matches this.
using context_type = x3::context<record_tag, cl_record, x3::unused_type>;

}  // namespace twinpost::parser_detail
