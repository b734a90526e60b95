// Records that select heads and channels and mark synchronisation points.
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "parser/detail/word_events.hpp"
#include "support/ascii.hpp"

namespace twinpost::detail {

namespace {
std::size_t where(const cl_record& r) { return r.args.empty() ? r.major_offset : r.args.front().offset; }

// A sync or channel number: a whole number an int holds. 1.5 would be read as 1 and pair with
// SYNC/1, 3000000000 and 4000000000 both as the largest int (attack 49).
bool whole_number(double v) {
  return std::floor(v) == v && std::abs(v) <= static_cast<double>(std::numeric_limits<int>::max());
}
}  // namespace

std::optional<head_event> read_head(const cl_record& r, build_issues& issues) {
  head_event e;
  if (!r.args.empty() && r.args[0].kind == arg_kind::number && r.args[0].number >= 1) {
    e.which = head_select::number;
    e.number = as_int(r.args[0].number);
    return e;
  }
  if (!r.args.empty() && r.args[0].kind == arg_kind::word) {
    std::string_view w = r.args[0].word;
    if (word_is(w, "MAIN")) return head_event{head_select::main, 0};
    if (word_is(w, "SIDE")) return head_event{head_select::side, 0};
    if (word_is(w, "BOTH")) return head_event{head_select::both, 0};
  }
  issues.push_back({severity::error, where(r), "HEAD needs a head number, MAIN, SIDE or BOTH"});
  return std::nullopt;
}

std::optional<channel_event> read_channel(const cl_record& r, build_issues& issues) {
  if (!r.args.empty() && r.args[0].kind == arg_kind::number && r.args[0].number >= 1)
    return channel_event{as_int(r.args[0].number)};
  issues.push_back({severity::error, where(r), fmt::format("{} needs a channel number", upper(r.major))});
  return std::nullopt;
}

std::optional<sync_event> read_sync(const cl_record& r, build_issues& issues) {
  std::vector<double> n = numbers_of(r);
  if (n.size() < 3) {
    issues.push_back({severity::error, where(r), "SYNC needs a sync number and two channels"});
    return std::nullopt;
  }
  for (double v : n)
    if (!whole_number(v)) {
      issues.push_back(
          {severity::error, where(r),
           fmt::format("SYNC: {} is no sync or channel number: a whole number up to 2147483647 is", v)});
      return std::nullopt;
    }
  sync_event e;
  e.source = sync_source::catia;
  e.index = as_int(n[0]);
  e.channels = {as_int(n[1]), as_int(n[2])};
  if (n.size() > 3) e.master = as_int(n[3]);
  return e;
}

std::optional<sync_event> read_synctr(const cl_record& r, build_issues& issues) {
  if (r.args.empty() || r.args[0].kind != arg_kind::word || !word_is(r.args[0].word, "NEXT")) {
    issues.push_back({severity::error, where(r), "SYNCTR needs NEXT[,marker[,channels]]"});
    return std::nullopt;
  }
  sync_event e;
  e.source = sync_source::icam;
  std::size_t i = 1;
  // A marker left out is the channel's previous one plus one: the router counts per channel.
  for (std::size_t k = i; k < r.args.size(); ++k)
    if (r.args[k].kind == arg_kind::number && !whole_number(r.args[k].number)) {
      issues.push_back(
          {severity::error, r.args[k].offset,
           fmt::format("SYNCTR: {} is no marker or channel number: a whole number up to 2147483647 is",
                       r.args[k].number)});
      return std::nullopt;
    }
  if (i < r.args.size() && r.args[i].kind == arg_kind::number) {
    e.index = as_int(r.args[i].number);
    ++i;
  }
  for (; i < r.args.size(); ++i)
    if (r.args[i].kind == arg_kind::number) e.channels.push_back(as_int(r.args[i].number));
  return e;
}

std::optional<sync_event> read_manus_sync(std::string_view text) {
  // UDE: MANUSPOST - SYNCHRONIZATION/SYNCHRONIZATION NUMBER=n
  std::string u = upper(text);
  if (u.rfind("UDE:", 0) != 0 || u.find("SYNCHRONIZATION") == std::string::npos) return std::nullopt;
  std::size_t eq = u.find("NUMBER=");
  if (eq == std::string::npos) return std::nullopt;
  std::size_t p = eq + 7;
  while (p < u.size() && u[p] == ' ') ++p;
  // Digits only (from_chars would take a sign); one too big for an int is not a sync.
  int n = 0;
  if (p == u.size() || !ascii::is_digit(u[p])) return std::nullopt;
  if (std::from_chars(u.data() + p, u.data() + u.size(), n).ec != std::errc{}) return std::nullopt;
  sync_event e;
  e.source = sync_source::manus;
  e.index = n;
  return e;
}

}  // namespace twinpost::detail
