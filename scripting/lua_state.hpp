#pragma once
// Inside scripting/ only: the state behind a lua_script. lua_script.cpp loads the script and
// runs its hooks in protected calls under the budgets; lua_sandbox.cpp builds the script's
// _ENV, the post table and the guarded library functions.
#include <ctime>
#include <string>
#include <vector>

// Lua built as C++ (liblua5.4-c++, CMakeLists.txt): C++ linkage, no extern "C".
#include <lauxlib.h>
#include <lua.h>

#include "scripting/lua_script.hpp"

namespace twinpost::scripting {

/// Why `block` cannot go into a program as one block ("" when it can): a '%', a NUL or other
/// control byte, or a byte >= 0x80, said as "a '%' (...)" / "the control byte \\x1b (...)" /
/// "the byte \\xc2 (...)".
std::string block_fault(std::string_view block);
/// Whether `block` holds none of them (nor a line break): one table look-up a byte.
bool block_clean(std::string_view block);

/// Which budget ran out.
enum class spent { none, call, job_instructions, job_time };

/// The library functions the sandbox wraps, kept to be called from the wrappers.
struct wrapped_functions {
  lua_CFunction find = nullptr, match = nullptr, gmatch = nullptr, gsub = nullptr, rep = nullptr;
  lua_CFunction setmetatable = nullptr;
};

struct script_state {
  enum hook { h_record, h_tool_change, h_program_start, h_program_end, h_block, h_count };

  std::string name;    // "catcher.lua"
  std::string dir;     // where post.read_file looks
  std::string source;  // the script's text, for the line an error quotes
  script_limits limits;
  std::size_t used = 0;  // bytes the state holds
  lua_State* L = nullptr;
  int hook_ref[h_count] = {LUA_NOREF, LUA_NOREF, LUA_NOREF, LUA_NOREF, LUA_NOREF};
  script_host* host = nullptr;  // set for the length of one call
  wrapped_functions orig;

  // The budgets. The count hook fires every `slice` VM instructions, across calls, so that
  // `job_count` (those instructions and the bytes of C work charged) is exact to a slice.
  long long job_count = 0;
  long long call_start = 0;    // job_count when the call began
  long long call_charged = 0;  // C work charged in this call (not the call's budget)
  int slice = 0;
  double seconds = 0;  // inside calls, before this one
  double call_began = 0;
  bool running = false;            // inside run(): the allocator charges large growths
  std::vector<void*> big_strings;  // the live strings of 1 MB or more (lua_script.cpp, alloc)
  // A budget ran out: from then on every instruction raises again, so a pcall in the script
  // cannot swallow the error and go on. `call` ends with the call; the job's budgets hold.
  spent exhausted = spent::none;
  int exhausted_line = 0;
  bool panicked = false;  // an unprotected error: the state is not touched again

  // What the script wrote and warned in the job.
  std::size_t emitted = 0, warned_bytes = 0;
  long warnings = 0;

  ~script_state();

  static script_state* of(lua_State* L) {
    void* ud = nullptr;
    lua_getallocf(L, &ud);
    return static_cast<script_state*>(ud);
  }
  static double now() {
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC_COARSE, &ts);
    return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
  }

  // lua_script.cpp: the budgets.
  spent over() const;
  void arm();
  static void budget_hook(lua_State* L, lua_Debug* ar);
  /// Charges `units` of C work (bytes processed) to the job's budget; raises when spent.
  void charge(lua_State* L, double units);
  [[noreturn]] void raise_spent(lua_State* L, spent s);

  // lua_sandbox.cpp: the script's _ENV, left on the stack.
  void make_env();

  // lua_script.cpp: errors and calls.
  [[noreturn]] void raise(int line, std::string message);
  [[noreturn]] void fail(int rc);
  std::string spent_message() const;
  void load(std::string_view text);
  /// Runs `body(L)` in a protected call under the budgets, with `h` receiving post.emit.
  template <class F>
  void run(F& body, script_host* h);
};

}  // namespace twinpost::scripting
