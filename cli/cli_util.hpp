#pragma once
// Small helpers shared by the sub-commands: option parsing with clear errors, files,
// and a diagnostic sink that prints to stderr as diagnostics arrive.
#include <boost/program_options.hpp>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>

#include "cli/commands.hpp"
#include "support/diagnostics.hpp"
#include "support/errors.hpp"

namespace twinpost::cli {

/// Parses `a` into `vm`. Returns the exit status when the command is done already: 2 after
/// printing "twinpost COMMAND: ..." for a bad option, 0 after printing `help` for --help;
/// nothing when the command should go on.
std::optional<int> parse_command(const args& a, const boost::program_options::options_description& opts,
                                 const boost::program_options::positional_options_description& pos,
                                 boost::program_options::variables_map& vm, const char* command,
                                 const std::string& help);

/// Prints "twinpost: error: MESSAGE" and a newline to stderr. The library never names the
/// program: this is the one place that puts its name before an error without a place.
void print_error(std::string_view message);

/// Prints `e` to stderr: as it is when it carries its own place ("m.toml:3:1: error: ..."),
/// else through print_error.
void print_error(const config_error& e);

/// The options' help text.
std::string to_string(const boost::program_options::options_description& opts);

/// The names of an enum's table joined for a message or a help text, in the table's order:
/// "a|b|c" (sep "|", last_sep "|") or "a, b or c" (sep ", ", last_sep " or ").
template <class Table, class Name>
std::string names_joined(const Table& table, Name name, std::string_view sep, std::string_view last_sep) {
  std::string s;
  for (std::size_t i = 0; i < table.size(); ++i) {
    if (i > 0) s += i + 1 == table.size() ? last_sep : sep;
    s += name(table[i]);
  }
  return s;
}

/// An open file, closed on destruction.
class open_file {
 public:
  explicit open_file(const std::string& path, const char* mode = "rb");
  ~open_file();
  open_file(const open_file&) = delete;
  open_file& operator=(const open_file&) = delete;
  explicit operator bool() const { return f_ != nullptr; }
  std::FILE* get() const { return f_; }

 private:
  std::FILE* f_;
};

/// Prints each diagnostic to stderr at once and counts them; one without a file (about the
/// run as a whole) gets the program name as its place.
class printing_sink : public diagnostic_sink {
 public:
  void report(diagnostic d) override;
  int errors() const { return counts_.errors; }
  int warnings() const { return counts_.warnings; }

 private:
  diagnostic_counts counts_;
};

}  // namespace twinpost::cli
