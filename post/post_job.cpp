#include "post/post_job.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <unistd.h>

#include "check/sync_check.hpp"
#include "formats/channel_writer.hpp"
#include "channels/job_channels.hpp"
#include "parser/job_scan.hpp"
#include "post/output_commit.hpp"
#include "post/output_names.hpp"
#include "formats/program_layout.hpp"
#include "post/sync_at_cl.hpp"
#include "formats/program_number.hpp"
#include "parser/cl_reader.hpp"
#include "support/ascii.hpp"
#include "support/errors.hpp"
#include "support/file_reader.hpp"

namespace fs = std::filesystem;

namespace twinpost {

namespace {

constexpr std::size_t progress_every = 1 << 16;  // events between progress calls

// Counts what passes through, so the run knows whether it failed.
class counting_sink : public diagnostic_sink {
 public:
  explicit counting_sink(diagnostic_sink& next) : next_(next) {}
  void report(diagnostic d) override {
    counts.add(d);
    // Router and writer diagnostics come while their record is the reader's current one.
    if (reader && d.column > 0 && d.source_line.empty() && d.file == file)
      d.source_line = std::string(reader->source_line(d.line));
    next_.report(std::move(d));
  }
  diagnostic_counts counts;
  const cl_reader* reader = nullptr;
  std::string file;

 private:
  diagnostic_sink& next_;
};

// Routes events to the channel writers; job-level events set the name and units.
class writers_sink : public channel_sink {
 public:
  std::vector<std::unique_ptr<channel_writer>> writers;  // index = channel - 1
  std::string partno;
  const machine* m = nullptr;
  diagnostic_sink* diags = nullptr;
  std::string file;
  void on_event(int ch, const event& e, bool both) override {
    if (ch == 0) {
      if (const auto* t = std::get_if<text_event>(&e.data)) {
        if (partno.empty()) {
          partno = t->text;
          if (m && diags) warn_program_number(*m, *diags, file, e, safe_file_stem(partno));
        }
      }
      if (const auto* u = std::get_if<units_event>(&e.data))
        for (auto& w : writers) w->set_units(u->units);
      return;
    }
    writers[static_cast<std::size_t>(ch - 1)]->on_event(e, both);
  }
  void on_wait(int ch, const wait_mark& w) override { writers[static_cast<std::size_t>(ch - 1)]->on_wait(w); }
};

// The job is read twice (the scan, then the reader): it must be a regular file, which a
// pipe, a FIFO, a folder or /dev/null is not.
file_ptr open_job(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);  // a FIFO must not block
  if (fd < 0) throw config_error(fmt::format("cannot read '{}': {}", path, std::strerror(errno)));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw config_error(fmt::format(
        "'{}' is not a regular file (a pipe, FIFO, folder or device): post reads the job "
        "twice, give it a file",
        path));
  }
  std::FILE* f = ::fdopen(fd, "rb");
  if (!f) {
    ::close(fd);
    throw config_error(fmt::format("cannot read '{}'", path));
  }
  return {f, &std::fclose};
}

}  // namespace

std::string safe_file_stem(std::string_view partno) {
  std::string s;
  for (char c : partno) {
    bool ok = ascii::is_alnum(c) || c == '_' || c == '-';
    s += ok ? c : '_';
    if (s.size() == 32) break;
  }
  while (!s.empty() && (s.back() == '_' || s.back() == '-')) s.pop_back();
  std::size_t lead = 0;
  while (lead < s.size() && (s[lead] == '_' || s[lead] == '-')) ++lead;
  s.erase(0, lead);
  return s.empty() ? "PROGRAM" : s;
}

