// The length offset's cancel away from home (analysis/length_offset.hpp), through the
// checker's reading (check_nc_resources): messages asserted to the letter.
#include <catch2/catch.hpp>

#include <string>

#include "analysis/shared_resources.hpp"
#include "check/sync_report.hpp"
#include "machines/machine_loader.hpp"

using namespace twinpost;

namespace {

std::string check(const std::string& program) {
  return format_sync_text(check_nc_resources({{"P.nc", program}}, load_machine("rotary-4axis")));
}

const std::string start = "%\nO1000\nG21\nG54 G90 G94 G17 G40 G49 G80\nG91 G28 Z0.\nG90\nT01 M6\nS3000 M3\n";
const std::string cut = "G0 X0. Y0.\nG0 G43 H1 Z50.\nG1 Z-5. F500.\nX20.\nG0 Z50.\n";
const std::string clean = "check: 1 channel, 0 waits paired, 0 errors\n";

}  // namespace

TEST_CASE("length offset: G49 after the home return is quiet, before it a warning at the G49", "[analysis]") {
  // The header's G49 (no offset in force) and the cancel after G91 G28 Z0.: quiet.
  CHECK(check(start + cut + "M5\nM9\nG91 G28 Z0.\nG90\nG49\nM30\n%\n") == clean);
  // Home and cancel in one block, either order of the words: at home.
  CHECK(check(start + cut + "G49 G91 G28 Z0.\nM30\n%\n") == clean);
  CHECK(check(start + cut + "G91 G28 Z0. G49\nM30\n%\n") == clean);
  // Z in machine coordinates (the Integrex's home blocks): at home.
  CHECK(check(start + cut + "G0 G90 G53 Z0.\nG49\nM30\n%\n") == clean);
  // G53 of X alone does not bring Z home.
  CHECK(check(start + cut + "G0 G90 G53 X0.\nG49\nG91 G28 Z0.\nM30\n%\n") ==
        "P.nc:15:1: warning: channel 1: G49 cancels the length offset (G43 at line 10) away from the "
        "home position: a control that cancels at once moves Z towards the part by the tool's length; "
        "cancel it after the reference return (G28/G53 Z)\nG49\n^\n"
        "check: 1 channel, 0 waits paired, 0 errors, 1 warning\n");
  // The order twinpost wrote before: G49 at the last CL point, then the home return.
  CHECK(check(start + cut + "G49\nM5\nG91 G28 Z0.\nG90\nM30\n%\n") ==
        "P.nc:14:1: warning: channel 1: G49 cancels the length offset (G43 at line 10) away from the "
        "home position: a control that cancels at once moves Z towards the part by the tool's length; "
        "cancel it after the reference return (G28/G53 Z)\nG49\n^\n"
        "check: 1 channel, 0 waits paired, 0 errors, 1 warning\n");
  // A move without a G word after the home leaves it; G43.4 is a length offset too.
  CHECK(check(start + "G0 A0.\nG0 G43.4 H1 X0. Y0. Z50. A0.\nG91 G28 Z0.\nG90\nX10.\nG49\nM30\n%\n") ==
        "P.nc:14:1: warning: channel 1: G49 cancels the length offset (G43.4 at line 10) away from the "
        "home position: a control that cancels at once moves Z towards the part by the tool's length; "
        "cancel it after the reference return (G28/G53 Z)\nG49\n^\n"
        "check: 1 channel, 0 waits paired, 0 errors, 1 warning\n");
}
