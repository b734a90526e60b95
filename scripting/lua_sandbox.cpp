// The script's _ENV (docs/scripting.md, "The sandbox" and "What a script cannot do"): a
// whitelist of the base library, copies of string (without dump), table, math and utf8, the
// post table; the library functions that work in C, out of the count hook's reach, wrapped so
// that their work is charged to the job's budget and bounded before it starts.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include <lualib.h>

#include "scripting/confined_file.hpp"
#include "scripting/lua_state.hpp"
#include "scripting/pattern_cost.hpp"

namespace twinpost::scripting {

std::string escape_controls(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto b = static_cast<unsigned char>(c);
    if ((b < 0x20 && b != '\t') || b >= 0x7f) {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02x", b);
      out += hex;
    } else {
      out += c;
    }
  }
  return out;
}

bool block_clean(std::string_view block) {
  // One look-up a byte: this runs on every block a script writes or replaces.
  static constexpr auto bad = [] {
    std::array<bool, 256> t{};
    for (int b = 0; b < 0x20; ++b) t[static_cast<std::size_t>(b)] = true;
    for (int b = 0x80; b < 0x100; ++b) t[static_cast<std::size_t>(b)] = true;
    t[0x7f] = t[static_cast<unsigned char>('%')] = true;
    return t;
  }();
  bool any = false;
  for (const char c : block) any |= bad[static_cast<unsigned char>(c)];
  return !any;
}

std::string block_fault(std::string_view block) {
  for (const char c : block) {
    const auto b = static_cast<unsigned char>(c);
    if (c == '%') return "a '%' (the tape mark: the control stops reading the program there)";
    if (b < 0x20 || b == 0x7f)
      return "the control byte " + escape_controls(std::string_view(&c, 1)) +
             " (no NUL or control byte goes into a program)";
    if (b >= 0x80) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", b);
      return std::string("the byte ") + hex +
             " (a control reads ISO or EIA code, ASCII only; an editor may break the line at a UTF-8 NEL or "
             "LS)";
    }
  }
  return {};
}

