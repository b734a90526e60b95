#include "parser/cl_reader.hpp"

#include <algorithm>
#include <cstring>
#include <vector>

#include <fmt/format.h>

#include "parser/event_builder.hpp"
#include "parser/record_parser.hpp"
#include "support/ascii.hpp"

namespace twinpost {

struct cl_reader::impl {
  impl(byte_source& src, cl_reader_options o, diagnostic_sink& s)
      : lines(src, o.chunk_size), options(std::move(o)), sink(s),
        d(options.forced ? *options.forced : detect_dialect(lines.peek(64 * 1024))), builder(d) {
    builder.set_posting(options.posting);
    builder.set_permissive(options.permissive);
    builder.set_user_records(options.user_records);
    builder.set_script_records(options.script_records, options.unknown_to_script);
  }

  void report(const build_issue& i) {
    diagnostic d_;
    d_.level = i.level;
    d_.file = options.file_name;
    d_.message = i.message;
    if (i.line > 0) {
      d_.line = i.line;
      d_.column = i.column;
    } else {
      source_position p = lines.locate(i.offset);
      d_.line = p.line;
      d_.column = p.column;
      d_.source_line = std::string(p.source_line);
    }
    sink.report(std::move(d_));
  }

  // Remembers the last record read (not a comment): whether it ends the job, and where it is.
  void note_record(int line) {
    // Only FINI, END..., and PPRINT can end a job: one look at the first letter for the rest.
    const char c = rec.major.empty() ? '\0' : ascii::upper(rec.major.front());
    ended = (c == 'F' || c == 'E' || c == 'P') && ends_job(rec);
    last_line = line;
    last_column =
        lines.column_of(rec.kind == record_kind::coordinates && !rec.args.empty() ? rec.args.front().offset
                                                                                  : rec.major_offset);
    // Kept in a fixed buffer: a string assignment per record shows in the benchmark.
    last_major_size =
        rec.kind == record_kind::coordinates ? 0 : std::min(rec.major.size(), sizeof last_major);
    std::copy_n(rec.major.data(), last_major_size, last_major);  // not memcpy: major may be null when empty
  }

  // note_record for a GOTO read by parse_goto_statement.
  void note_goto(int line) {
    ended = false;
    last_line = line;
    last_column = lines.column_of(go.major_offset);
    last_major_size = go.major.size();
    std::copy_n(go.major.data(), last_major_size, last_major);
  }

  static bool ends_job(const cl_record& r) {
    if (r.kind == record_kind::statement)
      return word_is(r.major, "FINI") || word_is(r.major, "END") || word_is(r.major, "END-OF-PATH");
    // Makino-style CL closes with its process section instead of FINI.
    return r.kind == record_kind::text && word_is(r.major, "PPRINT") &&
           r.text.starts_with("END-SECTION,PROCESS-END-PATH");
  }

  void report_missing_end() {
    diagnostic d;
    d.level = severity::warning;
    d.file = options.file_name;
    if (last_line == 0) {
      d.message = "the job has no records";
    } else {
      d.line = last_line;
      d.column = last_column;
      const std::string major = last_major_size == 0
                                    ? std::string("coordinate line")
                                    : ascii::upper_copy(std::string_view(last_major, last_major_size));
      d.message =
          fmt::format("the job ends without FINI or END after this {} record: is the file cut off?", major);
    }
    sink.report(std::move(d));
  }

  void report_line_problem(const logical_record& lr) {
    diagnostic d;
    d.file = options.file_name;
    d.line = lr.problem_line;
    d.column = lr.problem_column;
    d.source_line = std::string(lr.problem_source);
    d.message =
        lr.problem == record_problem::dangling
            ? std::string(
                  "the file ends in a continued record ('$' at the end of the last line): the job is cut off")
            : fmt::format("record longer than {} bytes: not CL data (a line without a newline?); skipped",
                          max_record_bytes);
    sink.report(std::move(d));
  }

  // Reads records until one yields events (or the input ends).
  bool refill() {
    queue.clear();
    head = 0;
    logical_record lr;
    while (queue.empty()) {
      if (!lines.next(lr)) {
        if (!finished) {
          finished = true;
          issues.clear();
          builder.finish(issues);
          for (const build_issue& i : issues) report(i);
          if (options.posting && !ended) report_missing_end();
        }
        return false;
      }
      ++record_count;
      if (lr.problem != record_problem::none) [[unlikely]] {
        report_line_problem(lr);
        builder.skip_record(record_kind::statement);
        ended = false;
        continue;
      }
      // The commonest record, a GOTO of three or six numbers, straight from its text into its
      // event: the same event, state and notes as parse_record and build() below make.
      if (parser_detail::parse_goto_statement(lr.text, go)) {
        note_goto(lr.line);
        builder.set_column(last_column);
        const std::size_t before = queue.size();
        if (builder.build_goto(go.numbers, go.count, lr.line, queue)) {
          for (std::size_t k = before; k < queue.size(); ++k)
            queue[k].column = queue[k].line == lr.line ? last_column : 0;
          continue;
        }
      }
      if (!parse_record(lr.text, rec, err)) {
        report(build_issue{severity::error, err.offset, err.message});
        builder.skip_record(rec.kind);
        ended = false;
        continue;
      }
      if (rec.kind != record_kind::comment) note_record(lr.line);
      builder.set_column(last_column);
      issues.clear();
      const std::size_t before = queue.size();
      if (!builder.build_goto(rec, lr.line, queue)) builder.build(rec, lr.line, queue, issues);
      for (const build_issue& i : issues) report(i);
      if (queue.size() > before) {
        // Later stages (router, writers) report at the record's major word.
        const int column = rec.kind == record_kind::comment ? 0 : last_column;
        for (std::size_t k = before; k < queue.size(); ++k)
          queue[k].column = queue[k].line == lr.line ? column : 0;
      }
    }
    return true;
  }

  line_reader lines;
  cl_reader_options options;
  diagnostic_sink& sink;
  dialect d;
  event_builder builder;
  cl_record rec;
  parser_detail::goto_statement go;
  record_error err;  // kept: a string made and dropped per record shows in the benchmark
  build_issues issues;
  event_queue queue;
  std::size_t head = 0;
  std::size_t record_count = 0;
  bool finished = false;
  bool ended = false;  // the last record read was FINI/END (or a dialect's end)
  int last_line = 0, last_column = 0;
  char last_major[32];  // of the last record read, for the missing-end warning
  std::size_t last_major_size = 0;
};

cl_reader::cl_reader(byte_source& src, cl_reader_options options, diagnostic_sink& sink)
    : impl_(std::make_unique<impl>(src, std::move(options), sink)) {}

cl_reader::~cl_reader() = default;

const event* cl_reader::next() {
  if (impl_->head >= impl_->queue.size() && !impl_->refill()) return nullptr;
  return &impl_->queue[impl_->head++];
}

bool cl_reader::next(event& out) {
  const event* e = next();
  if (!e) return false;
  out = *e;
  return true;
}

dialect cl_reader::current_dialect() const { return impl_->d; }
std::string_view cl_reader::source_line(int line) const { return impl_->lines.physical_line(line); }
std::size_t cl_reader::source_lines() const { return impl_->lines.physical_lines(); }
std::pair<int, std::string_view> cl_reader::source_line_at(std::size_t i) const {
  return impl_->lines.physical_line_at(i);
}
std::size_t cl_reader::records() const { return impl_->record_count; }
std::size_t cl_reader::bytes() const { return impl_->lines.bytes_read(); }

}  // namespace twinpost
