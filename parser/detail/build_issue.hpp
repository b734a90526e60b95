#pragma once
// A problem found while turning a record into events; the reader maps the offset to a
// physical line and column.
#include <cstddef>
#include <string>
#include <vector>

#include "support/diagnostics.hpp"

namespace twinpost {

struct build_issue {
  severity level = severity::error;
  std::size_t offset = 0;  ///< offset in the logical record text
  std::string message;
  int line = 0;    ///< when set: a physical line of an earlier record
  int column = 0;  ///< and the column of that record's major word (0: none)
};

using build_issues = std::vector<build_issue>;

}  // namespace twinpost
