// The machine's Lua script (scripting/lua_script): the sandbox, the budget, the error texts,
// and each hook's arguments and answers.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "scripting/lua_script.hpp"

using namespace twinpost::scripting;

namespace {

// Records what a script asks of the post.
struct recording_host : script_host {
  std::vector<std::string> blocks, warnings;
  bool emit(std::string_view b) override {
    blocks.emplace_back(b);
    return true;
  }
  void warning(std::string_view m) override { warnings.emplace_back(m); }
};

// The exact text of the error a script gives, or "" when none.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const script_error& e) {
    return e.what();
  }
  return "";
}

std::string load_error(const char* source) {
  return error_of([&] { lua_script s("/m/ev.lua", source); });
}

}  // namespace

TEST_CASE("lua script: a syntax error names the script and its line", "[scripting]") {
  CHECK(load_error("x = 1\nfunction on_block(t\n") == "ev.lua:3: ')' expected near <eof>");
}

TEST_CASE("lua script: the sandbox has no os, io, package, debug, load or require", "[scripting]") {
  for (const char* name : {"os", "io", "package", "debug", "load", "loadfile", "dofile", "require",
                           "collectgarbage", "print", "loadstring"}) {
    INFO(name);
    std::string src = std::string("assert(") + name + " == nil, 'open')";
    CHECK(load_error(src.c_str()).empty());
  }
  CHECK(load_error("os.exit(1)") == "ev.lua:1: attempt to index a nil value (global 'os')");
  CHECK(load_error("local f = io.open('/etc/passwd')") ==
        "ev.lua:1: attempt to index a nil value (global 'io')");
  CHECK(load_error("\n require('os')") == "ev.lua:2: attempt to call a nil value (global 'require')");
  CHECK(load_error("assert(string.dump == nil and string.format ~= nil and math.floor ~= nil "
                   "and table.concat ~= nil and utf8.char ~= nil)")
            .empty());
}

TEST_CASE("lua script: precompiled bytecode is refused", "[scripting]") {
  std::string chunk = "\x1bLua";
  CHECK(error_of([&] { lua_script s("/m/ev.lua", chunk); }) ==
        "ev.lua: attempt to load a binary chunk (mode is 't')");
}

TEST_CASE("lua script: a runaway call stops at its budget, even inside pcall", "[scripting]") {
  script_limits limits;
  limits.instructions_per_call = 100000;
  lua_script s("/m/ev.lua",
               "function on_block(t)\n"
               "  while true do\n"
               "    pcall(function() while true do end end)\n"
               "  end\n"
               "end\n",
               limits);
  recording_host host;
  std::string r;
  CHECK(error_of([&] { s.on_block("G0 X1", {}, host, r); }) ==
        "ev.lua:3: instruction budget of 100000 exceeded (an endless loop?)");
  // The script can be called again afterwards with a fresh budget; a second runaway too.
  CHECK(error_of([&] { s.on_block("G0 X1", {}, host, r); }) ==
        "ev.lua:3: instruction budget of 100000 exceeded (an endless loop?)");
  CHECK(load_error("while true do end").find("instruction budget") != std::string::npos);
}

TEST_CASE("lua script: memory has a ceiling", "[scripting]") {
  script_limits limits;
  limits.memory_bytes = 4u << 20;
  std::string e =
      error_of([&] { lua_script s("/m/ev.lua", "local s = 'x'\nwhile true do s = s .. s end", limits); });
  CHECK(e == "ev.lua: not enough memory");
}

TEST_CASE("lua script: a run-time error and post.error name the script line", "[scripting]") {
  lua_script s("/m/ev.lua",
               "function on_record(rec)\n"
               "  if rec.major == 'BAD' then post.error('no such catcher: ' .. rec.words[1]) end\n"
               "  local x = nil + 1\n"
               "end\n");
  recording_host host;
  CHECK(error_of([&] { s.on_record({"BAD", {"ON"}, 12}, host); }) == "ev.lua:2: no such catcher: ON");
  CHECK(error_of([&] {
          s.on_record({"OTHER", {}, 12}, host);
        }) == "ev.lua:3: attempt to perform arithmetic on a nil value");
  script_error e("ev.lua", 0, "x");
  CHECK(std::string(e.what()) == "ev.lua: x");
  CHECK(e.source_line.empty());
}

