#include "parser/record_policy.hpp"

#include <fmt/format.h>

namespace twinpost {

std::string_view record_use_name(record_use u) {
  switch (u) {
    case record_use::posted: return "posted";
    case record_use::ignored: return "ignored";
    case record_use::refused: return "error";
  }
  return "error";
}

std::string record_policy_markdown() {
  std::string s = "| record | in a post | how, or why |\n|---|---|---|\n";
  const std::span<const record_rule> rules = record_rules();
  for (std::size_t i = 0; i < rules.size(); ++i) {
    const record_rule& r = rules[i];
    // A word's catch-all row after rows for given minor words: "any other SET".
    const bool other = r.args.empty() && i > 0 && rules[i - 1].word == r.word;
    const std::string record = !r.args.empty() ? fmt::format("`{}/{}`", r.word, r.args)
                               : other         ? fmt::format("any other `{}`", r.word)
                                               : fmt::format("`{}`", r.word);
    s += fmt::format("| {} | {} | {} |\n", record, record_use_name(r.use), r.note);
  }
  return s;
}

}  // namespace twinpost
