// formats/block_writer and formats/text_buffer: blocks built in place, sequence numbers,
// the framing head and tail, and the buffer they are built in.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <string>

#include "file_test_support.hpp"
#include "formats/block_writer.hpp"
#include "formats/number_format.hpp"
#include "formats/text_buffer.hpp"

using namespace twinpost;

namespace {
// A file in a folder of its own (no other test or run writes there).
std::string temp_path(const char* name) { return test::fresh_temp_dir(name) + "/program.nc"; }
}  // namespace

TEST_CASE("text_buffer: room, commit, insert, truncate, growth", "[formats]") {
  text_buffer b;
  CHECK(b.empty());
  b += "G1";
  b += ' ';
  char* p = b.room(8);
  std::memcpy(p, "X12.5", 5);
  b.commit(p + 5);
  CHECK(b.view() == "G1 X12.5");
  b.insert(0, "N10 ");
  CHECK(b.view() == "N10 G1 X12.5");
  b.truncate(6);
  CHECK(b.view() == "N10 G1");
  std::string big(100000, 'Z');  // far past the first capacity: the text survives each growth
  b += big;
  CHECK(b.size() == 6 + big.size());
  CHECK(b.view().substr(0, 7) == "N10 G1Z");
  CHECK(b.back() == 'Z');
  text_buffer n;
  append_fixed(n, -12346, {3, true});
  append_number(n, 1e20, {3, true});  // out of the fixed range: the exact way, same buffer
  CHECK(n.view() ==
        "-12.346"
        "100000000000000000000.");  // 1e20: a one and twenty zeros
}

TEST_CASE("block_writer: numbered blocks built in place, dropped blocks, framing", "[formats]") {
  program_format fmt;
  fmt.sequence_start = 10;
  fmt.sequence_step = 5;
  const std::string path = temp_path("block-writer");
  {
    block_writer::framing frame;
    frame.head = [](sequence_numbers&) { return std::string("%\nO1000 (T)\n"); };
    frame.tail = [](sequence_numbers&) { return std::string("M30\n%\n"); };
    block_writer w(path, fmt, frame);
    w.block("G28 U0 W0");
    text_buffer& b = w.open_block();
    b += "G0 X64.";
    w.end_block();
    text_buffer& dropped = w.open_block();
    dropped += "X64.";  // already there: taken back, no number used
    w.drop_block();
    w.comment("rough od (fast)");
    w.raw("(INSERT TEXT AS IT IS)");
    text_buffer& c = w.open_block();
    c += "G1 Z-40.";
    w.end_block();
    CHECK(w.head_written() == "%\nO1000 (T)\n");
    CHECK(w.blocks() == 3);
    w.close();
  }
  CHECK(test::read_file(path) ==
        "%\nO1000 (T)\nN10 G28 U0 W0\nN15 G0 X64.\n(ROUGH OD  FAST)\n(INSERT TEXT AS IT IS)\nN20 G1 "
        "Z-40.\nM30\n%\n");
  std::filesystem::remove_all(std::filesystem::path(path).parent_path());
}

TEST_CASE("block_writer: a file with no block still gets its head and tail", "[formats]") {
  program_format fmt;
  const std::string path = temp_path("block-writer-empty");
  {
    block_writer::framing frame;
    frame.head = [](sequence_numbers&) { return std::string("%\n"); };
    frame.tail = [](sequence_numbers&) { return std::string("M30\n%\n"); };
    block_writer w(path, fmt, frame);
    CHECK(w.head_written().empty());  // nothing written yet
    w.close();
    CHECK(w.head_written() == "%\n");
  }
  CHECK(test::read_file(path) == "%\nM30\n%\n");
  std::filesystem::remove_all(std::filesystem::path(path).parent_path());
}
