#pragma once
// The templates of a machine file (tool_call, clamp, dwell, header and footer lines,
// program line, file name) are fmt format strings with named placeholders only. Each is
// given only the values that are real where it is used; the sets below say which, and the
// loader refuses a template that names any other (machines/toml_reader.cpp).
#include <initializer_list>
#include <string>
#include <string_view>

namespace twinpost {

/// The values a template (tool_call, clamp, header block, ...) may name as {program},
/// {name}, {channel}, {max}, {tool}, {offset}, {seconds}, {ms} and {rpm}. A writer fills
/// exactly the members of the template's placeholder set (template_uses below) from real
/// values; the others keep these defaults, which no valid template can reach.
struct template_args {
  int program = 0;     ///< program (O) number
  std::string name;    ///< program name (sanitized PARTNO)
  int channel = 0;     ///< channel number
  double max = 0;      ///< spindle speed clamp
  int tool = 0;        ///< tool number
  int offset = 0;      ///< tool offset number
  double seconds = 0;  ///< dwell time in seconds
  int ms = 0;          ///< dwell time in milliseconds
  double rpm = 0;      ///< spindle speed
  std::string text{};  ///< [events]: a name or the arguments of a record (machine_events.hpp)
  int code = 0;        ///< [events]: the wait code of a wait event
  /// [events]: the position at the event, each word's number as the program writes it ("44.",
  /// X in diameter on a lathe); `name` there is the tool's or the operation's name.
  std::string x{}, y{}, z{};
};

/// One placeholder of template_args.
enum class placeholder : unsigned {
  program = 1u << 0,
  name = 1u << 1,
  channel = 1u << 2,
  max = 1u << 3,
  tool = 1u << 4,
  offset = 1u << 5,
  seconds = 1u << 6,
  ms = 1u << 7,
  rpm = 1u << 8,
  text = 1u << 9,
  code = 1u << 10,
  x = 1u << 11,
  y = 1u << 12,
  z = 1u << 13,
};

/// The placeholders a template is given where it is used.
class placeholder_set {
 public:
  constexpr placeholder_set(std::initializer_list<placeholder> ps) {
    for (placeholder p : ps) bits_ |= static_cast<unsigned>(p);
  }
  constexpr bool has(placeholder p) const { return (bits_ & static_cast<unsigned>(p)) != 0; }
  /// "{program}, {name}" in the order of template_args; "no placeholder" when empty.
  std::string text() const;

 private:
  unsigned bits_ = 0;
};

/// Where each template is used and what it is given there (formats/ fills exactly these).
namespace template_uses {
using p = placeholder;
/// program.file_name, program.program_line: once per file, before any channel.
inline constexpr placeholder_set file{p::program, p::name};
/// program.header, program.footer: once per channel section.
inline constexpr placeholder_set section{p::program, p::name, p::channel};
/// program.section_marker: opens a channel's section, and the checker (check/nc_program)
/// finds the sections of a merged program by it, knowing nothing but the channel.
inline constexpr placeholder_set section_marker{p::channel};
/// channel.tool_call: at a tool change.
inline constexpr placeholder_set tool_call{p::tool, p::offset, p::channel};
/// spindle.clamp: with a constant surface speed; max and rpm are both the speed limit.
inline constexpr placeholder_set clamp{p::max, p::rpm, p::channel};
/// codes.dwell: at a DELAY.
inline constexpr placeholder_set dwell{p::seconds, p::ms, p::channel};
/// program.end_code and every [codes] entry but dwell: fixed blocks, given nothing; the
/// loader stores them formatted (`{{` as `{`).
inline constexpr placeholder_set fixed{};
}  // namespace template_uses

/// Formats template `tpl` with `a`; throws fmt::format_error for a bad template, including
/// a positional placeholder ({} or {0}), which would silently pick the wrong value.
std::string format_template(std::string_view tpl, const template_args& a);

/// The first placeholder (without braces) that `tpl` names and `known` does not hold, or ""
/// when it names only known ones. Names that are no placeholder at all are left to
/// format_template, which refuses them.
std::string unknown_placeholder(std::string_view tpl, placeholder_set known);

/// Why the format specs of template `tpl` are refused, or "": a width or precision above 64 (one
/// `{tool:>2000000000}` took 6 GB and three minutes) or given by another placeholder
/// (`{tool:>{max}}`, a width from the job's data).
/// `placeholders`: the widths given by a placeholder only; else the numbers only.
std::string template_spec_fault(std::string_view tpl, bool placeholders);

}  // namespace twinpost
