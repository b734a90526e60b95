#pragma once
// Test support for machine-file tests.
#include <string>

#include "machines/machine.hpp"
#include "machines/machine_loader.hpp"
#include "support/errors.hpp"

namespace twinpost::test {

/// Lines 1-5 of most test documents: a valid [machine] and [waits]. Line 6 is where a test
/// adds the key it is about.
inline const std::string machine_head =
    "[machine]\n"
    "name = \"m\"\n"
    "[waits]\n"
    "first = 100\n"
    "last = 103\n";

/// The X and Z axes every channel needs, as one line.
inline const std::string xz_axes = "axis = [{address = \"X\"}, {address = \"Z\"}]\n";

/// Two valid channels, appended after the line that a test is about.
inline const std::string two_channels =
    "[[channel]]\nnumber = 1\n" + xz_axes + "[[channel]]\nnumber = 2\n" + xz_axes;

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
