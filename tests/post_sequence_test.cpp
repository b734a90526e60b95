// N numbers: every block of a channel's section in one count (header, body, footer, end
// code; never '%', the program line or the section marker), or only the tool calls, the
// restart points; past the N format's largest number the count starts again.
#include <catch2/catch.hpp>

#include <string>

#include "file_test_support.hpp"
#include "machine_test_support.hpp"
#include "machines/machine_loader.hpp"
#include "post_test_jobs.hpp"

using namespace twinpost;

namespace {

// Tool 1, then its offset 21, then PARTNO after the first blocks: the head is written again
// under the late name, with the same numbers.
const std::string one_head_job =
    "HEAD/1\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/20,0,5\nGOTO/20,0,-10\n"
    "TURRET/1,21\nGOTO/18,0,-10\nPARTNO LATE\nFINI\n";

const std::string two_head_job =
    "HEAD/1\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/20,0,5\nGOTO/20,0,-10\n"
    "HEAD/2\nTURRET/4,4\nSPINDL/RPM,800,CLW\nFEDRAT/0.1,MMPR\nRAPID\nGOTO/-10,0,5\nGOTO/-10,0,-3\n"
    "PARTNO LATE\nFINI\n";

std::string file_of(const std::string& cl, const machine& m, const std::string& name,
                    const std::string& tag) {
  const test::posted p = test::post_in_fresh_dir(
      cl, m, "sequence-" + tag, [](const diagnostic& d) { return d.level == severity::error; });
  if (!p.ok) return "(failed)\n" + p.diagnostics;
  const auto f = p.files.find(name);
  return f == p.files.end() ? "(missing)" : f->second;
}

machine numbered(const std::string& name, sequence_mode mode, int n_digits = 5) {
  machine m = load_machine(name);
  m.program.sequence_start = 10;
  m.program.sequence_step = 10;
  m.program.sequence_numbers = mode;
  m.formats['N'] = {n_digits, 0};
  m.tools.push_back({1, 0, "turn"});  // the Integrex head has two spindles: tool 1 turns
  return m;
}

}  // namespace

TEST_CASE("header, blocks, footer and end code are numbered in one count", "[post][sequence]") {
  CHECK(file_of(one_head_job, numbered("fanuc-0itd-twin", sequence_mode::all), "LATE_1.nc", "all") ==
        "%\nO1000 (LATE)\nN10 G0 G18 G21 G40 G54 G80 G99\nN20 G28 U0.\nN30 G28 W0.\nN40 T0101\n"
        "N50 G97 S1000 M3\nN60 G0 X40. Z5.\nN70 G1 Z-10. F0.2\nN80 T0121\nN90 X36. Z-10.\nN100 M100\n"
        "N110 M9\nN120 G28 U0.\nN130 G28 W0.\nN140 M5\nN150 M30\n%\n");
}

TEST_CASE("past the largest number of the N format the count starts again", "[post][sequence]") {
  // N2: N10 ... N90, then N10 again (the Fusion posts restart past 99999 the same way).
  CHECK(file_of(one_head_job, numbered("fanuc-0itd-twin", sequence_mode::all, 2), "LATE_1.nc", "wrap") ==
        "%\nO1000 (LATE)\nN10 G0 G18 G21 G40 G54 G80 G99\nN20 G28 U0.\nN30 G28 W0.\nN40 T0101\n"
        "N50 G97 S1000 M3\nN60 G0 X40. Z5.\nN70 G1 Z-10. F0.2\nN80 T0121\nN90 X36. Z-10.\nN10 M100\n"
        "N20 M9\nN30 G28 U0.\nN40 G28 W0.\nN50 M5\nN60 M30\n%\n");
}

TEST_CASE("tool_change numbers only the tool calls, offset changes included", "[post][sequence]") {
  CHECK(
      file_of(one_head_job, numbered("fanuc-0itd-twin", sequence_mode::tool_change), "LATE_1.nc", "tools") ==
      "%\nO1000 (LATE)\nG0 G18 G21 G40 G54 G80 G99\nG28 U0.\nG28 W0.\nN10 T0101\nG97 S1000 M3\n"
      "G0 X40. Z5.\nG1 Z-10. F0.2\nN20 T0121\nX36. Z-10.\nM100\nM9\nG28 U0.\nG28 W0.\nM5\nM30\n%\n");
}

