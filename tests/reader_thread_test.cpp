// The CL reader on its own thread (post/reader_thread): it makes its cl_reader on that thread,
// so a failure of the reading at its very start (the dialect's look at the first bytes) or in
// the middle reaches the post's thread as the same exception, after the events read before it.
#include <catch2/catch.hpp>

#include <cstring>
#include <string>
#include <variant>

#include "parser/line_reader.hpp"
#include "post/reader_thread.hpp"
#include "support/diagnostics.hpp"
#include "support/errors.hpp"

using namespace twinpost;

namespace {

// `text`, then a read error once `fail_at` bytes have been given.
class failing_source : public byte_source {
 public:
  failing_source(std::string text, std::size_t fail_at) : text_(std::move(text)), fail_at_(fail_at) {}
  std::size_t read(char* dst, std::size_t n) override {
    if (at_ >= fail_at_) throw config_error("cannot read 'job.cls': Input/output error");
    n = std::min({n, text_.size() - at_, fail_at_ - at_});
    std::memcpy(dst, text_.data() + at_, n);
    at_ += n;
    return n;
  }

 private:
  std::string text_;
  std::size_t fail_at_, at_ = 0;
};

// The moves read before the exception, and its message ("" when none came).
std::pair<int, std::string> read_all(byte_source& src) {
  diagnostic_list sink;
  cl_reader_options o;
  o.file_name = "job.cls";
  o.chunk_size = 64;
  reader_thread r(src, o, sink);
  int moves = 0;
  try {
    while (const event* e = r.next())
      if (std::holds_alternative<motion_event>(e->data)) ++moves;
  } catch (const config_error& e) {
    return {moves, e.what()};
  }
  return {moves, ""};
}

std::string moves(int n) {
  std::string cl;
  for (int i = 0; i < n; ++i) cl += "GOTO/" + std::to_string(i) + ",0,0\n";
  return cl + "FINI\n";
}

}  // namespace

TEST_CASE("reader thread: a job read to its end", "[post]") {
  failing_source src(moves(5000), std::string::npos);
  CHECK(read_all(src) == std::pair<int, std::string>{5000, ""});
}

TEST_CASE("reader thread: a read error at the start reaches the post's thread", "[post]") {
  // The first read is the dialect's look, made by the cl_reader the thread makes.
  failing_source src(moves(10), 0);
  CHECK(read_all(src) == std::pair<int, std::string>{0, "cannot read 'job.cls': Input/output error"});
}

TEST_CASE("reader thread: a read error in the middle comes after the events before it", "[post]") {
  // Past the first 64 KB (the dialect's look) and past two batches of 4096 events: every move
  // before the cut comes, then the error.
  const std::string cl = moves(20000);
  const std::size_t cut = cl.find("GOTO/9000,");
  failing_source src(cl, cut);
  CHECK(read_all(src) == std::pair<int, std::string>{9000, "cannot read 'job.cls': Input/output error"});
}
