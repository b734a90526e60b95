#include "post/concurrent_check.hpp"

#include <algorithm>
#include <cerrno>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>
#include <thread>

#include "analysis/modal_state.hpp"
#include "analysis/shared_resources.hpp"
#include "analysis/spindle_state.hpp"
#include "check/nc_program.hpp"

namespace twinpost {

namespace {

constexpr std::size_t queue_pieces = 8;  // pieces of up to 64 KB waiting for the reader

// A record (or the job's units) noted for a channel's comparison, after `bytes` bytes of its
// program: before the block that starts there. Built in place in its piece's vector (one copy
// of the event, no optional around it).
struct noted {
  noted(std::uint64_t bytes, const event& e, bool both) : bytes(bytes), record(e), both(both) {}
  noted(std::uint64_t bytes, unit_system u) : bytes(bytes), is_units(true), units(u) {}
  std::uint64_t bytes = 0;
  event record;  // (when not is_units)
  bool both = false;
  bool is_units = false;
  unit_system units = unit_system::mm;
};

// A channel's state on each thread, in cache lines of its own: a line one core writes and the
// other reads goes to and fro between them at every write (the writer notes a record in `held`
// for every CL record, the thread hands them on and counts the bytes read for every block).
struct alignas(64) writer_lane {
  std::vector<noted> held;  // noted since the channel's last piece
};
struct alignas(64) reader_lane {
  std::deque<std::vector<noted>> due;  // pieces' records not yet handed
  std::size_t due_at = 0;              // the next of due's first piece's
  std::uint64_t fed = 0;               // the bytes of its pieces read
};

struct piece {
  int channel = 0;
  std::vector<noted> records;  // noted since the channel's piece before
  std::string opens;           // not empty: the program starts here, named this
  text_buffer bytes;           // its NUL (after the bytes) is the one the reader's scans stop at
  std::FILE* f = nullptr;      // the file the bytes are written to once read
};

}  // namespace

struct alignas(64) concurrent_check::impl {
  impl(const machine& m, timeline_feed* feed, std::vector<cl_comparison*> compare)
      : m(m), feed(feed), compare(std::move(compare)), written_lanes(m.channels.size()),
        read_lanes(m.channels.size()), names(m.channels.size()), pending(m.channels.size()),
        write_errors(m.channels.size()), thread([this] { run(); }) {}

  ~impl() {
    stop();
    if (thread.joinable()) thread.join();
  }

  // Queues `p` (the writer's thread) and gives back an empty buffer.
  text_buffer push(piece p) {
    const auto c = static_cast<std::size_t>(p.channel - 1);
    std::unique_lock lock(mutex);
    // A full queue: the writer waits until the reader has read half of it, not for each piece
    // (a wait and a wake-up per piece once the check is the slower thread: four times the
    // threads' switches on the lathe job).
    if (queue.size() >= queue_pieces) room.wait(lock, [this] { return queue.size() <= queue_pieces / 2; });
    ++pending[c];
    queue.push_back(std::move(p));
    text_buffer empty;
    if (!spare.empty()) {
      empty = std::move(spare.back());
      spare.pop_back();
    }
    // Its records' vector too comes round: memory this thread allocated, freed on the other,
    // goes back to this thread's arena under its lock, for every piece.
    if (written_lanes[c].held.capacity() == 0 && !spare_records.empty()) {
      written_lanes[c].held = std::move(spare_records.back());
      spare_records.pop_back();
    }
    lock.unlock();
    ready.notify_one();
    return empty;
  }

  // The errno of the first failed write of `channel`'s pieces; `all`: once all are written.
  int write_error(int channel, bool all) {
    const auto i = static_cast<std::size_t>(channel - 1);
    std::unique_lock lock(mutex);
    if (all) written.wait(lock, [&] { return pending[i] == 0; });
    return write_errors[i];
  }

  void stop() {
    {
      std::lock_guard lock(mutex);
      stopping = true;
    }
    ready.notify_one();
  }

