#include "machines/macro_variables.hpp"

#include <algorithm>

namespace twinpost {

std::vector<macro_use> macro_uses(std::string_view b) {
  std::vector<macro_use> out;
  bool comment = false;  // a control ends a comment at the first ')': comments do not nest
  for (std::size_t i = 0; i < b.size(); ++i) {
    const char c = b[i];
    if (c == '(') comment = true;
    if (c == ')') {
      comment = false;
      continue;
    }
    // A `;` comment runs to the end of the line, as the word splitter reads it (attack 67 M10: a
    // PPRINT's `#500=0` after it was read as a write of a reserved variable).
    if (!comment && c == ';') break;
    if (comment || c != '#') continue;
    std::size_t k = i + 1;
    while (k < b.size() && b[k] == ' ') ++k;
    if (k < b.size() && b[k] == '[') {  // #[...]: its number is known at run time only
      int nest = 0;
      std::size_t e = k;
      for (; e < b.size(); ++e) {
        if (b[e] == '[') ++nest;
        if (b[e] == ']' && --nest == 0) break;
      }
      if (e >= b.size()) break;
      ++e;
      while (e < b.size() && b[e] == ' ') ++e;
      const bool write = e < b.size() && b[e] == '=' && (e + 1 >= b.size() || b[e + 1] != '=');
      out.push_back({-1, static_cast<int>(i + 1), write});
      i = k;  // the variables inside are read
      continue;
    }
    if (k >= b.size() || b[k] < '0' || b[k] > '9') continue;  // a lone '#'
    // A control that skips blanks reads `#5 00` as #500.
    long n = 0;
    while (k < b.size() &&
           ((b[k] >= '0' && b[k] <= '9') ||
            (b[k] == ' ' && k + 1 < b.size() && (b[k + 1] == ' ' || (b[k + 1] >= '0' && b[k + 1] <= '9'))))) {
      if (b[k] != ' ' && n < 100'000'000) n = n * 10 + (b[k] - '0');
      ++k;
    }
    std::size_t e = k;
    while (e < b.size() && b[e] == ' ') ++e;
    const bool write = e < b.size() && b[e] == '=' && (e + 1 >= b.size() || b[e + 1] != '=');
    out.push_back({static_cast<int>(n), static_cast<int>(i + 1), write});
    i = k - 1;
  }
  return out;
}

std::vector<reserved_variable> reserved_variables(const machine& m) {
  std::vector<reserved_variable> out;
  auto add = [&](int n, std::string why) {
    for (const reserved_variable& r : out)
      if (r.number == n) return;
    out.push_back({n, std::move(why)});
  };
  for (int v : m.program.reserved_variables) add(v, "program.reserved_variables");
  const std::pair<const char*, const std::vector<std::string>*> lists[] = {
      {"transfer.grip", &m.transfer.grip},
      {"transfer.release", &m.transfer.release},
      {"transfer.release_after_cutoff", &m.transfer.release_after_cutoff}};
  for (const auto& [name, blocks] : lists) {
    std::vector<int> written;
    for (const std::string& b : *blocks)
      for (const macro_use& u : macro_uses(b))
        if (u.write) written.push_back(u.number);
    for (const std::string& b : *blocks)
      for (const macro_use& u : macro_uses(b))
        if (!u.write && u.number > 0 && std::find(written.begin(), written.end(), u.number) == written.end())
          add(u.number, std::string("read by ") + name);
  }
  std::sort(out.begin(), out.end(),
            [](const reserved_variable& a, const reserved_variable& b) { return a.number < b.number; });
  return out;
}

}  // namespace twinpost
