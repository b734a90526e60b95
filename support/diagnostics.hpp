#pragma once
// Compiler-style diagnostics: `file:line:col: error: message`, the source line, a caret.
// The library reports into a sink; only the command-line tool prints.
#include <string>
#include <vector>

namespace twinpost {

enum class severity { note, warning, error };

/// "note", "warning" or "error": the word in a diagnostic's text and in the JSON report.
const char* severity_name(severity s);

/// One diagnostic. line and column are 1-based; column 0 means "no column".
struct diagnostic {
  severity level = severity::error;
  std::string file;
  int line = 0;
  int column = 0;
  std::string message;
  std::string source_line;  ///< the physical source line, without its line ending
  /// Where the caret goes under source_line when the place has no column of its own (a Lua
  /// error knows its line only): 1-based, not written in the `file:line:` prefix. 0: column.
  int caret = 0;
};

/// Errors and warnings counted as diagnostics pass by: whether a run failed is decided from
/// this one count (a note counts as neither).
struct diagnostic_counts {
  int errors = 0;
  int warnings = 0;
  void add(const diagnostic& d) {
    errors += d.level == severity::error;
    warnings += d.level == severity::warning;
  }
};

/// Formats `d` as `file:line:col: error: message`, then the source line and a caret line
/// when a source line is known. Ends with a newline.
std::string format_diagnostic(const diagnostic& d);

/// Receives diagnostics as they happen.
class diagnostic_sink {
 public:
  virtual ~diagnostic_sink() = default;
  virtual void report(diagnostic d) = 0;
};

/// A sink that keeps every diagnostic and counts errors.
class diagnostic_list : public diagnostic_sink {
 public:
  void report(diagnostic d) override;
  const std::vector<diagnostic>& all() const { return items_; }
  int errors() const { return counts_.errors; }
  int warnings() const { return counts_.warnings; }

 private:
  std::vector<diagnostic> items_;
  diagnostic_counts counts_;
};

}  // namespace twinpost
