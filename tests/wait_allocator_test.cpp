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

TEST_CASE("partner lists in the machine's style, up to channel 64", "[channels]") {
  CHECK(partner_list({1, 2, 3}, partner_style::path_numbers) == "123");
  CHECK(partner_list({1, 2}, partner_style::binary) == "3");
  CHECK(partner_list({1, 64}, partner_style::binary) == "9223372036854775809");
  CHECK(partner_list({1, 2}, partner_style::none) == "");
}