TEST_CASE("lua script: an error carries the script line it names, as written", "[scripting]") {
  const auto line_of = [](std::string_view source, const char* major) {
    try {
      lua_script s("/m/ev.lua", source);
      recording_host host;
      s.on_record({major, {}, 1}, host);
    } catch (const script_error& e) {
      return std::to_string(e.line) + "|" + e.source_line;
    }
    return std::string("(no error)");
  };
  // CRLF line ends are not part of the line; the last line may have no line end.
  const std::string crlf =
      "function on_record(rec)\r\n\tif rec.major == 'A' then post.error('a') end\r\n"
      "  local x = nil + 1 end";
  CHECK(line_of(crlf, "A") == "2|\tif rec.major == 'A' then post.error('a') end");
  CHECK(line_of(crlf, "B") == "3|  local x = nil + 1 end");
  // No line: nothing quoted.
  CHECK(line_of("function on_record(rec) error({}) end", "A") == "0|");
  CHECK(error_of([&] { lua_script t("/m/ev.lua", "error({})"); }) == "ev.lua: error object is a table value");
}

TEST_CASE("lua script: on_record gets major, words and line, emits and warns", "[scripting]") {
  lua_script s(
      "/m/ev.lua",
      "function on_record(rec)\n"
      "  post.emit(string.format('(%s %s L%d)', rec.major, table.concat(rec.words, ','), rec.line))\n"
      "  if rec.words[1] == 'ON' then post.emit('M77') else post.warning('off') end\n"
      "end\n");
  CHECK(s.has_on_record());
  CHECK_FALSE(s.has_on_block());
  CHECK_FALSE(s.has_on_tool_change());
  recording_host host;
  s.on_record({"PARTS_CATCHER", {"ON", "2"}, 40}, host);
  s.on_record({"PARTS_CATCHER", {"OFF"}, 41}, host);
  CHECK(host.blocks ==
        std::vector<std::string>{"(PARTS_CATCHER ON,2 L40)", "M77", "(PARTS_CATCHER OFF L41)"});
  CHECK(host.warnings == std::vector<std::string>{"off"});
  CHECK(error_of([&] {
          lua_script t("/m/ev.lua", "function on_record() post.emit('M1\\nM2') end");
          t.on_record({"X", {}, 1}, host);
        }) == "ev.lua:1: post.emit: one block per call, without a line break");
}

TEST_CASE("lua script: on_block keeps, replaces or drops, post.vars lives through the job", "[scripting]") {
  lua_script s("/m/ev.lua",
               "post.vars.n = 0\n"
               "function on_block(text, ctx)\n"
               "  post.vars.n = post.vars.n + 1\n"
               "  if text == 'G28 U0.' then return 'G30 U0.' end\n"
               "  if text:match('^%(') then return false end\n"
               "  if text == 'COUNT' then return '#500=' .. post.vars.n .. ' (CH' .. ctx.channel .. ')' end\n"
               "end\n");
  recording_host host;
  std::string r;
  CHECK(s.on_block("G0 X1.", {}, host, r) == block_verdict::keep);
  CHECK(s.on_block("G28 U0.", {}, host, r) == block_verdict::replace);
  CHECK(r == "G30 U0.");
  CHECK(s.on_block("(T1 DRILL)", {}, host, r) == block_verdict::drop);
  CHECK(s.on_block("COUNT", {2, "O1000", 7}, host, r) == block_verdict::replace);
  CHECK(r == "#500=4 (CH2)");
  lua_script bad("/m/ev.lua", "function on_block() return 3 end");
  CHECK(error_of([&] { bad.on_block("G0", {}, host, r); }) ==
        "ev.lua: on_block returned a number: return a string, false or nothing");
  lua_script two("/m/ev.lua", "function on_block() return 'M1\\nM2' end");
  CHECK(error_of([&] { two.on_block("G0", {}, host, r); }) ==
        "ev.lua: on_block returned more than one block (a line break)");
  CHECK(load_error("on_block = 3") == "ev.lua: on_block must be a function");
}

