#include "post/user_records.hpp"

#include <fmt/format.h>

#include "parser/record_policy.hpp"

namespace twinpost {

std::optional<diagnostic> known_user_record(const machine& m) {
  for (const record_event& r : m.events.records)
    for (const record_rule& rule : record_rules()) {
      if (rule.word != r.major) continue;
      diagnostic d;
      d.file = m.source;
      d.line = r.line;
      d.column = r.column;
      d.message = fmt::format(
          "events.record.major \"{}\" is a record the post knows ({} in a post, docs/records.md): "
          "it never reaches [[events.record]], which takes only words the post does not know",
          r.major, record_use_name(rule.use));
      return d;
    }
  return std::nullopt;
}

}  // namespace twinpost
