// channels/router: which channel gets each event and where the waits go, asserted as the
// exact trace a recording sink sees.
#include <catch2/catch.hpp>

#include <fmt/format.h>

#include <climits>
#include <string>

#include "channels/router.hpp"

using namespace twinpost;

namespace {

machine twin(int channels = 2, partner_style p = partner_style::none, bool reuse = false) {
  machine m;
  m.name = "twin";
  for (int c = 1; c <= channels; ++c) {
    channel_def ch;
    ch.number = c;
    ch.heads = {c};
    ch.head_names = {c == 1 ? "MAIN" : c == 2 ? "SIDE" : "THIRD"};
    m.channels.push_back(ch);
  }
  m.waits.first = 100;
  m.waits.last = 103;
  m.waits.reuse = reuse;
  m.waits.partners = p;
  return m;
}

// "c1:goto" for events, "c2:M100" / "c1:M100P12" for waits, one per line.
struct trace_sink : channel_sink {
  std::string trace;
  void on_event(int ch, const event& e, bool both) override {
    const char* what = std::holds_alternative<motion_event>(e.data) ? "goto" : "other";
    trace += fmt::format("c{}:{}{}\n", ch, what, both ? "(both)" : "");
  }
  void on_wait(int ch, const wait_mark& w) override {
    trace += fmt::format("c{}:M{}{}{}\n", ch, w.code, w.partner_text.empty() ? "" : "P", w.partner_text);
  }
};

event go(int line) { return {line, motion_event{}}; }
event head(int n, int line = 0) { return {line, head_event{head_select::number, n}}; }
event head_both() { return {0, head_event{head_select::both, 0}}; }
event icam(std::optional<int> marker, std::vector<int> channels = {}) {
  sync_event s;
  s.source = sync_source::icam;
  s.index = marker;
  s.channels = std::move(channels);
  return {0, s};
}

std::string run(const machine& m, sync_policy p, const std::vector<event>& events, diagnostic_list& diags,
                std::vector<int> used = {1, 2}) {
  trace_sink sink;
  channel_router r(m, p, sink, diags, "job.cls", std::move(used));
  for (const event& e : events) r.route(e);
  r.finish(99);
  return sink.trace;
}

}  // namespace

TEST_CASE("sequential: a wait at every head switch, and a last one before the footers", "[router]") {
  diagnostic_list d;
  CHECK(run(twin(), sync_policy::sequential, {go(1), head(2), go(2), head(1), go(3)}, d) ==
        "c1:goto\n"
        "c1:M100\nc2:M100\n"
        "c2:goto\n"
        "c1:M101\nc2:M101\n"
        "c1:goto\n"
        "c1:M102\nc2:M102\n");
  CHECK(d.errors() == 0);
}

TEST_CASE("no wait before any channel has worked, and none twice in a row", "[router]") {
  diagnostic_list d;
  CHECK(run(twin(), sync_policy::sequential, {head(2), go(1), head(1), head(2), head(1)}, d) ==
        "c2:goto\n"
        "c1:M100\nc2:M100\n");
}

TEST_CASE("ICAM SYNCTR/NEXT without a marker counts per channel", "[router]") {
  diagnostic_list d;
  // Head 1 marks 1, 2; head 2 marks 1, 2: the same codes in the same order. Both end on
  // mark 2 with nothing after it, so the last common wait collapses into it.
  CHECK(run(twin(), sync_policy::explicit_marks,
            {go(1), icam({}), go(2), icam({}), head(2), go(3), icam({}), go(4), icam({})}, d) ==
        "c1:goto\nc1:M100\nc1:goto\nc1:M101\n"
        "c2:goto\nc2:M100\nc2:goto\nc2:M101\n");
  CHECK(d.errors() == 0);
}

TEST_CASE("an ICAM marker left out is named by the router's number in messages", "[router]") {
  diagnostic_list d;
  // Head 1 has marks 1 and 2; head 2's first mark without a number is its mark 1 (the
  // parser no longer numbers it: `twinpost parse` prints index=next).
  run(twin(), sync_policy::explicit_marks,
      {go(1), icam({}), go(2), icam({}), head(2), go(3), icam({}, {2, 5})}, d);
  REQUIRE(d.errors() == 1);
  CHECK(format_diagnostic(d.all().front()) ==
        "job.cls: error: sync 1 names channel 5, machine 'twin' has 2 channels\n");
}

TEST_CASE("an ICAM marker left out after marker INT_MAX stays INT_MAX", "[router]") {
  // Regression (moved from the parser): INT_MAX + 1 was a signed overflow. The mark after
  // it is the second occurrence of INT_MAX in both channels: the same code in both.
  diagnostic_list d;
  CHECK(run(twin(), sync_policy::explicit_marks,
            {go(1), icam(INT_MAX), go(2), icam({}), head(2), go(3), icam(INT_MAX), go(4), icam({})}, d) ==
        "c1:goto\nc1:M100\nc1:goto\nc1:M101\n"
        "c2:goto\nc2:M100\nc2:goto\nc2:M101\n");
  CHECK(d.errors() == 0);
}

TEST_CASE("a sync naming no channels means the channels the job uses", "[router]") {
  diagnostic_list d;
  // Three paths, the job uses 1 and 2: the mark is P12, the last wait takes in path 3.
  CHECK(run(twin(3, partner_style::path_numbers), sync_policy::explicit_marks,
            {go(1), icam(1), head(2), go(2), icam(1)}, d) ==
        "c1:goto\nc1:M100P12\nc2:goto\nc2:M100P12\n"
        "c1:M101P123\nc2:M101P123\nc3:M101P123\n");
}

TEST_CASE("HEAD/BOTH is framed by waits and copies events to both channels", "[router]") {
  diagnostic_list d;
  CHECK(run(twin(), sync_policy::explicit_marks, {go(1), head_both(), go(2), head(1), go(3)}, d) ==
        "c1:goto\n"
        "c1:M100\nc2:M100\n"
        "c1:goto(both)\nc2:goto(both)\n"
        "c1:M101\nc2:M101\n"
        "c1:goto\n"
        "c1:M102\nc2:M102\n");
}

TEST_CASE("running out of wait codes is one error naming the mark", "[router]") {
  diagnostic_list d;
  std::vector<event> events;
  for (int i = 0; i < 6; ++i) {
    events.push_back(go(10 + i));
    events.push_back(head(i % 2 == 0 ? 2 : 1, 20 + i));
  }
  run(twin(), sync_policy::sequential, events, d);
  REQUIRE(d.errors() == 1);
  CHECK(format_diagnostic(d.all().front()) ==
        "job.cls:24: error: no wait code left for a head switch: M100-M103 is used up and "
        "machine 'twin' does not reuse codes\n");
}

TEST_CASE("a machine that reuses codes starts its range again", "[router]") {
  diagnostic_list d;
  std::vector<event> events;
  for (int i = 0; i < 5; ++i) {
    events.push_back(go(i + 1));
    events.push_back(head(i % 2 == 0 ? 2 : 1));
  }
  std::string t = run(twin(2, partner_style::none, true), sync_policy::sequential, events, d);
  CHECK(d.errors() == 0);
  CHECK(t.find("c1:M103\n") != std::string::npos);
  CHECK(t.rfind("c2:M100\n") > t.find("c2:M103\n"));  // M100 again after M103
}
