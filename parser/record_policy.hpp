#pragma once
// The record policy: every major word twinpost knows and what a post does with it. The one
// table lives in parser/record_table.cpp, each row with its handler; this header shows it
// to the rest of the program (docs/records.md, `twinpost parse --records`).
#include <span>
#include <string>
#include <string_view>

namespace twinpost {

enum class record_use : unsigned char {
  posted,   ///< written to the programs (`note` says how)
  ignored,  ///< passed over on purpose (`note` says why that is safe)
  refused,  ///< a post stops with an error naming the record (`note` says why)
};

/// One row of the policy. A word may have rows for given leading minor words (`args`,
/// `MODE,ABSOL`; a trailing `...` lets more arguments follow), then one row for any other
/// use of the word (`args` empty), always last.
struct record_rule {
  std::string_view word;  ///< upper case, as CL writes it ("TOOL PATH" holds a blank)
  std::string_view args;
  record_use use = record_use::refused;
  std::string_view note;
};

/// The rows, sorted by word.
std::span<const record_rule> record_rules();

/// "posted", "ignored", "error".
std::string_view record_use_name(record_use u);

/// The table as Markdown rows (`| record | in a post | how or why |`), one line each, as
/// docs/records.md lists them between its markers.
std::string record_policy_markdown();

}  // namespace twinpost
