#include "machines/machine.hpp"

#include <algorithm>

namespace twinpost {

namespace {

char ascii_upper(char c) { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c; }

// CL dialects disagree on case (HEAD/MAIN, head/main), so head words match without it.
bool same_word(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return ascii_upper(x) == ascii_upper(y);
         });
}

}  // namespace

bool wait_rules::is_wait_code(int code) const {
  if (code < first || code > last || step < 1) return false;
  if ((static_cast<long long>(code) - first) % step != 0) return false;  // first may be < 0 in code
  return std::find(excluded.begin(), excluded.end(), code) == excluded.end();
}

const axis_def* channel_def::axis(char address) const {
  for (const axis_def& a : axes)
    if (a.address == address) return &a;
  return nullptr;
}

const channel_def* machine::channel_for_head(int head) const {
  for (const channel_def& c : channels)
    if (std::find(c.heads.begin(), c.heads.end(), head) != c.heads.end()) return &c;
  return nullptr;
}

const channel_def* machine::channel_for_head(std::string_view word) const {
  for (const channel_def& c : channels)
    for (const std::string& h : c.head_names)
      if (same_word(h, word)) return &c;
  return nullptr;
}

const spindle_def* machine::spindle(std::string_view name) const {
  for (const spindle_def& s : spindles)
    if (s.name == name) return &s;
  return nullptr;
}

std::optional<int> machine::program_number_of(std::string_view name) const {
  if (name.empty() || name.size() > 9 || name.find_first_not_of("0123456789") != std::string_view::npos)
    return std::nullopt;
  int n = 0;
  for (char c : name) n = n * 10 + (c - '0');
  if (n < 1 || n > formats['O'].max_count(0)) return std::nullopt;
  return n;
}

}  // namespace twinpost
