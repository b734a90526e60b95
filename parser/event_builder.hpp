#pragma once
// Dialect knowledge: turns CL records into typed events, one record at a time. Keeps the
// little state the records need: position, modal tool axis, one-shot RAPID, a pending
// CIRCLE waiting for its end point, units, ICAM marker numbers.
#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "parser/detail/build_issue.hpp"
#include "parser/dialect.hpp"
#include "parser/event_queue.hpp"
#include "parser/events.hpp"
#include "parser/record.hpp"
#include "parser/record_policy.hpp"

namespace twinpost {

class event_builder {
 public:
  explicit event_builder(dialect d) : dialect_(d) {}
  /// Reading for a post: a record that cannot be posted (an unknown major word) is an error
  /// and makes no event; otherwise it is a passthrough event with a warning.
  void set_posting(bool on) { posting_ = on; }
  /// A permissive post: an unknown major word is a warning, not an error. A known word the
  /// post refuses (parser/record_table.cpp) stays an error.
  void set_permissive(bool on) { permissive_ = on; }
  /// Major words (upper case) that the machine file turns into blocks ([[events.record]]): such a
  /// word the post does not know is a passthrough event with `user` set, not an error.
  void set_user_records(std::vector<std::string> words) { user_records_ = std::move(words); }
  /// The machine's script: `words` (upper case) go to its on_record in place of the post's
  /// own events; with `unknown`, so does every unknown word (cl_reader_options).
  void set_script_records(std::vector<std::string> words, bool unknown) {
    script_records_ = std::move(words);
    unknown_to_script_ = unknown;
    any_script_records_ = !script_records_.empty();
  }
  /// The column of the next record's major word, for messages about it that come later.
  void set_column(int column) { column_ = column; }

  /// Appends the events of record `r` (from physical line `line`) to `out`.
  void build(const cl_record& r, int line, event_queue& out, build_issues& issues);
  /// build() for a GOTO of three or six numbers, most records of a long job: the same event
  /// and the same state, without the look-up of its handler. False, with nothing done, for
  /// any other record, and for every record when a script takes records (build() then).
  bool build_goto(const cl_record& r, int line, event_queue& out);
  /// build_goto for a GOTO read straight into its numbers (parse_goto_statement): `count` is 3
  /// or 6. False, with nothing done, when a script takes records.
  bool build_goto(const double* numbers, std::size_t count, int line, event_queue& out);
  /// Notes a record that could not be parsed (already reported; `seen` is what it looked
  /// like). It ends a GOTO, and the coordinate lines right after it are dropped without
  /// further errors; a bad coordinate line inside a GOTO leaves the GOTO going.
  void skip_record(record_kind seen);
  /// Reports what the end of input leaves open (a CIRCLE with no end point).
  void finish(build_issues& issues);

 private:
  struct pending_circle {
    vec3 center;
    vec3 normal{0, 0, 1};
    std::optional<double> radius;
    std::optional<bool> ccw;  // explicit CLOCKWISE / COUNTERCLOCKWISE word
    int turns = 0;            // NX TIMES,n: full turns
    int line = 0;
    int column = 0;  // of the CIRCLE word, for a message after its record is gone
  };

  void statement(const cl_record& r, int line, event_queue& out, build_issues& issues);

  friend std::span<const record_rule> record_rules();

