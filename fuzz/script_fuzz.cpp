// libFuzzer target: generated Lua scripts through the machine script's sandbox
// (scripting/lua_script, docs/scripting.md) with small limits. The first byte picks how many
// blocks go through on_block (1..8) and whether the hooks are called again after an error;
// the rest is the script, loaded as the file fz.lua of a scratch folder that also holds a
// regular file (tools.csv), a symbolic link to /etc/passwd (passwd) and a FIFO (fifo).
// Properties:
// - only script_error comes out of the load and of every hook: no other exception, no crash,
//   no sanitizer report, no abort from an unprotected Lua error;
// - every error names the script ("fz.lua: " or "fz.lua:LINE: ") and holds no control byte
//   but tab;
// - what reaches the post holds no line break, '%', NUL or control byte (blocks), no control
//   byte but tab (warnings), and stays within the emit and warning limits;
// - no hang: the input's whole run takes under 20 s of wall-clock time (the job's time
//   budget is 1 s; the pattern and C-work bounds hold inside C functions).
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "fuzz/fuzz_support.hpp"
#include "scripting/lua_script.hpp"

using namespace twinpost;
using namespace twinpost::scripting;

namespace {

bool clean(std::string_view s, bool block) {
  for (const char c : s) {
    const auto b = static_cast<unsigned char>(c);
    if (b == 0x7f || (b < 0x20 && (block || b != '\t')) || (block && c == '%')) return false;
  }
  return true;
}

struct checking_host : script_host {
  std::size_t bytes = 0, warned = 0;
  bool emit(std::string_view b) override {
    fuzz::require(clean(b, true), "post.emit passed a block with a line break, '%' or a control byte");
    bytes += b.size();
    return true;
  }
  void warning(std::string_view m) override {
    fuzz::require(clean(m, false), "post.warning passed a control byte");
    warned += 1;
  }
};

const std::string& folder() {
  static const std::string dir = [] {
    const std::string d = fuzz::scratch_dir() + "/script";
    ::mkdir(d.c_str(), 0700);
    fuzz::write_all(d + "/tools.csv", "5;DRILL 8\n6;MILL 10\n");
    (void)::symlink("/etc/passwd", (d + "/passwd").c_str());
    (void)::mkfifo((d + "/fifo").c_str(), 0600);
    return d;
  }();
  return dir;
}

void check_error(const script_error& e) {
  const std::string what = e.what();
  fuzz::require(what.rfind("fz.lua:", 0) == 0, "a script error that does not name the script");
  fuzz::require(clean(what, false), "a script error with a control byte");
}

// Runs `f`; a script_error is checked, anything else escapes (a finding).
template <class F>
bool call(F&& f) {
  try {
    f();
    return true;
  } catch (const script_error& e) {
    check_error(e);
    return false;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int blocks = 1 + data[0] % 8;
  const bool go_on = (data[0] & 0x10) != 0;
  const std::string_view source(reinterpret_cast<const char*>(data) + 1, size - 1);
  script_limits limits;
  limits.instructions_per_call = 100'000;
  limits.instructions_per_job = 2'000'000;
  limits.seconds_per_job = 1;
  limits.memory_bytes = 16u << 20;
  limits.read_file_bytes = 64u << 10;
  limits.pattern_steps = 1e7;
  limits.emit_bytes = 64u << 10;
  limits.warnings = 50;
  limits.warning_bytes = 4096;
  const auto t0 = std::chrono::steady_clock::now();
  checking_host host;
  {
    std::unique_ptr<lua_script> s;
    if (call([&] { s = std::make_unique<lua_script>(folder() + "/fz.lua", source, limits); })) {
      bool ok = true;
      auto step = [&](auto&& f) {
        if (ok || go_on) ok = call(f) && ok;
      };
      script_context ctx{1, "O1000", 3};
      step([&] { s->on_program_start(ctx, host); });
      step([&] { s->on_tool_change({1, 1, "TURN", "turn", 100, 0, 1}, host); });
      step([&] { s->on_record({"PARTS_CATCHER", {"ON", "2"}, 4}, host); });
      const char* texts[] = {"G0 X44. Z2.", "G1 Z-30. F0.2", "M100", "(T1 DRILL)"};
      for (int i = 0; i < blocks; ++i) {
        step([&] {
          std::string r;
          const std::string_view text = texts[i % 4];
          if (s->on_block(text, ctx, host, r) == block_verdict::replace)
            fuzz::require(clean(r, true), "on_block's replacement has a line break, '%' or a control byte");
        });
      }
      step([&] { s->on_program_end(ctx, host); });
    }
  }  // the state closes here: no finalizer may run on
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  fuzz::require(secs < 20, "a script ran past its budgets (20 s)");
  fuzz::require(host.bytes <= limits.emit_bytes + 4096, "post.emit wrote past the job's limit");
  fuzz::require(host.warned <= static_cast<std::size_t>(limits.warnings),
                "more warnings than the job's limit");
  return 0;
}