namespace {

script_state* self_of(lua_State* L) { return script_state::of(L); }

// Errors with a text made by snprintf (lua_pushfstring knows no %g).
template <class... A>
[[noreturn]] void error_f(lua_State* L, const char* format, A... args) {
  char text[512];
  std::snprintf(text, sizeof text, format, args...);
  luaL_error(L, "%s", text);
  __builtin_unreachable();  // luaL_error raises
}

constexpr std::size_t max_set_bytes = 512;

// string.find/match/gmatch/gsub: the subject's length bounded, its bytes and the pattern's
// charged, and the matcher's worst case worked out before the one C call the count hook
// cannot interrupt. The runs the estimate scans for are charged before the scan.
void guard_pattern(lua_State* L, const char* what, bool anchor_works) {
  script_state* self = self_of(L);
  std::size_t n = 0, m = 0;
  const char* s = luaL_checklstring(L, 1, &n);
  const char* p = luaL_checklstring(L, 2, &m);
  if (n > self->limits.pattern_subject_bytes)
    error_f(L, "%s: a subject of %zu bytes is over the limit of %zu bytes", what, n,
            self->limits.pattern_subject_bytes);
  self->charge(L, static_cast<double>(n) + static_cast<double>(m));
  const pattern_shape shape = pattern_items({p, m}, anchor_works);
  // The matcher walks a set for every byte it tries: a set names at most 256 bytes, and 512
  // bytes of set (ranges, classes, escapes) say all of them.
  if (shape.longest_set > max_set_bytes)
    error_f(L,
            "%s: the pattern has a set [...] of %zu bytes (at most %zu): name its bytes once, or by ranges",
            what, shape.longest_set, max_set_bytes);
  self->charge(L, pattern_scan_bytes(shape, n));
  const double steps = pattern_steps(shape, {s, n}, self->limits.pattern_steps);
  if (steps > self->limits.pattern_steps) {
    const std::string shown = escape_controls(std::string_view(p, std::min<std::size_t>(m, 40)));
    error_f(
        L,
        "%s: the pattern '%s%s' may take more than %.3g steps on a subject of %zu bytes (the limit of one "
        "call): %s",
        what, shown.c_str(), m > 40 ? "..." : "", self->limits.pattern_steps, n,
        anchor_works ? "anchor it with '^' or repeat fewer items ('.-', '.*')"
                     : "repeat fewer items ('.-', '.*'); in gmatch '^' is no anchor");
  }
}

// Lua's own test for a pattern string.find searches for as it is (lstrlib.c, nospecials).
bool no_specials(std::string_view p) { return p.find_first_of("^$*+?.([%-") == std::string_view::npos; }

// The first `needle` in `hay`: memchr and memcmp while their worst case (hay x needle) is
// small, else Knuth-Morris-Pratt, linear in both (Lua's lmemfind is the first way at any size:
// 'aaa...ab' in 'aaaa...' takes hay x needle steps in one call; libstdc++'s Boyer-Moore builds
// its table in needle^2 for such a needle).
std::size_t first_of(std::string_view hay, std::string_view needle) {
  if (needle.size() > hay.size()) return std::string_view::npos;
  if (static_cast<double>(hay.size()) * static_cast<double>(needle.size()) <= 1e7) return hay.find(needle);
  std::vector<std::size_t> border(needle.size() + 1, 0);  // border[i]: of needle[0, i)
  for (std::size_t i = 1, k = 0; i < needle.size(); ++i) {
    while (k > 0 && needle[i] != needle[k]) k = border[k];
    if (needle[i] == needle[k]) ++k;
    border[i + 1] = k;
  }
  for (std::size_t i = 0, k = 0; i < hay.size(); ++i) {
    while (k > 0 && hay[i] != needle[k]) k = border[k];
    if (hay[i] == needle[k]) ++k;
    if (k == needle.size()) return i + 1 - k;
  }
  return std::string_view::npos;
}

int w_find(lua_State* L) {
  std::size_t n = 0, m = 0;
  const char* s = luaL_checklstring(L, 1, &n);
  const char* p = luaL_checklstring(L, 2, &m);
  if (!lua_toboolean(L, 4) && !no_specials({p, m})) {
    guard_pattern(L, "string.find", true);
    return self_of(L)->orig.find(L);
  }
  // A plain search, as str_find_aux does it (Lua 5.4 lstrlib.c), with the linear search.
  script_state* self = self_of(L);
  if (n > self->limits.pattern_subject_bytes)
    error_f(L, "string.find: a subject of %zu bytes is over the limit of %zu bytes", n,
            self->limits.pattern_subject_bytes);
  self->charge(L, static_cast<double>(n) + static_cast<double>(m));
  lua_Integer init = luaL_optinteger(L, 3, 1);
  const auto len = static_cast<lua_Integer>(n);
  if (init == 0 || init < -len)
    init = 1;
  else if (init < 0)
    init = len + init + 1;
  if (init > len + 1) {
    luaL_pushfail(L);
    return 1;
  }
  const std::size_t from = static_cast<std::size_t>(init - 1);
  const std::size_t at = first_of(std::string_view(s + from, n - from), std::string_view(p, m));
  if (at == std::string_view::npos) {
    luaL_pushfail(L);
    return 1;
  }
  lua_pushinteger(L, static_cast<lua_Integer>(from + at + 1));
  lua_pushinteger(L, static_cast<lua_Integer>(from + at + m));
  return 2;
}
int w_match(lua_State* L) {
  guard_pattern(L, "string.match", true);
  return self_of(L)->orig.match(L);
}
int w_gmatch(lua_State* L) {  // gmatch reads a leading '^' as a byte (Lua 5.4 lstrlib.c)
  guard_pattern(L, "string.gmatch", false);
  return self_of(L)->orig.gmatch(L);
}
int w_gsub(lua_State* L) {
  guard_pattern(L, "string.gsub", true);
  if (lua_iscfunction(L, 3))
    return luaL_error(
        L,
        "string.gsub: a replacement function written in C is refused (its calls run outside the "
        "budgets); give a Lua function, a string or a table");
  // A string replacement is read at every match, and a match may be empty: `%1` of an empty
  // capture writes nothing (so no allocation looks at the clock) and costs a step. Charged
  // before the call: one reading per byte of the subject, and one more.
  if (lua_type(L, 3) == LUA_TSTRING)
    self_of(L)->charge(L,
                       (static_cast<double>(lua_rawlen(L, 1)) + 1) * static_cast<double>(lua_rawlen(L, 3)));
  return self_of(L)->orig.gsub(L);
}

// string.rep: a result past the memory ceiling is refused before it is built; charged by its
// bytes, and by its count (rep('', n) copies nothing n times).
int w_rep(lua_State* L) {
  script_state* self = self_of(L);
  std::size_t l = 0, lsep = 0;
  luaL_checklstring(L, 1, &l);
  const lua_Integer n = luaL_checkinteger(L, 2);
  luaL_optlstring(L, 3, "", &lsep);
  const double count = n > 0 ? static_cast<double>(n) : 0;
  const double total = count * static_cast<double>(l + lsep);
  if (total > static_cast<double>(self->limits.memory_bytes))
    error_f(L, "string.rep: a result of %.0f bytes is over the memory ceiling of %zu bytes", total,
            self->limits.memory_bytes);
  self->charge(L, total + count);
  return self->orig.rep(L);
}

// setmetatable: no __gc. A finalizer runs when the collector decides, with the count hook
// off (Lua 5.4), so no budget could hold it.
int w_setmetatable(lua_State* L) {
  if (lua_type(L, 2) == LUA_TTABLE) {
    lua_pushliteral(L, "__gc");
    if (lua_rawget(L, 2) != LUA_TNIL)
      return luaL_error(L,
                        "setmetatable: a metatable with __gc is refused (a finalizer runs outside the "
                        "script's budgets)");
    lua_pop(L, 1);
  }
  return self_of(L)->orig.setmetatable(L);
}

// The other library functions whose work is a loop in C: charged before they run, by the
// bytes of their string arguments, the length of their table as they read it (luaL_len, so a
// __len is asked as the library asks it), their range, or for table.sort n log n comparisons
// of the table's strings.
enum cost_kind { cost_strings, cost_table, cost_unpack, cost_concat, cost_sort, cost_range };

// The length of the table argument as the table library takes it; 0 for anything else.
double table_length(lua_State* L) {
  if (lua_type(L, 1) != LUA_TTABLE) return 0;
  return static_cast<double>(luaL_len(L, 1));
}

// j - i + 1 for the optional range arguments at `i_at` and `i_at + 1` (j defaults to #t).
double range_of(lua_State* L, int i_at) {
  const double len = table_length(L);
  const double i = lua_isnumber(L, i_at) ? lua_tonumber(L, i_at) : 1;
  const double j = lua_isnumber(L, i_at + 1) ? lua_tonumber(L, i_at + 1) : len;
  return std::max({0.0, j - i + 1, len});
}

int w_charged(lua_State* L) {
  const lua_CFunction f = lua_tocfunction(L, lua_upvalueindex(1));
  const auto kind = static_cast<cost_kind>(lua_tointeger(L, lua_upvalueindex(2)));
  script_state* self = self_of(L);
  double units = 0;
  switch (kind) {
    case cost_strings:
      for (int i = 1, top = lua_gettop(L); i <= top; ++i)
        if (lua_type(L, i) == LUA_TSTRING) units += static_cast<double>(lua_rawlen(L, i));
      break;
    case cost_range:  // table.move(a1, f, e, t [,a2]); 1e12 is a float: table.move takes it
      if (lua_isnumber(L, 2) && lua_isnumber(L, 3))
        units = std::max(0.0, lua_tonumber(L, 3) - lua_tonumber(L, 2) + 1);
      break;
    case cost_table: units = table_length(L); break;  // insert, remove
    case cost_unpack: units = range_of(L, 2); break;  // table.unpack(t [,i [,j]])
    case cost_concat: {                               // table.concat(t [,sep [,i [,j]]])
      units = range_of(L, 3);
      if (lua_type(L, 2) == LUA_TSTRING) units *= static_cast<double>(lua_rawlen(L, 2)) + 1;
      break;
    }
    case cost_sort: {
      // A comparator in C (pcall, string.char) runs a C call per comparison, out of the count's
      // reach: a sort with `pcall` compared for 271 s against a 60 s budget.
      if (lua_iscfunction(L, 2))
        return luaL_error(L,
                          "table.sort: a comparator written in C is refused (its calls run outside the "
                          "budgets); give a Lua function");
      // Through a metatable (__index a table of 20 MB strings) the sort reads and compares in C
      // what no charge here can see: refused.
      if (lua_type(L, 1) == LUA_TTABLE && lua_getmetatable(L, 1))
        return luaL_error(L,
                          "table.sort: a table with a metatable is refused (its reads and compares would run "
                          "outside the budgets); sort a plain table");
      const double n = table_length(L);
      const double log_n = std::log2(n + 2);
      self->charge(L, n * log_n);  // first: a huge n is refused before the strings are read
      double bytes = 0;
      const auto raw = static_cast<lua_Integer>(std::min(n, static_cast<double>(lua_rawlen(L, 1))));
      for (lua_Integer i = 1; i <= raw; ++i) {
        if (lua_rawgeti(L, 1, i) == LUA_TSTRING) bytes += static_cast<double>(lua_rawlen(L, -1));
        lua_pop(L, 1);
      }
      units = bytes * log_n;
      break;
    }
  }
  self->charge(L, units);
  return f(L);
}

// Copies the whitelisted names of table `from` (on the stack) into a new table.
void copy_fields(lua_State* L, int from, std::initializer_list<const char*> names) {
  lua_createtable(L, 0, static_cast<int>(names.size()));
  for (const char* n : names) {
    lua_getfield(L, from, n);
    lua_setfield(L, -2, n);
  }
}

// Replaces field `name` of the table on top by the charged wrapper of its function.
void charge_field(lua_State* L, const char* name, cost_kind kind) {
  lua_getfield(L, -1, name);
  lua_CFunction f = lua_tocfunction(L, -1);
  lua_pop(L, 1);
  if (!f) return;
  lua_pushcfunction(L, f);
  lua_pushinteger(L, kind);
  lua_pushcclosure(L, w_charged, 2);
  lua_setfield(L, -2, name);
}

// Replaces field `name` of the table on top by `w`, keeping the original in `orig`.
void wrap_field(lua_State* L, const char* name, lua_CFunction w, lua_CFunction& orig) {
  lua_getfield(L, -1, name);
  orig = lua_tocfunction(L, -1);
  lua_pop(L, 1);
  lua_pushcfunction(L, w);
  lua_setfield(L, -2, name);
}

}  // namespace

