#pragma once
// What the router's tests share (tests/wait_plan_test.cpp, tests/wait_plan_three_test.cpp): a
// machine of `n` channels, head k on channel k, waits M100-M109; and a sink that writes each
// event as "c<channel>:<line>" and each wait as "c<channel>:M<code>", followed by "/<its
// partners>" when `partners` is on.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <string>

#include "channels/router.hpp"

namespace twinpost::test {

inline machine router_machine(int n) {
  machine m;
  m.name = n == 2 ? "twin" : "three";
  for (int c = 1; c <= n; ++c) {
    channel_def ch;
    ch.number = c;
    ch.heads = {c};
    m.channels.push_back(ch);
  }
  m.waits.first = 100;
  m.waits.last = 109;
  return m;
}

struct trace_sink : channel_sink {
  explicit trace_sink(bool partners = false) : partners_(partners) {}
  std::string trace;
  void on_event(int ch, const event& e, bool) override { trace += fmt::format("c{}:{}\n", ch, e.line); }
  void on_wait(int ch, const wait_mark& w) override {
    trace += partners_ ? fmt::format("c{}:M{}/{}\n", ch, w.code, fmt::join(w.partners, ""))
                       : fmt::format("c{}:M{}\n", ch, w.code);
  }

 private:
  bool partners_;
};

}  // namespace twinpost::test
