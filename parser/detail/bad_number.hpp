#pragma once
// What is wrong with a token meant as a number that the grammar did not read as one:
// `1e999` (out of range), `nan`/`-inf` (not a number), `1e`, `1.2.3` (malformed). Shared by
// the record parser (tokens the grammar stopped at) and the event builder (words where a
// number belongs), so both name the token alike.
#include <charconv>
#include <optional>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "parser/record.hpp"
#include "support/ascii.hpp"

namespace twinpost::detail {

/// The message for `token` when it is a number gone wrong, else nullopt (a real word).
inline std::optional<std::string> bad_number_message(std::string_view token) {
  std::string_view body = token;
  if (!body.empty() && (body.front() == '-' || body.front() == '+')) body.remove_prefix(1);
  if (body.empty()) return std::nullopt;
  if (word_is(body, "NAN") || word_is(body, "INF") || word_is(body, "INFINITY"))
    return fmt::format("not a number: '{}'", token);
  const char c0 = body.front();
  if (!(ascii::is_digit(c0) || c0 == '.')) return std::nullopt;
  if (body.find_first_not_of("0123456789.eE+-") != std::string_view::npos) return std::nullopt;
  double v = 0;
  const auto r = std::from_chars(body.data(), body.data() + body.size(), v);
  if (r.ec == std::errc::result_out_of_range && r.ptr == body.data() + body.size())
    return fmt::format("number out of range: '{}'", token);
  if (r.ec == std::errc() && r.ptr == body.data() + body.size()) return std::nullopt;  // a number after all
  return fmt::format("malformed number '{}'", token);
}

}  // namespace twinpost::detail
