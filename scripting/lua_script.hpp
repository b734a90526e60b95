#pragma once
// A machine's Lua 5.4 script (issue 25, level 2): loaded once per job, run in a sandbox built
// from a whitelist, every call held to an instruction budget. This layer knows nothing of CL
// records or NC blocks beyond their text: the caller (machining/) hands it plain values and
// writes whatever post.emit() gives back through its own block writer, so a script's blocks
// pass the same checks as the post's own.
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace twinpost::scripting {

/// A script failed: a Lua syntax or run-time error, the budget ran out, or post.error().
/// `file` is the script's name as the user wrote it ("catcher.lua"), `line` the script line
/// (0 when Lua knows none). The caller adds the CL record being posted as a note.
struct script_error : std::runtime_error {
  script_error(std::string file_, int line_, std::string message_);
  std::string file;
  int line = 0;
  std::string message;      ///< without the "NAME.lua:LINE: " prefix
  std::string source_line;  ///< the script's line `line` as written (empty when line is 0)
};

/// What a script may do to the post: write a block at the current place, warn. Its functions
/// run inside a Lua call and must not throw: a host that refuses a block keeps the error and
/// reports it after the call returns.
class script_host {
 public:
  virtual ~script_host() = default;
  /// post.emit(text): one block into the current channel, at the current place. False when the
  /// post refused it (its checks reported why): the script stops there, so that a loop of
  /// refused blocks cannot flood the terminal with one error each.
  virtual bool emit(std::string_view block) = 0;
  /// post.warning(msg): a warning at the CL record being posted.
  virtual void warning(std::string_view message) = 0;
};

/// One CL record handed to on_record(rec): rec.major, rec.words, rec.line.
struct script_record {
  std::string_view major;
  std::vector<std::string> words;
  int line = 0;
};

/// The tool handed to on_tool_change(tool).
struct script_tool {
  int number = 0;
  int offset = 0;
  std::string_view name;
  std::string_view kind;
  double length = 0;
  double diameter = 0;
  int channel = 0;
};

/// The context table of on_program_start/end(ctx) and on_block(text, ctx).
struct script_context {
  int channel = 0;
  std::string_view program;  ///< the program's name or number as written
  int cl_line = 0;           ///< the CL record being posted (0: none)
  /// on_block's: where the block stands, "header", "body" or "footer"; null: not given.
  const char* part = nullptr;
};

/// on_block's answer.
enum class block_verdict { keep, replace, drop };

/// The limits of the sandbox (docs/scripting.md, "What a script cannot do"). The job's
/// instructions and seconds may be raised by the machine file ([events] script_instructions,
/// script_seconds); the others are fixed.
struct script_limits {
  long instructions_per_call = 10'000'000;         ///< Lua VM instructions per hook call
  long long instructions_per_job = 1'000'000'000;  ///< VM instructions + bytes of C work, whole job
  double seconds_per_job = 60;                     ///< wall-clock time inside the script, whole job
  std::size_t memory_bytes = 64u << 20;            ///< the whole Lua state
  std::size_t read_file_bytes = 16u << 20;         ///< one post.read_file()
  std::size_t script_bytes = 4u << 20;             ///< the script file itself
  std::size_t pattern_subject_bytes = 1u << 20;    ///< a subject of string.find/match/gmatch/gsub
  double pattern_steps = 1e8;                      ///< the matcher's worst case for one call
  std::size_t emit_bytes = 64u << 20;              ///< post.emit and on_block's growth, whole job
  long warnings = 1000;                            ///< post.warning calls, whole job
  std::size_t warning_bytes = 1u << 20;            ///< their text, whole job
};

/// `text` with every control byte but tab (0x00-0x1f, 0x7f) and every byte >= 0x80 written as
/// \xHH, so that a script's message cannot send a terminal escape sequence (C1 controls
/// included: U+009B is CSI to a terminal, and a bare 0x9B to an 8-bit one).
std::string escape_controls(std::string_view text);

struct script_state;  // scripting/lua_state.hpp

/// A loaded script. Not copyable; one per job (post.vars lives as long as the object).
class lua_script {
 public:
  /// Loads `path` (named in error messages by its file name) and runs its top level in the
  /// sandbox. post.read_file reads beside `path`. Throws script_error.
  lua_script(const std::string& path, script_limits limits = {});
  /// Loads `source` as if it were the file `path` (tests, and files already read).
  lua_script(const std::string& path, std::string_view source, script_limits limits = {});
  ~lua_script();
  lua_script(const lua_script&) = delete;
  lua_script& operator=(const lua_script&) = delete;

  /// The file name errors use ("catcher.lua").
  const std::string& name() const;

  /// Which hooks the script defines: the caller asks once and keeps a pointer test per event.
  bool has_on_record() const;
  bool has_on_tool_change() const;
  bool has_on_program_start() const;
  bool has_on_program_end() const;
  bool has_on_block() const;

  /// Each call runs the hook if defined (else does nothing), with `host` receiving post.emit
  /// and post.warning. Throws script_error.
  void on_record(const script_record& rec, script_host& host);
  void on_tool_change(const script_tool& tool, script_host& host);
  void on_program_start(const script_context& ctx, script_host& host);
  void on_program_end(const script_context& ctx, script_host& host);
  /// on_block(text, ctx): a string replaces the block (into `replacement`), false drops it,
  /// nothing (or true) keeps it. Throws script_error, also for any other return value.
  block_verdict on_block(std::string_view text, const script_context& ctx, script_host& host,
                         std::string& replacement);

 private:
  std::unique_ptr<script_state> impl_;
};

}  // namespace twinpost::scripting