  // One handler per major word, in the record policy's table (parser/record_table.cpp):
  // statement() finds it in the sorted table, without allocating, and `other` takes every
  // word the table lacks. Text records (PARTNO, INSERT, ...) are found in it too.
  using statement_handler = void (event_builder::*)(const cl_record&, int, event_queue&, build_issues&);
  struct rule_row {
    record_rule rule;
    statement_handler handler;
  };
  struct rule_index;
  static const rule_index& rules();
  static statement_handler handler_of(std::string_view major);
  /// The row of the table that `r` falls under; nullptr for a word not in it.
  static const rule_row* rule_of(const cl_record& r);
  /// The handler of the last major word as written (a long job repeats GOTO): a hit costs a
  /// length test and one compare of at most 8 bytes instead of the table's case-blind search.
  struct handler_cache {
    std::array<char, 8> word{};
    std::size_t size = 0;
    statement_handler handler = nullptr;
  };
  handler_cache last_handler_;
  std::vector<std::string> user_records_;
  std::vector<std::string> script_records_;
  bool unknown_to_script_ = false;
  bool any_script_records_ = false;  ///< one flag test per record (no script: false)
  /// True (and the record is out as a `user` passthrough) when the script takes `r` over.
  bool to_script(const cl_record& r, int line, event_queue& out);
  template <motion_kind K>
  void on_motion(const cl_record& r, int line, event_queue& out, build_issues& issues) {
    motion(r, K, line, out, issues);
  }
  template <tool_source S>
  void on_tool(const cl_record& r, int line, event_queue& out, build_issues& issues);
  template <bool Prefun>
  void on_aux(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_rapid(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_spindl(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_fedrat(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_coolnt(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_cutcom(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_cycle(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_delay(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_thread(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_load_tool(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_tool_data(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_units(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_machin(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_multax(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_coordsys(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_tlaxis(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_head(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_channel(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_sync(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_synctr(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_stop(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_transfer(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_end(const cl_record& r, int line, event_queue& out, build_issues& issues);
  template <text_kind K>
  void on_text(const cl_record& r, int line, event_queue& out, build_issues& issues);
  void on_insert(const cl_record& r, int line, event_queue& out, build_issues& issues);
  /// A word with rows for given minor words (SET/MODE,ABSOL): the handler of the row that
  /// matches.
  void by_args(const cl_record& r, int line, event_queue& out, build_issues& issues);
  /// A word the policy ignores: a passthrough event, no block.
  void on_ignored(const cl_record& r, int line, event_queue& out, build_issues& issues);
  /// A word the policy refuses: an error naming it in a post, a passthrough event otherwise.
  void on_refused(const cl_record& r, int line, event_queue& out, build_issues& issues);
  /// A word not in the table: an error in a post (a warning in a permissive one), a
  /// passthrough event with a warning otherwise.
  void other(const cl_record& r, int line, event_queue& out, build_issues& issues);

  void comment(const cl_record& r, int line, event_queue& out);
  void motion(const cl_record& r, motion_kind kind, int line, event_queue& out, build_issues& issues);
  /// The record's numbers, in a vector reused from record to record (no allocation per GOTO);
  /// valid until the next call. Inline: it is asked once per GOTO.
  std::span<const double> numbers(const cl_record& r) {
    // Sized once, then written through a pointer: no capacity check per number.
    if (numbers_.size() < r.args.size()) numbers_.resize(r.args.size());
    double* p = numbers_.data();
    if (r.numbers_only) {
      for (const cl_arg& a : r.args) *p++ = a.number;
    } else {
      for (const cl_arg& a : r.args)
        if (a.kind == arg_kind::number) *p++ = a.number;
    }
    return {numbers_.data(), static_cast<std::size_t>(p - numbers_.data())};
  }
  void point(std::span<const double> n, bool continued, motion_kind kind, int line, event_queue& out);
  void circle(const cl_record& r, int line, event_queue& out, build_issues& issues);
  /// Inline: every statement ends the motion record before it.
  void end_of_motion_record() {
    in_goto_ = false;
    rapid_record_ = false;
    if (circle_used_) circle_.reset(), circle_used_ = false;
  }

  dialect dialect_;
  unit_system units_ = unit_system::mm;
  vec3 pos_;
  std::optional<vec3> axis_;
  bool rapid_ = false;         // RAPID seen, waiting for its move
  bool rapid_record_ = false;  // the current GOTO record is rapid (its coordinate lines too)
  bool posting_ = false;
  bool permissive_ = false;
  int column_ = 0;
  bool in_goto_ = false;           // the last statement was a GOTO: coordinate lines continue it
  bool after_bad_record_ = false;  // the last record (comments aside) did not parse
  std::vector<double> numbers_;    // scratch for numbers()
  std::optional<pending_circle> circle_;
  bool circle_used_ = false;  // the pending circle has had its GOTO
  int catia_rows_ = -1;       // >= 0 while reading the `$$*CATIA0` matrix rows
  std::vector<double> catia_matrix_;
  int catia_line_ = 0;
};

}  // namespace twinpost
