// Partner lists of waits, written by the post and read by the checker
// (machines/partner_list.hpp).
#include <catch2/catch.hpp>

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "machines/partner_list.hpp"

using namespace twinpost;

namespace {

// The channels of subset `bits` of 1..n (bit c-1 set: channel c), ascending.
std::vector<int> subset(std::uint32_t bits, int n) {
  std::vector<int> out;
  for (int c = 1; c <= n; ++c)
    if (bits & (std::uint32_t{1} << (c - 1))) out.push_back(c);
  return out;
}

// Encodes every non-empty subset of 1..n, checks that it decodes to the same channels and
// that no two subsets share a text; returns how many subsets were checked.
int round_trip_all(int n, partner_style style) {
  std::set<std::string> texts;
  std::vector<int> back;
  int checked = 0;
  for (std::uint32_t bits = 1; bits < (std::uint32_t{1} << n); ++bits) {
    const std::vector<int> channels = subset(bits, n);
    const std::string text = partner_list(channels, style);
    INFO("subset " << bits << " of 1.." << n << " written as '" << text << "'");
    REQUIRE(decode_partner_list(text, style, back));
    REQUIRE(back == channels);
    REQUIRE(texts.insert(text).second);
    ++checked;
  }
  return checked;
}

}  // namespace

TEST_CASE("partner lists in the machine's style, up to channel 64", "[machines][partners]") {
  CHECK(partner_list({1, 2}, partner_style::path_numbers) == "12");
  CHECK(partner_list({1, 2, 3}, partner_style::path_numbers) == "123");
  CHECK(partner_list({2, 9}, partner_style::path_numbers) == "29");
  CHECK(partner_list({1, 2}, partner_style::binary) == "3");
  CHECK(partner_list({1, 3}, partner_style::binary) == "5");
  CHECK(partner_list({1, 2, 3}, partner_style::binary) == "7");
  CHECK(partner_list({1, 64}, partner_style::binary) == "9223372036854775809");
  CHECK(partner_list({1, 2}, partner_style::none) == "");
}

TEST_CASE("every non-empty channel set survives a round trip in both styles", "[machines][partners]") {
  // Path numbers name a channel by one digit: the loader allows them up to 9 channels.
  for (int n = 1; n <= 9; ++n) {
    INFO("path_numbers, " << n << " channels");
    CHECK(round_trip_all(n, partner_style::path_numbers) == (1 << n) - 1);
  }
  for (int n = 1; n <= 16; ++n) {
    INFO("binary, " << n << " channels");
    CHECK(round_trip_all(n, partner_style::binary) == (1 << n) - 1);
  }
  // Binary masks reach channel 64 (the top bit of an unsigned 64-bit mask).
  std::vector<int> back;
  for (const std::vector<int>& channels :
       {std::vector<int>{63, 64}, std::vector<int>{1, 32, 33, 64}, std::vector<int>{64}}) {
    REQUIRE(decode_partner_list(partner_list(channels, partner_style::binary), partner_style::binary, back));
    CHECK(back == channels);
  }
  std::vector<int> all64;
  for (int c = 1; c <= 64; ++c) all64.push_back(c);
  CHECK(partner_list(all64, partner_style::binary) == "18446744073709551615");
  REQUIRE(decode_partner_list("18446744073709551615", partner_style::binary, back));
  CHECK(back == all64);
}

TEST_CASE("partner lists not in the machine's form are refused", "[machines][partners]") {
  std::vector<int> p{7};
  for (const char* text : {"", "-12", "+12", "1.5", "12.", " 12", "12 ", "1a", "#1", "P12", "[12]"}) {
    INFO("'" << text << "'");
    CHECK_FALSE(decode_partner_list(text, partner_style::path_numbers, p));
    CHECK(p.empty());
    CHECK_FALSE(decode_partner_list(text, partner_style::binary, p));
    CHECK(p.empty());
  }
  // One past the largest 64-bit mask: there is no channel 65.
  CHECK_FALSE(decode_partner_list("18446744073709551616", partner_style::binary, p));
  CHECK(p.empty());
}

TEST_CASE("lists in the right form but naming wrong channels decode as written", "[machines][partners]") {
  // The form is right, so they decode; check/sync_check then reports each at its place in
  // the program (tests/sync_check_test.cpp: channel 4 of 3, channel 1 twice).
  std::vector<int> p;
  REQUIRE(decode_partner_list("112", partner_style::path_numbers, p));
  CHECK(p == std::vector<int>{1, 1, 2});
  REQUIRE(decode_partner_list("14", partner_style::path_numbers, p));
  CHECK(p == std::vector<int>{1, 4});
  REQUIRE(decode_partner_list("0", partner_style::path_numbers, p));
  CHECK(p == std::vector<int>{0});
  REQUIRE(decode_partner_list("0", partner_style::binary, p));
  CHECK(p.empty());
  REQUIRE(decode_partner_list("007", partner_style::binary, p));
  CHECK(p == std::vector<int>{1, 2, 3});
}
