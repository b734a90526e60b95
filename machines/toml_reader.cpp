#include "machines/toml_reader.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "machines/machine.hpp"
#include "machines/name_template.hpp"
#include "support/ascii.hpp"
#include "support/errors.hpp"

namespace twinpost::detail {

void fail_at(std::string_view source, const toml::source_region& where, std::string_view message) {
  throw config_error::at(source, where.begin.line, where.begin.column, message);
}

std::string_view type_phrase(toml::node_type t) {
  switch (t) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a floating-point number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::date: return "a date";
    case toml::node_type::time: return "a time";
    case toml::node_type::date_time: return "a date-time";
    case toml::node_type::array: return "an array";
    case toml::node_type::table: return "a table";
    case toml::node_type::none: break;
  }
  return "nothing";
}

table_reader::table_reader(const toml::table& t, std::string path, std::string_view source,
                           std::initializer_list<std::string_view> known)
    : table_(t), path_(std::move(path)), source_(source) {
  // toml++ keeps keys sorted by name; report the unknown key that comes first in the file
  // so that the message matches what a reader of the file meets first.
  const toml::key* first_unknown = nullptr;
  for (auto&& [k, v] : t) {
    if (std::find(known.begin(), known.end(), k.str()) != known.end()) continue;
    const auto& b = k.source().begin;
    if (!first_unknown || b.line < first_unknown->source().begin.line ||
        (b.line == first_unknown->source().begin.line && b.column < first_unknown->source().begin.column))
      first_unknown = &k;
  }
  if (first_unknown)
    fail_at(source_, first_unknown->source(),
            fmt::format("unknown key '{}'", key_path(first_unknown->str())));
}

const toml::node* table_reader::find(std::string_view key) const { return table_.get(key); }

std::string table_reader::key_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : fmt::format("{}.{}", path_, key);
}

void table_reader::fail(const toml::node& n, std::string_view message) const {
  fail_at(source_, n.source(), message);
}

void table_reader::fail_here(std::string_view message) const { fail_at(source_, table_.source(), message); }

void table_reader::require(std::string_view key) const {
  if (!find(key)) fail_here(fmt::format("{} is required", key_path(key)));
}

void table_reader::wrong_type(std::string_view key, const toml::node& n, std::string_view wanted) const {
  fail(n, fmt::format("{} must be {}, not {}", key_path(key), wanted, type_phrase(n.type())));
}

int table_reader::to_int(std::string_view key, const toml::node& n) const {
  const auto* v = n.as_integer();
  if (!v) wrong_type(key, n, "an integer");
  const std::int64_t i = v->get();
  if (i < std::numeric_limits<int>::min() || i > std::numeric_limits<int>::max())
    fail(n, fmt::format("{} is out of range: {}", key_path(key), i));
  return static_cast<int>(i);
}

bool table_reader::read(std::string_view key, std::string& out) const {
  const toml::node* n = find(key);
  if (!n) return false;
  const auto* s = n->as_string();
  if (!s) wrong_type(key, *n, "a string");
  out = s->get();
  return true;
}

bool table_reader::read(std::string_view key, int& out) const {
  const toml::node* n = find(key);
  if (!n) return false;
  out = to_int(key, *n);
  return true;
}

bool table_reader::read(std::string_view key, double& out) const {
  const toml::node* n = find(key);
  if (!n) return false;
  if (const auto* f = n->as_floating_point())
    out = f->get();
  else if (const auto* i = n->as_integer())
    out = static_cast<double>(i->get());
  else
    wrong_type(key, *n, "a number");
  // TOML's nan and inf are floats: a limit of nan compares false both ways and switches its
  // check off (attack 45: rotary max = nan wrote A150. on a head that stops at 110).
  if (!std::isfinite(out)) fail(*n, fmt::format("{} must be a finite number, not {}", key_path(key), out));
  return true;
}

bool table_reader::read(std::string_view key, bool& out) const {
  const toml::node* n = find(key);
  if (!n) return false;
  const auto* b = n->as_boolean();
  if (!b) wrong_type(key, *n, "a boolean");
  out = b->get();
  return true;
}

bool table_reader::read(std::string_view key, std::optional<int>& out) const {
  int v = 0;
  if (!read(key, v)) return false;
  out = v;
  return true;
}

bool table_reader::read(std::string_view key, std::optional<double>& out) const {
  double v = 0;
  if (!read(key, v)) return false;
  out = v;
  return true;
}

bool table_reader::read(std::string_view key, std::vector<int>& out) const {
  const toml::node* n = find(key);
  if (!n) return false;
  const auto* a = n->as_array();
  if (!a) wrong_type(key, *n, "an array of integers");
  out.clear();
  for (const toml::node& e : *a) {
    if (!e.is_integer())
      fail(e, fmt::format("{} must hold only integers, not {}", key_path(key), type_phrase(e.type())));
    out.push_back(to_int(key, e));
  }
  return true;
}

