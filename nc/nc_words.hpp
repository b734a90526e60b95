#pragma once
// The NC word model (issue 37, "one owner of the NC words"): one block's words as a control
// reads them, split once and decoded once, for every reader of NC text: the checker's reader
// (check/nc_program), the analyses (analysis/), the comparison with the CL. A layer of its own
// below check/ and machining/, knowing text and nothing of a machine.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace twinpost {

/// One word of an NC block, read once: its number is decoded when the block is split, so
/// that no consumer reads the digits again. `value` is a view into the split line (no copy
/// per word): a word is good while the text it was split from lives.
struct nc_word {
  char address = 0;         ///< upper case letter
  std::string_view value;   ///< the number as written ("100", "-1.5"), in the split line; empty when none
  bool expression = false;  ///< the value is a variable or expression (M#100, M[#1+2])
  int column = 0;           ///< 1-based column of the address letter
  bool numeric = false;     ///< `value` is a plain number ("-1.5", "+2", "100."), decoded in `number`
  bool point = false;       ///< the number is written with a decimal point ("1." and "1.5", not "1")
  double number = 0;        ///< the value when `numeric` (as std::from_chars reads it), else 0
};

/// The letters (A..Z) of a block's words as a bit mask, bit 0 for A: one test says whether a
/// block has a G, M or S at all. An address that is no letter (a bang wait's `!`) has no bit.
constexpr std::uint32_t nc_letter(char address) {
  return address >= 'A' && address <= 'Z' ? std::uint32_t{1} << (address - 'A') : 0;
}

/// Not a letter: set in a block's letters (split_nc_words, nc_block::letters) when it may have
/// a '#' outside its comments, a macro variable read or written (`#5221=-5.`, `X#100`): one
/// test instead of a search of the text by each reader that looks for variables, which then
/// reads the line exactly (macro_uses). Never missing where there is one; also set for a '#'
/// after a `;` (a comment to the split, not always to a control: attack 70 F1).
inline constexpr std::uint32_t nc_variable_bit = std::uint32_t{1} << 26;

/// One block of a channel's program as the reader hands it on (nc_read_options::on_block).
/// It is split at most once, on the first call of words() by any consumer, and that split
/// serves them all; a consumer that needs no words of most blocks asks letters() first.
class nc_block {
 public:
  /// A block not split yet; `store` is the reader's reusable word vector.
  nc_block(int channel, const std::string& file, int line, std::string_view text, std::vector<nc_word>& store)
      : channel(channel), file(file), line(line), text(text), store_(&store) {}
  /// A block the reader has split already into `words`, with their `letters`.
  nc_block(int channel, const std::string& file, int line, std::string_view text, std::vector<nc_word>& words,
           std::uint32_t letters)
      : channel(channel), file(file), line(line), text(text), store_(&words), split_(true), letters_(letters),
        has_letters_(true) {}

  int channel = 0;          ///< 1-based channel number
  const std::string& file;  ///< the file's name (as in messages)
  int line = 0;             ///< 1-based line number
  std::string_view text;    ///< the physical line, without its line ending

  /// Its words (split_nc_words), split on the first call. Inline: every consumer asks, and
  /// all but the first find it split.
  const std::vector<nc_word>& words() const { return split_ ? *store_ : split(); }
  /// The addresses it may have (nc_letter bits, and nc_variable_bit): exact once split, else
  /// every letter of the text, comments included (a superset: a bit not set is a word not there).
  std::uint32_t letters() const { return has_letters_ ? letters_ : scan_letters(); }
  /// Whether it may have a word of an address of `mask` (nc_letter bits), as `letters() & mask`
  /// says; a long block not split yet is scanned for G, M and S only when the mask asks no
  /// other letter (a scan the compiler makes vector code, where every letter is a table
  /// look-up per character: the long lines of 5-axis programs; on a short line the vector
  /// code's set-up costs more than the look-ups).
  bool may_have(std::uint32_t mask) const {
    constexpr std::uint32_t gms = nc_letter('G') | nc_letter('M') | nc_letter('S');
    if (has_letters_ || (mask & ~gms) != 0 || text.size() < 32) return (letters() & mask) != 0;
    if (!has_gms_) {  // kept: the spindle rules and the length offset's rule both ask
      gms_ = scan_gms();
      has_gms_ = true;
    }
    return (gms_ & mask) != 0;
  }

 private:
  std::uint32_t scan_gms() const;
  const std::vector<nc_word>& split() const;
  std::uint32_t scan_letters() const;
  std::vector<nc_word>* store_;
  mutable bool split_ = false;
  mutable std::uint32_t letters_ = 0;
  mutable bool has_letters_ = false;
  mutable bool has_gms_ = false;
  mutable std::uint32_t gms_ = 0;  // scan_gms, once asked
};

/// Splits one physical NC line into its words. Skips `(...)` and `;` comments, `%` lines,
/// block delete `/` (`/2`), `#` variables, `[...]` expressions and keywords (IF, GOTO, ...).
/// Reads glued (`M100P12`), spaced (`M100 P12`, `M 100`) and lower-case words.
/// The words' values point into `line`: it must outlive them.
std::vector<nc_word> split_nc_words(std::string_view line);
/// The same for a literal (which lives for ever).
inline std::vector<nc_word> split_nc_words(const char* line) {
  return split_nc_words(std::string_view(line));
}
/// A temporary string would die before its words: refused at compile time.
std::vector<nc_word> split_nc_words(std::string&& line) = delete;
/// The number of a word's value ("-1.5", "+2", "100."): false for an empty value or anything
/// else (an expression, "1.2.3").
bool nc_number(std::string_view value, double& out);
/// The same into `words`, reusing its elements: no allocation per block once it has grown.
/// Returns the addresses found (nc_letter bits), and nc_variable_bit for a '#' outside the
/// `(...)` comments (in a word's value, a bracket, on its own, or after a `;`).
std::uint32_t split_nc_words(std::string_view line, std::vector<nc_word>& words);
inline std::uint32_t split_nc_words(const char* line, std::vector<nc_word>& words) {
  return split_nc_words(std::string_view(line), words);
}
std::uint32_t split_nc_words(std::string&& line, std::vector<nc_word>& words) = delete;

}  // namespace twinpost
