// Formatting the machine file's templates (tool call, clamp, header lines, file names)
// with named values; see machines/name_template.hpp.
#include "machines/name_template.hpp"

#include <fmt/format.h>

#include "support/ascii.hpp"

namespace twinpost {

namespace {

// fmt numbers named arguments as well, so "{}" or "{0}" would quietly print the program
// number where the author meant, say, the spindle limit.
void reject_positional(std::string_view tpl) {
  for (std::size_t i = 0; i + 1 < tpl.size(); ++i) {
    if (tpl[i] != '{') continue;
    const char c = tpl[i + 1];
    if (c == '{') {
      ++i;
      continue;
    }
    if (c == '}' || c == ':' || ascii::is_digit(c))
      throw fmt::format_error("positional placeholder; use a name such as {tool}");
  }
}

}  // namespace

std::string format_template(std::string_view tpl, const template_args& a) {
  reject_positional(tpl);
  return fmt::format(fmt::runtime(tpl), fmt::arg("program", a.program), fmt::arg("name", a.name),
                     fmt::arg("channel", a.channel), fmt::arg("max", a.max),
                     fmt::arg("tool", a.tool), fmt::arg("offset", a.offset),
                     fmt::arg("seconds", a.seconds), fmt::arg("ms", a.ms),
                     fmt::arg("rpm", a.rpm));
}

template_args sample_template_args() {
  return {.program = 1000, .name = "PART", .channel = 1, .max = 3000, .tool = 1, .offset = 1,
          .seconds = 1.5, .ms = 1500, .rpm = 1000};
}

}  // namespace twinpost
