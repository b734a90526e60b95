#pragma once
// Test support for machine-file tests.
#include <string>

#include "machines/machine.hpp"
#include "machines/machine_loader.hpp"
#include "support/errors.hpp"

namespace twinpost::test {

/// The message of the config_error that parsing `text` (as "m.toml") throws, or "(no error)".
/// Every error in a machine file is at a place in it: one made without a place (which the
/// tool would print after its name) shows as "(no place) MESSAGE" and fails the test.
inline std::string machine_error_of(const std::string& text) {
  try {
    (void)parse_machine(text, "m.toml");
  } catch (const config_error& e) {
    return e.located() ? std::string(e.what()) : "(no place) " + std::string(e.what());
  }
  return "(no error)";
}

}  // namespace twinpost::test