TEST_CASE("lua script: on_tool_change and the program hooks get their tables", "[scripting]") {
  lua_script s("/m/ev.lua",
               "function on_tool_change(t)\n"
               "  post.emit(string.format('(T%d D%d %s %s L%.1f D%.1f CH%d)', t.number, t.offset,\n"
               "    t.name, t.kind, t.length, t.diameter, t.channel))\n"
               "end\n"
               "function on_program_start(c) post.emit('(START ' .. c.program .. ')') end\n"
               "function on_program_end(c) post.emit('(END CH' .. c.channel .. ')') end\n");
  recording_host host;
  s.on_tool_change({5, 105, "DRILL 8", "drill", 120.5, 8, 1}, host);
  s.on_program_start({1, "O1000", 0}, host);
  s.on_program_end({2, "O2000", 0}, host);
  CHECK(host.blocks ==
        std::vector<std::string>{"(T5 D105 DRILL 8 drill L120.5 D8.0 CH1)", "(START O1000)", "(END CH2)"});
}

TEST_CASE("lua script: post.read_file reads beside the script and nowhere else", "[scripting]") {
  std::string tmp = "/tmp/twinpost-lua-test-tools.csv";
  {
    std::ofstream out(tmp);
    out << "5;DRILL 8\n";
  }
  lua_script s("/tmp/ev.lua",
               "function on_record(rec)\n"
               "  post.emit(post.read_file(rec.words[1]))\n"
               "end\n");
  recording_host host;
  std::string csv = "twinpost-lua-test-tools.csv";
  CHECK(error_of([&] {
          s.on_record({"R", {csv}, 1}, host);
        }) == "ev.lua:2: post.emit: one block per call, without a line break");
  lua_script t("/tmp/ev.lua",
               "function on_record(rec) post.emit((post.read_file(rec.words[1]):gsub('\\n', ''))) end");
  t.on_record({"R", {csv}, 1}, host);
  CHECK(host.blocks == std::vector<std::string>{"5;DRILL 8"});
  CHECK(error_of([&] {
          t.on_record({"R", {"../etc/passwd"}, 1}, host);
        }) == "ev.lua:1: post.read_file: '../etc/passwd' is not a file name beside the machine file");
  CHECK(error_of([&] {
          t.on_record({"R", {"/etc/passwd"}, 1}, host);
        }) == "ev.lua:1: post.read_file: '/etc/passwd' is not a file name beside the machine file");
  CHECK(error_of([&] {
          t.on_record({"R", {"none.csv"}, 1}, host);
        }) == "ev.lua:1: post.read_file: no file 'none.csv' beside the machine file");
  std::remove(tmp.c_str());
}

TEST_CASE("lua script: a missing script file", "[scripting]") {
  CHECK(error_of([] { lua_script s("/nonexistent/ev.lua"); }) ==
        "ev.lua: cannot read the script '/nonexistent/ev.lua'");
}

// Issue 38: what a script from someone else cannot do to the post.

TEST_CASE("lua script: a strict mode on _ENV neither crashes the load nor hides the hooks", "[scripting]") {
  lua_script s("/m/ev.lua",
               "setmetatable(_ENV, {__index = function(_, k) error('undefined ' .. k) end})\n"
               "function on_block(text)\n"
               "  return undefined_name\n"
               "end\n");
  CHECK(s.has_on_block());
  CHECK_FALSE(s.has_on_record());
  recording_host host;
  std::string r;
  CHECK(error_of([&] { s.on_block("G0", {}, host, r); }) == "ev.lua:1: undefined undefined_name");
  CHECK(load_error("setmetatable(_ENV, {__index = function(_, k) error('undefined ' .. k, 2) end})\n"
                   "local x = y\n") == "ev.lua:2: undefined y");
}

TEST_CASE("lua script: a metatable with __gc is refused", "[scripting]") {
  CHECK(load_error("setmetatable({}, {__gc = function() while true do end end})") ==
        "ev.lua:1: setmetatable: a metatable with __gc is refused (a finalizer runs outside the script's "
        "budgets)");
  CHECK(load_error("local t = setmetatable({}, {}); getmetatable(t).__gc = function() end").empty());
}

