#pragma once
// Test support for machine-file tests.
#include <string>

#include "machines/machine.hpp"
#include "machines/machine_loader.hpp"
#include "support/errors.hpp"

namespace twinpost::test {

/// The message of the config_error that parsing `text` (as "m.toml") throws, or "(no error)".
inline std::string machine_error_of(const std::string& text) {
  try {
    (void)parse_machine(text, "m.toml");
  } catch (const config_error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace twinpost::test