namespace {

int post_emit(lua_State* L) {
  script_state* self = self_of(L);
  std::size_t n = 0;
  const char* s = luaL_checklstring(L, 1, &n);
  const std::string_view text(s, n);
  if (!block_clean(text)) {
    if (text.find_first_of("\r\n") != std::string_view::npos)
      return luaL_error(L, "post.emit: one block per call, without a line break");
    return luaL_error(L, "post.emit: the block has %s", block_fault(text).c_str());
  }
  self->emitted += n + 1;  // with its line break: an empty block is a line too
  if (self->emitted > self->limits.emit_bytes)
    error_f(L, "post.emit: the script wrote more than %zu bytes in the job (its limit)",
            self->limits.emit_bytes);
  self->charge(L, static_cast<double>(n));
  if (script_host* host = self->host; host && !host->emit(text))
    return luaL_error(L, "post.emit: the post refused the block (its error is above); the script stops here");
  return 0;
}

int post_warning(lua_State* L) {
  script_state* self = self_of(L);
  std::size_t n = 0;
  const char* s = luaL_checklstring(L, 1, &n);
  if (++self->warnings > self->limits.warnings)
    error_f(L, "post.warning: more than %ld warnings in the job (its limit)", self->limits.warnings);
  self->warned_bytes += n;
  if (self->warned_bytes > self->limits.warning_bytes)
    error_f(L, "post.warning: more than %zu bytes of warnings in the job (its limit)",
            self->limits.warning_bytes);
  self->charge(L, static_cast<double>(n));
  if (script_host* host = self->host) host->warning(escape_controls(std::string_view(s, n)));
  return 0;
}

int post_error(lua_State* L) {
  const char* s = luaL_checkstring(L, 1);
  luaL_where(L, 1);  // the script line that called post.error
  lua_pushstring(L, s);
  lua_concat(L, 2);
  return lua_error(L);
}

// post.read_file(name): a plain file name beside the machine file, a regular file there.
int post_read_file(lua_State* L) {
  script_state* self = self_of(L);
  const std::string file = luaL_checkstring(L, 1);
  if (file.empty() || file.find_first_of("/\\:") != std::string::npos || file[0] == '.')
    return luaL_error(L, "post.read_file: '%s' is not a file name beside the machine file", file.c_str());
  std::string text, why;
  switch (read_confined(self->dir + '/' + file, self->limits.read_file_bytes, text, why)) {
    case read_refusal::none: break;
    case read_refusal::missing:
      return luaL_error(L, "post.read_file: no file '%s' beside the machine file", file.c_str());
    case read_refusal::symlink:
      return luaL_error(
          L, "post.read_file: '%s' is a symbolic link (only a regular file beside the machine file is read)",
          file.c_str());
    case read_refusal::not_regular:
      return luaL_error(L, "post.read_file: '%s' is not a regular file (a FIFO, a device or a folder)",
                        file.c_str());
    case read_refusal::too_large:
      error_f(L, "post.read_file: '%s' is larger than %zu bytes", file.c_str(), self->limits.read_file_bytes);
    case read_refusal::other:
      return luaL_error(L, "post.read_file: cannot read '%s': %s", file.c_str(), why.c_str());
  }
  self->charge(L, static_cast<double>(text.size()));
  lua_pushlstring(L, text.data(), text.size());
  return 1;
}

}  // namespace

