#include "machines/word_format.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fmt/format.h>

#include "support/ascii.hpp"

namespace twinpost {

namespace {

std::int64_t pow10(int n) {
  std::int64_t p = 1;
  while (n-- > 0) p *= 10;
  return p;
}

}  // namespace

std::string word_format::text() const {
  return decimals > 0 ? fmt::format("{}.{}", whole, decimals) : fmt::format("{}", whole);
}

std::string word_format::max_text() const {
  std::string s(static_cast<std::size_t>(whole), '9');
  if (decimals > 0) s += '.' + std::string(static_cast<std::size_t>(decimals), '9');
  return s;
}

std::int64_t word_format::max_count(int written) const {
  // 99999.999 written with 3 decimals is the count 99999999; with 1 decimal 999999 (the
  // control's last places are zeros); with 4 decimals 999999990.
  const int extra = written > decimals ? written - decimals : 0;
  return pow10(whole + written) - pow10(extra);
}

word_formats default_word_formats(std::string_view control, bool inch) {
  word_formats f;
  // Fanuc 0i-TD / 31i-B, metric, increment system IS-B: axis words (X Y Z U V W, and the
  // arc words I J K R) take 8 digits with 3 decimals, +-99999.999.
  for (char a : std::string_view("XYZUVWABCIJKR")) f[a] = {5, 3};
  // F: feed per minute up to 6 digits (240000 mm/min on 0i), per revolution 4 decimals
  // (0.0001 mm/rev); S 5 digits; T 4 digits (two for the tool, two for the offset,
  // T0101); M 8 digits (parameter 3030); G 3 digits; P (dwell ms, partner lists) 8 digits.
  f['F'] = {6, 4};
  f['S'] = {5, 0};
  f['T'] = {4, 0};
  f['M'] = {8, 0};
  f['G'] = {3, 0};
  f['N'] = {5, 0};
  f['P'] = {8, 0};
  // O: four digits on Fanuc 0i/31i (O0001-O9999); Mazak EIA programs take up to eight.
  f['O'] = {control.starts_with("mazak") ? 8 : 4, 0};
  if (inch) {
    // Inch output, IS-B: lengths 0.0001 in, +-9999.9999; feeds as the public Fusion posts
    // write them in inch (2 decimals per minute, 5 per revolution), up to 9999 in/min.
    for (char a : std::string_view("XYZUVWIJKR")) f[a] = {4, 4};
    f['F'] = {4, 5};
  }
  return f;
}

bool parse_word_format(std::string_view text, word_format& out, std::string& why) {
  word_format f;
  const char* p = text.data();
  const char* end = p + text.size();
  auto r = std::from_chars(p, end, f.whole);
  if (r.ec != std::errc() || r.ptr == p || *p == '-' || *p == '+') {
    why = "must be digits before and after the point, such as \"5.3\" or \"4\"";
    return false;
  }
  p = r.ptr;
  if (p != end) {
    if (*p != '.' || p + 1 == end || !ascii::is_digit(p[1])) {
      why = "must be digits before and after the point, such as \"5.3\" or \"4\"";
      return false;
    }
    auto d = std::from_chars(p + 1, end, f.decimals);
    if (d.ec != std::errc() || d.ptr != end) {
      why = "must be digits before and after the point, such as \"5.3\" or \"4\"";
      return false;
    }
  }
  if (f.whole < 1 || f.whole > 9) {
    why = fmt::format("has {} digits before the point; 1..9 are allowed", f.whole);
    return false;
  }
  if (f.decimals > 6) {
    why = fmt::format("has {} decimals; 0..6 are allowed", f.decimals);
    return false;
  }
  out = f;
  return true;
}

std::string word_misfit_message(char address, std::string_view value, const word_format& f) {
  return fmt::format("{} word {} does not fit the control's format ({}: at most {})", address, value,
                     f.text(), f.max_text());
}

std::string check_block_words(std::string_view block, const word_formats& f, char open, char close) {
  std::size_t i = 0;
  while (i < block.size()) {
    const char c = block[i];
    if (c == open) {
      const std::size_t e = block.find(close, i + 1);
      if (e == std::string_view::npos) return "";
      i = e + 1;
      continue;
    }
    const bool starts_word = ascii::is_upper(c) && (i == 0 || !ascii::is_upper(block[i - 1]));
    // A word is a letter and a number (or what a number printed wrong looks like: "inf").
    const char next = i + 1 < block.size() ? block[i + 1] : ' ';
    const bool numberish =
        ascii::is_digit(next) || next == '-' || next == '+' || next == '.' || ascii::is_lower(next);
    if (!starts_word || !numberish) {
      ++i;
      continue;
    }
    const word_format& wf = f[c];
    std::size_t j = i + 1;
    if (block[j] == '-' || block[j] == '+') ++j;
    int whole = 0, decimals = 0;
    while (j < block.size() && ascii::is_digit(block[j])) ++j, ++whole;
    if (j < block.size() && block[j] == '.') {
      ++j;
      while (j < block.size() && ascii::is_digit(block[j])) ++j, ++decimals;
    }
    // Whatever follows a number must start the next word or end the block.
    bool ends = j == block.size() || block[j] == ' ' || ascii::is_upper(block[j]) || block[j] == open;
    std::size_t word_end = j;
    while (word_end < block.size() && block[word_end] != ' ' && block[word_end] != open) ++word_end;
    std::string_view value = block.substr(i + 1, (ends ? j : word_end) - i - 1);
    // Digits as written count, padding included: T0101 is four digits, O12345 five.
    const bool number = ends && whole + decimals > 0;
    // A G code may have one decimal place whatever the format (G54.1, G43.4, G12.1, G84.2).
    const int decimals_allowed = c == 'G' ? std::max(wf.decimals, 1) : wf.decimals;
    if (!number || (wf.whole > 0 && (whole > wf.whole || decimals > decimals_allowed))) {
      if (wf.whole == 0) return fmt::format("{} word {} is not a number the control reads", c, value);
      return word_misfit_message(c, value, wf);
    }
    i = ends ? j : word_end;
  }
  return "";
}

}  // namespace twinpost
