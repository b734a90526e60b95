// scripting/pattern_cost.hpp: a walk over a Lua pattern's items (Lua 5.4 manual §6.4.1), with
// the single-byte classes and sets matched here to find each repeated item's longest run.
#include "scripting/pattern_cost.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace twinpost::scripting {

namespace {

bool in_class(unsigned char c, unsigned char cl) {
  bool r = false;
  switch (cl | 0x20) {
    case 'a': r = (c | 0x20) >= 'a' && (c | 0x20) <= 'z'; break;
    case 'c': r = c < 0x20 || c == 0x7f; break;
    case 'd': r = c >= '0' && c <= '9'; break;
    case 'g': r = c > 0x20 && c < 0x7f; break;
    case 'l': r = c >= 'a' && c <= 'z'; break;
    case 'p': r = c > 0x20 && c < 0x7f && !in_class(c, 'w'); break;
    case 's': r = c == ' ' || (c >= '\t' && c <= '\r'); break;
    case 'u': r = c >= 'A' && c <= 'Z'; break;
    case 'w': r = in_class(c, 'a') || in_class(c, 'd'); break;
    case 'x': r = in_class(c, 'd') || ((c | 0x20) >= 'a' && (c | 0x20) <= 'f'); break;
    default: return c == cl;  // an escaped byte: %. %% %[
  }
  return (cl >= 'A' && cl <= 'Z') ? !r : r;
}

// The index of the ']' that closes the set opening at p, or npos when there is none.
std::size_t set_end(std::string_view pat, std::size_t p) {
  std::size_t q = p + 1;
  if (q < pat.size() && pat[q] == '^') ++q;
  do {  // the first byte of a set, ']' included, is a member
    if (q >= pat.size()) return std::string_view::npos;
    if (pat[q++] == '%') ++q;
  } while (q < pat.size() && pat[q] != ']');
  return q < pat.size() ? q : std::string_view::npos;
}

bool in_set(unsigned char c, std::string_view set) {  // set: between '[' and ']'
  std::size_t p = 0;
  bool neg = !set.empty() && set[0] == '^';
  if (neg) ++p;
  for (; p < set.size(); ++p) {
    const auto b = static_cast<unsigned char>(set[p]);
    if (b == '%' && p + 1 < set.size()) {
      if (in_class(c, static_cast<unsigned char>(set[++p]))) return !neg;
    } else if (p + 2 < set.size() && set[p + 1] == '-') {
      if (b <= c && c <= static_cast<unsigned char>(set[p + 2])) return !neg;
      p += 2;
    } else if (b == c) {
      return !neg;
    }
  }
  return neg;
}

struct item {
  std::string_view text;  // ".", "%a", "[...]" or one byte
};

bool matches(unsigned char c, const item& it) {
  if (it.text[0] == '.' && it.text.size() == 1) return true;
  if (it.text[0] == '%') return in_class(c, static_cast<unsigned char>(it.text[1]));
  if (it.text[0] == '[') return in_set(c, it.text.substr(1, it.text.size() - 2));
  return c == static_cast<unsigned char>(it.text[0]);
}

std::size_t longest_run(std::string_view s, const item& it) {
  std::size_t best = 0, run = 0;
  for (char ch : s) {
    run = matches(static_cast<unsigned char>(ch), it) ? run + 1 : 0;
    best = std::max(best, run);
  }
  return best;
}

}  // namespace

pattern_shape pattern_items(std::string_view pat, bool anchor_works) {
  pattern_shape shape;
  std::size_t p = 0;
  shape.anchored = anchor_works && !pat.empty() && pat[0] == '^';
  if (shape.anchored) p = 1;
  while (p < pat.size()) {
    const char c = pat[p];
    if (c == '(' || c == ')' || (c == '$' && p + 1 == pat.size())) {
      ++p;
      continue;
    }
    std::size_t ep = p + 1;
    if (c == '%') {
      if (p + 1 >= pat.size()) break;
      const char d = pat[p + 1];
      if (d == 'b') {
        if (p + 3 >= pat.size()) break;
        shape.linear = true;
        p += 4;
        continue;
      }
      if (d == 'f') {
        if (p + 2 >= pat.size() || pat[p + 2] != '[') break;
        const std::size_t e = set_end(pat, p + 2);
        if (e == std::string_view::npos) break;
        shape.longest_set = std::max(shape.longest_set, e - (p + 2) + 1);
        ++shape.singles;
        p = e + 1;
        continue;
      }
      if (d >= '0' && d <= '9') {
        shape.linear = true;
        p += 2;
        continue;
      }
      ep = p + 2;
    } else if (c == '[') {
      const std::size_t e = set_end(pat, p);
      if (e == std::string_view::npos) break;
      shape.longest_set = std::max(shape.longest_set, e - p + 1);
      ep = e + 1;
    }
    const char q = ep < pat.size() ? pat[ep] : '\0';
    if (q == '*' || q == '+' || q == '-') {
      shape.repeated.push_back(pat.substr(p, ep - p));
      p = ep + 1;
    } else if (q == '?') {
      ++shape.optional;
      p = ep + 1;
    } else {
      ++shape.singles;
      p = ep;
    }
  }
  return shape;
}

namespace {

// The bound before the runs are known: every run as long as the subject.
double base_steps(const pattern_shape& s, double n) {
  return (s.anchored ? 1 : n + 1) * static_cast<double>(s.repeated.size() + s.singles + 1) *
         std::pow(2.0, s.optional) * (s.linear ? n + 1 : 1);
}

constexpr double no_scan_below = 1e6;

}  // namespace

double pattern_scan_bytes(const pattern_shape& shape, std::size_t subject_bytes) {
  const double n = static_cast<double>(subject_bytes);
  const double bound = base_steps(shape, n) * std::pow(n + 1, static_cast<double>(shape.repeated.size()));
  return bound <= no_scan_below ? 0 : n * static_cast<double>(shape.repeated.size());
}

double pattern_steps(const pattern_shape& shape, std::string_view subject, double cap) {
  const double n = static_cast<double>(subject.size());
  double steps = base_steps(shape, n);
  // First with every run as long as the subject: a short subject needs no scan.
  const double bound = steps * std::pow(n + 1, static_cast<double>(shape.repeated.size()));
  if (bound <= no_scan_below || steps > cap) return bound;
  for (const std::string_view it : shape.repeated) {
    steps *= static_cast<double>(longest_run(subject, item{it})) + 1;
    if (steps > cap) return steps;
  }
  return steps;
}

}  // namespace twinpost::scripting