  // What the reader reads with besides the resource check (which feeds the timeline): each
  // block to its channel's comparison, after the records noted before it.
  nc_read_options reading() {
    nc_read_options more;
    if (std::none_of(compare.begin(), compare.end(), [](const cl_comparison* c) { return c != nullptr; }))
      return more;
    // The records written before a block with the states as the blocks before left them; the
    // block itself once the reading's states have applied it (nc_read_options::before_block).
    more.before_block = [this](const nc_block& b) { compare_due(b); };
    more.on_block = [this](const nc_block& b) { compare_block(b); };
    more.on_macro = [this](const nc_block& b) { compare_block(b); };
    return more;
  }

  cl_comparison* comparison(std::size_t i) const { return i < compare.size() ? compare[i] : nullptr; }

  // Block `b` to its channel's comparison, after the records noted before it: at or before the
  // byte its line starts at. A line in the piece being read starts where its text is in the
  // piece; one the reader carried over from the piece before (its start there) starts before
  // this piece, after every record noted there (records are noted between blocks, and a
  // writer's pieces end at a line's end).
  void compare_due(const nc_block& b) {
    const auto i = static_cast<std::size_t>(b.channel - 1);
    if (!comparison(i) || drained) return;  // (the reader's finish() after drain(): its findings are said)
    const char* t = b.text.data();
    std::uint64_t starts =
        now_read.channel == b.channel ? now_read.at : read_lanes[i].fed;  // (carried: just before)
    if (now_read.channel == b.channel && t >= now_read.begin && t < now_read.end)
      starts += static_cast<std::uint64_t>(t - now_read.begin);
    else if (starts > 0)
      --starts;
    hand_due(i, starts);
  }
  // (compare_due first: the records at or before the byte it starts at.)
  void compare_block(const nc_block& b) {
    cl_comparison* c = comparison(static_cast<std::size_t>(b.channel - 1));
    if (!c || drained) return;
    const std::vector<nc_word>& words = b.words();  // first: then letters() is the split's, exact
    c->block(b.line, b.text, words, b.letters());
  }

  // Channel i's records noted at or before byte `at`, to its comparison.
  void hand_due(std::size_t i, std::uint64_t at_byte) {
    std::deque<std::vector<noted>>& q = read_lanes[i].due;
    std::size_t& at = read_lanes[i].due_at;
    cl_comparison* const c = compare[i];
    while (!q.empty()) {
      // (Its size and the comparison kept: a call may change anything, for all the compiler
      // knows, and the size is a division.)
      const noted* const front = q.front().data();
      const std::size_t count = q.front().size();
      for (; at < count; ++at) {
        const noted& n = front[at];
        if (n.bytes > at_byte) return;
        if (!n.is_units)
          c->record(n.record, n.both);
        else
          c->units(n.units);
      }
      if (handed.size() < queue_pieces) {
        q.front().clear();
        handed.push_back(std::move(q.front()));
      }
      q.pop_front();
      at = 0;
    }
  }

  void join() {
    stop();
    if (thread.joinable()) thread.join();
  }

  bool drain(std::string* why) {
    join();
    if (!drained) {
      drained = true;
      if (!failed) try {
          for (std::size_t i = 0; i < read_lanes.size(); ++i)
            if (comparison(i)) hand_due(i, std::numeric_limits<std::uint64_t>::max());
        } catch (const std::exception& e) {
          fail(e.what());
        }
    }
    if (why) *why = failure;
    for (cl_comparison* c : compare)
      if (c && failed) return false;
    return true;
  }

  void fail(const char* what) {
    failed = true;
    failure = what;
  }