TEST_CASE("lua script: the job's budget of instructions and of time", "[scripting]") {
  script_limits limits;
  limits.instructions_per_job = 1'000'000;
  lua_script s("/m/ev.lua",
               "function on_block(text)\n"
               "  for i = 1, 30000 do end\n"
               "end\n",
               limits);
  recording_host host;
  std::string r;
  std::string e;
  int calls = 0;
  while (e.empty() && calls < 1000) {
    e = error_of([&] { s.on_block("G0", {}, host, r); });
    ++calls;
  }
  CHECK(e ==
        "ev.lua:2: the job's budget of 1000000 instructions exceeded (bytes of string work count as "
        "instructions; [events] script_instructions raises it)");
  // 30 000 instructions a call (one FORLOOP an iteration): the 34th call crosses 10^6.
  CHECK(calls == 34);
  // Spent for the job: the next call fails at once.
  CHECK(error_of([&] { s.on_block("G0", {}, host, r); }) == e);

  script_limits slow;
  slow.instructions_per_call = 2'000'000'000;
  slow.instructions_per_job = 1'000'000'000'000;
  slow.seconds_per_job = 0.2;
  CHECK(error_of([&] { lua_script t("/m/ev.lua", "local n = 0\nwhile true do n = n + 1 end", slow); }) ==
        "ev.lua:2: the job's time budget of 0.2 s exceeded ([events] script_seconds raises it)");
}

TEST_CASE("lua script: C work is bounded before it starts and charged to the job", "[scripting]") {
  CHECK(
      load_error("local s = string.rep('a', 1e5)\nlocal i = s:find('.-.-.-.-b')") ==
      "ev.lua:2: string.find: the pattern '.-.-.-.-b' may take more than 1e+08 steps on a subject of 100000 "
      "bytes (the limit of one call): anchor it with '^' or repeat fewer items ('.-', '.*')");
  CHECK(load_error("local s = ('a'):rep(2^20 + 1)\nlocal i = s:find('a', 1, true)") ==
        "ev.lua:2: string.find: a subject of 1048577 bytes is over the limit of 1048576 bytes");
  CHECK(load_error("local s = string.rep('ab', 1e9)") ==
        "ev.lua:1: string.rep: a result of 2000000000 bytes is over the memory ceiling of 67108864 bytes");
  // Ordinary patterns on ordinary subjects pass.
  CHECK(load_error("local s = string.rep('5;DRILL 8\\n', 20000)\n"
                   "local n = 0 for a, b in s:gmatch('(%d+);([^\\n]*)\\n') do n = n + 1 end\n"
                   "assert(n == 20000)\n"
                   "assert(('N120 G1 X42.512 "
                   "Z-17.25'):match('^N(%d+)%s*G(%d+)%s*X([%-%d%.]+)%s*Z([%-%d%.]+)') == '120')\n"
                   "assert(select(2, s:gsub('DRILL', 'MILL')) == 20000)")
            .empty());
  // A loop of cheap VM instructions over expensive C calls: the bytes count.
  script_limits limits;
  limits.instructions_per_job = 10'000'000;
  CHECK(error_of([&] {
          lua_script t("/m/ev.lua",
                       "local s = string.rep('a', 1e6)\n"
                       "for i = 1, 100 do local x = s:find('b', 1, true) end\n",
                       limits);
        }) ==
        "ev.lua:2: the job's budget of 10000000 instructions exceeded (bytes of string work count as "
        "instructions; [events] script_instructions raises it)");
  CHECK(error_of([&] {
          lua_script t("/m/ev.lua",
                       "local s = string.rep('a', 1e6)\nfor i = 1, 100 do local x = s:upper() end\n", limits);
        }).find("ev.lua:2: the job's budget of 10000000") == 0);
  CHECK(error_of([&] {
          lua_script t("/m/ev.lua", "table.move({}, 1, 1e12, 2)", limits);
        }).find("ev.lua:1: the job's budget of 10000000") == 0);
}

TEST_CASE("lua script: string.dump is out of reach, also through the strings' metatable", "[scripting]") {
  CHECK(load_error("assert(string.dump == nil)\n"
                   "assert(('').dump == nil)\n"
                   "assert(getmetatable('') == false)\n"
                   "assert(('x'):upper() == 'X')\n"
                   "string.twice = function(s) return s .. s end\n"
                   "assert(('ab'):twice() == 'abab')")
            .empty());
  CHECK(load_error("local f = ('').dump(print)") == "ev.lua:1: attempt to call a nil value (field 'dump')");
}

