// The one translation unit that compiles the CL record grammar.
#include "parser/detail/grammar_def.hpp"

namespace twinpost::parser_detail {
BOOST_SPIRIT_INSTANTIATE(record_type, iterator_type, context_type)
}  // namespace twinpost::parser_detail
