// post/sync_at_cl: the post's self-check findings moved from the programs it never
// writes to the CL records that made the waits.
#include <catch2/catch.hpp>

#include <filesystem>

#include "check/sync_check.hpp"
#include "file_test_support.hpp"
#include "machines/machine_loader.hpp"
#include "post/sync_at_cl.hpp"

using namespace twinpost;

TEST_CASE("an unpaired wait is reported at its SYNC record, the program's end at the job's", "[post][sync]") {
  const std::string dir = test::fresh_temp_dir("sync-at-cl");
  const std::string cl = dir + "/job.cls";
  REQUIRE(test::write_file(cl, "PARTNO P\nHEAD/1\n  SYNC/1,1,2\nHEAD/2\nFINI"));  // no final newline
  const machine m = load_machine("fanuc-0itd-twin");
  const std::vector<nc_source> files{{"out/P_1.nc", "%\nO1000\nG0 X1.\nM100\nM30\n%\n"},
                                     {"out/P_2.nc", "%\nO1000\nG0 X2.\nM30\n%\n"}};
  const sync_result found = check_nc_files(files, m);
  REQUIRE(found.diagnostics.size() == 1);
  const std::vector<diagnostic> moved = sync_diagnostics_at_cl(found.diagnostics, files, m, cl, {{3}, {}}, 5);
  REQUIRE(moved.size() == 2);
  CHECK(format_diagnostic(moved[0]) ==
        cl + ":3:3: error: wait M100 of channel 1 is never met: channel 2 ends at " + cl +
            ":5 without a matching wait\n  SYNC/1,1,2\n  ^\n");
  CHECK(format_diagnostic(moved[1]) ==
        "out/P_1.nc:4:1: note: the wait in the program as it would have been written (no file is "
        "written)\nM100\n^\n");
  std::filesystem::remove_all(dir);
}
