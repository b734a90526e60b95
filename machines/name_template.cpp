// Formatting the machine file's templates (tool call, clamp, header lines, file names)
// with named values; see machines/name_template.hpp.
#include "machines/name_template.hpp"

#include <algorithm>
#include <array>
#include <utility>

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

// In the order of template_args.
constexpr std::array<std::pair<std::string_view, placeholder>, 14> names{{
    {"program", placeholder::program},
    {"name", placeholder::name},
    {"channel", placeholder::channel},
    {"max", placeholder::max},
    {"tool", placeholder::tool},
    {"offset", placeholder::offset},
    {"seconds", placeholder::seconds},
    {"ms", placeholder::ms},
    {"rpm", placeholder::rpm},
    {"text", placeholder::text},
    {"code", placeholder::code},
    {"x", placeholder::x},
    {"y", placeholder::y},
    {"z", placeholder::z},
}};

// {seconds} is a dwell time, and a Fanuc control reads a dwell word without a decimal point in
// its least increment (G4 U1 is 1 ms with decimal-point programming off, the default): with no
// format spec it is written as an NC number that always has its point (1., 0.5, 2.25), to the
// millisecond, as the Autodesk Fusion posts' secFormat (3 decimals, forceDecimal) writes it. A
// template that gives a spec ({seconds:.1f}) gets fmt's own formatting of the number.
struct dwell_seconds {
  double value;
};

}  // namespace
}  // namespace twinpost

template <>
struct fmt::formatter<twinpost::dwell_seconds> : fmt::formatter<double> {
  bool nc = true;
  constexpr auto parse(format_parse_context& ctx) {
    if (ctx.begin() == ctx.end() || *ctx.begin() == '}') return ctx.begin();
    nc = false;
    return fmt::formatter<double>::parse(ctx);
  }
  template <typename Context>
  auto format(const twinpost::dwell_seconds& s, Context& ctx) const {
    if (!nc) return fmt::formatter<double>::format(s.value, ctx);
    std::string text = fmt::format("{:.3f}", s.value);
    while (text.back() == '0') text.pop_back();  // "1.500" -> "1.5", "2.000" -> "2."
    if (text == "-0.") text = "0.";
    return std::copy(text.begin(), text.end(), ctx.out());
  }
};

namespace twinpost {
namespace {

bool name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

}  // namespace

std::string placeholder_set::text() const {
  std::string s;
  for (const auto& [n, p] : names) {
    if (!has(p)) continue;
    if (!s.empty()) s += ", ";
    s += fmt::format("{{{}}}", n);
  }
  return s.empty() ? "no placeholder" : s;
}

namespace {

// The first non-empty answer of `on_field(open, end)` for each replacement field of `tpl`: `open`
// at its '{' (a "{{" is a literal brace, no field), `end` just after its name (at ':' or '}').
// A nested "{width}" in a spec is a field of its own.
template <class F>
std::string first_of_fields(std::string_view tpl, F&& on_field) {
  for (std::size_t i = 0; i < tpl.size(); ++i) {
    if (tpl[i] != '{') continue;
    if (i + 1 < tpl.size() && tpl[i + 1] == '{') {
      ++i;
      continue;
    }
    std::size_t end = i + 1;
    while (end < tpl.size() && name_char(tpl[end])) ++end;
    if (std::string found = on_field(i, end); !found.empty()) return found;
  }
  return {};
}

}  // namespace

std::string unknown_placeholder(std::string_view tpl, placeholder_set known) {
  return first_of_fields(tpl, [&](std::size_t open, std::size_t end) -> std::string {
    const std::string_view name = tpl.substr(open + 1, end - open - 1);
    for (const auto& [n, p] : names)
      if (n == name && !known.has(p)) return std::string(name);
    return {};
  });
}

std::string template_spec_fault(std::string_view tpl, bool placeholders) {
  return first_of_fields(tpl, [&](std::size_t, std::size_t end) -> std::string {
    if (end >= tpl.size() || tpl[end] != ':') return {};
    // The spec runs to its '}'; a nested "{name}" in it is a width or precision by placeholder.
    for (std::size_t j = end + 1; j < tpl.size() && tpl[j] != '}'; ++j) {
      if (tpl[j] == '{') {
        if (placeholders) return "a width or precision given by a placeholder; write the number";
        while (j < tpl.size() && tpl[j] != '}') ++j;
        if (j == tpl.size()) break;
        continue;
      }
      // A presentation type other than a number's (`{tool:c}` prints the number as a byte).
      if (!placeholders && ascii::is_letter(tpl[j]) && (j + 1 >= tpl.size() || tpl[j + 1] == '}') &&
          std::string_view("dfFeEgGs").find(tpl[j]) == std::string_view::npos)
        return fmt::format(
            "the presentation type '{}' (a number as a byte, in hex or octal, ...); write {{name}}, "
            "{{name:d}} or {{name:.3f}}",
            tpl[j]);
      if (placeholders || !ascii::is_digit(tpl[j])) continue;
      long n = 0;
      for (; j < tpl.size() && ascii::is_digit(tpl[j]) && n <= 64; ++j) n = n * 10 + (tpl[j] - '0');
      if (n > 64) return "a width or precision above 64; a word of the control has at most a few digits";
      --j;
    }
    return {};
  });
}

namespace {

// A value from the CL (an operation's name, a record's text) as a template writes it: a line
// break would start another NC line, a '%' is the tape mark, a parenthesis or ';' would end or
// start a comment (`(OP {name})` with a name `A)G55(`), a control byte or one above ASCII is no
// text: each becomes a blank, as in the post's own comments (formats/block_writer's
// safe_comment_text).
std::string printable(std::string_view v) {
  std::string out(v);
  for (char& c : out) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u >= 0x7f || c == '%' || c == '(' || c == ')' || c == ';') c = ' ';
  }
  return out;
}

}  // namespace

std::string format_template(std::string_view tpl, const template_args& a) {
  reject_positional(tpl);
  const auto clean = [](std::string_view v) {
    return std::none_of(v.begin(), v.end(), [](char c) {
      const auto u = static_cast<unsigned char>(c);
      return u < 0x20 || u >= 0x7f || c == '%' || c == '(' || c == ')' || c == ';';
    });
  };
  if (!clean(a.name) || !clean(a.text)) {
    template_args b = a;
    b.name = printable(a.name);
    b.text = printable(a.text);
    return format_template(tpl, b);
  }
  return fmt::format(fmt::runtime(tpl), fmt::arg("program", a.program), fmt::arg("name", a.name),
                     fmt::arg("channel", a.channel), fmt::arg("max", a.max), fmt::arg("tool", a.tool),
                     fmt::arg("offset", a.offset), fmt::arg("seconds", dwell_seconds{a.seconds}),
                     fmt::arg("ms", a.ms), fmt::arg("rpm", a.rpm), fmt::arg("text", a.text),
                     fmt::arg("code", a.code), fmt::arg("x", a.x), fmt::arg("y", a.y), fmt::arg("z", a.z));
}

}  // namespace twinpost
