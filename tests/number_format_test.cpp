// NC numbers: exact expectations, and the fast path checked against std::to_chars.
#include <catch2/catch.hpp>

#include <charconv>
#include <cmath>
#include <random>
#include <string>

#include "formats/number_format.hpp"

using namespace twinpost;

namespace {

// The reference rule: to_chars rounds the binary value, then zeros and "-0" are trimmed.
std::string reference(double v, number_style s) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, s.decimals);
  char* b = buf;
  char* e = r.ptr;
  if (s.decimals > 0) {
    while (e > b && e[-1] == '0') --e;
    if (!s.trailing_point && e > b && e[-1] == '.') --e;
  }
  bool zero = true;
  for (char* p = b; p < e; ++p)
    if (*p >= '1' && *p <= '9') zero = false;
  if (zero && *b == '-') ++b;
  return std::string(b, e);
}

}  // namespace

TEST_CASE("NC numbers: trailing point, trimmed zeros, no -0", "[formats]") {
  number_style fanuc{3, true};
  CHECK(format_nc_number(10, fanuc) == "10.");
  CHECK(format_nc_number(12.5, fanuc) == "12.5");
  CHECK(format_nc_number(-0.0004, fanuc) == "0.");
  CHECK(format_nc_number(-0.0, fanuc) == "0.");
  CHECK(format_nc_number(-12.3456, fanuc) == "-12.346");
  CHECK(format_nc_number(0.0005001, fanuc) == "0.001");
  number_style plain{3, false};
  CHECK(format_nc_number(10, plain) == "10");
  CHECK(format_nc_number(-0.0001, plain) == "0");
  CHECK(format_nc_number(1200.4, {0, false}) == "1200");
  CHECK(format_nc_number(0.25, {4, true}) == "0.25");
  // Exact ties go to even, as std::to_chars and printf round them.
  CHECK(format_nc_number(0.0625, fanuc) == "0.062");
  CHECK(format_nc_number(12.1875, fanuc) == "12.188");
  CHECK(format_nc_number(-0.125, {2, true}) == "-0.12");
  CHECK(format_nc_number(2.5, {0, false}) == "2");
  CHECK(format_nc_number(3.5, {0, false}) == "4");
  CHECK(format_nc_number(1e20, fanuc) == "100000000000000000000.");
}

TEST_CASE("NC numbers: the fast path agrees with to_chars", "[formats]") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> wide(-2000, 2000);
  std::uniform_real_distribution<double> huge(-5e8, 5e8);  // whole parts past eight digits
  std::uniform_real_distribution<double> grid(-2e6, 2e6);
  long mismatches = 0;
  for (int decimals : {0, 1, 2, 3, 4, 6, 8, 9}) {
    for (bool point : {true, false}) {
      number_style s{decimals, point};
      for (int i = 0; i < 50000; ++i) {
        double v = wide(rng);
        double on_grid = std::round(grid(rng)) / 10000.0;                     // CL-like 4-decimal values
        double tie = (std::round(grid(rng)) + 0.5) / std::pow(10, decimals);  // near halves
        // Exact binary halves: odd / 2^(d+1) is k + 0.5 in units of 10^-d (0.0625 at 3).
        double exact_tie = (2 * std::round(grid(rng) / 2) + 1) / std::pow(2, decimals + 1);
        for (double x : {v, on_grid, tie, exact_tie, huge(rng)})
          if (format_nc_number(x, s) != reference(x, s)) ++mismatches;
      }
    }
  }
  CHECK(mismatches == 0);
}
