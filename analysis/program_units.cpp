// analysis/program_units.hpp: the program's unit and the codes that change it.
#include "analysis/program_units.hpp"

#include <cmath>

#include "nc/nc_words.hpp"

namespace twinpost {

namespace {

long tenths(double g) { return std::lround(g * 10); }

}  // namespace

std::optional<bool> program_units::selected_by(double number) const {
  const long g = tenths(number);
  if (g == (system_c ? 700 : 200)) return true;
  if (g == (system_c ? 710 : 210)) return false;
  return std::nullopt;
}

program_units units_of(const machine& m) {
  program_units u;
  u.inch = m.program.output_units == output_unit::inch;
  bool g7071 = false, g2021 = false;
  for (const std::string& b : m.program.header)
    for (const nc_word& w : split_nc_words(b))
      if (w.address == 'G' && w.numeric) {
        const long g = tenths(w.number);
        g7071 = g7071 || g == 700 || g == 710;
        g2021 = g2021 || g == 200 || g == 210;
      }
  u.system_c = g7071 && !g2021;
  return u;
}

}  // namespace twinpost
