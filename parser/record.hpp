#pragma once
// The CL record: one logical line of CL text (after `$` continuations are joined), as the
// grammar sees it. This is the parser's AST. It holds views into the reader's buffer, so
// a record is valid only until the reader moves on; nothing here allocates per record
// once the argument vector has grown to its working size.
#include <cstddef>
#include <string_view>
#include <vector>

#include "support/ascii.hpp"

namespace twinpost {

enum class arg_kind : unsigned char { number, word, empty };

/// One argument of a record: a number, a word (minor word), or an empty slot (`a,,b`).
struct cl_arg {
  arg_kind kind = arg_kind::empty;
  double number = 0;
  std::string_view word;   ///< the word as written (compare case-insensitively)
  std::size_t offset = 0;  ///< offset of the argument in the logical record text
};

enum class record_kind : unsigned char {
  statement,    ///< `MAJOR/args`, `MAJOR,args` or a bare `MAJOR`
  text,         ///< free-text record: PARTNO, PPRINT, INSERT, ... (`text` holds the rest)
  coordinates,  ///< numbers only: a further point of a Pro/E multi-point GOTO
  comment,      ///< `$$ ...` (`text` holds what follows `$$`; a `$$->` data comment also
                ///< has `major` and `args`, with `data_comment` set)
};

/// One logical CL record.
struct cl_record {
  record_kind kind = record_kind::statement;
  std::string_view major;  ///< major word, e.g. "GOTO", "TOOL PATH" (empty for comments)
  std::size_t major_offset = 0;
  std::vector<cl_arg> args;   ///< arguments in order; a trailing empty argument is dropped
  std::string_view text;      ///< text records and comments: the free text, blanks trimmed
  bool data_comment = false;  ///< parsed from inside a `$$->` pseudo-comment (Creo)
  /// Every argument is a number (the fast path's records, which are most of a job): readers
  /// of the numbers may skip the test of each argument's kind. False says nothing.
  bool numbers_only = false;
  std::string_view source;    ///< the whole logical record text; offsets count from here
  std::size_t arg_start = 0;  ///< grammar scratch: where the argument being read starts

  void clear() {
    kind = record_kind::statement;
    major = {};
    major_offset = 0;
    args.clear();
    text = {};
    data_comment = false;
    numbers_only = false;
    source = {};
  }
};

/// Case-insensitive ASCII comparison of a CL word with an upper-case keyword.
inline bool word_is(std::string_view word, std::string_view upper_keyword) {
  return ascii::equals_keyword(word, upper_keyword);
}

}  // namespace twinpost
