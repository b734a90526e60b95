#pragma once
// The control's number format per address: how many digits a word may have before and
// after the decimal point (Fanuc's "X5.3": at most 99999.999). Every word the post writes
// from a CL value is held to it; a value that does not fit stops the post at its record.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace twinpost {

/// Digits of one address: `whole` before the point, `decimals` after (0: a whole number).
struct word_format {
  int whole = 0;  ///< 0: the address has no format (never checked)
  int decimals = 0;
  /// "5.3", or "4" for a whole number.
  std::string text() const;
  /// The largest magnitude the control reads, as text: "99999.999", "9999".
  std::string max_text() const;
  /// The largest count of the last written place when the word is written with `written`
  /// decimals (5.3 written with 3 decimals: 99999999; with 1: 999999).
  std::int64_t max_count(int written) const;
};

/// The formats of the addresses A..Z.
struct word_formats {
  std::array<word_format, 26> by_address{};
  const word_format& operator[](char address) const {
    return by_address[static_cast<std::size_t>(address - 'A')];
  }
  word_format& operator[](char address) { return by_address[static_cast<std::size_t>(address - 'A')]; }
};

/// The defaults for `control` (the machine's control name), in mm or `inch` output: see
/// docs/machines.md.
word_formats default_word_formats(std::string_view control, bool inch = false);

/// Reads "5.3" or "4" into `out`; false (with `why`) when it is not digits in range.
bool parse_word_format(std::string_view text, word_format& out, std::string& why);

/// "Z word 1e+308 does not fit the control's format (5.3: at most 99999.999)".
std::string word_misfit_message(char address, std::string_view value, const word_format& f);

/// Checks every word of a block formatted from a template (tool call, dwell, clamp, program
/// line): an address letter, then a number. Text in comments (between `open` and `close`)
/// is skipped. Returns "" when all fit, else the message for the first that does not.
std::string check_block_words(std::string_view block, const word_formats& f, char open, char close);

}  // namespace twinpost
