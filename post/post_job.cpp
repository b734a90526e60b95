#include "post/post_job.hpp"

#include <algorithm>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fcntl.h>
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>

#include "analysis/cl_compare.hpp"
#include "analysis/control_emulator.hpp"
#include "analysis/interference.hpp"
#include "analysis/shared_resources.hpp"
#include "analysis/timeline_report.hpp"
#include "channels/job_channels.hpp"
#include "check/sync_check.hpp"
#include "formats/program_layout.hpp"
#include "formats/program_number.hpp"
#include "machines/layout_rules.hpp"
#include "machining/channel_writer.hpp"
#include "parser/cl_reader.hpp"
#include "parser/job_scan.hpp"
#include "post/concurrent_check.hpp"
#include "post/output_commit.hpp"
#include "post/output_names.hpp"
#include "post/reader_thread.hpp"
#include "post/sync_at_cl.hpp"
#include "post/sync_optimise.hpp"
#include "post/user_records.hpp"
#include "support/ascii.hpp"
#include "support/errors.hpp"
#include "support/file_reader.hpp"

namespace fs = std::filesystem;

namespace twinpost {

namespace {

constexpr std::size_t progress_every = 1 << 16;  // events between progress calls

// The CL events: from the reader on this thread, or on a thread of its own a few batches
// ahead (post/reader_thread.hpp), which gives out the same events, diagnostics and lines.
class job_events {
 public:
  job_events(byte_source& src, cl_reader_options o, diagnostic_sink& sink, diagnostic_sink& as_is,
             bool threaded, kin_lookahead* ahead) {
    if (threaded)
      two_.emplace(src, std::move(o), as_is, ahead);
    else
      one_.emplace(src, std::move(o), sink);
  }
  const event* next() { return one_ ? one_->next() : two_->next(); }
  /// cl_reader::source_line, for the event returned last.
  std::string_view source_line(int line) const {
    return one_ ? one_->source_line(line) : two_->source_line(line);
  }
  std::size_t bytes() const { return one_ ? one_->bytes() : two_->bytes(); }
  std::size_t records() const { return one_ ? one_->records() : two_->records(); }

 private:
  std::optional<cl_reader> one_;
  std::optional<reader_thread> two_;
};

// Counts what passes through, so the run knows whether it failed.
class counting_sink : public diagnostic_sink {
 public:
  explicit counting_sink(diagnostic_sink& next) : next_(next) {}
  void report(diagnostic d) override {
    // Router and writer diagnostics come while their record is the reader's current one.
    if (reader && d.column > 0 && d.source_line.empty() && d.file == file)
      d.source_line = std::string(reader->source_line(d.line));
    pass(std::move(d));
  }
  /// Counted and passed on as it is (the reader thread's, whose lines are given already).
  void pass(diagnostic d) {
    counts.add(d);
    next_.report(std::move(d));
  }
  diagnostic_counts counts;
  const job_events* reader = nullptr;
  std::string file;

 private:
  diagnostic_sink& next_;
};

// counting_sink::pass as a sink.
class passing_sink : public diagnostic_sink {
 public:
  explicit passing_sink(counting_sink& to) : to_(to) {}
  void report(diagnostic d) override { to_.pass(std::move(d)); }

 private:
  counting_sink& to_;
};

// The comparison of a channel's program with its CL (analysis/cl_compare). Its findings are
// kept until the programs are written, then said channel by channel (report_comparisons),
// however the programs were read: on this thread, or on the self-check's.
struct channel_comparison {
  channel_comparison(const machine& m, const channel_def& ch, std::string cl_file)
      : cmp(m, ch, found, std::move(cl_file)) {}
  diagnostic_list found;
  cl_comparison cmp;
};

// The comparison shown what a writer writes, on this thread (one core, or a program the
// self-check does not read while it is written): it reads the lines itself.
class compared_writing : public write_observer {
 public:
  explicit compared_writing(cl_comparison& c) : cmp_(c) {}
  void line(std::string_view text) override { cmp_.line(text); }
  void units(unit_system u) override { cmp_.units(u); }
  void record(const event& e, bool both) override { cmp_.record(e, both); }