TEST_CASE("lua script: what a script writes and warns is bounded and gated", "[scripting]") {
  recording_host host;
  std::string r;
  const auto emit_error = [&](const char* src) {
    return error_of([&] {
      lua_script t("/m/ev.lua", src);
      t.on_record({"X", {}, 1}, host);
    });
  };
  CHECK(emit_error("function on_record() post.emit('%') end") ==
        "ev.lua:1: post.emit: the block has a '%' (the tape mark: the control stops reading the program "
        "there)");
  CHECK(emit_error("function on_record() post.emit('G0\\0X1') end") ==
        "ev.lua:1: post.emit: the block has the control byte \\x00 (no NUL or control byte goes into a "
        "program)");
  CHECK(emit_error("function on_record() post.emit('(\\27[2J)') end") ==
        "ev.lua:1: post.emit: the block has the control byte \\x1b (no NUL or control byte goes into a "
        "program)");
  // Empty blocks count their line breaks: a loop of post.emit('') is bounded too.
  script_limits tight;
  tight.emit_bytes = 100;
  CHECK(error_of([&] {
          lua_script t("/m/ev.lua", "function on_record() for i = 1, 1000 do post.emit('') end end", tight);
          recording_host empty;
          t.on_record({"X", {}, 1}, empty);
        }) == "ev.lua:1: post.emit: the script wrote more than 100 bytes in the job (its limit)");
  CHECK(emit_error("function on_record() post.emit('(\\194\\133)') end") ==
        "ev.lua:1: post.emit: the block has the byte \\xc2 (a control reads ISO or EIA code, ASCII only; an "
        "editor may break the line at a UTF-8 NEL or LS)");
  lua_script esc("/m/ev.lua", "function on_block() return 'M30\\27' end");
  CHECK(error_of([&] { esc.on_block("G0", {}, host, r); }) ==
        "ev.lua: on_block returned a block with the control byte \\x1b (no NUL or control byte goes into a "
        "program)");
  lua_script pct("/m/ev.lua", "function on_block() return '%' end");
  CHECK(error_of([&] { pct.on_block("G0", {}, host, r); }) ==
        "ev.lua: on_block returned a block with a '%' (the tape mark: the control stops reading the program "
        "there)");

  script_limits limits;
  limits.emit_bytes = 100;
  limits.warnings = 3;
  limits.warning_bytes = 50;
  lua_script s("/m/ev.lua",
               "function on_record(rec)\n"
               "  if rec.major == 'EMIT' then for i = 1, 100 do post.emit('G4 X1.') end end\n"
               "  if rec.major == 'WARN' then for i = 1, 100 do post.warning('w') end end\n"
               "  if rec.major == 'LONG' then post.warning(string.rep('x', 60)) end\n"
               "  if rec.major == 'ESC' then post.warning('\\27[2Jgone\\0') end\n"
               "end\n",
               limits);
  CHECK(error_of([&] {
          s.on_record({"EMIT", {}, 1}, host);
        }) == "ev.lua:2: post.emit: the script wrote more than 100 bytes in the job (its limit)");
  CHECK(host.blocks.size() == 14);  // 14 blocks of 6 bytes and their line breaks: 98 bytes
  CHECK(error_of([&] { s.on_record({"ESC", {}, 1}, host); }).empty());
  CHECK(host.warnings == std::vector<std::string>{"\\x1b[2Jgone\\x00"});
  // C1 controls (U+009B, CSI; a bare 0x9B) and every other byte >= 0x80 are escaped too.
  lua_script c1("/m/ev.lua", "function on_record() post.warning('x\\194\\155' .. '2J\\155') end");
  host.warnings.clear();
  CHECK(error_of([&] { c1.on_record({"X", {}, 1}, host); }).empty());
  CHECK(host.warnings == std::vector<std::string>{"x\\xc2\\x9b2J\\x9b"});
  CHECK(error_of([&] {
          s.on_record({"WARN", {}, 1}, host);
        }) == "ev.lua:3: post.warning: more than 3 warnings in the job (its limit)");
  lua_script w("/m/ev.lua", "function on_record() post.warning(string.rep('x', 60)) end", limits);
  CHECK(error_of([&] {
          w.on_record({"X", {}, 1}, host);
        }) == "ev.lua:1: post.warning: more than 50 bytes of warnings in the job (its limit)");
  // An error's text keeps no control byte either.
  CHECK(load_error("error('\\27[31mred')") == "ev.lua:1: \\x1b[31mred");
  // A C function's error without a place gets the script's line.
  CHECK(load_error("\nlocal s = string.rep()") ==
        "ev.lua:2: bad argument #1 to 'rep' (string expected, got no value)");
}