TEST_CASE("each section of a merged program counts from the start, also under a late PARTNO",
          "[post][sequence]") {
  CHECK(file_of(two_head_job, numbered("integrex-i200st", sequence_mode::all), "LATE.EIA", "merged") ==
        "%\nO1000(LATE)\nG109 L1\nN10 G21\nN20 G0 G90 G54 G97 G18\nN30 G40 G49 G80 G67 G69\nN40 G10.9 X1\n"
        "N50 G0 G90 G53 X0. Y0.\nN60 G0 G90 G53 Z0.\nN70 T01 M6\nN80 M901\nN90 G97 S1000 M203\nN100 G95\n"
        "N110 M108\nN120 G0 G53 B0.\nN130 M107\nN140 G0 G43 P1 H#3020 X40. Y0. Z5.\n"
        "N150 G1 Z-10. F0.2\nN160 M950\nN170 M951\nN180 M9\nN190 M5\nN200 M205\nN210 M305\n"
        "N220 G0 G90 G53 X0. Y0.\nN230 G0 G90 G53 Z0.\nN240 M30\nG109 L2\nN10 G21\n"
        "N20 G0 G90 G54 G97 G18\nN30 G40 G49 G80 G67 G69\nN40 G10.9 X1\nN50 G0 G90 G53 X0.\n"
        "N60 G0 G90 G53 Z0.\nN70 M950\nN80 T0404\nN90 M901\nN100 G97 S800 M203\nN110 G95\nN120 G0 X20. Z5.\n"
        "N130 G1 Z-3. F0.1\nN140 M951\nN150 M9\nN160 M5\nN170 M205\nN180 M305\n"
        "N190 G0 G90 G53 X0.\nN200 G0 G90 G53 Z0.\nN210 M30\n%\n");
}

TEST_CASE("the machine file's numbering is checked at load", "[machines][sequence]") {
  CHECK(test::machine_error_of(test::machine_head + "[program]\nsequence_start = 100000\n" +
                               test::two_channels) ==
        "m.toml:7:18: error: program.sequence_start must be at most 99999 (format.N 5), not 100000");
  CHECK(test::machine_error_of(test::machine_head + "[program]\nsequence_numbers = \"some\"\n" +
                               test::two_channels) ==
        "m.toml:7:20: error: program.sequence_numbers must be all or tool_change, not 'some'");
}

TEST_CASE("auto: the job's own sync records, else waits placed where the machine is timed, else sequential",
          "[post][sync]") {
  const machine m = load_machine("fanuc-0itd-twin");
  const std::string one = "PARTNO ONE\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/20,0,5\nFINI\n";
  CHECK(test::post_in_fresh_dir(one, m, "one-head").diagnostics == "");
  CHECK(test::post_in_fresh_dir(one_head_job, m, "one-head-late").diagnostics == "");
  // Two heads, no sync records, a machine with [timing]: optimise, without a word.
  const std::string dir = test::fresh_temp_dir("two-heads");
  diagnostic_list d;
  const post_summary placed = test::post_text(dir, "job.cls", two_head_job, m, dir + "/out", d);
  std::filesystem::remove_all(dir);
  CHECK(placed.ok);
  CHECK(d.all().empty());
  CHECK(placed.policy == sync_policy::optimise);
  CHECK(placed.passes == 2);
  // Without [timing] the waits cannot be placed by time: sequential, and why.
  machine untimed = m;
  for (channel_def& c : untimed.channels) c.timing.given = false;
  CHECK(test::post_in_fresh_dir(two_head_job, untimed, "two-heads-untimed").diagnostics ==
        "job.cls: warning: no sync records in the job: channels wait for each other at every head switch "
        "(sequential), since machine 'fanuc-0itd-twin' has no [timing] table to place waits by; concurrent "
        "machining needs SYNC/SYNCTR records\n");
  // Three channels: placed too (waits that name two or three paths).
  const std::string three =
      two_head_job.substr(0, two_head_job.find("PARTNO")) +
      "HEAD/3\nTLDATA/TURN\nTURRET/21,21\nSPINDL/RPM,600,CLW\nRAPID\nGOTO/30,0,5\nFINI\n";
  const std::string dir3 = test::fresh_temp_dir("three-heads");
  const post_summary placed3 =
      test::post_text(dir3, "job.cls", three, load_machine("fanuc-31i-3path"), dir3 + "/out", d);
  std::filesystem::remove_all(dir3);
  CHECK(placed3.ok);
  CHECK(d.all().empty());
  CHECK(placed3.policy == sync_policy::optimise);
  CHECK(placed3.channels == 3);
}