void script_state::make_env() {
  luaL_requiref(L, LUA_GNAME, luaopen_base, 1);
  luaL_requiref(L, LUA_STRLIBNAME, luaopen_string, 1);
  luaL_requiref(L, LUA_TABLIBNAME, luaopen_table, 1);
  luaL_requiref(L, LUA_MATHLIBNAME, luaopen_math, 1);
  luaL_requiref(L, LUA_UTF8LIBNAME, luaopen_utf8, 1);
  lua_pop(L, 5);
  lua_pushglobaltable(L);
  const int g = lua_gettop(L);
  copy_fields(L, g,
              {"assert", "error", "ipairs", "next", "pairs", "pcall", "select", "tonumber", "tostring",
               "type", "rawequal", "rawget", "rawset", "rawlen", "setmetatable", "getmetatable", "_VERSION"});
  const int env = lua_gettop(L);
  wrap_field(L, "setmetatable", w_setmetatable, orig.setmetatable);
  // tonumber(s, base) reads every byte of s in one C call.
  charge_field(L, "tonumber", cost_strings);
  lua_getfield(L, g, "string");
  // string.dump is left out: bytecode has no use without load.
  copy_fields(L, lua_gettop(L),
              {"byte", "char", "find", "format", "gmatch", "gsub", "len", "lower", "match", "rep", "reverse",
               "sub", "upper", "pack", "packsize", "unpack"});
  wrap_field(L, "find", w_find, orig.find);
  wrap_field(L, "match", w_match, orig.match);
  wrap_field(L, "gmatch", w_gmatch, orig.gmatch);
  wrap_field(L, "gsub", w_gsub, orig.gsub);
  wrap_field(L, "rep", w_rep, orig.rep);
  for (const char* f : {"byte", "format", "lower", "upper", "reverse", "sub", "pack", "unpack"})
    charge_field(L, f, cost_strings);
  // The strings' metatable: its __index is this copy (so ("").dump is nil, and s:find is the
  // guarded find), and getmetatable("") gives false, not the table.
  lua_pushliteral(L, "");
  lua_getmetatable(L, -1);
  lua_pushvalue(L, -3);
  lua_setfield(L, -2, "__index");
  lua_pushboolean(L, 0);
  lua_setfield(L, -2, "__metatable");
  lua_pop(L, 2);
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
    if (lib[0] == 't') {
      for (const char* f : {"insert", "remove"}) charge_field(L, f, cost_table);
      charge_field(L, "unpack", cost_unpack);
      charge_field(L, "concat", cost_concat);
      charge_field(L, "sort", cost_sort);
      charge_field(L, "move", cost_range);
    } else if (lib[0] == 'u') {
      for (const char* f : {"char", "codepoint", "len", "offset"}) charge_field(L, f, cost_strings);
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
  luaL_setfuncs(L, fns, 0);
  lua_createtable(L, 0, 0);
  lua_setfield(L, -2, "vars");
  lua_setfield(L, env, "post");
  lua_pushvalue(L, env);
  lua_setfield(L, env, "_G");
  lua_remove(L, g);  // env stays
}

}  // namespace twinpost::scripting
