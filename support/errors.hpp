#pragma once
// The library's exception types. The library never prints or exits: the CLI catches these,
// prefixes the program name once and chooses the exit status.
#include <stdexcept>

namespace twinpost {

/// The one exception type for fatal configuration and I/O errors (bad machine file, bad
/// format, an output folder that cannot be written). The message is complete, e.g.
/// "m.toml:12:3: error: waits.first must be <= waits.last".
struct config_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace twinpost
