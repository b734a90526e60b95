#pragma once
// The CL record grammar: rule declarations (the interface of the grammar).
// Spirit naming: rule ID foo_class, rule type foo_type, definition foo_def, object foo.
#include "parser/detail/config.hpp"

namespace twinpost::parser_detail {

struct record_class;
/// One logical CL record; fills the cl_record found under record_tag in the context.
using record_type = x3::rule<record_class>;
BOOST_SPIRIT_DECLARE(record_type)

/// The record rule object.
const record_type& record_rule();

}  // namespace twinpost::parser_detail
