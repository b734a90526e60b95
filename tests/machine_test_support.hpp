#pragma once
// Test support for machine-file tests.
#include <stdexcept>
#include <string>

#include "file_test_support.hpp"
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

/// The built-in fanuc-0itd-twin with a header in G-code system C (G71 millimetres, G90
/// absolute), which no built-in machine is in: G70/G71 are its units, G20/G21 its cycles.
inline machine system_c_twin() {
  std::string text = read_file(std::string(TWINPOST_SOURCE_DIR) + "/machines/builtin/fanuc-0itd-twin.toml");
  const std::string header = "header = [\"G0 G18 G21 G40 G54 G80 G99\"]";
  const std::size_t at = text.find(header);
  if (at == std::string::npos) throw std::logic_error("fanuc-0itd-twin.toml's header changed");
  text.replace(at, header.size(), "header = [\"G0 G18 G71 G40 G54 G80 G90 G99\"]");
  return parse_machine(text, "sysc.toml");
}

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
