// Blocks per second through a script's on_block that returns its argument (issue 25's
// benchmark goal: at least 1 M/s). Usage: lua_on_block [BLOCKS]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "scripting/lua_script.hpp"

namespace {
struct null_host : twinpost::scripting::script_host {
  bool emit(std::string_view) override { return true; }
  void warning(std::string_view) override {}
};
}  // namespace

int main(int argc, char** argv) {
  using namespace twinpost::scripting;
  long n = argc > 1 ? std::atol(argv[1]) : 2'000'000;
  lua_script s("bench.lua", "function on_block(text, ctx) return text end");
  null_host host;
  std::string out, block = "N120 G1 X42.512 Z-17.25 F0.15";
  script_context ctx{1, "O1000", 0};
  auto t0 = std::chrono::steady_clock::now();
  long replaced = 0;
  for (long i = 0; i < n; ++i) replaced += s.on_block(block, ctx, host, out) == block_verdict::replace;
  double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%ld blocks in %.3f s: %.2f M blocks/s (%ld replaced)\n", n, secs, n / secs / 1e6, replaced);
  return replaced == n ? 0 : 1;
}
