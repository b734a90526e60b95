#include "parser/cl_reader.hpp"

#include <vector>

#include "parser/event_builder.hpp"
#include "parser/record_parser.hpp"

namespace twinpost {

struct cl_reader::impl {
  impl(byte_source& src, cl_reader_options o, diagnostic_sink& s)
      : lines(src, o.chunk_size), options(std::move(o)), sink(s),
        d(options.forced ? *options.forced : detect_dialect(lines.peek(64 * 1024))), builder(d) {}

  void report(const build_issue& i) {
    diagnostic d_;
    d_.level = i.level;
    d_.file = options.file_name;
    d_.message = i.message;
    if (i.line > 0) {
      d_.line = i.line;
    } else {
      source_position p = lines.locate(i.offset);
      d_.line = p.line;
      d_.column = p.column;
      d_.source_line = std::string(p.source_line);
    }
    sink.report(std::move(d_));
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
        }
        return false;
      }
      ++record_count;
      record_error err;
      if (!parse_record(lr.text, rec, err)) {
        report(build_issue{severity::error, err.offset, err.message});
        builder.skip_record(rec.kind);
        continue;
      }
      issues.clear();
      builder.build(rec, lr.line, queue, issues);
      for (const build_issue& i : issues) report(i);
    }
    return true;
  }

  line_reader lines;
  cl_reader_options options;
  diagnostic_sink& sink;
  dialect d;
  event_builder builder;
  cl_record rec;
  build_issues issues;
  event_queue queue;
  std::size_t head = 0;
  std::size_t record_count = 0;
  bool finished = false;
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
std::size_t cl_reader::records() const { return impl_->record_count; }
std::size_t cl_reader::bytes() const { return impl_->lines.bytes_read(); }

}  // namespace twinpost