bool table_reader::read(std::string_view key, std::vector<std::string>& out) const {
  const toml::node* n = find(key);
  if (!n) return false;
  const auto* a = n->as_array();
  if (!a) wrong_type(key, *n, "an array of strings");
  out.clear();
  for (const toml::node& e : *a) {
    const auto* s = e.as_string();
    if (!s) fail(e, fmt::format("{} must hold only strings, not {}", key_path(key), type_phrase(e.type())));
    out.push_back(s->get());
  }
  return true;
}

bool table_reader::read_char(std::string_view key, char& out, bool letter) const {
  std::string s;
  if (!read(key, s)) return false;
  const bool ok = s.size() == 1 && (!letter || ascii::is_upper(s[0]));
  if (!ok)
    fail(*find(key), fmt::format("{} must be {}, not '{}'", key_path(key),
                                 letter ? "one upper-case letter" : "one character", s));
  out = s[0];
  return true;
}

namespace {

// Sample values that every template is formatted with once at load, so that a bad template
// is an error there and not in the middle of a post. Load time only: real output is made
// from real values (formats/), never from these.
template_args sample_template_args() {
  return {.program = 1000,
          .name = "PART",
          .channel = 1,
          .max = 3000,
          .tool = 1,
          .offset = 1,
          .seconds = 1.5,
          .ms = 1500,
          .rpm = 1000,
          .text = "TEXT",
          .code = 100,
          .x = "1.",
          .y = "1.",
          .z = "1."};
}

}  // namespace

void table_reader::check_template(std::string_view key, const toml::node& n, placeholder_set known) const {
  const std::string& tpl = n.as_string()->get();
  // A line break would make one template several NC lines that nothing reads as blocks, a '%'
  // is the tape mark where a control stops reading (issue 38, sixth attack).
  for (const char c : tpl) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u >= 0x7f || c == '%')
      fail(n,
           fmt::format("{}: a template holds {}: a block is one line of printable text", key_path(key),
                       c == '%' ? std::string("'%', the tape mark where a control stops reading")
                       : u >= 0x80
                           ? fmt::format("the byte 0x{:02x}, no ASCII (a 7-bit link strips its top bit)", u)
                           : fmt::format("the control byte 0x{:02x}", u)));
  }
  // The widths before the template is formatted with the sample values (a width of 2e9).
  if (const std::string why = template_spec_fault(tpl, false); !why.empty())
    fail(n, fmt::format("{}: template \"{}\": {}", key_path(key), tpl, why));
  try {
    (void)format_template(tpl, sample_template_args());
  } catch (const fmt::format_error& e) {
    fail(n, fmt::format("{}: bad template \"{}\": {}", key_path(key), tpl, e.what()));
  }
  // A placeholder that is not given where the template is used would print a value that
  // means nothing there.
  if (const std::string name = unknown_placeholder(tpl, known); !name.empty())
    fail(n, fmt::format("{}: template \"{}\" names {{{}}}, which is not known there (it is "
                        "given {})",
                        key_path(key), tpl, name, known.text()));
  if (const std::string why = template_spec_fault(tpl, true); !why.empty())
    fail(n, fmt::format("{}: template \"{}\": {}", key_path(key), tpl, why));
}

bool table_reader::read_template(std::string_view key, std::string& out, placeholder_set known) const {
  if (!read(key, out)) return false;
  check_template(key, *find(key), known);
  return true;
}

bool table_reader::read_templates(std::string_view key, std::vector<std::string>& out,
                                  placeholder_set known) const {
  if (!read(key, out)) return false;
  for (const toml::node& e : *find(key)->as_array()) check_template(key, e, known);
  return true;
}

bool table_reader::read_fixed(std::string_view key, std::string& out) const {
  if (!read_template(key, out, template_uses::fixed)) return false;
  out = format_template(out, {});
  return true;
}

bool table_reader::read_fixed(std::string_view key, std::vector<std::string>& out) const {
  if (!read_templates(key, out, template_uses::fixed)) return false;
  for (std::string& s : out) s = format_template(s, {});
  return true;
}

const toml::table* table_reader::sub_table(std::string_view key) const {
  const toml::node* n = find(key);
  if (!n) return nullptr;
  const auto* t = n->as_table();
  if (!t) wrong_type(key, *n, "a table");
  return t;
}

std::vector<const toml::table*> table_reader::tables(std::string_view key) const {
  std::vector<const toml::table*> out;
  const toml::node* n = find(key);
  if (!n) return out;
  const auto* a = n->as_array();
  if (!a) wrong_type(key, *n, fmt::format("an array of tables ([[{}]])", key_path(key)));
  for (const toml::node& e : *a) {
    const auto* t = e.as_table();
    if (!t) fail(e, fmt::format("{} must hold only tables, not {}", key_path(key), type_phrase(e.type())));
    out.push_back(t);
  }
  return out;
}

}  // namespace twinpost::detail
