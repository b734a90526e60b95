#include "post/reader_thread.hpp"

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace twinpost {

namespace {

// A new event holds a move: the reading thread copies moves into one (run).
static_assert(std::is_same_v<std::variant_alternative_t<0, event_data>, motion_event>);

constexpr std::size_t batch_events = 4096;  // events handed over at a time
constexpr std::size_t queue_batches = 4;    // batches read ahead at most
constexpr std::size_t ahead_batches = 3;    // with a look-ahead: in each of its two queues

struct line_ref {
  int line = 0;
  std::size_t offset = 0, size = 0;  // in batch::text
};

// Events read one after the other, with what the post's thread needs to give them out as
// the reader would have: the diagnostics between them and their records' source lines.
struct batch {
  std::vector<event> events;
  std::vector<std::uint32_t> record_of;     // per event: its record (index into record_start)
  std::vector<std::uint32_t> record_start;  // per record: its first line in `lines`
  std::vector<line_ref> lines;              // the records' physical lines, one after another
  std::string text;                         // their text
  std::vector<std::pair<std::size_t, diagnostic>> diagnostics;  // each before event [first]
  std::size_t bytes = 0, records = 0;                           // the reader's counts at the batch's end
  bool last = false;                                            // the input ends after it
  std::uint32_t end_record = 0;                                 // last: the record read last
  std::exception_ptr error;                                     // last: the reader threw this
  kin_lookahead::notes worked;  // the look-ahead's moves (reader_thread's `ahead`), else empty

  void clear() {
    worked.clear();
    events.clear();
    record_of.clear();
    record_start.clear();
    lines.clear();
    text.clear();
    diagnostics.clear();
    bytes = records = 0;
    last = false;
    end_record = 0;
    error = nullptr;
  }
};

}  // namespace

struct reader_thread::impl {
  // The reader's diagnostics, kept in the batch being filled at the place they came, their
  // source line given as the post's own sink would (the reader's record is the one of now).
  struct keeping_sink : diagnostic_sink {
    explicit keeping_sink(impl* p) : p(p) {}
    impl* p;
    void report(diagnostic d) override {
      if (d.column > 0 && d.source_line.empty() && d.file == p->file && p->reader)  // not while it is made
        d.source_line = std::string(p->reader->source_line(d.line));
      p->filling->diagnostics.emplace_back(p->filling->events.size(), std::move(d));
    }
  };

  impl(byte_source& src, cl_reader_options options, diagnostic_sink& out, kin_lookahead* ahead)
      : src(src), options(std::move(options)), file(this->options.file_name), keep(this), out(out),
        ahead(ahead), thread([this] { run(); }) {
    if (ahead) looking = std::thread([this] { look(); });
  }

  ~impl() {
    {
      std::lock_guard lock(mutex);
      stopping = true;
    }
    room.notify_all();
    ready.notify_all();
    looked_room.notify_all();
    looked_ready.notify_all();
    if (thread.joinable()) thread.join();
    if (looking.joinable()) looking.join();
  }

  // --- the reading thread ---------------------------------------------------------------

  void run() {
    std::size_t seen = 0;  // reader.records() when the current record's lines were kept
    // The reader and its first batch are made here, on this thread: their memory (the line
    // buffer, the record, the events), written for every record, then comes from this thread's
    // allocator and shares no cache line with the post's state (post/concurrent_check.cpp).
    filling = std::make_unique<batch>();  // before the reader: it may report at once
    try {
      reader.emplace(src, std::move(options), keep);
      while (const event* e = reader->next()) {
        batch& b = *filling;
        if (const std::size_t now = reader->records(); b.record_start.empty() || now != seen) {
          keep_record(b);
          seen = now;
        }
        // A move (most events) is copied as itself into a new event, which holds a move
        // already: not through the variant's table of copies.
        if (const auto* m = std::get_if<motion_event>(&e->data)) {
          event& copy = b.events.emplace_back();
          copy.line = e->line;
          copy.column = e->column;
          *std::get_if<motion_event>(&copy.data) = *m;
        } else {
          b.events.push_back(*e);
        }
        b.record_of.push_back(static_cast<std::uint32_t>(b.record_start.size() - 1));
        if (b.events.size() == batch_events && !hand_over()) return;
      }
      keep_record(*filling);
      filling->end_record = static_cast<std::uint32_t>(filling->record_start.size() - 1);
    } catch (...) {
      filling->error = std::current_exception();
    }
    filling->last = true;
    hand_over();
  }

  // The lines of the reader's current record into `b`.
  void keep_record(batch& b) {
    b.record_start.push_back(static_cast<std::uint32_t>(b.lines.size()));
    for (std::size_t i = 0, n = reader->source_lines(); i < n; ++i) {
      const auto [line, text] = reader->source_line_at(i);
      b.lines.push_back({line, b.text.size(), text.size()});
      b.text.append(text);
    }
  }

  // Queues the batch being filled and takes an empty one; false when the post has stopped.
  bool hand_over() {
    filling->bytes = reader ? reader->bytes() : 0;
    filling->records = reader ? reader->records() : 0;
    std::unique_lock lock(mutex);
    room.wait(lock, [this] { return queue.size() < (ahead ? ahead_batches : queue_batches) || stopping; });
    if (stopping) return false;
    queue.push_back(std::move(filling));
    if (!spare.empty()) {
      filling = std::move(spare.back());
      spare.pop_back();
    } else {
      filling = std::make_unique<batch>();
    }
    lock.unlock();
    ready.notify_one();
    // The record of the next event is kept again in the new batch (keep_record).
    return true;
  }

  // --- the look-ahead's thread (with `ahead` only) ----------------------------------------

  // Takes each batch the reader queued, works out its moves, and queues it for the post.
  void look() {
    for (;;) {
      std::unique_lock lock(mutex);
      ready.wait(lock, [this] { return !queue.empty() || stopping; });
      if (stopping) return;
      std::unique_ptr<batch> b = std::move(queue.front());
      queue.pop_front();
      lock.unlock();
      room.notify_one();
      try {
        ahead->look(b->events, b->worked);
      } catch (...) {
        b->worked.clear();  // nothing worked out ahead: the writer works every move out itself
      }
      const bool last = b->last;
      lock.lock();
      looked_room.wait(lock, [this] { return looked.size() < ahead_batches || stopping; });
      if (stopping) return;
      looked.push_back(std::move(b));
      lock.unlock();
      looked_ready.notify_one();
      if (last) return;
    }
  }

  // --- the post's thread -----------------------------------------------------------------

  const event* next() {
    for (;;) {
      if (current) {
        batch& b = *current;
        while (told < b.diagnostics.size() && b.diagnostics[told].first <= at)
          out.report(std::move(b.diagnostics[told++].second));
        if (at < b.events.size()) {
          record = b.record_of[at];
          if (ahead) ahead->at(&b.worked, at);
          return &b.events[at++];
        }
        if (b.error) std::rethrow_exception(b.error);
        if (b.last) {
          record = b.end_record;
          return nullptr;
        }
      }
      take();
    }
  }

  // The next batch: the reader's, or with `ahead` the look-ahead's.
  void take() {
    if (ahead) ahead->at(nullptr, 0);  // the batch it points into goes back to the reader
    std::deque<std::unique_ptr<batch>>& from = ahead ? looked : queue;
    std::condition_variable& filled = ahead ? looked_ready : ready;
    std::unique_lock lock(mutex);
    filled.wait(lock, [&] { return !from.empty(); });
    if (current) {
      current->clear();
      spare.push_back(std::move(current));
    }
    current = std::move(from.front());
    from.pop_front();
    lock.unlock();
    (ahead ? looked_room : room).notify_one();
    at = told = 0;
  }

  std::string_view source_line(int line) const {
    if (!current || current->record_start.empty()) return {};
    const batch& b = *current;
    const std::size_t from = b.record_start[record];
    const std::size_t to = record + 1 < b.record_start.size() ? b.record_start[record + 1] : b.lines.size();
    for (std::size_t i = from; i < to; ++i)
      if (b.lines[i].line == line) return std::string_view(b.text).substr(b.lines[i].offset, b.lines[i].size);
    return {};
  }

  byte_source& src;           // until the thread makes its reader of it
  cl_reader_options options;  // likewise
  std::string file;           // the job's name in diagnostics
  keeping_sink keep;
  std::unique_ptr<batch> filling;   // the thread's
  std::optional<cl_reader> reader;  // made and used by the thread only
  diagnostic_sink& out;

  kin_lookahead* ahead;  // nullptr: the post takes the reader's batches as they are

  std::mutex mutex;
  std::condition_variable ready, room;
  std::deque<std::unique_ptr<batch>> queue;  // read, for the look-ahead (with `ahead`) or the post
  std::condition_variable looked_ready, looked_room;
  std::deque<std::unique_ptr<batch>> looked;  // with `ahead`: looked at, for the post
  std::vector<std::unique_ptr<batch>> spare;  // emptied batches for the thread to fill again
  bool stopping = false;

  std::unique_ptr<batch> current;  // the post thread's: the batch being given out
  std::size_t at = 0, told = 0;    // its next event and next diagnostic
  std::uint32_t record = 0;        // the record of the event given out last

  std::thread thread;   // last: starts when everything it uses exists
  std::thread looking;  // the look-ahead's, started after `thread`
};

reader_thread::reader_thread(byte_source& src, cl_reader_options options, diagnostic_sink& sink,
                             kin_lookahead* ahead)
    : p_(std::make_unique<impl>(src, std::move(options), sink, ahead)) {}

reader_thread::~reader_thread() = default;

const event* reader_thread::next() { return p_->next(); }
std::string_view reader_thread::source_line(int line) const { return p_->source_line(line); }
std::size_t reader_thread::bytes() const { return p_->current ? p_->current->bytes : 0; }
std::size_t reader_thread::records() const { return p_->current ? p_->current->records : 0; }

}  // namespace twinpost
