#pragma once
// The library's exception types. The library never prints or exits, and never names the
// program: the CLI catches these, puts the program name before a message that has no place
// of its own, and chooses the exit status.
#include <stdexcept>
#include <string>
#include <string_view>

namespace twinpost {

/// The one exception type for fatal configuration and I/O errors (bad machine file, bad
/// format, an output folder that cannot be written). Two kinds, told apart by how the error
/// was made, never by its text:
/// - about the run as a whole (`config_error("cannot read 'a.cls': ...")`): the message
///   alone; the tool prints its own name and "error: " before it;
/// - at a place in an input (`config_error::at(...)`): the message is complete,
///   "m.toml:12:3: error: waits.first must be <= waits.last", and is printed as it is.
struct config_error : std::runtime_error {
  explicit config_error(const std::string& message) : std::runtime_error(message) {}

  /// An error at line:column of `file` (1-based): "FILE:LINE:COL: error: MESSAGE".
  static config_error at(std::string_view file, long line, long column, std::string_view message) {
    std::string full(file);
    full += ':' + std::to_string(line) + ':' + std::to_string(column) + ": error: ";
    full += message;
    return config_error(std::move(full), true);
  }

  /// True when the message begins with its own place (made by at()).
  bool located() const noexcept { return located_; }

 private:
  config_error(std::string full, bool located) : std::runtime_error(full), located_(located) {}
  bool located_ = false;
};

}  // namespace twinpost