TEST_CASE("lua script: reads stay in the machine file's folder, on regular files", "[scripting]") {
  char tmpl[] = "/tmp/twinpost-lua-XXXXXX";
  REQUIRE(mkdtemp(tmpl));
  const std::string dir = tmpl;
  {
    std::ofstream(dir + "/tools.csv") << "5;DRILL 8";
    std::ofstream(dir + "/big.csv") << std::string(100, 'x');
  }
  REQUIRE(symlink("/etc/passwd", (dir + "/passwd").c_str()) == 0);
  REQUIRE(mkfifo((dir + "/fifo").c_str(), 0600) == 0);
  REQUIRE(mkdir((dir + "/sub").c_str(), 0700) == 0);
  script_limits limits;
  limits.read_file_bytes = 50;
  lua_script s(dir + "/ev.lua", "function on_record(rec) post.emit(post.read_file(rec.major)) end", limits);
  recording_host host;
  const auto read = [&](const char* file) { return error_of([&] { s.on_record({file, {}, 1}, host); }); };
  CHECK(read("tools.csv").empty());
  CHECK(host.blocks == std::vector<std::string>{"5;DRILL 8"});
  CHECK(read("passwd") ==
        "ev.lua:1: post.read_file: 'passwd' is a symbolic link (only a regular file beside the machine file "
        "is read)");
  CHECK(read("fifo") ==
        "ev.lua:1: post.read_file: 'fifo' is not a regular file (a FIFO, a device or a folder)");
  CHECK(read("sub") ==
        "ev.lua:1: post.read_file: 'sub' is not a regular file (a FIFO, a device or a folder)");
  CHECK(read("big.csv") == "ev.lua:1: post.read_file: 'big.csv' is larger than 50 bytes");

  // The script file itself: no symbolic link, no FIFO, a size limit, its name in the error.
  { std::ofstream(dir + "/real.lua") << "x = 1"; }
  REQUIRE(symlink((dir + "/real.lua").c_str(), (dir + "/link.lua").c_str()) == 0);
  CHECK(error_of([&] { lua_script t(dir + "/link.lua"); }) ==
        "link.lua: the script '" + dir +
            "/link.lua' is a symbolic link (only a regular file beside the machine file is read)");
  CHECK(error_of([&] { lua_script t(dir + "/fifo"); }) ==
        "fifo: the script '" + dir + "/fifo' is not a regular file (a FIFO, a device or a folder)");
  script_limits small;
  small.script_bytes = 4;
  CHECK(error_of([&] { lua_script t(dir + "/real.lua", small); }) ==
        "real.lua: the script '" + dir + "/real.lua' is larger than 4 bytes");
  CHECK(error_of([&] { lua_script t(dir + "/real.lua"); }).empty());
  std::filesystem::remove_all(dir);
}

TEST_CASE("lua script: a malformed pattern counts the items before its fault", "[scripting]") {
  // Found by the script fuzz target: the matcher backtracks through '.-.-' for every start
  // and never reaches the unclosed '[' (the literal before it fails first).
  CHECK(load_error("local s = string.rep('a', 1e5)\nlocal i = s:find('.-.-x[y')") ==
        "ev.lua:2: string.find: the pattern '.-.-x[y' may take more than 1e+08 steps on a subject of 100000 "
        "bytes (the limit of one call): anchor it with '^' or repeat fewer items ('.-', '.*')");
  CHECK(load_error("local i = ('abc'):find('[a')") == "ev.lua:1: malformed pattern (missing ']')");
}

