// Tool calls in a post: a change of offset on the same tool is written, never dropped.
#include <catch2/catch.hpp>

#include <string>

#include "file_test_support.hpp"
#include "machines/machine_loader.hpp"
#include "post_test_jobs.hpp"

using namespace twinpost;

TEST_CASE("the same tool under another offset writes the new offset without indexing the turret",
          "[post][tools]") {
  // Roughing on offset 01, finishing with the same insert on offset 21 (wear compensated
  // apart): the finish must run on T0121, not on the roughing offset.
  const std::string dir = test::fresh_temp_dir("tools-offset");
  diagnostic_list diags;
  const post_summary s =
      test::post_text(dir, "job.cls",
                      "PARTNO TOOLS\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nFEDRAT/0.2,MMPR\n"
                      "GOTO/20,0,5\nGOTO/20,0,-10\nTURRET/1,21\nGOTO/19.5,0,5\nGOTO/19.5,0,-10\n"
                      "TURRET/1,21\nGOTO/19.5,0,5\nFINI\n",
                      load_machine("fanuc-0itd-twin"), dir + "/out", diags);
  REQUIRE(s.ok);
  const std::string program = test::read_file(dir + "/out/TOOLS_1.nc");
  CHECK(program ==
        "%\nO1000 (TOOLS)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0101\nG97 S1000 M3\nG1 X40. "
        "Z5. F0.2\nZ-10.\n"
        "T0121\nX39. Z5.\nZ-10.\nZ5.\nM100\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
  std::filesystem::remove_all(dir);
}

TEST_CASE("offset 0 in a lathe tool call is an error, not T0300", "[post][tools]") {
  const std::string dir = test::fresh_temp_dir("tools-zero");
  diagnostic_list diags;
  const post_summary s =
      test::post_text(dir, "job.cls", "PARTNO TOOLS\nHEAD/1\nLOADTL/3,0\nRAPID\nGOTO/20,0,5\nFINI\n",
                      load_machine("fanuc-0itd-twin"), dir + "/out", diags);
  CHECK_FALSE(s.ok);
  std::string errors;
  for (const diagnostic& d : diags.all())
    if (d.level == severity::error) errors += d.message + "\n";
  CHECK(errors ==
        "channel 1: tool 3 with offset 0 would be called as T0300, which cancels the tool offset; give the "
        "offset number (or set channel.offset_zero where the control's tool table applies it)\n");
  CHECK(test::list_dir(dir + "/out") == "(missing)");
  // A channel whose control applies the geometry by tool number may say so.
  machine m = load_machine("fanuc-0itd-twin");
  m.channels[0].offset_zero = true;
  diagnostic_list allowed;
  CHECK(test::post_text(dir, "job.cls", "PARTNO TOOLS\nHEAD/1\nLOADTL/3,0\nRAPID\nGOTO/20,0,5\nFINI\n", m,
                        dir + "/out", allowed)
            .ok);
  CHECK(test::read_file(dir + "/out/TOOLS_1.nc") ==
        "%\nO1000 (TOOLS)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nT0300\nG0 X40. Z5.\nM100\nM9\n"
        "G28 U0.\nG28 W0.\nM5\nM30\n%\n");
  std::filesystem::remove_all(dir);
}
