// The fast path for numeric statements must read exactly what the X3 grammar reads: for
// every record it accepts, the record is the grammar's to the bit (kind, major, arguments,
// numbers, offsets). Checked on tricky records, on random ones, and on the real CL files.
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>

#include "fuzz/fast_path_check.hpp"
#include "parser/detail/fast_record.hpp"
#include "parser/event_builder.hpp"
#include "parser/event_text.hpp"
#include "parser/line_reader.hpp"
#include "parser/record_parser.hpp"
#include "tests/shared_samples.hpp"

using namespace twinpost;

namespace {

using fuzz::fast_path_difference;

bool fast_accepts(std::string_view text) {
  cl_record r;
  return parser_detail::parse_numeric_statement(text, r);
}

// Two builders fed the same records, one through build() alone, the other through
// build_goto() first (as cl_reader does): their events and messages, record by record.
struct goto_lane_pair {
  explicit goto_lane_pair(dialect d) : general(d), lane(d) {}
  event_builder general, lane;
  int taken = 0;  // records build_goto took

  // "" when both gave the same; else what each gave.
  // The lane as cl_reader takes it: parse_goto_statement into build_goto's numbers, else
  // build_goto of the record, else build().
  std::string feed(std::string_view text, int line) {
    cl_record r;
    record_error err;
    event_queue a, b;
    build_issues ia, ib;
    parser_detail::goto_statement g;
    const bool direct =
        parser_detail::parse_goto_statement(text, g) && lane.build_goto(g.numbers, g.count, line, b);
    if (!parse_record(text, r, err)) {
      general.skip_record(r.kind);
      lane.skip_record(r.kind);
      return direct ? "parse_goto_statement took a record parse_record refuses" : "";
    }
    general.build(r, line, a, ia);
    if (direct || lane.build_goto(r, line, b))
      ++taken;
    else
      lane.build(r, line, b, ib);
    const std::string ga = describe(a, ia), gb = describe(b, ib);
    return ga == gb ? std::string() : "build: " + ga + "\nbuild_goto: " + gb;
  }
  static std::string describe(const event_queue& q, const build_issues& issues) {
    std::string out;
    for (const event& e : q) out += event_to_json(e) + "\n";
    for (const build_issue& i : issues) out += i.message + "\n";
    return out;
  }
};

// "" when parse_goto_statement reads `text` as parse_numeric_statement does: the same GOTO of
// three or six numbers (major, its offset, the numbers to the bit), or nothing from either.
std::string goto_statement_difference(std::string_view text) {
  cl_record r;
  const bool statement = parser_detail::parse_numeric_statement(text, r) && parser_detail::is_goto(r.major) &&
                         (r.args.size() == 3 || r.args.size() == 6);
  parser_detail::goto_statement g;
  const bool lane = parser_detail::parse_goto_statement(text, g);
  if (statement != lane)
    return lane ? "only parse_goto_statement takes it" : "only parse_numeric_statement takes it";
  if (!lane) return {};
  if (g.major != r.major || g.major_offset != r.major_offset) return "major differs";
  if (g.count != r.args.size()) return "count differs";
  for (std::size_t i = 0; i < g.count; ++i)
    if (std::memcmp(&g.numbers[i], &r.args[i].number, sizeof(double)) != 0) return "number differs";
  return {};
}

// Each real CL file of ../shared/cl-samples, read by a line_reader (skipped without them).
template <class F>
void for_each_sample_file(F&& read) {
  const std::filesystem::path dir = test::require_shared_samples();
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    if (!entry.is_regular_file() || entry.path().filename() == "README.md") continue;
    std::FILE* f = std::fopen(entry.path().c_str(), "rb");
    REQUIRE(f);
    file_source src(f);
    line_reader lines(src);
    read(entry.path(), lines);
    std::fclose(f);
  }
}

}  // namespace

TEST_CASE("fast path: takes the common numeric records", "[parser][fast]") {
  for (const char* t :
       {"GOTO/1,2,3", "GOTO / 7.4300, 5.8500, 3.7750", "  goto/-0.000000,95.,.9625", "FEDRAT/250",
        "CIRCLE/1,2,3,0,0,1,5,0.06,0.5,20,0", "RAPID", "FINI ", "GOTO/1,2,3,", "LOADTL/2,1", "END-OF-PATH"}) {
    INFO(t);
    CHECK(fast_accepts(t));
    CHECK(fast_path_difference(t).empty());
    CHECK(goto_statement_difference(t).empty());
  }
}

TEST_CASE("fast path: leaves everything else to the grammar", "[parser][fast]") {
  for (const char* t : {"GOTO/1,,3", "GOTO/1.5E-3,0,0", "SPINDL/RPM,800", "PARTNO 12", "PPRINT/1,2",
                        "TOOL PATH/1", "$$ 1,2", "1,2,3", "CHANNEL,1", "GOTO/1 2,3", "GOTO 1,2,3",
                        "GOTO/1STPECK", "GOTO/inf,0,0", "GOTO/1234567890123456,0,0", "GOTO/1,2,3)"}) {
    INFO(t);
    CHECK_FALSE(fast_accepts(t));
    CHECK(goto_statement_difference(t).empty());
  }
}

