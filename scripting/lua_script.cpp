// scripting/lua_script.hpp: the Lua state, its allocator with a ceiling, the budgets (the
// count hook, the job's count and clock) and the hooks' calls, each a protected call: no Lua
// error escapes unprotected (lua_atpanic is the last resort), so every failure is a
// script_error. The sandbox itself is lua_sandbox.cpp.
#include "scripting/lua_script.hpp"

#include <algorithm>
#include <charconv>
#include <cstdlib>

#include "scripting/confined_file.hpp"
#include "scripting/lua_state.hpp"

namespace twinpost::scripting {

script_error::script_error(std::string file_, int line_, std::string message_)
    : std::runtime_error(line_ > 0 ? file_ + ':' + std::to_string(line_) + ": " + message_
                                   : file_ + ": " + message_),
      file(std::move(file_)), line(line_), message(std::move(message_)) {}

namespace {

constexpr const char* hook_names[] = {"on_record", "on_tool_change", "on_program_start", "on_program_end",
                                      "on_block"};
// VM instructions between two looks at the budgets. One VM instruction may do C work of the
// length of a string (comparing two 30 MB strings: about 5 ms), so the slice bounds how far a
// loop of such instructions runs past the clock: 1 000 of them, about 5 s at 10 000.
constexpr long long hook_slice = 1'000;
// An allocation at least this large is C work worth a look at the budgets right away: a
// concatenation of long strings copies them in one instruction.
constexpr std::size_t big_allocation = 64u << 10;
// While a string at least this long lives, one VM instruction may work on it for a long time:
// comparing two 30 MB strings of NUL bytes is 30 million strcoll calls, 0.13 s (1 MB: about 4
// ms, so 1 000 of them 4 s). The hook then fires every big_string_slice instructions instead
// of hook_slice.
constexpr std::size_t big_string = 64u << 10;
constexpr long long big_string_slice = 10;
// Of an error's text, at most this much is kept: error(string.rep("\1", 25e6)) is 25 MB.
constexpr std::size_t error_text_bytes = 1000;

std::string base_name(const std::string& path) {
  auto slash = path.find_last_of("/\\");
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string dir_name(const std::string& path) {
  auto slash = path.find_last_of("/\\");
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

// The allocator with a ceiling (lua_Alloc): refusing a growth makes Lua raise "not enough
// memory", which the call reports like any other error.
void forget_big_string(script_state* self, void* ptr) {
  auto& v = self->big_strings;
  const auto at = std::find(v.begin(), v.end(), ptr);
  if (at == v.end()) return;
  v.erase(at);
  if (v.empty() && self->L && self->exhausted == spent::none) self->arm();
}

void* alloc(void* ud, void* ptr, std::size_t old_size, std::size_t new_size) {
  auto* self = static_cast<script_state*>(ud);
  std::size_t old_used = ptr ? old_size : 0;
  if (new_size == 0) {
    if (ptr && old_size >= big_string) forget_big_string(self, ptr);
    std::free(ptr);
    self->used -= old_used;
    return nullptr;
  }
  // A string is made once and freed once (ptr null, old_size the kind: Lua 5.4 manual, lua_Alloc).
  const bool new_big_string = !ptr && old_size == LUA_TSTRING && new_size >= big_string;
  if (ptr && old_size >= big_string) forget_big_string(self, ptr);
  if (new_size > old_used && self->used - old_used + new_size > self->limits.memory_bytes) return nullptr;
  // A large growth inside a call is charged by its bytes, and the budgets looked at: one
  // that is spent refuses the growth, and Lua raises, as for the memory ceiling (fail()
  // reports the budget).
  if (new_size >= big_allocation && new_size > old_used && self->running) {
    if (self->exhausted != spent::none) return nullptr;
    const auto grown = static_cast<long long>(new_size - old_used);
    self->job_count += grown;
    self->call_charged += grown;
    if (const spent s = self->over(); s != spent::none && s != spent::call) {
      self->exhausted = s;
      // Lua calls no message handler for a memory error: the line is read here (lua_getinfo
      // "l" allocates nothing).
      lua_Debug ar;
      for (int level = 0; self->exhausted_line == 0 && lua_getstack(self->L, level, &ar); ++level)
        if (lua_getinfo(self->L, "l", &ar) && ar.currentline > 0) self->exhausted_line = ar.currentline;
      lua_sethook(self->L, script_state::budget_hook, LUA_MASKCOUNT, 1);  // a pcall cannot go on
      return nullptr;
    }
  }
  void* p = std::realloc(ptr, new_size);
  if (p) self->used = self->used - old_used + new_size;
  if (p && new_big_string) {
    self->big_strings.push_back(p);
    if (self->big_strings.size() == 1 && self->L && self->exhausted == spent::none) self->arm();
  }
  return p;
}

// An error outside every protected call: the state cannot be trusted any more. Thrown as a
// script_error instead of Lua's abort().
int panic(lua_State* L) {
  script_state* self = script_state::of(L);
  self->panicked = true;
  const char* s = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "an error object that is no string";
  throw script_error(self->name, 0, std::string("unprotected error: ") + s);
}

// The message handler of every call: an error text without the script's place (raised in a C
// function as error(msg, 0) does) gets the line of the innermost script function.
int message_handler(lua_State* L) {
  script_state* self = script_state::of(L);
  lua_Debug ar;
  if (self->exhausted != spent::none) {  // a budget spent in C (an allocation): the line is here
    for (int level = 1; self->exhausted_line == 0 && lua_getstack(L, level, &ar); ++level)
      if (lua_getinfo(L, "l", &ar) && ar.currentline > 0) self->exhausted_line = ar.currentline;
    return 1;
  }
  if (lua_type(L, 1) != LUA_TSTRING) return 1;
  const std::string prefix = self->name + ':';
  if (std::string_view(lua_tostring(L, 1)).substr(0, prefix.size()) == prefix) return 1;
  for (int level = 1; lua_getstack(L, level, &ar); ++level) {
    if (lua_getinfo(L, "l", &ar) && ar.currentline > 0) {
      lua_pushfstring(L, "%s:%d: %s", self->name.c_str(), ar.currentline, lua_tostring(L, 1));
      return 1;
    }
  }
  return 1;
}

}  // namespace

script_state::~script_state() {
  if (!L || panicked) return;  // after a panic the state is left as it is
  // No finalizer can be set (setmetatable refuses __gc); should one run, it stops at its
  // first instruction.
  exhausted = spent::job_instructions;
  lua_sethook(L, budget_hook, LUA_MASKCOUNT, 1);
  lua_close(L);
}

spent script_state::over() const {
  if (job_count - call_start - call_charged >= limits.instructions_per_call) return spent::call;
  if (job_count >= limits.instructions_per_job) return spent::job_instructions;
  if (seconds + (now() - call_began) > limits.seconds_per_job) return spent::job_time;
  return spent::none;
}

void script_state::arm() {
  const long long left = std::max(limits.instructions_per_job - job_count, 1LL);
  const long long every = big_strings.empty() ? hook_slice : big_string_slice;
  slice = static_cast<int>(
      std::max(std::min({every, static_cast<long long>(limits.instructions_per_call), left}), 1LL));
  lua_sethook(L, budget_hook, LUA_MASKCOUNT, slice);
}

void script_state::budget_hook(lua_State* L, lua_Debug* ar) {
  script_state* self = of(L);
  if (self->exhausted == spent::none) {
    self->job_count += self->slice;
    const spent s = self->over();
    if (s == spent::none) {
      if (self->limits.instructions_per_job - self->job_count < self->slice) self->arm();
      return;
    }
    self->exhausted = s;
    if (lua_getinfo(L, "l", ar)) self->exhausted_line = ar->currentline;
    lua_sethook(L, budget_hook, LUA_MASKCOUNT, 1);
  }
  luaL_error(L, "budget");
}

void script_state::charge(lua_State* L, double units) {
  const auto n = static_cast<long long>(std::min(units, 1e18));
  job_count += n;
  call_charged += n;
  if (job_count >= limits.instructions_per_job)
    raise_spent(L, spent::job_instructions);
  else if (seconds + (now() - call_began) > limits.seconds_per_job)
    raise_spent(L, spent::job_time);
}

void script_state::raise_spent(lua_State* L, spent s) {
  exhausted = s;
  lua_Debug ar;
  if (lua_getstack(L, 1, &ar) && lua_getinfo(L, "l", &ar)) exhausted_line = ar.currentline;
  lua_sethook(L, budget_hook, LUA_MASKCOUNT, 1);
  luaL_error(L, "budget");
  __builtin_unreachable();  // luaL_error raises
}

std::string script_state::spent_message() const {
  if (exhausted == spent::job_instructions)
    return "the job's budget of " + std::to_string(limits.instructions_per_job) +
           " instructions exceeded (bytes of string work count as instructions; [events] "
           "script_instructions raises it)";
  if (exhausted == spent::job_time) {
    char secs[32];
    std::snprintf(secs, sizeof secs, "%g", limits.seconds_per_job);
    return std::string("the job's time budget of ") + secs +
           " s exceeded ([events] script_seconds raises it)";
  }
  return "instruction budget of " + std::to_string(limits.instructions_per_call) +
         " exceeded (an endless loop?)";
}

// A script_error at script line `line`, with that line's text for the diagnostic's quote.
void script_state::raise(int line, std::string message) {
  script_error e(name, line, escape_controls(message));
  std::string_view rest = source;
  for (int i = 1; i < line && !rest.empty(); ++i) {
    const std::size_t nl = rest.find('\n');
    rest = nl == std::string_view::npos ? std::string_view() : rest.substr(nl + 1);
  }
  if (line > 0) {
    rest = rest.substr(0, rest.find('\n'));
    if (!rest.empty() && rest.back() == '\r') rest.remove_suffix(1);
    e.source_line = escape_controls(rest);
  }
  throw e;
}

// Turns the error value on the stack into script_error: "NAME.lua:LINE: text" is split,
// anything else keeps line 0.
void script_state::fail(int rc) {
  if (exhausted != spent::none) {
    lua_settop(L, 0);
    raise(exhausted_line, spent_message());
  }
  std::string text;
  if (rc == LUA_ERRMEM)
    text = "not enough memory";
  else if (lua_type(L, -1) == LUA_TSTRING) {
    std::size_t n = 0;
    const char* t = lua_tolstring(L, -1, &n);
    text.assign(t, std::min(n, error_text_bytes));
    if (n > error_text_bytes) text += "... (" + std::to_string(n) + " bytes in all)";
  } else
    text = std::string("error object is a ") + luaL_typename(L, -1) + " value";
  lua_settop(L, 0);
  std::string prefix = name + ':';
  if (text.compare(0, prefix.size(), prefix) == 0) {
    const char* b = text.data() + prefix.size();
    const char* e = text.data() + text.size();
    int line = 0;
    auto [p, ec] = std::from_chars(b, e, line);
    if (ec == std::errc() && p + 1 < e && p[0] == ':' && p[1] == ' ') raise(line, std::string(p + 2, e));
  }
  throw script_error(name, 0, escape_controls(text));
}

template <class F>
void script_state::run(F& body, script_host* h) {
  if (panicked) throw script_error(name, 0, "the script cannot run again after an unprotected error");
  if (exhausted == spent::call) {  // a fresh budget for this call
    exhausted = spent::none;
    arm();
  }
  host = h;
  call_start = job_count;
  call_charged = 0;
  call_began = now();
  running = true;
  lua_settop(L, 0);
  lua_pushcfunction(L, message_handler);
  lua_pushcfunction(L, [](lua_State* S) -> int {
    (*static_cast<F*>(lua_touserdata(S, 1)))(S);
    return 0;
  });
  lua_pushlightuserdata(L, &body);
  const int rc = lua_pcall(L, 1, 0, 1);
  running = false;
  seconds += now() - call_began;
  host = nullptr;
  if (rc != LUA_OK) fail(rc);
  lua_settop(L, 0);
}

void script_state::load(std::string_view text) {
  if (text.size() > limits.script_bytes)
    throw script_error(name, 0,
                       "the script is larger than " + std::to_string(limits.script_bytes) + " bytes");
  source = text;
  L = lua_newstate(alloc, this);
  if (!L) throw script_error(name, 0, "cannot create the Lua state");
  lua_atpanic(L, panic);
  arm();
  // The sandbox, the chunk, its top level and the hooks' look-up, all in one protected call.
  auto body = [this](lua_State* S) {
    make_env();
    const int env = lua_gettop(S);
    const std::string chunk = '@' + name;
    if (luaL_loadbufferx(S, source.data(), source.size(), chunk.c_str(), "t") != LUA_OK) lua_error(S);
    lua_pushvalue(S, env);
    lua_setupvalue(S, -2, 1);  // the chunk's one upvalue is _ENV
    lua_call(S, 0, 0);
    // rawget: a hook is what the script defined; _ENV's metatable (a strict mode's
    // __index raising on an undefined name) is not asked.
    for (int i = 0; i < h_count; ++i) {
      lua_pushstring(S, hook_names[i]);
      const int t = lua_rawget(S, env);
      if (t == LUA_TFUNCTION)
        hook_ref[i] = luaL_ref(S, LUA_REGISTRYINDEX);
      else if (t == LUA_TNIL)
        lua_pop(S, 1);
      else
        luaL_error(S, "%s must be a function", hook_names[i]);
    }
  };
  run(body, nullptr);
}

lua_script::lua_script(const std::string& path_, script_limits limits) : impl_(new script_state) {
  // The names go into messages as the terminal may show them (a name may hold ESC).
  if (path_.find('\0') != std::string::npos)
    throw script_error(escape_controls(base_name(path_)), 0, "the script's name holds a NUL byte");
  const std::string path = escape_controls(path_);
  impl_->name = base_name(path);
  impl_->dir = dir_name(path);
  impl_->limits = limits;
  std::string text, why;
  switch (read_confined(path_, limits.script_bytes, text, why)) {
    case read_refusal::none: break;
    case read_refusal::missing: throw script_error(impl_->name, 0, "cannot read the script '" + path + "'");
    case read_refusal::symlink:
      throw script_error(impl_->name, 0,
                         "the script '" + path +
                             "' is a symbolic link (only a regular file beside the machine file is read)");
    case read_refusal::not_regular:
      throw script_error(impl_->name, 0,
                         "the script '" + path + "' is not a regular file (a FIFO, a device or a folder)");
    case read_refusal::too_large:
      throw script_error(
          impl_->name, 0,
          "the script '" + path + "' is larger than " + std::to_string(limits.script_bytes) + " bytes");
    case read_refusal::other:
      throw script_error(impl_->name, 0, "cannot read the script '" + path + "': " + why);
  }
  impl_->load(text);
}

lua_script::lua_script(const std::string& path, std::string_view source, script_limits limits)
    : impl_(new script_state) {
  impl_->name = escape_controls(base_name(path));
  impl_->dir = dir_name(path);
  impl_->limits = limits;
  impl_->load(source);
}

lua_script::~lua_script() = default;

const std::string& lua_script::name() const { return impl_->name; }
bool lua_script::has_on_record() const { return impl_->hook_ref[script_state::h_record] != LUA_NOREF; }
bool lua_script::has_on_tool_change() const {
  return impl_->hook_ref[script_state::h_tool_change] != LUA_NOREF;
}
bool lua_script::has_on_program_start() const {
  return impl_->hook_ref[script_state::h_program_start] != LUA_NOREF;
}
bool lua_script::has_on_program_end() const {
  return impl_->hook_ref[script_state::h_program_end] != LUA_NOREF;
}
bool lua_script::has_on_block() const { return impl_->hook_ref[script_state::h_block] != LUA_NOREF; }

namespace {

void push_context(lua_State* L, const script_context& ctx) {
  lua_createtable(L, 0, 4);
  lua_pushinteger(L, ctx.channel);
  lua_setfield(L, -2, "channel");
  lua_pushlstring(L, ctx.program.data(), ctx.program.size());
  lua_setfield(L, -2, "program");
  lua_pushinteger(L, ctx.cl_line);
  lua_setfield(L, -2, "line");
  if (ctx.part) {
    lua_pushstring(L, ctx.part);
    lua_setfield(L, -2, "part");
  }
}

}  // namespace

void lua_script::on_record(const script_record& rec, script_host& host) {
  auto& s = *impl_;
  const int ref = s.hook_ref[script_state::h_record];
  if (ref == LUA_NOREF) return;
  auto body = [&](lua_State* L) {
    lua_rawgeti(L, LUA_REGISTRYINDEX, ref);
    lua_createtable(L, 0, 3);
    lua_pushlstring(L, rec.major.data(), rec.major.size());
    lua_setfield(L, -2, "major");
    lua_createtable(L, static_cast<int>(rec.words.size()), 0);
    for (std::size_t i = 0; i < rec.words.size(); ++i) {
      lua_pushlstring(L, rec.words[i].data(), rec.words[i].size());
      lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
    lua_setfield(L, -2, "words");
    lua_pushinteger(L, rec.line);
    lua_setfield(L, -2, "line");
    lua_call(L, 1, 0);
  };
  s.run(body, &host);
}

void lua_script::on_tool_change(const script_tool& tool, script_host& host) {
  auto& s = *impl_;
  const int ref = s.hook_ref[script_state::h_tool_change];
  if (ref == LUA_NOREF) return;
  auto body = [&](lua_State* L) {
    lua_rawgeti(L, LUA_REGISTRYINDEX, ref);
    lua_createtable(L, 0, 7);
    lua_pushinteger(L, tool.number);
    lua_setfield(L, -2, "number");
    lua_pushinteger(L, tool.offset);
    lua_setfield(L, -2, "offset");
    lua_pushlstring(L, tool.name.data(), tool.name.size());
    lua_setfield(L, -2, "name");
    lua_pushlstring(L, tool.kind.data(), tool.kind.size());
    lua_setfield(L, -2, "kind");
    lua_pushnumber(L, tool.length);
    lua_setfield(L, -2, "length");
    lua_pushnumber(L, tool.diameter);
    lua_setfield(L, -2, "diameter");
    lua_pushinteger(L, tool.channel);
    lua_setfield(L, -2, "channel");
    lua_call(L, 1, 0);
  };
  s.run(body, &host);
}

// on_program_start and on_program_end: the hook `which`, called with the context table.
static void call_context_hook(script_state& s, int which, const script_context& ctx, script_host& host) {
  const int ref = s.hook_ref[which];
  if (ref == LUA_NOREF) return;
  auto body = [&](lua_State* L) {
    lua_rawgeti(L, LUA_REGISTRYINDEX, ref);
    push_context(L, ctx);
    lua_call(L, 1, 0);
  };
  s.run(body, &host);
}

void lua_script::on_program_start(const script_context& ctx, script_host& host) {
  call_context_hook(*impl_, script_state::h_program_start, ctx, host);
}

void lua_script::on_program_end(const script_context& ctx, script_host& host) {
  call_context_hook(*impl_, script_state::h_program_end, ctx, host);
}

block_verdict lua_script::on_block(std::string_view text, const script_context& ctx, script_host& host,
                                   std::string& replacement) {
  auto& s = *impl_;
  const int ref = s.hook_ref[script_state::h_block];
  if (ref == LUA_NOREF) return block_verdict::keep;
  int type = LUA_TNIL;
  bool truth = false;
  auto body = [&](lua_State* L) {
    lua_rawgeti(L, LUA_REGISTRYINDEX, ref);
    lua_pushlstring(L, text.data(), text.size());
    push_context(L, ctx);
    lua_call(L, 2, 1);
    type = lua_type(L, -1);
    if (type == LUA_TSTRING) {
      std::size_t n = 0;
      const char* r = lua_tolstring(L, -1, &n);
      replacement.assign(r, n);
    } else {
      truth = lua_toboolean(L, -1);
    }
  };
  s.run(body, &host);
  if (type == LUA_TBOOLEAN) return truth ? block_verdict::keep : block_verdict::drop;
  if (type == LUA_TNIL) return block_verdict::keep;
  if (type != LUA_TSTRING)
    throw script_error(s.name, 0,
                       std::string("on_block returned a ") + lua_typename(s.L, type) +
                           ": return a string, false or nothing");
  // The block given back as it came is the post's own: nothing new to gate.
  if (replacement == text) return block_verdict::replace;
  if (!block_clean(replacement)) {
    if (replacement.find_first_of("\r\n") != std::string::npos)
      throw script_error(s.name, 0, "on_block returned more than one block (a line break)");
    throw script_error(s.name, 0, "on_block returned a block with " + block_fault(replacement));
  }
  if (replacement.size() > text.size()) {
    s.emitted += replacement.size() - text.size();
    if (s.emitted > s.limits.emit_bytes)
      throw script_error(s.name, 0,
                         "on_block: the script wrote more than " + std::to_string(s.limits.emit_bytes) +
                             " bytes in the job (its limit)");
  }
  return block_verdict::replace;
}

}  // namespace twinpost::scripting
