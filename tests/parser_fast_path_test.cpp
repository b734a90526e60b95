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

}  // namespace

TEST_CASE("fast path: takes the common numeric records", "[parser][fast]") {
  for (const char* t :
       {"GOTO/1,2,3", "GOTO / 7.4300, 5.8500, 3.7750", "  goto/-0.000000,95.,.9625", "FEDRAT/250",
        "CIRCLE/1,2,3,0,0,1,5,0.06,0.5,20,0", "RAPID", "FINI ", "GOTO/1,2,3,", "LOADTL/2,1", "END-OF-PATH"}) {
    INFO(t);
    CHECK(fast_accepts(t));
    CHECK(fast_path_difference(t).empty());
  }
}

TEST_CASE("fast path: leaves everything else to the grammar", "[parser][fast]") {
  for (const char* t : {"GOTO/1,,3", "GOTO/1.5E-3,0,0", "SPINDL/RPM,800", "PARTNO 12", "PPRINT/1,2",
                        "TOOL PATH/1", "$$ 1,2", "1,2,3", "CHANNEL,1", "GOTO/1 2,3", "GOTO 1,2,3",
                        "GOTO/1STPECK", "GOTO/inf,0,0", "GOTO/1234567890123456,0,0", "GOTO/1,2,3)"}) {
    INFO(t);
    CHECK_FALSE(fast_accepts(t));
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
  }
  CHECK(accepted > 10000);  // the fast path is really taken
}

TEST_CASE("fast path: the real CL files read alike", "[parser][fast][samples]") {
  const std::filesystem::path dir = test::require_shared_samples();
  int records = 0, accepted = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    if (!entry.is_regular_file() || entry.path().filename() == "README.md") continue;
    std::FILE* f = std::fopen(entry.path().c_str(), "rb");
    REQUIRE(f);
    file_source src(f);
    line_reader lines(src);
    logical_record lr;
    while (lines.next(lr)) {
      ++records;
      if (fast_accepts(lr.text)) ++accepted;
      INFO(entry.path().filename().string() << ":" << lr.line << ": " << lr.text);
      REQUIRE(fast_path_difference(lr.text).empty());
    }
    std::fclose(f);
  }
  CHECK(records > 5000);
  CHECK(accepted > records / 2);
}