  // The reading thread: pieces in the order they were written, until stop() and an empty
  // queue. After a failure of the reading it goes on writing the pieces (a writer must never
  // wait for ever, and its file gets every byte).
  void run() {
    // The check is made here, on its thread: its memory (the reader's words, the timer's and the
    // rules' state, written for every block) then comes from this thread's allocator, never in a
    // cache line with the writer's state. Made on the post's thread, some of it shared lines with
    // the reader's, and the two cores passed those lines to and fro: a third more time.
    try {
      parts = std::make_unique<check_parts>(reading(), feed, m, read);
      // The comparisons read the reading's spindle and modal states, not states of their own.
      for (std::size_t i = 0; i < compare.size(); ++i)
        if (compare[i])
          compare[i]->follow(&parts->check.spindles().channel(static_cast<int>(i) + 1),
                             &parts->check.modes().channel(static_cast<int>(i) + 1));
    } catch (const std::exception& e) {
      fail(e.what());
    } catch (...) {
      fail("unknown");
    }
    for (;;) {
      std::unique_lock lock(mutex);
      ready.wait(lock, [this] { return !queue.empty() || stopping; });
      if (queue.empty()) return;
      piece p = std::move(queue.front());
      queue.pop_front();
      const auto i = static_cast<std::size_t>(p.channel - 1);
      const bool write = write_errors[i] == 0;  // after a failed write, nothing more of it
      const bool half = queue.size() == queue_pieces / 2;
      lock.unlock();
      if (half) room.notify_one();
      if (!failed) try {
          if (!p.records.empty()) read_lanes[i].due.push_back(std::move(p.records));
          if (p.f) {  // (else records alone: flush_records)
            if (!p.opens.empty()) parts->reader.open(p.channel, std::move(p.opens));
            now_read = {p.channel, p.bytes.data(), p.bytes.data() + p.bytes.size(), read_lanes[i].fed};
            read_lanes[i].fed +=
                p.bytes.size();  // (a line carried over to the next piece starts before this)
            parts->reader.feed(p.channel, p.bytes.view());
            now_read = {};
            for (cl_comparison* c : compare)  // (the piece's bytes go now)
              if (c) c->keep_texts();
          }
        } catch (const std::exception& e) {
          fail(e.what());  // the check after the fact meets it again and says it; drain() tells
        } catch (...) {
          fail("unknown");
        }
      p.records.clear();
      int err = 0;
      if (write && p.f && std::fwrite(p.bytes.data(), 1, p.bytes.size(), p.f) != p.bytes.size()) err = errno;
      p.bytes.clear();
      lock.lock();
      if (err != 0) write_errors[i] = err;
      --pending[i];
      if (spare.size() < queue_pieces) spare.push_back(std::move(p.bytes));
      for (std::vector<noted>& r : handed)
        if (spare_records.size() < queue_pieces) spare_records.push_back(std::move(r));
      handed.clear();
      lock.unlock();
      written.notify_all();
    }
  }

  struct check_parts {
    check_parts(const nc_read_options& more, timeline_feed* feed, const machine& m, diagnostic_list& read)
        : check(m, more, feed), reader(m, read, check.options()) {}
    compact_resource_check check;  // the waits, the spindle rules, and the feed
    nc_stream_reader reader;
  };

  const machine& m;
  timeline_feed* feed;
  std::vector<cl_comparison*> compare;            // by channel, or empty: used by the thread
  std::vector<writer_lane> written_lanes;         // by channel: the writers' thread
  std::vector<reader_lane> read_lanes;            // by channel: the thread
  std::vector<std::vector<noted>> handed;         // due's vectors done with, for spare_records (the thread)
  std::vector<std::vector<noted>> spare_records;  // for the writers to fill again (under mutex)
  struct alignas(64) piece_read {                 // the piece being read (the thread; a line of its own)
    int channel = 0;
    const char* begin = nullptr;
    const char* end = nullptr;
    std::uint64_t at = 0;  // its first byte's place in its program
  } now_read;
  bool drained = false;
  std::string failure;                 // what failed() says
  diagnostic_list read;                // the reading's problems (any: the check after the fact)
  std::unique_ptr<check_parts> parts;  // made and used by the thread until it is joined
  std::vector<std::string> names;      // by channel: the name each program was read under ("" : not opened)
  bool failed = false;                 // written by the thread, read after the join

