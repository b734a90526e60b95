#pragma once
// [[events.record]] entries against the parser's record table: an entry can only take a word
// the post does not know (docs/customising.md).
#include <optional>

#include "machines/machine.hpp"
#include "support/diagnostics.hpp"

namespace twinpost {

/// The error for the first [[events.record]] of `m` whose major word the post knows (it would
/// never reach the entry: the post handles or refuses it itself), at the entry in the machine
/// file; nullopt when there is none.
std::optional<diagnostic> known_user_record(const machine& m);

}  // namespace twinpost
