// post/output_names: the names a machine file gives the programs stay plain file names
// in the output folder, and one post never writes two files of the same name.
#include <catch2/catch.hpp>

#include <string>

#include "machines/machine_loader.hpp"
#include "post/output_names.hpp"
#include "post_test_jobs.hpp"
#include "support/errors.hpp"

using namespace twinpost;

namespace {

// A built-in machine's TOML with `from` replaced by `to`, loaded as "m.toml".
machine edited(const std::string& builtin, const std::string& from, const std::string& to) {
  std::string text =
      test::read_file(std::string(TWINPOST_SOURCE_DIR) + "/machines/builtin/" + builtin + ".toml");
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  text.replace(at, from.size(), to);
  return parse_machine(text, "m.toml");
}

// The config error of posting the RACE job for `m`, and what the test folder holds after it.
std::pair<std::string, std::string> failed_post(const machine& m, const std::string& tag,
                                                std::optional<layout_kind> layout = {}) {
  const std::string dir = test::fresh_temp_dir(tag);
  diagnostic_list d;
  std::string error = "(no error)";
  try {
    test::post_text(dir, "job.cls", test::race_job('A'), m, dir + "/out", d, layout);
  } catch (const config_error& e) {
    error = e.what();
  }
  std::string listing = test::list_dir(dir);  // out/ made by the run is gone again
  std::filesystem::remove_all(dir);
  return {error, listing};
}

}  // namespace

TEST_CASE("what a plain file name is", "[post][names]") {
  CHECK(file_name_problem("RACE_1.nc") == "");
  CHECK(file_name_problem("") == "it is empty");
  CHECK(file_name_problem(".") == "it names a folder");
  CHECK(file_name_problem("..") == "it names a folder");
  CHECK(file_name_problem("../RACE.nc") == "it has a '/'");
  CHECK(file_name_problem(std::string("A\0B", 3)) == "it has a NUL byte");
  CHECK(file_name_problem(std::string(256, 'A')) == "it is longer than 255 bytes");
  CHECK(file_name_problem(std::string(255, 'A')) == "");
  CHECK(file_name_problem(".twinpost-12-0") == "names beginning '.twinpost-' are the post's own");
}

TEST_CASE("a machine file's file name may not leave the output folder", "[post][names]") {
  const auto up = failed_post(
      edited("fanuc-0itd-twin", "file_name = \"{name}\"", "file_name = \"../{name}\""), "names-up");
  CHECK(up.first ==
        "machine file 'm.toml': file_name \"../{name}\", file_suffix \"_1\" and extension \".nc\" "
        "give the file name '../RACE_1.nc' for channel 1: not a plain file name in the output folder (it has "
        "a '/')");
  CHECK(up.second == "job.cls");  // nothing beside the job, nothing left in out/
  const auto fill = failed_post(
      edited("integrex-i200st", "file_name = \"{name}\"", "file_name = \"{name:/>40}\""), "names-fill");
  CHECK(fill.first ==
        "machine file 'm.toml': file_name \"{name:/>40}\" and extension \".EIA\" give the file name "
        "'////////////////////////////////////RACE.EIA' for channel 1: not a plain file name in the output "
        "folder "
        "(it has a '/')");
  CHECK(fill.second == "job.cls");
}

TEST_CASE("two channels may not be written to one file", "[post][names]") {
  const auto twice =
      failed_post(edited("fanuc-0itd-twin", "file_suffix = \"_2\"", "file_suffix = \"_1\""), "names-twice");
  CHECK(twice.first ==
        "machine file 'm.toml': channels 1 and 2 would both be written to 'RACE_1.nc' "
        "(file_name \"{name}\", split layout): give the channels distinct file_suffix values");
  CHECK(twice.second == "job.cls");
}

TEST_CASE("the Integrex split into one program per head", "[post][names]") {
  const std::string dir = test::fresh_temp_dir("names-integrex-split");
  diagnostic_list d;
  const post_summary s = test::post_text(dir, "job.cls", test::race_job('A'), load_machine("integrex-i200st"),
                                         dir + "/out", d, layout_kind::split);
  CHECK(s.ok);
  CHECK(test::list_dir(dir + "/out") == "RACE_HD1.EIA RACE_HD2.EIA");
  CHECK(test::read_file(dir + "/out/RACE_HD2.EIA").find("VERSION A") != std::string::npos);
  std::filesystem::remove_all(dir);
}