TEST_CASE("post --compare-optimum: the cycle of the placed waits beside the job's own, nothing more written",
          "[post][sync]") {
  const machine m = load_machine("fanuc-0itd-twin");
  // Head 1 then head 2 on tools of unknown size: the optimiser keeps them in the CL's order, so
  // the job's own waits (none between the two: they overlap) give the shorter cycle.
  const std::string job =
      "PARTNO CMP\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nFEDRAT/0.2,MMPR\nRAPID\n"
      "GOTO/20,0,5\nSYNC/1,1,2\nGOTO/20,0,-10\nHEAD/2\nTURRET/4,4\nFEDRAT/0.1,MMPR\n"
      "RAPID\nGOTO/-10,0,5\nSYNC/1,1,2\nGOTO/-10,0,-3\nFINI\n";
  const auto compared = [](post_options& o) { o.compare_optimum = true; };
  const std::string dir = test::fresh_temp_dir("compare-optimum");
  diagnostic_list d;
  const post_summary with = test::post_text(dir, "job.cls", job, m, dir + "/with", d, {}, compared);
  const post_summary without = test::post_text(dir, "job.cls", job, m, dir + "/without", d);
  const auto with_files = test::read_dir_files(dir + "/with");
  const auto without_files = test::read_dir_files(dir + "/without");
  std::filesystem::remove_all(dir);
  std::string said;
  for (const diagnostic& x : d.all()) said += format_diagnostic(x);
  CHECK(said == "");
  REQUIRE(with.ok);
  CHECK(with.policy == sync_policy::explicit_marks);
  REQUIRE(with.optimum_cycle);
  REQUIRE(with.timing);
  CHECK(*with.optimum_cycle > with.timing->cycle);
  CHECK(with.optimum_passes == 2);
  CHECK(with.optimum_unknown.empty());
  CHECK_FALSE(without.optimum_cycle);
  CHECK(with_files == without_files);
  CHECK(with_files.size() == 2);
  // Three channels (posted sequentially): no cycle to compare, and why.
  const std::string three =
      "PARTNO CMP3\nHEAD/1\nTLDATA/TURN\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nRAPID\n"
      "GOTO/20,0,5\nHEAD/2\nTLDATA/TURN\nTURRET/4,4\nRAPID\nGOTO/-10,0,5\n"
      "HEAD/3\nTLDATA/TURN\nTURRET/21,21\nSPINDL/RPM,600,CLW\nRAPID\nGOTO/30,0,5\nFINI\n";
  const std::string dir3 = test::fresh_temp_dir("compare-optimum-3");
  const post_summary s3 = test::post_text(dir3, "job.cls", three, load_machine("fanuc-31i-3path"),
                                          dir3 + "/out", d, {}, [](post_options& o) {
                                            o.compare_optimum = true;
                                            o.policy = sync_policy::sequential;
                                          });
  std::filesystem::remove_all(dir3);
  CHECK(s3.ok);
  REQUIRE(s3.timing);
  REQUIRE(s3.optimum_cycle);
  CHECK(*s3.optimum_cycle < s3.timing->cycle);
  CHECK(s3.optimum_unknown.empty());
  // A machine without [timing]: refused, as --timeline is.
  machine untimed = m;
  for (channel_def& c : untimed.channels) c.timing.given = false;
  CHECK(test::post_in_fresh_dir(job, untimed, "compare-untimed", {}, {}, compared).diagnostics ==
        untimed.source +
            ": error: --compare-optimum: machine 'fanuc-0itd-twin' has no [timing] table "
            "(docs/machines.md, \"[timing]\")\n");
}

TEST_CASE("post --sync optimise on a job of one head: sequential, and why", "[post][sync]") {
  const std::string one = "PARTNO ONE\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/20,0,5\nFINI\n";
  CHECK(test::post_in_fresh_dir(one, load_machine("fanuc-0itd-twin"), "optimise-one-head", {}, {},
                                [](post_options& o) { o.policy = sync_policy::optimise; })
            .diagnostics ==
        "job.cls: warning: --sync optimise: it places waits between two to 4 channels, and this job does not "
        "use two "
        "to 4; "
        "the channels wait for each other at every head switch (sequential)\n");
}

TEST_CASE("a job of more operations than the optimiser weighs is posted sequentially, and why",
          "[post][sync]") {
  // 1001 head switches: 1001 operations a channel, 1002001 pairs, one more stretch than the limit.
  std::string job = "PARTNO MANY\n";
  for (int i = 0; i < 1001; ++i)
    job +=
        "HEAD/1\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/30,0,2\nGOTO/30,0,-10\n"
        "HEAD/2\nTURRET/11,11\nFEDRAT/0.1,MMPR\nRAPID\nGOTO/-20,0,2\nGOTO/-20,0,-5\n";
  job += "FINI\n";
  const test::posted p = test::post_in_fresh_dir(job, load_machine("fanuc-0itd-twin"), "optimise-many");
  CHECK(p.ok);
  CHECK(
      p.diagnostics ==
      "job.cls: warning: --sync auto (optimise): channels 1 and 2 have 1001 and 1001 operations between two "
      "barriers, "
      "more than the 1000000 pairs of them it weighs; the channels wait for each other at every head switch "
      "(sequential)\n");
}
