// The Lua sandbox. Only the base, string, table, math and utf8 libraries are opened at all
// (never os, io, package, debug), and the script's _ENV is a fresh table filled from a
// whitelist, so load/loadfile/dofile/require/collectgarbage/print are simply not there.
// Chunks are loaded as text only ("t"): no precompiled bytecode. A count hook stops a call
// after its instruction budget; an allocator with a ceiling stops a script that grows memory.
#include "scripting/lua_script.hpp"

#include <charconv>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>

// Lua built as C++ (liblua5.4-c++, CMakeLists.txt): C++ linkage, no extern "C".
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>

namespace twinpost::scripting {

script_error::script_error(std::string file_, int line_, std::string message_)
    : std::runtime_error(line_ > 0 ? file_ + ':' + std::to_string(line_) + ": " + message_
                                   : file_ + ": " + message_),
      file(std::move(file_)), line(line_), message(std::move(message_)) {}

namespace {

constexpr const char* hook_names[] = {"on_record", "on_tool_change", "on_program_start", "on_program_end",
                                      "on_block"};
enum hook { h_record, h_tool_change, h_program_start, h_program_end, h_block, h_count };

std::string base_name(const std::string& path) {
  auto slash = path.find_last_of("/\\");
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string dir_name(const std::string& path) {
  auto slash = path.find_last_of("/\\");
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

}  // namespace

struct lua_script::impl {
  std::string name;    // "catcher.lua"
  std::string dir;     // where post.read_file looks
  std::string source;  // the script's text, for the line an error quotes
  script_limits limits;
  std::size_t used = 0;
  lua_State* L = nullptr;
  int env_ref = LUA_NOREF;
  int hook_ref[h_count] = {LUA_NOREF, LUA_NOREF, LUA_NOREF, LUA_NOREF, LUA_NOREF};
  script_host* host = nullptr;  // set for the length of one call
  // The budget ran out in this call: from then on every instruction raises again, so a
  // pcall in the script cannot swallow the error and go on looping.
  bool exhausted = false;
  int exhausted_line = 0;

  ~impl() {
    if (!L) return;
    // A __gc finalizer runs at close: with the budget exhausted it stops at its first
    // instruction instead of looping forever.
    exhausted = true;
    lua_sethook(L, budget_hook, LUA_MASKCOUNT, 1);
    lua_close(L);
  }

  // The allocator with a ceiling (lua_Alloc): refusing a growth makes Lua raise "not enough
  // memory", which the call reports like any other error.
  static void* alloc(void* ud, void* ptr, std::size_t old_size, std::size_t new_size) {
    auto* self = static_cast<impl*>(ud);
    std::size_t old_used = ptr ? old_size : 0;
    if (new_size == 0) {
      std::free(ptr);
      self->used -= old_used;
      return nullptr;
    }
    if (new_size > old_used && self->used - old_used + new_size > self->limits.memory_bytes) return nullptr;
    void* p = std::realloc(ptr, new_size);
    if (p) self->used = self->used - old_used + new_size;
    return p;
  }

  static impl* self_of(lua_State* L) { return static_cast<impl*>(lua_touserdata(L, lua_upvalueindex(1))); }

  // Runs when the budget is spent: the error carries the line the script was at.
  static void budget_hook(lua_State* L, lua_Debug* ar) {
    impl* self = nullptr;
    lua_getallocf(L, reinterpret_cast<void**>(&self));
    if (!self->exhausted) {
      self->exhausted = true;
      if (lua_getinfo(L, "l", ar)) self->exhausted_line = ar->currentline;
      lua_sethook(L, budget_hook, LUA_MASKCOUNT, 1);
    }
    luaL_error(L, "budget");
  }

  static int post_emit(lua_State* L) {
    std::size_t n = 0;
    const char* s = luaL_checklstring(L, 1, &n);
    std::string_view text(s, n);
    if (text.find_first_of("\r\n") != std::string_view::npos)
      return luaL_error(L, "post.emit: one block per call, without a line break");
    if (auto* host = self_of(L)->host) host->emit(text);
    return 0;
  }
  static int post_warning(lua_State* L) {
    std::size_t n = 0;
    const char* s = luaL_checklstring(L, 1, &n);
    if (auto* host = self_of(L)->host) host->warning(std::string_view(s, n));
    return 0;
  }
  static int post_error(lua_State* L) {
    const char* s = luaL_checkstring(L, 1);
    luaL_where(L, 1);  // the script line that called post.error
    lua_pushstring(L, s);
    lua_concat(L, 2);
    return lua_error(L);
  }
  // post.read_file(name): a plain file name beside the machine file, nothing else.
  static int post_read_file(lua_State* L) {
    auto* self = self_of(L);
    std::string file = luaL_checkstring(L, 1);
    if (file.empty() || file.find_first_of("/\\:") != std::string::npos || file[0] == '.')
      return luaL_error(L, "post.read_file: '%s' is not a file name beside the machine file", file.c_str());
    std::ifstream in(self->dir + '/' + file, std::ios::binary);
    if (!in) return luaL_error(L, "post.read_file: no file '%s' beside the machine file", file.c_str());
    std::string text;
    char buf[65536];
    while (in.read(buf, sizeof buf) || in.gcount() > 0) {
      text.append(buf, static_cast<std::size_t>(in.gcount()));
      if (text.size() > self->limits.read_file_bytes)
        return luaL_error(L, "post.read_file: '%s' is larger than %d bytes", file.c_str(),
                          static_cast<int>(self->limits.read_file_bytes));
    }
    lua_pushlstring(L, text.data(), text.size());
    return 1;
  }

  // Copies the whitelisted names of table `from` (on the stack) into a new table.
  void copy_fields(int from, std::initializer_list<const char*> names) {
    lua_createtable(L, 0, static_cast<int>(names.size()));
    for (const char* n : names) {
      lua_getfield(L, from, n);
      lua_setfield(L, -2, n);
    }
  }

  // The script's _ENV, left on the stack.
  void make_env() {
    luaL_requiref(L, LUA_GNAME, luaopen_base, 1);
    luaL_requiref(L, LUA_STRLIBNAME, luaopen_string, 1);
    luaL_requiref(L, LUA_TABLIBNAME, luaopen_table, 1);
    luaL_requiref(L, LUA_MATHLIBNAME, luaopen_math, 1);
    luaL_requiref(L, LUA_UTF8LIBNAME, luaopen_utf8, 1);
    lua_pop(L, 5);
    lua_pushglobaltable(L);
    int g = lua_gettop(L);
    copy_fields(
        g, {"assert", "error", "ipairs", "next", "pairs", "pcall", "select", "tonumber", "tostring", "type",
            "xpcall", "rawequal", "rawget", "rawset", "rawlen", "setmetatable", "getmetatable", "_VERSION"});
    int env = lua_gettop(L);
    lua_getfield(L, g, "string");
    // string.dump is left out: bytecode has no use without load.
    copy_fields(lua_gettop(L), {"byte", "char", "find", "format", "gmatch", "gsub", "len", "lower", "match",
                                "rep", "reverse", "sub", "upper", "pack", "packsize", "unpack"});
    lua_setfield(L, env, "string");
    lua_pop(L, 1);
    for (const char* lib : {"table", "math", "utf8"}) {
      lua_getfield(L, g, lib);
      lua_createtable(L, 0, 0);
      lua_pushnil(L);
      while (lua_next(L, -3)) {  // a shallow copy: the script cannot reach the shared one
        lua_pushvalue(L, -2);
        lua_insert(L, -2);
        lua_settable(L, -4);
      }
      lua_setfield(L, env, lib);
      lua_pop(L, 1);
    }
    lua_createtable(L, 0, 5);  // post
    const luaL_Reg fns[] = {{"emit", post_emit},
                            {"warning", post_warning},
                            {"error", post_error},
                            {"read_file", post_read_file},
                            {nullptr, nullptr}};
    lua_pushlightuserdata(L, this);
    luaL_setfuncs(L, fns, 1);
    lua_createtable(L, 0, 0);
    lua_setfield(L, -2, "vars");
    lua_setfield(L, env, "post");
    lua_pushvalue(L, env);
    lua_setfield(L, env, "_G");
    lua_remove(L, g);  // env stays
  }

  // A script_error at script line `line`, with that line's text for the diagnostic's quote.
  [[noreturn]] void raise(int line, std::string message) {
    script_error e(name, line, std::move(message));
    std::string_view rest = source;
    for (int i = 1; i < line && !rest.empty(); ++i) {
      const std::size_t nl = rest.find('\n');
      rest = nl == std::string_view::npos ? std::string_view() : rest.substr(nl + 1);
    }
    if (line > 0) {
      rest = rest.substr(0, rest.find('\n'));
      if (!rest.empty() && rest.back() == '\r') rest.remove_suffix(1);
      e.source_line = rest;
    }
    throw e;
  }

  // Turns the error value on the stack into script_error: "NAME.lua:LINE: text" is split,
  // anything else keeps line 0.
  [[noreturn]] void fail() {
    if (exhausted) {
      lua_settop(L, 0);
      raise(exhausted_line, "instruction budget of " + std::to_string(limits.instructions_per_call) +
                                " exceeded (an endless loop?)");
    }
    std::string text;
    if (const char* s = lua_tostring(L, -1))
      text = s;
    else
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
    throw script_error(name, 0, std::move(text));
  }

  // Calls the function below `nargs` arguments with the budget set; leaves `nres` results.
  void call(int nargs, int nres, script_host* h) {
    host = h;
    exhausted = false;
    lua_sethook(L, budget_hook, LUA_MASKCOUNT, static_cast<int>(limits.instructions_per_call));
    int rc = lua_pcall(L, nargs, nres, 0);
    host = nullptr;
    if (rc != LUA_OK) fail();
  }

  void load(std::string_view text) {
    source = text;
    L = lua_newstate(alloc, this);
    if (!L) throw script_error(name, 0, "cannot create the Lua state");
    make_env();
    int env = lua_gettop(L);
    std::string chunk = '@' + name;
    if (luaL_loadbufferx(L, source.data(), source.size(), chunk.c_str(), "t") != LUA_OK) fail();
    lua_pushvalue(L, env);
    lua_setupvalue(L, -2, 1);  // the chunk's one upvalue is _ENV
    call(0, 0, nullptr);
    for (int i = 0; i < h_count; ++i) {
      if (lua_getfield(L, env, hook_names[i]) == LUA_TFUNCTION)
        hook_ref[i] = luaL_ref(L, LUA_REGISTRYINDEX);
      else if (lua_isnil(L, -1))
        lua_pop(L, 1);
      else
        throw script_error(name, 0, std::string(hook_names[i]) + " must be a function");
    }
    env_ref = luaL_ref(L, LUA_REGISTRYINDEX);
  }

  bool push_hook(hook h) {
    if (hook_ref[h] == LUA_NOREF) return false;
    lua_rawgeti(L, LUA_REGISTRYINDEX, hook_ref[h]);
    return true;
  }

  void push_context(const script_context& ctx) {
    lua_createtable(L, 0, 3);
    lua_pushinteger(L, ctx.channel);
    lua_setfield(L, -2, "channel");
    lua_pushlstring(L, ctx.program.data(), ctx.program.size());
    lua_setfield(L, -2, "program");
    lua_pushinteger(L, ctx.cl_line);
    lua_setfield(L, -2, "line");
  }
};

lua_script::lua_script(const std::string& path, script_limits limits) : impl_(new impl) {
  impl_->name = base_name(path);
  impl_->dir = dir_name(path);
  impl_->limits = limits;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw script_error(impl_->name, 0, "cannot read the script '" + path + "'");
  std::string source((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  impl_->load(source);
}

lua_script::lua_script(const std::string& path, std::string_view source, script_limits limits)
    : impl_(new impl) {
  impl_->name = base_name(path);
  impl_->dir = dir_name(path);
  impl_->limits = limits;
  impl_->load(source);
}

lua_script::~lua_script() = default;

const std::string& lua_script::name() const { return impl_->name; }
bool lua_script::has_on_record() const { return impl_->hook_ref[h_record] != LUA_NOREF; }
bool lua_script::has_on_tool_change() const { return impl_->hook_ref[h_tool_change] != LUA_NOREF; }
bool lua_script::has_on_program_start() const { return impl_->hook_ref[h_program_start] != LUA_NOREF; }
bool lua_script::has_on_program_end() const { return impl_->hook_ref[h_program_end] != LUA_NOREF; }
bool lua_script::has_on_block() const { return impl_->hook_ref[h_block] != LUA_NOREF; }

void lua_script::on_record(const script_record& rec, script_host& host) {
  auto& s = *impl_;
  if (!s.push_hook(h_record)) return;
  lua_State* L = s.L;
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
  s.call(1, 0, &host);
}

void lua_script::on_tool_change(const script_tool& tool, script_host& host) {
  auto& s = *impl_;
  if (!s.push_hook(h_tool_change)) return;
  lua_State* L = s.L;
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
  s.call(1, 0, &host);
}

void lua_script::on_program_start(const script_context& ctx, script_host& host) {
  auto& s = *impl_;
  if (!s.push_hook(h_program_start)) return;
  s.push_context(ctx);
  s.call(1, 0, &host);
}

void lua_script::on_program_end(const script_context& ctx, script_host& host) {
  auto& s = *impl_;
  if (!s.push_hook(h_program_end)) return;
  s.push_context(ctx);
  s.call(1, 0, &host);
}

block_verdict lua_script::on_block(std::string_view text, const script_context& ctx, script_host& host,
                                   std::string& replacement) {
  auto& s = *impl_;
  if (!s.push_hook(h_block)) return block_verdict::keep;
  lua_State* L = s.L;
  lua_pushlstring(L, text.data(), text.size());
  s.push_context(ctx);
  s.call(2, 1, &host);
  block_verdict v = block_verdict::keep;
  int t = lua_type(L, -1);
  if (t == LUA_TSTRING) {
    std::size_t n = 0;
    const char* r = lua_tolstring(L, -1, &n);
    replacement.assign(r, n);
    v = block_verdict::replace;
  } else if (t == LUA_TBOOLEAN) {
    v = lua_toboolean(L, -1) ? block_verdict::keep : block_verdict::drop;
  } else if (t != LUA_TNIL) {
    std::string what = luaL_typename(L, -1);
    lua_settop(L, 0);
    throw script_error(s.name, 0, "on_block returned a " + what + ": return a string, false or nothing");
  }
  lua_settop(L, 0);
  if (v == block_verdict::replace && replacement.find_first_of("\r\n") != std::string::npos)
    throw script_error(s.name, 0, "on_block returned more than one block (a line break)");
  return v;
}

}  // namespace twinpost::scripting