  std::mutex mutex;
  std::condition_variable ready, room, written;
  std::deque<piece> queue;
  std::vector<text_buffer> spare;    // buffers written, for the writers to fill again
  std::vector<std::size_t> pending;  // by channel: pieces queued or being read, not yet written
  std::vector<int> write_errors;     // by channel: errno of the first failed write, 0: none
  bool stopping = false;
  std::thread thread;  // last: starts when everything it uses exists
};

// One channel's writer's relay: its pieces queued for the thread.
struct concurrent_check::channel_relay : block_writer::relay {
  channel_relay(concurrent_check::impl& p, int channel, std::function<std::string()> name)
      : p(p), channel(channel), name(std::move(name)) {}

  text_buffer pass(text_buffer&& bytes, std::FILE* f) override {
    piece next;
    next.channel = channel;
    std::vector<noted>& held = p.written_lanes[static_cast<std::size_t>(channel - 1)].held;
    next.records = std::move(held);
    held = {};  // (push gives a spare one back)
    std::string& opened = p.names[static_cast<std::size_t>(channel - 1)];
    if (opened.empty()) {
      opened = name();
      next.opens = opened;
    }
    next.bytes = std::move(bytes);
    next.f = f;
    return p.push(std::move(next));
  }

  int write_error(bool all) override { return p.write_error(channel, all); }

  concurrent_check::impl& p;
  int channel;
  std::function<std::string()> name;
};

concurrent_check::concurrent_check(const machine& m, timeline_feed* feed, std::vector<cl_comparison*> compare)
    : p_(std::make_unique<impl>(m, feed, std::move(compare))) {}

concurrent_check::~concurrent_check() = default;

std::unique_ptr<block_writer::relay> concurrent_check::relay_for(int channel,
                                                                 std::function<std::string()> name) {
  return std::make_unique<channel_relay>(*p_, channel, std::move(name));
}

namespace {

// A record (or the units: `args`) held for `channel`'s next piece, made in place; true when
// records_per_piece wait.
template <class... Args>
bool hold(std::vector<writer_lane>& lanes, int channel, const Args&... args) {
  std::vector<noted>& h = lanes[static_cast<std::size_t>(channel - 1)].held;
  if (h.capacity() == 0) h.reserve(concurrent_check::records_per_piece / 4);  // (given away with each piece)
  h.emplace_back(args...);
  return h.size() >= concurrent_check::records_per_piece;
}

}  // namespace

bool concurrent_check::note_record(int channel, std::uint64_t bytes, const event& e, bool both) {
  return hold(p_->written_lanes, channel, bytes, e, both);
}

bool concurrent_check::note_units(int channel, std::uint64_t bytes, unit_system u) {
  return hold(p_->written_lanes, channel, bytes, u);
}

void concurrent_check::flush_records(int channel) {
  std::vector<noted>& h = p_->written_lanes[static_cast<std::size_t>(channel - 1)].held;
  if (h.empty()) return;
  piece p;  // no bytes, no file: records alone, after the bytes passed before them
  p.channel = channel;
  p.records = std::move(h);
  h = {};
  text_buffer back = p_->push(std::move(p));
  std::lock_guard lock(p_->mutex);  // (a buffer it gave back, for the writers' next piece)
  if (p_->spare.size() < queue_pieces) p_->spare.push_back(std::move(back));
}

bool concurrent_check::drain(std::string* why) { return p_->drain(why); }

std::optional<sync_result> concurrent_check::finish(const std::vector<std::string>& names,
                                                    const std::vector<bool>& rewritten) {
  p_->join();
  if (p_->failed || names != p_->names) return std::nullopt;
  for (bool r : rewritten)
    if (r) return std::nullopt;
  const nc_programs programs = p_->parts->reader.finish();
  std::optional<sync_result> r = p_->parts->check.result(programs, p_->read);
  if (!r || !r->diagnostics.empty()) return std::nullopt;
  return r;
}

}  // namespace twinpost
