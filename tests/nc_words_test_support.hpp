#pragma once
// Reading NC blocks back in the tests' models of a control: a word's value and a whole word.
#include <cctype>
#include <sstream>
#include <string>

namespace twinpost::test {

/// The value of the first word with `address` in `block` (X12.5, X-3., X.5), or `fallback`;
/// `given` says whether the block had one.
inline double word(const std::string& block, char address, double fallback, bool* given = nullptr) {
  std::istringstream in(block);
  std::string w;
  while (in >> w)
    if (w[0] == address && w.size() > 1 &&
        (std::isdigit(static_cast<unsigned char>(w[1])) || w[1] == '-' || w[1] == '.')) {
      if (given) *given = true;
      return std::stod(w.substr(1));
    }
  if (given) *given = false;
  return fallback;
}

/// Whether `block` holds the word `w` as a whole (G12.1, not G12.10).
inline bool has(const std::string& block, const std::string& w) {
  return (" " + block + " ").find(" " + w + " ") != std::string::npos;
}

}  // namespace twinpost::test
