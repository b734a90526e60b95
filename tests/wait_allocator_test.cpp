// Wait codes handed out in turn (channels/wait_allocator.hpp).
#include <catch2/catch.hpp>

#include <climits>
#include <optional>
#include <string>
#include <vector>

#include "channels/wait_allocator.hpp"

using namespace twinpost;

namespace {
std::string codes(wait_allocator& a, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) {
    const std::optional<int> c = a.next();
    if (!out.empty()) out += ' ';
    out += c ? std::to_string(*c) : "none";
  }
  return out;
}
}  // namespace

TEST_CASE("the allocator steps through the range, skips excluded codes and reuses", "[channels]") {
  wait_rules r;
  r.first = 100;
  r.last = 106;
  r.step = 2;
  r.excluded = {102};
  wait_allocator once(r);
  CHECK(codes(once, 5) == "100 104 106 none none");
  r.reuse = true;
  wait_allocator again(r);
  CHECK(codes(again, 5) == "100 104 106 100 104");
  CHECK(again.handed_out() == 5);
}

TEST_CASE("a range at the end of an int does not overflow the allocator", "[channels]") {
  // The loader refuses such a range; a machine made in code may still hold one (UBSan).
  wait_rules r;
  r.first = 2147483640;
  r.last = INT_MAX;
  r.step = 5;
  wait_allocator once(r);
  CHECK(codes(once, 3) == "2147483640 2147483645 none");
  r.reuse = true;
  wait_allocator again(r);
  CHECK(codes(again, 3) == "2147483640 2147483645 2147483640");
  r.step = 0;  // no grid at all: nothing, and no endless loop
  wait_allocator none(r);
  CHECK(codes(none, 1) == "none");
}

TEST_CASE("a range used up without reuse gives nothing from then on", "[channels]") {
  wait_rules r;
  r.first = 100;
  r.last = 103;
  wait_allocator a(r);
  CHECK(codes(a, 6) == "100 101 102 103 none none");
  CHECK(a.handed_out() == 4);
}

TEST_CASE("the step is counted from first, and a last off the grid is never handed out", "[channels]") {
  wait_rules r;
  r.first = 950;
  r.last = 967;
  r.step = 5;
  wait_allocator a(r);
  CHECK(codes(a, 5) == "950 955 960 965 none");
  r.reuse = true;
  wait_allocator again(r);
  CHECK(codes(again, 6) == "950 955 960 965 950 955");
}

TEST_CASE("excluded codes at both ends of the range are skipped, also after reuse", "[channels]") {
  wait_rules r;
  r.first = 100;
  r.last = 104;
  r.excluded = {100, 104};
  wait_allocator once(r);
  CHECK(codes(once, 4) == "101 102 103 none");
  r.reuse = true;
  wait_allocator again(r);
  CHECK(codes(again, 7) == "101 102 103 101 102 103 101");
  CHECK(again.handed_out() == 7);
}

TEST_CASE("reuse starts again at first, in the same order", "[channels]") {
  wait_rules r;
  r.first = 200;
  r.last = 202;
  r.reuse = true;
  wait_allocator a(r);
  CHECK(codes(a, 8) == "200 201 202 200 201 202 200 201");
  r.last = 200;  // a range of one code: every wait has it
  wait_allocator one(r);
  CHECK(codes(one, 3) == "200 200 200");
  r.last = 201;  // every code excluded: nothing, even with reuse, and no endless loop
  r.excluded = {200, 201};
  wait_allocator none(r);
  CHECK(codes(none, 2) == "none none");
  CHECK(none.handed_out() == 0);
}
