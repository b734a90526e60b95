// formats/post_job and formats/job_scan: file names from PARTNO, and the quick scan.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <string>

#include "formats/job_scan.hpp"
#include "formats/post_job.hpp"
#include "machines/machine_loader.hpp"

using namespace twinpost;

TEST_CASE("a PARTNO never leaves the output folder", "[post]") {
  CHECK(safe_file_stem("SHAFT-OD-DRILL") == "SHAFT-OD-DRILL");
  CHECK(safe_file_stem("../../etc/passwd") == "etc_passwd");
  CHECK(safe_file_stem("/abs/path") == "abs_path");
  CHECK(safe_file_stem("PART TO BE MACHINED") == "PART_TO_BE_MACHINED");
  CHECK(safe_file_stem("..") == "PROGRAM");
  CHECK(safe_file_stem("") == "PROGRAM");
  CHECK(safe_file_stem("G\xE9n\xE9r\xE9") == "G_n_r");
  CHECK(safe_file_stem(std::string(40, 'A')) == std::string(32, 'A'));
}

namespace {
std::string write_temp(const std::string& text) {
  std::string path = (std::filesystem::temp_directory_path() / "twinpost_scan_test.cls").string();
  std::FILE* f = std::fopen(path.c_str(), "wb");
  std::fwrite(text.data(), 1, text.size(), f);
  std::fclose(f);
  return path;
}
}  // namespace

TEST_CASE("the job scan finds sync records and the heads in use", "[post]") {
  job_scan s = scan_job(write_temp("HEAD / 2\n$$ SYNC/1,1,2 in a comment does not count\n"
                                   "  head/both\nCHANNEL,3\ngoto/1,2,3"));
  CHECK_FALSE(s.explicit_sync);
  CHECK(s.heads == std::vector<int>{2, 1, 2});
  CHECK(s.channels == std::vector<int>{3});
  CHECK(scan_job(write_temp("HEAD/SIDE\r\n  synctr/next\r\n")).explicit_sync);
  job_scan words = scan_job(write_temp("HEAD/SIDE\n"));
  CHECK(words.head_words == std::vector<std::string>{"SIDE"});
  CHECK(scan_job(write_temp("$$UDE: MANUSPOST - SYNCHRONIZATION/SYNCHRONIZATION NUMBER=1")).explicit_sync);
}

TEST_CASE("the channels a job uses, on a 3-path machine", "[post]") {
  machine m = load_machine("fanuc-31i-3path");
  job_scan s;
  CHECK(used_channels(s, m) == std::vector<int>{1});  // no HEAD at all: head 1
  s.head_words = {"SIDE"};
  CHECK(used_channels(s, m) == std::vector<int>{1, 2});
  s.heads = {3};
  CHECK(used_channels(s, m) == std::vector<int>{1, 2, 3});
}