 private:
  cl_comparison& cmp_;
};

// The comparison made on the self-check's thread from its reading of the program: the writer's
// records are noted there with the number of lines written before each.
class noted_writing : public write_observer {
 public:
  noted_writing(concurrent_check& cc, channel_writer& w, int channel) : cc_(cc), w_(w), channel_(channel) {}
  bool wants_lines() const override { return false; }
  void line(std::string_view) override {}
  void units(unit_system u) override {
    if (cc_.note_units(channel_, w_.bytes_written(), u)) pass();
  }
  void record(const event& e, bool both) override {
    if (cc_.note_record(channel_, w_.bytes_written(), e, both)) pass();
  }

 private:
  // The bytes written so far go to the check with the records, or the records alone.
  void pass() {
    w_.pass_written();
    cc_.flush_records(channel_);
  }
  concurrent_check& cc_;
  channel_writer& w_;
  int channel_;
};

// Routes events to the channel writers; job-level events set the name and units.
class writers_sink : public channel_sink {
 public:
  std::vector<std::unique_ptr<channel_writer>> writers;          // index = channel - 1
  std::vector<std::unique_ptr<channel_comparison>> comparisons;  // likewise
  std::vector<std::unique_ptr<write_observer>> observers;        // likewise
  job_spindles spindles;                                         // the starts all writers note
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
    throw config_error(
        fmt::format("'{}' is not a regular file (a pipe, FIFO, folder or device): post reads the job "
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

// What a sync record that names no channels means, and whether the job has any: one quick
// pass over the text before posting. A one-channel machine has nothing to wait for: no
// pass (a long 5-axis job is read once), and a sync record in its job is an error under the
// explicit policy (no partner channel).
// The scan stops once its two answers cannot change (channels/job_channels' scan_settled).
job_scan scan_for_sync(const post_options& o, const machine& m) {
  if (m.channels.size() == 1) return {};
  const bool policy_given = o.policy != sync_policy::automatic;
  return scan_job(o.cl_path, [&](const job_scan& s) { return scan_settled(s, m, policy_given); });
}

// The policy `auto` stands for: the job's sync records if it has any; else, on a machine with
// [timing] whose job uses two to four channels, the waits placed for the shortest cycle (optimise,
// docs/wait-placement.md); else a rendezvous at every head switch (said in a warning, since the
// channels then never cut at once).
sync_policy choose_policy(const post_options& o, const machine& m, const job_scan& scan,
                          diagnostic_sink& sink) {
  if (o.policy != sync_policy::automatic) return o.policy;
  const bool one_channel = m.channels.size() == 1;
  if (one_channel || scan.explicit_sync) return sync_policy::explicit_marks;
  // A job that never leaves one head has no head switch to wait at: nothing to warn about.
  std::vector<int> heads = scan.heads;
  std::sort(heads.begin(), heads.end());
  heads.erase(std::unique(heads.begin(), heads.end()), heads.end());
  if (heads.size() + scan.head_words.size() + scan.channels.size() <= 1) return sync_policy::sequential;
  const std::size_t used = used_channels(scan, m).size();
  if (has_timing(m) && used >= 2 && used <= static_cast<std::size_t>(schedule_max_channels))
    return sync_policy::optimise;
  diagnostic d;
  d.level = severity::warning;
  d.file = o.cl_path;
  d.message = fmt::format(
      "no sync records in the job: channels wait for each other at every head switch (sequential), "
      "since {}; concurrent machining needs SYNC/SYNCTR records",
      !has_timing(m) ? fmt::format("machine '{}' has no [timing] table to place waits by", m.name)
                     : fmt::format("waits are placed between two to {} channels and the job uses {}",
                                   schedule_max_channels, used));
  sink.report(std::move(d));
  return sync_policy::sequential;
}

// The programs of this post: written into the stage, named for the output folder.
frame_request staged_request(const post_options& o, const machine& m, const std::string& stage_dir) {
  frame_request req;
  req.machine_def = &m;
  req.layout = o.layout.value_or(m.layout);
  req.tmp_dir = stage_dir;
  req.out_dir = o.out_dir;
  return req;
}

cl_reader_options posting_reader(const post_options& o, const machine& m,
                                 const scripting::lua_script* script) {
  cl_reader_options ro;
  for (const record_event& r : m.events.records) ro.user_records.push_back(r.major);
  if (script && script->has_on_record()) {
    ro.script_records = m.events.script_records;
    ro.unknown_to_script = true;
  }
  ro.file_name = o.cl_path;
  ro.forced = o.forced_dialect;
  ro.posting = true;
  ro.permissive = o.permissive;
  return ro;
}

// The frame request as far as the job has named the program (PARTNO, once it is read).
frame_request named_request(const frame_request& req, const writers_sink& ws) {
  frame_request r = req;
  r.name = safe_file_stem(ws.partno);
  return r;
}

// One writer per channel. Each writes straight into its program file where its blocks open
// one (the name from PARTNO as known by then); the others of a merged program spill their
// sections to a body file. The frames read `req` and `ws` when they are written: both outlive the writers.
void open_writers(const post_options& o, const machine& m, const frame_request& req, writers_sink& ws,
                  diagnostic_sink& sink) {
  for (const channel_def& ch : m.channels) {
    const channel_target target = frame_target(req, ch);
    block_writer::framing frame;
    frame.head = [&req, &ws, &ch](sequence_numbers& seq) {
      return frame_head(named_request(req, ws), ch, seq);
    };
    frame.tail = [&req, &ws, &ch](sequence_numbers& seq) {
      // Asked for when the channel's writer closes its file: it exists and knows its end.
      const channel_writer& w = *ws.writers[static_cast<std::size_t>(ch.number - 1)];
      return frame_tail(named_request(req, ws), ch, seq, w.footer_in_force());
    };
    frame.name = [&req, &ws, &ch, &o] {
      return (fs::path(o.out_dir) / frame_file_name(named_request(req, ws), ch)).string();
    };
    ws.writers.push_back(
        std::make_unique<channel_writer>(m, ch, target.path, sink, o.cl_path, std::move(frame)));
  }
  for (const channel_def& ch : m.channels) {
    std::optional<int> start;
    for (const auto& [channel, tool] : o.start_tools)
      if (channel == ch.number) start = tool;
    ws.writers[static_cast<std::size_t>(ch.number - 1)]->start_with(start, o.tool_kind);
    if (o.frame) ws.writers[static_cast<std::size_t>(ch.number - 1)]->write_in(*o.frame);
  }
  // Each channel's program held to its CL as it is written: a channel with a kinematic chain
  // through the forward transform of its words (its writer checks its own points that way too,
  // channel_multiaxis, before its blocks go out), a mill/turn head with an indexing head by the
  // tip at each index (its G68.2 frames passed over). Shown to it here, unless the self-check
  // reads the programs while they are written (compare_during).
  for (const channel_def& ch : m.channels) {
    ws.comparisons.push_back(std::make_unique<channel_comparison>(m, ch, o.cl_path));
    ws.observers.push_back(std::make_unique<compared_writing>(ws.comparisons.back()->cmp));
    ws.writers[static_cast<std::size_t>(ch.number - 1)]->set_observer(ws.observers.back().get());
  }
  ws.spindles.started.assign(m.spindles.size(), std::vector<char>(m.channels.size(), 0));
  for (auto& w : ws.writers) w->share_spindles(&ws.spindles);
  // Under HEAD/BOTH the channel of head 1 commands the spindle; the other's copy follows it.
  if (const channel_def* master = m.channel_for_head(1))
    for (auto& w : ws.writers)
      w->set_balance_master(ws.writers[static_cast<std::size_t>(master->number - 1)].get());
}

// The threads the post may use (post_options::threads).
int threads(const post_options& o) {
  return o.threads > 0 ? o.threads : std::thread::hardware_concurrency() >= 2 ? 2 : 1;
}

// Whether channel `ch`'s comparison with the CL is made on the self-check's thread, from its
// reading. Where that reading splits every block of the channel anyway — for the cycle time
// (`timed`: every block), the interference rule (a channel with an envelope) or the emulator's
// rotary sweep (a chain with a head) — the comparison shares the split. A channel with a
// kinematic chain that turns (a table's too) goes there as well: its comparison follows the
// chain through every block (the rotary words, the forward transform at each record), most of
// the writer's thread on a 5-axis job, while the check's thread has little else to do there
// (docs/benchmark.md, thirty-seventh session: mill5-tcp's post thread 538 M instructions, the
// check's 70 M). Another channel's comparison stays with its writer: handing the records over (a
// copy of each, its lines counted, the pieces passed more often) cost more than the split it
// would share (thirty-sixth session: the 3-axis mill's job 7 % more CPU on the check's thread).
bool compared_on_check(const machine& m, const channel_def& ch, bool timed) {
  const kinematic_chain* chain = m.chain(ch.number);
  return timed || (interference_checked(m) && m.interference.channel(ch.number) != nullptr) ||
         sweeps_chain(m, ch.number) || (chain && !chain->rotaries.empty());
}

// The comparisons made on the self-check's thread, from its reading (by channel; null: made on
// this thread, compared_on_check).
std::vector<cl_comparison*> compared_during(const machine& m, writers_sink& ws, bool timed) {
  std::vector<cl_comparison*> out;
  for (std::size_t i = 0; i < ws.comparisons.size(); ++i)
    out.push_back(compared_on_check(m, m.channels[i], timed) ? &ws.comparisons[i]->cmp : nullptr);
  return out;
}

// Each writer whose comparison is made on the self-check's thread notes its records there
// instead of showing its lines here.
void note_during(writers_sink& ws, concurrent_check& cc, const std::vector<cl_comparison*>& during) {
  for (std::size_t i = 0; i < ws.writers.size(); ++i) {
    if (!during[i]) continue;
    ws.observers[i] = std::make_unique<noted_writing>(cc, *ws.writers[i], static_cast<int>(i) + 1);
    ws.writers[i]->set_observer(ws.observers[i].get());
  }
}

// The comparisons' findings, channel by channel, at their CL records (with the CL's lines),
// once the programs are written; `during`: the self-check that made them, waited for.
void report_comparisons(const post_options& o, writers_sink& ws, concurrent_check* during,
                        diagnostic_sink& sink) {
  std::string why;
  if (during && !during->drain(&why))
    sink.report({severity::error,
                 o.cl_path,
                 0,
                 0,
                 fmt::format("the programs could not be compared with the CL to their end: {}", why),
                 {}});
  std::vector<diagnostic> found;
  for (auto& c : ws.comparisons)
    for (const diagnostic& d : c->found.all()) found.push_back(d);
  fill_cl_lines(found, o.cl_path);
  for (diagnostic& d : found) sink.report(std::move(d));
}

// Every piece each writer writes goes through the concurrent check, which reads it and then
// writes it; the program is named as the frame names it.
void relay_writers(const post_options& o, const frame_request& req, writers_sink& ws, concurrent_check& cc) {
  for (std::size_t i = 0; i < ws.writers.size(); ++i) {
    const channel_def& ch = ws.m->channels[i];
    ws.writers[i]->set_relay(cc.relay_for(ch.number, [&o, &req, &ws, &ch] {
      return (fs::path(o.out_dir) / frame_file_name(named_request(req, ws), ch)).string();
    }));
  }
}

struct stream_totals {
  int last_line = 0;    // of the last event
  long statements = 0;  // records other than comments
};

// The one pass that posts: every event of the job through the router to the writers.
stream_totals stream_job(const post_options& o, job_events& reader, channel_router& router) {
  stream_totals t;
  std::size_t until_progress = progress_every;
  while (const event* e = reader.next()) {
    t.last_line = e->line;
    if (!std::holds_alternative<comment_event>(e->data)) ++t.statements;
    router.route(*e);
    if (--until_progress == 0) {
      until_progress = progress_every;
      if (o.progress) o.progress(reader.bytes());
    }
  }
  return t;
}

void report_empty_job(const post_options& o, diagnostic_sink& sink) {
  diagnostic d;
  d.file = o.cl_path;
  d.message = "the job has no CL records (only comments or nothing)";
  sink.report(std::move(d));
}

// The staged programs framed under their final names, which must be safe and distinct.
std::vector<framed_file> frame_files(const frame_request& named, const writers_sink& ws) {
  std::vector<std::string> heads;
  for (auto& w : ws.writers) heads.push_back(w->head_written());
  std::vector<framed_file> files = finish_frames(named, heads);
  check_output_names(named, files);
  return files;
}

// The staged programs as NC inputs, named as they will be written.
std::vector<nc_source> staged_sources(const post_options& o, const std::vector<framed_file>& files) {
  std::vector<nc_source> sources;
  for (const framed_file& f : files)
    sources.push_back({(fs::path(o.out_dir) / f.name).string(), {}, f.tmp_path});
  return sources;
}

// The same check as `twinpost check`, on the files exactly as they will be written; what it
// finds is reported at the CL record that made the wait. True when they are sound.
// `feed`, when given, is fed the same reading (the cycle time, without a read of its own).
// `done`: the check made while the files were written (post/concurrent_check.hpp), which
// then stands for it.
bool self_check(const post_options& o, const machine& m, const std::vector<framed_file>& files,
                const writers_sink& ws, int last_line, diagnostic_sink& sink, timeline_feed* feed,
                std::optional<sync_result> done, std::vector<std::uint64_t>& rendezvous) {
  const std::vector<nc_source> sources = staged_sources(o, files);
  sync_result check = done ? std::move(*done) : check_nc_resources(sources, m, {}, feed);
  if (!check.diagnostics.empty()) {
    fill_source_lines(check.diagnostics, sources, m);  // the interference rule's (done: not yet)
    std::vector<std::vector<int>> wait_lines;
    std::vector<std::vector<cl_block>> blocks;
    std::vector<cl_block_index> block_lines;  // the interference rule's (channel_writer::block_cl_line)
    for (auto& w : ws.writers) {
      const channel_writer* writer = w.get();
      block_lines.push_back({writer->block_cl_count(),
                             [writer](std::size_t i) { return writer->block_cl_line(i); },
                             writer->wait_block_indices()});
      wait_lines.push_back(w->wait_cl_lines());
      // The head's lines first (no CL record), so that a block of the same text there is
      // counted as the checker reads it.
      blocks.emplace_back();
      const std::string& head = w->head_written();
      for (std::size_t at = 0; at < head.size();) {
        const std::size_t end = std::min(head.find('\n', at), head.size());
        blocks.back().push_back({0, head.substr(at, end - at), 0});
        at = end + 1;
      }
      for (const channel_writer::noted_block& b : w->noted_blocks())
        blocks.back().push_back({b.segment, b.text, b.cl_line});
    }
    for (diagnostic& d : sync_diagnostics_at_cl(check.diagnostics, sources, m, o.cl_path, wait_lines,
                                                last_line, blocks, block_lines))
      sink.report(std::move(d));
  }
  rendezvous = std::move(check.rendezvous);
  return check.ok;
}

std::vector<std::string> commit_files(output_stage& stage, const std::vector<framed_file>& files,
                                      const std::optional<staged_file>& page, const std::string& job) {
  std::vector<staged_file> staged;
  for (const framed_file& f : files) staged.push_back({f.tmp_path, f.name});
  if (page) staged.push_back(*page);
  return stage.commit(staged, job);
}

// --timeline: a plain name in the output folder that no program takes; "" when it is one.
std::string timeline_name_problem(const post_options& o, const std::vector<framed_file>& files) {
  if (std::string why = file_name_problem(o.timeline_file); !why.empty())
    return fmt::format("--timeline '{}': {} (the page is written into the output folder)", o.timeline_file,
                       why);
  for (const framed_file& f : files)
    if (f.name == o.timeline_file)
      return fmt::format("--timeline '{}' is the name of a program of this post", o.timeline_file);
  return "";
}

// Feed blocks the control cannot read as fast as they go by (limits.blocks_per_second): one
// warning per channel, at its shortest block. The control would slow the feed down there (it
// starves), or jerk; the fix is the CAM's (a coarser tolerance) or the chain's chordal_tolerance.
void report_short_blocks(const timeline& t, const machine& m, diagnostic_sink& sink) {
  for (const channel_times& c : t.channels) {
    if (c.short_blocks == 0) continue;
    const double per_block = 1000 / m.limits.blocks_per_second;
    sink.report(
        {severity::warning, c.shortest_at.file, c.shortest_at.line, c.shortest_at.column,
         fmt::format("channel {}: {} feed block{} take{} less than the {:.3g} ms a block the control "
                     "reads (limits.blocks_per_second = {:g}); this one, the shortest, {:.3g} ms at its "
                     "feed: the control would slow the feed down there (a coarser chordal_tolerance or "
                     "CAM tolerance gives fewer, longer blocks)",
                     c.channel, c.short_blocks, c.short_blocks == 1 ? "" : "s",
                     c.short_blocks == 1 ? "s" : "", per_block, m.limits.blocks_per_second,
                     c.shortest * 1000),
         c.shortest_at.source_line});
  }
}

// The cycle time of the staged programs (fed by the self-check's reading, checked sound) and,
// with --timeline, the page staged beside them. Blocks are kept only for the page, and
// dropped once it is written.
std::optional<staged_file> time_programs(const post_options& o, const machine& m,
                                         const std::string& stage_dir, timeline_feed& feed,
                                         const std::vector<std::uint64_t>& rendezvous, post_summary& sum,
                                         diagnostic_sink& sink) {
  timeline t = feed.finish(rendezvous);
  if (!t.ok) return std::nullopt;
  report_short_blocks(t, m, sink);
  if (!has_timing(m)) return std::nullopt;  // read for the block rate alone
  std::optional<staged_file> page;
  if (!o.timeline_file.empty()) {
    const std::string path = (fs::path(stage_dir) / "timeline-page.tmp").string();
    const std::string html = timeline_page(t, fmt::format("{} on {}", o.cl_path, m.name));
    std::FILE* f = std::fopen(path.c_str(), "wb");
    const bool ok = f && std::fwrite(html.data(), 1, html.size(), f) == html.size();
    if (!f || std::fclose(f) != 0 || !ok)
      throw config_error(fmt::format("cannot write the timeline page '{}': {}", path, std::strerror(errno)));
    page = staged_file{path, o.timeline_file};
  }
  for (channel_times& c : t.channels) std::vector<timed_block>().swap(c.kept);
  sum.timing = std::move(t);
  return page;
}

}  // namespace

post_threads plan_threads(const post_options& o, const machine& m) {
  post_threads p;
  if (threads(o) < 2) return p;
  // The look-ahead: on a machine of one channel with a kinematic chain (a post routes a
  // multi-channel job's events only as it writes them).
  p.look_ahead = m.channels.size() == 1 && m.chain(m.channels.front().number) != nullptr;
  // The check while writing: on programs each written whole by its channel's writer (split
  // layout), as far as the checker handles the machine's channels.
  p.check = o.layout.value_or(m.layout) == layout_kind::split && m.channels.size() <= 64;
  // The reader: not where the check times the programs or checks the turrets' interference.
  // That check then has about as much work per block as the reader and the writer together,
  // and a third busy thread only makes two cores share three (docs/benchmark.md, "Issue 23,
  // sixth pass": the two-turret lathe job 0.188 s on three threads, 0.160 s on two). The
  // look-ahead works between the reader's thread and the post's, and keeps it.
  p.reader = p.look_ahead || !(p.check && (has_timing(m) || interference_checked(m)));
  return p;
}

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

// How a pass is set up: the policy, decided by the first pass from the job's scan (made while
// its reader reads ahead) unless given.
struct pass_setup {
  std::optional<sync_policy> policy;
  std::optional<job_scan> scan;  ///< made once by post_job when it chose the policy
  bool operation_waits = false;  ///< channel_router::set_operation_waits
  bool aside_sync = false;       ///< channel_router::set_aside_sync
};

// One posting of the job: the programs written into a stage of their own, checked, timed, and
// committed with `commit` when sound. `waits`: the plan under the optimise policy. Returns the
// job's operations as the router found them (channels/wait_plan.hpp).
job_operations post_pass(const post_options& o, const machine& m, pass_setup& setup,
                         const job_operations* waits, bool commit, diagnostic_sink& diags,
                         post_summary& sum) {
  counting_sink sink(diags);
  // The machine's script, once per job, before the reader: on_record decides what it reads.
  // It runs on this thread only, in the writers (machining/channel_script.cpp).
  std::unique_ptr<scripting::lua_script> lua;
  if (!m.events.script_path.empty()) {
    try {
      scripting::script_limits limits;
      if (m.events.script_instructions > 0)
        limits.instructions_per_job = static_cast<long long>(m.events.script_instructions);
      if (m.events.script_seconds > 0) limits.seconds_per_job = m.events.script_seconds;
      lua = std::make_unique<scripting::lua_script>(m.events.script_path, limits);
    } catch (const scripting::script_error& e) {
      sink.report(script_diagnostic(e));
      return {};
    }
  }
  job_script script{lua.get()};
  file_ptr in = open_job(o.cl_path);
  // On two threads the reader starts at once, and reads ahead while the scan below runs; a
  // 5-axis job's moves are worked out by a third thread between the two.
  file_source src(in.get());
  passing_sink as_is(sink);
  std::optional<kin_lookahead> ahead;  // before the reader, whose thread uses it
  const post_threads plan = plan_threads(o, m);
  if (plan.look_ahead) ahead.emplace(m, m.channels.front().number);
  job_events reader(src, posting_reader(o, m, lua.get()), sink, as_is, plan.reader,
                    ahead ? &*ahead : nullptr);  // to the end: messages quote it
  // Everything is written into a stage inside the output folder and committed as a set.
  output_stage stage(o.out_dir);
  const job_scan scan = setup.scan ? *setup.scan : scan_for_sync(o, m);
  if (!setup.policy) setup.policy = choose_policy(o, m, scan, sink);
  sum.policy = *setup.policy;

  writers_sink ws;
  ws.m = &m;
  ws.diags = &sink;
  ws.file = o.cl_path;
  frame_request req = staged_request(o, m, stage.dir());
  // The header and footer blocks through the script's on_block, as the body's blocks.
  if (lua && lua->has_on_block())
    req.edit_block = [&ws](const channel_def& ch, const std::string& b, bool header, std::size_t index) {
      return ws.writers[static_cast<std::size_t>(ch.number - 1)]->frame_block(b, header, index);
    };
  for (const auto& [channel, tool] : o.start_tools)
    if (channel < 1 || channel > static_cast<int>(m.channels.size()))
      throw config_error(fmt::format("--tool {}:{}: machine '{}' has no channel {} (it has {})", channel,
                                     tool, m.name, channel, m.channels.size()));
  open_writers(o, m, req, ws, sink);
  if (ahead) ws.writers.front()->set_lookahead(&*ahead);
  if (lua)
    for (auto& w : ws.writers) w->use_script(&script);
  channel_router router(m, sum.policy, ws, sink, o.cl_path, used_channels(scan, m));
  router.set_plan(waits);
  router.set_operation_waits(setup.operation_waits);
  router.set_aside_sync(setup.aside_sync);
  timeline_options to;
  to.keep_blocks = !o.timeline_file.empty();
  std::optional<timeline_feed> feed;  // the cycle time, fed by the self-check's reading
  if ((has_timing(m) || m.limits.blocks_per_second > 0) && m.channels.size() <= 64) feed.emplace(m, to);
  std::optional<concurrent_check> during;  // after `feed`: its thread feeds it
  if (plan.check) {
    const std::vector<cl_comparison*> compared = compared_during(m, ws, feed.has_value());
    during.emplace(m, feed ? &*feed : nullptr, compared);
    relay_writers(o, req, ws, *during);
    note_during(ws, *during, compared);
  }

  sink.reader = &reader;
  sink.file = o.cl_path;
  ws.spindles.quote = [&reader](int line) { return std::string(reader.source_line(line)); };
  const stream_totals t = stream_job(o, reader, router);
  router.finish(t.last_line);
  for (auto& w : ws.writers) w->finish();
  report_comparisons(o, ws, during ? &*during : nullptr, sink);
  sum.records = static_cast<long>(reader.records());
  sum.channels = static_cast<int>(m.channels.size());
  sum.waits = router.rendezvous();
  for (auto& w : ws.writers) sum.blocks += w->blocks();
  if (t.statements == 0) report_empty_job(o, sink);
  if (sink.counts.errors > 0) return router.operations();

  const std::vector<framed_file> files = frame_files(named_request(req, ws), ws);
  if (sink.counts.errors > 0) return router.operations();  // a header written again, refused by on_block
  if (!o.timeline_file.empty())
    if (std::string why = timeline_name_problem(o, files); !why.empty()) {
      sink.report({severity::error, o.cl_path, 0, 0, std::move(why), {}});
      return router.operations();
    }
  std::optional<sync_result> done;
  if (during) {
    std::vector<std::string> names(m.channels.size());
    std::vector<bool> rewritten;
    for (const framed_file& f : files) {
      names[static_cast<std::size_t>(f.channel - 1)] = (fs::path(o.out_dir) / f.name).string();
      rewritten.push_back(f.rewritten);
    }
    done = during->finish(names, rewritten);
    if (!done && feed) {  // checked again after the fact: a fresh feed for that reading
      feed.reset();
      feed.emplace(m, to);
    }
  }
  std::vector<std::uint64_t> rendezvous;
  if (!self_check(o, m, files, ws, t.last_line, sink, feed ? &*feed : nullptr, std::move(done), rendezvous))
    return router.operations();
  std::optional<staged_file> page;
  if (feed) page = time_programs(o, m, stage.dir(), *feed, rendezvous, sum, sink);
  if (commit) sum.files = commit_files(stage, files, page, o.cl_path);
  sum.ok = true;
  return router.operations();
}

post_summary post_job(const post_options& o, const machine& m, diagnostic_sink& diags) {
  post_summary sum;
  counting_sink sink(diags);
  if (m.check_only) {
    sink.report({severity::error,
                 m.source,
                 0,
                 0,
                 fmt::format("machine '{}' is a definition for check only (machine.check_only = true): its "
                             "codes beyond the waits are not verified for posting",
                             m.name),
                 {}});
    return sum;
  }
  if (std::optional<diagnostic> d = known_user_record(m)) {
    sink.report(std::move(*d));
    return sum;
  }
  // A layout given in the options is held to the rule the loader holds the machine file to.
  if (std::string why = layout_problem(m, o.layout.value_or(m.layout)); !why.empty()) {
    sink.report({severity::error, m.source, 0, 0, std::move(why), {}});
    return sum;
  }
  for (const auto& [given, option] :
       {std::pair{!o.timeline_file.empty(), "--timeline"}, std::pair{o.compare_optimum, "--compare-optimum"}})
    if (given && !has_timing(m)) {
      sink.report({severity::error,
                   m.source,
                   0,
                   0,
                   fmt::format("{}: machine '{}' has no [timing] table (docs/machines.md, \"[timing]\")",
                               option, m.name),
                   {}});
      return sum;
    }
  // `auto` on a machine of several channels is decided here, once: optimise posts the job
  // several times.
  pass_setup setup;
  if (o.policy == sync_policy::automatic && m.channels.size() > 1) {
    (void)open_job(o.cl_path);  // a FIFO, a folder or a missing job: refused before the scan opens it
    setup.scan = scan_for_sync(o, m);
    setup.policy = choose_policy(o, m, *setup.scan, sink);
  }
  // The optimiser's posts; `compare`: the job's sync records set aside and nothing written.
  auto attempts = [&](bool compare) {
    return [&o, &m, &setup, compare](optimise_step step, const job_operations* plan, diagnostic_sink& to) {
      optimise_attempt a;
      pass_setup each_setup;
      each_setup.scan = setup.scan;
      each_setup.policy = step == optimise_step::planned             ? sync_policy::optimise
                          : step == optimise_step::fallback_explicit ? sync_policy::explicit_marks
                                                                     : sync_policy::sequential;
      each_setup.operation_waits = step == optimise_step::timing;
      each_setup.aside_sync = compare;
      post_options each = o;
      if (step == optimise_step::timing || compare)
        each.timeline_file.clear();  // the page only of programs written
      a.ops = post_pass(each, m, each_setup, plan, step != optimise_step::timing && !compare, to, a.sum);
      return a;
    };
  };
  if (setup.policy.value_or(o.policy) == sync_policy::optimise)
    return post_optimised(o, m, sink, attempts(false));
  post_pass(o, m, setup, nullptr, true, sink, sum);
  // What the optimiser would make of the job, its sync records set aside: said, never written.
  // The programs are written by now: what goes wrong after is said in the summary, never the
  // post's failure (the job changed or gone, the memory short).
  if (o.compare_optimum && sum.ok && sum.channels > 1) {
    try {
      diagnostic_list unused;
      const post_summary best = post_optimised(o, m, unused, attempts(true), true);
      if (best.ok && best.timing) {
        sum.optimum_cycle = best.timing->cycle;
        sum.optimum_passes = best.passes;
        sum.optimum_kept_apart = best.kept_apart;
        sum.optimum_schedule = best.schedule;
      } else {
        sum.optimum_unknown = best.optimum_unknown.empty() ? "no schedule was found" : best.optimum_unknown;
      }
    } catch (const std::exception& e) {
      sum.optimum_unknown = e.what();
    }
  }
  return sum;
}

}  // namespace twinpost