TEST_CASE("lua script: the second attack's C work is charged or refused before it runs", "[scripting]") {
  script_limits limits;
  limits.instructions_per_job = 10'000'000;
  auto job_error = [&](const char* source) {
    return error_of([&] { lua_script t("/m/ev.lua", source, limits); });
  };
  const std::string spent = "the job's budget of 10000000 instructions exceeded";
  // rep('', n) copies nothing n times: charged by its count.
  CHECK(job_error("local s = string.rep('', math.maxinteger)").find("ev.lua:1: " + spent) == 0);
  // The table library reads the length through __len (luaL_len): so does the charge.
  CHECK(job_error("local t = setmetatable({}, {__len = function() return 1e15 end})\ntable.insert(t, 1, 'x')")
            .find("ev.lua:2: " + spent) == 0);
  CHECK(job_error("local t = setmetatable({}, {__len = function() return 1e15 end})\ntable.remove(t, 1)")
            .find("ev.lua:2: " + spent) == 0);
  CHECK(job_error("local t = setmetatable({}, {__index = function() return '' end})\n"
                  "local s = table.concat(t, '', 1, 1e12)")
            .find("ev.lua:2: " + spent) == 0);
  // table.sort compares strings: their bytes count, times log n.
  CHECK(
      job_error("local big, t = string.rep('x', 1e6), {} for i = 1, 5 do t[i] = big .. i end\ntable.sort(t)")
          .find("ev.lua:2: " + spent) == 0);
  // tonumber(s, base) reads every byte.
  CHECK(job_error("local s = string.rep('1', 1e6)\nfor i = 1, 20 do local n = tonumber(s, 36) end")
            .find("ev.lua:2: " + spent) == 0);
  // A plain search is linear (Boyer-Moore past 10^7 byte pairs) and charged by its bytes.
  CHECK(job_error("local s, p = string.rep('a', 1e6), string.rep('a', 5000) .. 'b'\n"
                  "for i = 1, 20 do local x = s:find(p, 1, true) end")
            .find("ev.lua:2: " + spent) == 0);
  // A concatenation of long strings is one instruction: its allocation is charged.
  CHECK(job_error("local a = string.rep('x', 1e6)\nfor i = 1, 100 do local c = a .. i end")
            .find("ev.lua:2: " + spent) == 0);
}

TEST_CASE("lua script: a plain search answers as Lua's string.find does", "[scripting]") {
  CHECK(
      load_error(
          "assert(('hello world'):find('o w', 1, true) == 5)\n"
          "assert(('hello'):find('l') == 3)\n"
          "assert(('hello'):find('', 10) == nil)\n"
          "assert(('hello'):find('', 6) == 6)\n"
          "assert(('hello'):find('lo', -2) == 4)\n"
          "assert(('hello'):find('lo', -99) == 4)\n"
          "assert(('a.b'):find('.', 1, true) == 2)\n"
          "local a, b = ('xx'):find('') assert(a == 1 and b == 0)\n"
          "local c, d = ('abcabc'):find('cab', 2, true) assert(c == 3 and d == 5)\n"
          "assert(('abc'):find('d', 1, true) == nil)\n"
          "local s = string.rep('a', 1e5) .. 'b' local e, f = s:find(string.rep('a', 500) .. 'b', 1, true)\n"
          "assert(e == 1e5 - 499 and f == 1e5 + 1)")
          .empty());
}

TEST_CASE("lua script: the pattern guard's own work is bounded", "[scripting]") {
  // Long literal patterns compare at every start: the items count.
  CHECK(
      load_error("local s = string.rep('a', 1e6)\nlocal x = s:match(string.rep('a', 5000) .. 'b')") ==
      "ev.lua:2: string.match: the pattern 'aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa...' may take more than "
      "1e+08 steps on a subject of 1000000 bytes (the limit of one call): anchor it with '^' or repeat fewer "
      "items ('.-', '.*')");
  // In gmatch '^' is a byte, not an anchor (Lua 5.4 lstrlib.c).
  CHECK(
      load_error("local s = string.rep('a', 1e5)\nfor x in s:gmatch('^.-.-.-b') do end") ==
      "ev.lua:2: string.gmatch: the pattern '^.-.-.-b' may take more than 1e+08 steps on a subject of 100000 "
      "bytes (the limit of one call): repeat fewer items ('.-', '.*'); in gmatch '^' is no anchor");
  // 3 000 repeated items over a megabyte: the scans for their runs are charged before they run.
  script_limits limits;
  limits.instructions_per_job = 10'000'000;
  CHECK(error_of([&] {
          lua_script t("/m/ev.lua",
                       "local s = string.rep('1', 1e6)\nlocal x = s:find(string.rep('[a-z]*', 3000))",
                       limits);
        }).find("ev.lua:2: the job's budget of 10000000 instructions exceeded") == 0);
}

