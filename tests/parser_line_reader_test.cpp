// line_reader on its own: logical records, `$` joining, trailing comments, positions.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "parser/line_reader.hpp"

using namespace twinpost;

namespace {

struct logical {
  std::string text;
  int line;
  bool operator==(const logical& o) const { return text == o.text && line == o.line; }
};

std::ostream& operator<<(std::ostream& os, const logical& l) { return os << l.line << ":'" << l.text << "'"; }

std::vector<logical> records_of(std::string_view text, std::size_t chunk = 16) {
  string_source src(text);
  line_reader lines(src, chunk);
  std::vector<logical> out;
  logical_record r;
  while (lines.next(r)) out.push_back({std::string(r.text), r.line});
  return out;
}

}  // namespace

TEST_CASE("line_reader joins $ continuations and cuts trailing comments", "[parser][line_reader]") {
  CHECK(records_of("GOTO/1,$\n 2,$\n3 $$ note\n\n$$ comment $\nRAPID\n") ==
        std::vector<logical>{{"GOTO/1, 2,3 ", 1}, {"$$ comment $", 5}, {"RAPID", 6}});
}

TEST_CASE("line_reader continues $$-> lines but not plain $$ lines", "[parser][line_reader]") {
  CHECK(records_of("$$-> CSYS / 1, $\n 2\n$$ a $\nGOTO/1,2,3\n") ==
        std::vector<logical>{{"$$-> CSYS / 1,  2", 1}, {"$$ a $", 3}, {"GOTO/1,2,3", 4}});
}

TEST_CASE("line_reader strips CR and handles a missing last newline", "[parser][line_reader]") {
  CHECK(records_of("A\r\nB,$\r\nC\r\nD") == std::vector<logical>{{"A", 1}, {"B,C", 2}, {"D", 4}});
}

TEST_CASE("line_reader maps offsets of a joined record to physical lines", "[parser][line_reader]") {
  std::string text = "X\nGOTO/1,$\n   2,$\n 3\n";
  string_source src(text);
  line_reader lines(src, 16);
  logical_record r;
  REQUIRE(lines.next(r));
  REQUIRE(lines.next(r));
  CHECK(r.text == "GOTO/1,   2, 3");
  source_position p = lines.locate(10);  // the '2'
  CHECK(p.line == 3);
  CHECK(p.column == 4);
  CHECK(p.source_line == "   2,$");
  p = lines.locate(13);  // the '3'
  CHECK(p.line == 4);
  CHECK(p.column == 2);
  CHECK(p.source_line == " 3");
  CHECK_FALSE(lines.next(r));
  CHECK(lines.bytes_read() == text.size());
}

TEST_CASE("line_reader grows its buffer for a line longer than a chunk", "[parser][line_reader]") {
  std::string big(60000, 'x');  // under max_record_bytes
  CHECK(records_of("A\n" + big + "\nB\n", 16) == std::vector<logical>{{"A", 1}, {big, 2}, {"B", 3}});
}

TEST_CASE("line_reader peek sees the head without consuming it", "[parser][line_reader]") {
  std::string text = "PPRINT/APTCL-SPEC,MAKINO-FF,1\nGOTO/1,2,3\n";
  string_source src(text);
  line_reader lines(src, 16);
  CHECK(lines.peek(12) == "PPRINT/APTCL");
  CHECK(lines.peek(1000) == text);
  logical_record r;
  REQUIRE(lines.next(r));
  CHECK(r.text == "PPRINT/APTCL-SPEC,MAKINO-FF,1");
  CHECK(r.line == 1);
}