post_summary post_job(const post_options& o, const machine& m, diagnostic_sink& diags) {
  post_summary sum;
  counting_sink sink(diags);
  file_ptr in = open_job(o.cl_path);
  // Everything is written into a stage inside the output folder and committed as a set.
  output_stage stage(o.out_dir);

  // One quick pass over the text before posting: does the job carry sync records, and which
  // channels does it use (a sync naming no channels means those)? A one-channel machine has
  // nothing to wait for: no pass (a long 5-axis job is read once), and a sync record in its
  // job is an error under the explicit policy (no partner channel).
  const bool one_channel = m.channels.size() == 1;
  const job_scan scan = one_channel ? job_scan{} : scan_job(o.cl_path);
  sum.policy = o.policy;
  if (o.policy == sync_policy::automatic) {
    sum.policy = one_channel || scan.explicit_sync ? sync_policy::explicit_marks : sync_policy::sequential;
    if (sum.policy == sync_policy::sequential && m.channels.size() > 1) {
      diagnostic d;
      d.level = severity::warning;
      d.file = o.cl_path;
      d.message = "no sync records in the job: channels wait for each other at every head switch "
                  "(sequential); concurrent machining needs SYNC/SYNCTR records";
      sink.report(std::move(d));
    }
  }

  // Each channel writes straight into its program file where its blocks open one (the
  // name from PARTNO as known by then); the others of a merged program spill to a body file.
  writers_sink ws;
  ws.m = &m;
  ws.diags = &sink;
  ws.file = o.cl_path;
  frame_request req;
  req.machine_def = &m;
  req.layout = o.layout.value_or(m.layout);
  req.tmp_dir = stage.dir();
  req.out_dir = o.out_dir;
  auto request_now = [&req, &ws] {
    frame_request r = req;
    r.name = safe_file_stem(ws.partno);
    return r;
  };
  for (const channel_def& ch : m.channels) {
    const channel_target target = frame_target(req, ch);
    block_writer::framing frame;
    if (target.direct) {
      frame.head = [&request_now, &ch] { return frame_head(request_now(), ch); };
      frame.tail = [&request_now, &ch] { return frame_tail(request_now(), ch); };
    }
    frame.name = [&request_now, &ch, &o] { return (fs::path(o.out_dir) / frame_file_name(request_now(), ch)).string(); };
    ws.writers.push_back(std::make_unique<channel_writer>(m, ch, target.path, sink, o.cl_path, std::move(frame)));
  }
  channel_router router(m, sum.policy, ws, sink, o.cl_path, used_channels(scan, m));
  cl_reader_options ro;
  ro.file_name = o.cl_path;
  ro.forced = o.forced_dialect;
  ro.posting = true;
  file_source src(in.get());
  cl_reader reader(src, ro, sink);
  sink.reader = &reader;
  sink.file = o.cl_path;
  int last_line = 0;
  std::size_t until_progress = progress_every;
  long statements = 0;  // records other than comments
  while (const event* e = reader.next()) {
    last_line = e->line;
    if (!std::holds_alternative<comment_event>(e->data)) ++statements;
    router.route(*e);
    if (--until_progress == 0) {
      until_progress = progress_every;
      if (o.progress) o.progress(reader.bytes());
    }
  }
  router.finish(last_line);
  for (auto& w : ws.writers) w->finish();
  sum.records = static_cast<long>(reader.records());
  sum.channels = static_cast<int>(m.channels.size());
  sum.waits = router.rendezvous();
  for (auto& w : ws.writers) sum.blocks += w->blocks();
  if (statements == 0) {
    diagnostic d;
    d.file = o.cl_path;
    d.message = "the job has no CL records (only comments or nothing)";
    sink.report(std::move(d));
  }
  if (sink.counts.errors > 0) return sum;

  req.name = safe_file_stem(ws.partno);
  std::vector<std::string> heads;
  for (auto& w : ws.writers) heads.push_back(w->head_written());
  std::vector<framed_file> files = finish_frames(req, heads);
  check_output_names(req, files);

  // The same check as `twinpost check`, on the files exactly as they will be written.
  std::vector<nc_source> sources;
  for (const framed_file& f : files) sources.push_back({(fs::path(o.out_dir) / f.name).string(), {}, f.tmp_path});
  sync_result check = check_nc_files(sources, m);
  if (!check.diagnostics.empty()) {
    std::vector<std::vector<int>> wait_lines;
    for (auto& w : ws.writers) wait_lines.push_back(w->wait_cl_lines());
    for (diagnostic& d : sync_diagnostics_at_cl(check.diagnostics, sources, m, o.cl_path, wait_lines, last_line))
      sink.report(std::move(d));
  }
  if (!check.ok) return sum;

  std::vector<staged_file> staged;
  for (const framed_file& f : files) staged.push_back({f.tmp_path, f.name});
  sum.files = stage.commit(staged);
  sum.ok = true;
  return sum;
}

}  // namespace twinpost