TEST_CASE("lua script: an error's text and the script's name reach the terminal bounded and escaped",
          "[scripting]") {
  const std::string e = load_error("error(string.rep('\\1', 25e6))");
  // The first 1 000 bytes of "ev.lua:1: " and the 25 MB, each \x01 shown as 4.
  CHECK(e.size() == 10 + 990 * 4 + std::string("... (25000010 bytes in all)").size());
  CHECK(e.substr(e.size() - 27) == "... (25000010 bytes in all)");
  CHECK(e.substr(0, 18) == "ev.lua:1: \\x01\\x01");
  CHECK(error_of([] { lua_script s("/m/e\x1b[2Jv.lua", "error('x')"); }) == "e\\x1b[2Jv.lua:1: x");
  CHECK(error_of([] { lua_script s(std::string("/m/ev.lua\0/etc/passwd", 21)); }) ==
        "passwd: the script's name holds a NUL byte");
}

TEST_CASE("lua script: the third attack's patterns and searches are refused or linear", "[scripting]") {
  // A needle longer than the subject finds nothing at once; a long one is searched in linear time.
  CHECK(load_error(
            "local n = string.rep('a', 1e6) .. 'b'\nassert(('aaaa'):find(n, 1, true) == nil)\n"
            "local s = string.rep('a', 1e6)\nassert(s:find(string.rep('a', 5e5) .. 'b', 1, true) == nil)")
            .empty());
  // The matcher walks a set for every byte: a set is at most 512 bytes.
  CHECK(load_error("local s = string.rep('a', 1e5)\nlocal i = s:find('[' .. string.rep('b', 4000) .. ']')") ==
        "ev.lua:2: string.find: the pattern has a set [...] of 4002 bytes (at most 512): name its bytes "
        "once, or "
        "by ranges");
  CHECK(load_error("assert(('x1'):find('[%a%d_%-%.]+') == 1)").empty());
  // gsub reads its replacement at every match, empty ones too: charged before the call.
  {
    script_limits limits;
    limits.instructions_per_job = 10'000'000;
    CHECK(error_of([&] {
            lua_script t(
                "/m/ev.lua",
                "local s = string.rep('b', 1e6)\nlocal out = s:gsub('b(c*)', string.rep('%1', 3000))",
                limits);
          }).find("ev.lua:2: the job's budget of 10000000 instructions exceeded") == 0);
  }
  // xpcall's handler runs with the count hook off (Lua 5.4): it is not in the sandbox.
  CHECK(load_error("assert(xpcall == nil)").empty());
  // C callbacks run outside the count.
  CHECK(load_error("local t = {'b', 'a'}\ntable.sort(t, pcall)") ==
        "ev.lua:2: table.sort: a comparator written in C is refused (its calls run outside the budgets); "
        "give a Lua "
        "function");
  CHECK(load_error("local s = ('ab'):gsub('.', pcall)") ==
        "ev.lua:1: string.gsub: a replacement function written in C is refused (its calls run outside the "
        "budgets); give a Lua function, a string or a table");
  CHECK(
      load_error("local t = {'b', 'a'}\ntable.sort(t, function(x, y) return x < y end)\nassert(t[1] == 'a')\n"
                 "assert(('ab'):gsub('.', function(c) return c .. c end) == 'aabb')")
          .empty());
  // table.sort through a metatable reads and compares in C what no charge sees.
  CHECK(load_error("local t = setmetatable({}, {__index = {'b', 'a'}, __len = function() return 2 end})\n"
                   "table.sort(t)") ==
        "ev.lua:2: table.sort: a table with a metatable is refused (its reads and compares would run outside "
        "the "
        "budgets); sort a plain table");
  CHECK(load_error("local t = {'b', 'a'}\ntable.sort(t)\nassert(t[1] == 'a')").empty());
}
