#pragma once
// Checked reading of the TOML tables of a machine definition. Every read checks the type,
// every table rejects keys it does not know, and every error is a config_error carrying
// the file, line and column of the offending node. Internal to machines/: toml++ types
// appear here, so nothing outside machines/ includes this header.
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "machines/name_template.hpp"
#include "support/errors.hpp"

namespace twinpost {
struct machine;
struct spindle_def;
struct cycle_rules;
struct c_axis_codes;
struct channel_def;
}  // namespace twinpost

namespace twinpost::detail {

/// Throws config_error "SOURCE:LINE:COL: error: MESSAGE" for the start of `where`.
[[noreturn]] void fail_at(std::string_view source, const toml::source_region& where,
                          std::string_view message);

/// "an integer", "a string", ... for messages about a node of type `t`.
std::string_view type_phrase(toml::node_type t);

/// Reads the keys of one table; `path` names the table in messages ("waits", "channel.axis",
/// "" for the document root).
class table_reader {
 public:
  /// Throws for the first key of `t` (in file order) that is not in `known`.
  table_reader(const toml::table& t, std::string path, std::string_view source,
               std::initializer_list<std::string_view> known);

  /// The value of `key`, or nullptr.
  const toml::node* find(std::string_view key) const;
  /// "waits.first" for key "first" of table "waits".
  std::string key_path(std::string_view key) const;
  /// The table itself (its position is where a missing key is reported).
  const toml::table& table() const { return table_; }
  std::string_view source() const { return source_; }

  /// Throws `message` at node `n`.
  [[noreturn]] void fail(const toml::node& n, std::string_view message) const;
  /// Throws `message` at this table.
  [[noreturn]] void fail_here(std::string_view message) const;
  /// Throws "PATH.KEY is required" at this table when `key` is absent.
  void require(std::string_view key) const;

  // Each read leaves `out` untouched and returns false when the key is absent.
  bool read(std::string_view key, std::string& out) const;
  bool read(std::string_view key, int& out) const;
  bool read(std::string_view key, double& out) const;  ///< integers are accepted too
  bool read(std::string_view key, bool& out) const;
  bool read(std::string_view key, std::optional<int>& out) const;
  bool read(std::string_view key, std::optional<double>& out) const;
  bool read(std::string_view key, std::vector<int>& out) const;
  bool read(std::string_view key, std::vector<std::string>& out) const;
  /// A string of exactly one character; `letter` also demands an upper-case letter A-Z.
  bool read_char(std::string_view key, char& out, bool letter) const;
  /// A string that is a format template, checked by formatting it with sample values and
  /// against the placeholders `known` where it is used (machines/name_template.hpp).
  bool read_template(std::string_view key, std::string& out, placeholder_set known) const;
  /// An array of format templates, each checked.
  bool read_templates(std::string_view key, std::vector<std::string>& out, placeholder_set known) const;
  /// A template that is given no placeholder (a fixed block such as codes.home), checked
  /// and stored formatted, so that `{{` is written as the `{` it means.
  bool read_fixed(std::string_view key, std::string& out) const;
  bool read_fixed(std::string_view key, std::vector<std::string>& out) const;

  /// The sub-table `key`, or nullptr when absent.
  const toml::table* sub_table(std::string_view key) const;
  /// The tables of array `key` ([[key]]), in file order; empty when absent.
  std::vector<const toml::table*> tables(std::string_view key) const;

 private:
  [[noreturn]] void wrong_type(std::string_view key, const toml::node& n, std::string_view wanted) const;
  int to_int(std::string_view key, const toml::node& n) const;
  void check_template(std::string_view key, const toml::node& n, placeholder_set known) const;

  const toml::table& table_;
  std::string path_;
  std::string_view source_;
};

/// Reads every [[channel]] with its [[channel.axis]] into `m` (after the spindles, which
/// channels name), checks numbers and heads across channels, and sorts them by number.
/// Lives in machine_channels.cpp.
void read_channels(const table_reader& root, machine& m);

/// Reads `key` into `out` and fails at it unless it is one of `allowed` (machine_cycles.cpp).
void read_choice(const table_reader& r, std::string_view key, std::string& out,
                 std::initializer_list<std::string_view> allowed);
/// Reads [cycles] (machine_cycles.cpp): the kinds and codes of drilling and tapping cycles.
void read_cycles(const table_reader& root, cycle_rules& c);

/// Reads [timing] and its [timing.channel.N] overrides into every channel of `m` (after the
/// channels). Lives in machine_timing.cpp.
void read_timing(const table_reader& root, machine& m);
/// Reads [events] and its [[events.record]] (machine_events.cpp).
void read_events(const table_reader& root, machine& m);
/// Reads every [[kinematics]] chain (machine_kinematics.cpp), after the channels.
void read_kinematics(const table_reader& root, machine& m);

// Mill/turn (machine_milling.cpp, machines/millturn_rules.hpp).
/// A [[spindle]]'s c_on, c_off, c_clamp and c_unclamp.
void read_c_axis(const table_reader& spindle, c_axis_codes& c);
/// Holds a spindle's c_* blocks to every spindle's M-codes: M35 cannot both hold the spindle as C
/// and stop the live tool (the checker, too, reads each code one way).
void check_c_axis_codes(const table_reader& spindle, const c_axis_codes& c,
                        const std::vector<spindle_def>& all);
/// A [[channel]]'s [channel.head_index], after its axes.
void read_head_index(const table_reader& channel, channel_def& c);
/// [milling], after [limits].
void read_milling(const table_reader& root, machine& m);

/// Throws at the first value of the file (in file order) that names a wait code of `m`
/// outside [waits]: spindle codes, [codes], program blocks, tool calls; a default the file
/// leaves in place is reported at the table that omits it (machines/code_overlap.hpp).
/// Lives in code_overlap.cpp.
void check_code_overlaps(const table_reader& root, const machine& m);

}  // namespace twinpost::detail