TEST_CASE("fast path: random numeric records read as the grammar reads them", "[parser][fast]") {
  std::mt19937_64 rng(11);
  const char* majors[] = {"GOTO", "FROM", "circle", "FEDRAT", "X_1", "GO-TO"};
  const char* blanks[] = {"", " ", "  ", "\t"};
  int accepted = 0;
  for (int i = 0; i < 20000; ++i) {
    std::string t = blanks[rng() % 4];
    t += majors[rng() % 6];
    t += blanks[rng() % 4];
    t += '/';
    int n = 1 + static_cast<int>(rng() % 7);
    for (int k = 0; k < n; ++k) {
      if (k) t += ',';
      t += blanks[rng() % 4];
      char buf[48];
      double v = std::uniform_real_distribution<double>(-1e5, 1e5)(rng);
      const char* forms[] = {"%.4f", "%.10f", "%.0f", "%.0f.", "%g", "+%.3f"};
      std::snprintf(buf, sizeof buf, forms[rng() % 6], v);
      t += buf;
      t += blanks[rng() % 4];
    }
    if (rng() % 5 == 0) t += ',';
    if (fast_accepts(t)) ++accepted;
    INFO(t);
    REQUIRE(fast_path_difference(t).empty());
    REQUIRE(goto_statement_difference(t).empty());
  }
  CHECK(accepted > 10000);  // the fast path is really taken
}

TEST_CASE("fast path: the real CL files read alike", "[parser][fast][samples]") {
  int records = 0, accepted = 0;
  for_each_sample_file([&](const std::filesystem::path& path, line_reader& lines) {
    logical_record lr;
    while (lines.next(lr)) {
      ++records;
      if (fast_accepts(lr.text)) ++accepted;
      INFO(path.filename().string() << ":" << lr.line << ": " << lr.text);
      REQUIRE(fast_path_difference(lr.text).empty());
      REQUIRE(goto_statement_difference(lr.text).empty());
    }
  });
  CHECK(records > 5000);
  CHECK(accepted > records / 2);
}

TEST_CASE("the GOTO lane builds what build() builds", "[parser][fast]") {
  // RAPID before it, six numbers and the modal axis, a Pro/E coordinate line after it, a
  // CIRCLE it ends on, a GODLTA from where it ends, the wrong counts, words, and a record
  // that does not parse before a coordinate line.
  const char* job[] = {"RAPID",
                       "GOTO/1,2,3",
                       "GOTO/4,5,6,0,0,1",
                       "goto / 7.5, 8, 9 ",
                       "10,11,12",
                       "GOTO/1,1,1",
                       "CIRCLE/0,0,0,0,0,1,5",
                       "GOTO/5,0,0",
                       "GOTO/0,5,0",
                       "GODLTA/1,1,1",
                       "GOTO/1,2",
                       "13,14,15",
                       "GOTO/1,2,3,4",
                       "GOTO/1,2,3,4,5,6,7",
                       "GOTO/1,2,ABC",
                       "RAPID",
                       "FROM/1,1,1",
                       "GOTO/0,0,0",
                       "GOTO/1,2,3,",
                       "GOTOX/1,2,3",
                       "GoTo/2,3,4",
                       "G0TO/1,2,3",
                       "GOT/1,2,3",
                       "GOTO/1,,3",
                       "16,17,18",
                       "GOTO/-0,+2.5,.5",
                       "END"};
  for (dialect d : {dialect::generic, dialect::creo, dialect::nx}) {
    goto_lane_pair p(d);
    int line = 0;
    for (const char* text : job) {
      INFO(text);
      CHECK(p.feed(text, ++line) == "");
    }
    CHECK(p.taken == 10);
  }
  // A script that takes records gets every record through build().
  event_builder b(dialect::generic);
  b.set_script_records({"GOTO"}, false);
  cl_record r;
  record_error err;
  REQUIRE(parse_record("GOTO/1,2,3", r, err));
  event_queue q;
  CHECK_FALSE(b.build_goto(r, 1, q));
  const double n[] = {1, 2, 3};
  CHECK_FALSE(b.build_goto(n, 3, 1, q));
  CHECK(q.empty());
}

TEST_CASE("the GOTO lane: the real CL files build alike", "[parser][fast][samples]") {
  int taken = 0;
  for_each_sample_file([&](const std::filesystem::path& path, line_reader& lines) {
    goto_lane_pair p(detect_dialect(lines.peek(64 * 1024)));
    logical_record lr;
    while (lines.next(lr)) {
      INFO(path.filename().string() << ":" << lr.line << ": " << lr.text);
      REQUIRE(p.feed(lr.text, lr.line) == "");
    }
    taken += p.taken;
  });
  CHECK(taken > 2000);
}
