#include "post/concurrent_check.hpp"

#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>

#include "analysis/shared_resources.hpp"
#include "check/nc_program.hpp"

namespace twinpost {

namespace {

constexpr std::size_t queue_pieces = 8;  // pieces of up to 256 KB waiting for the reader

struct piece {
  int channel = 0;
  bool opens = false;  // `text` is the program's name, not its bytes
  std::string text;    // its NUL is the one the reader's scans stop at
};

nc_read_options feeding(timeline_feed* feed) {
  nc_read_options more;
  if (feed) {
    more.on_block = [feed](const nc_block& b) { feed->block(b); };
    more.on_wait = [feed](const nc_wait& w) { feed->wait(w); };
  }
  return more;
}

}  // namespace

struct concurrent_check::impl {
  impl(const machine& m, timeline_feed* feed)
      : check(m, feeding(feed)), reader(m, read, check.options()), names(m.channels.size()),
        thread([this] { run(); }) {}

  ~impl() {
    stop();
    if (thread.joinable()) thread.join();
  }

  void push(piece p) {
    std::unique_lock lock(mutex);
    room.wait(lock, [this] { return queue.size() < queue_pieces; });
    queue.push_back(std::move(p));
    lock.unlock();
    ready.notify_one();
  }

  void stop() {
    {
      std::lock_guard lock(mutex);
      stopping = true;
    }
    ready.notify_one();
  }

  // The reading thread: pieces in the order they were written, until stop() and an empty
  // queue. After a failure it goes on taking pieces (a writer must never wait for ever).
  void run() {
    for (;;) {
      std::unique_lock lock(mutex);
      ready.wait(lock, [this] { return !queue.empty() || stopping; });
      if (queue.empty()) return;
      piece p = std::move(queue.front());
      queue.pop_front();
      lock.unlock();
      room.notify_one();
      if (failed) continue;
      try {
        if (p.opens)
          reader.open(p.channel, std::move(p.text));
        else
          reader.feed(p.channel, p.text);
      } catch (...) {
        failed = true;  // the check after the fact meets it again and says it
      }
    }
  }

  diagnostic_list read;            // the reading's problems (any: the check after the fact)
  compact_resource_check check;    // the waits, the spindle rules, and the feed
  nc_stream_reader reader;         // used by the thread until it is joined
  std::vector<std::string> names;  // by channel: the name each program was read under ("" : not opened)
  bool failed = false;             // written by the thread, read after the join

  std::mutex mutex;
  std::condition_variable ready, room;
  std::deque<piece> queue;
  bool stopping = false;
  std::thread thread;  // last: starts when everything it uses exists
};

concurrent_check::concurrent_check(const machine& m, timeline_feed* feed)
    : p_(std::make_unique<impl>(m, feed)) {}

concurrent_check::~concurrent_check() = default;

bool concurrent_check::opened(int channel) const {
  return !p_->names[static_cast<std::size_t>(channel - 1)].empty();
}

void concurrent_check::open(int channel, std::string name) {
  p_->names[static_cast<std::size_t>(channel - 1)] = name;
  p_->push({channel, true, std::move(name)});
}

void concurrent_check::put(int channel, std::string_view bytes) {
  p_->push({channel, false, std::string(bytes)});
}

std::optional<sync_result> concurrent_check::finish(const std::vector<std::string>& names,
                                                    const std::vector<bool>& rewritten) {
  p_->stop();
  p_->thread.join();
  if (p_->failed || names != p_->names) return std::nullopt;
  for (bool r : rewritten)
    if (r) return std::nullopt;
  const nc_programs programs = p_->reader.finish();
  std::optional<sync_result> r = p_->check.result(programs, p_->read);
  if (!r || !r->diagnostics.empty()) return std::nullopt;
  return r;
}

}  // namespace twinpost
