// The machine's Lua script (scripting/lua_script): the sandbox, the budget, the error texts,
// and each hook's arguments and answers.
#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "scripting/lua_script.hpp"

using namespace twinpost::scripting;

namespace {

// Records what a script asks of the post.
struct recording_host : script_host {
  std::vector<std::string> blocks, warnings;
  void emit(std::string_view b) override { blocks.emplace_back(b); }
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
