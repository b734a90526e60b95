// Inputs read once (check/nc_input.hpp): a pipe or a FIFO is checked as the program it
// carries, though the checker reads its inputs twice when it has something to report.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include "check/nc_input.hpp"
#include "check/sync_check.hpp"
#include "check/sync_report.hpp"
#include "file_test_support.hpp"
#include "support/errors.hpp"

using namespace twinpost;

namespace {

machine fanuc2() {
  machine m;
  m.name = "test";
  m.control = "fanuc-test";
  m.channels.resize(2);
  m.channels[0].number = 1;
  m.channels[1].number = 2;
  m.waits.first = 100;
  m.waits.last = 103;
  return m;
}

// Two programs that wait for each other on different codes.
const std::string deadlock_1 = "O1000\nM100\nG0 X10.\nM101\nM30\n";
const std::string deadlock_2 = "O1000\nM100\nM102\nM30\n";
const std::string deadlock_report =
    "one.nc:4:1: error: deadlock: channel 1 waits on M101 at one.nc:4 while channel 2 waits on "
    "M102 at two.nc:3 (different codes, Fanuc PS0160)\n"
    "M101\n^\n"
    "check: 2 channels, 2 waits paired, 1 error\n";

/// A pipe holding `text`, its write end closed: readable once, by its /dev/fd name.
struct filled_pipe {
  int fds[2] = {-1, -1};
  explicit filled_pipe(const std::string& text) {
    REQUIRE(::pipe(fds) == 0);
    REQUIRE(::write(fds[1], text.data(), text.size()) == static_cast<ssize_t>(text.size()));
    ::close(fds[1]);
  }
  ~filled_pipe() { ::close(fds[0]); }
  std::string path() const { return "/dev/fd/" + std::to_string(fds[0]); }
};

/// A fresh folder of its own under the temp directory (no race under ctest -j).
struct temp_dir {
  std::string path;
  temp_dir() {
    std::string tpl = (std::filesystem::temp_directory_path() / "twinpost-input-XXXXXX").string();
    REQUIRE(::mkdtemp(tpl.data()) != nullptr);
    path = tpl;
  }
  ~temp_dir() { std::filesystem::remove_all(path); }
};

std::string error_of(const std::vector<nc_source>& files) {
  try {
    (void)rereadable(files);
  } catch (const config_error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("a deadlocking pair through pipes is a deadlock", "[check]") {
  filled_pipe one(deadlock_1), two(deadlock_2);
  CHECK(format_sync_text(check_nc_files({{"one.nc", {}, one.path()}, {"two.nc", {}, two.path()}},
                                        fanuc2())) == deadlock_report);
}

TEST_CASE("a deadlocking pair through named FIFOs is a deadlock, and nothing hangs", "[check]") {
  temp_dir dir;
  const std::string a = dir.path + "/a.fifo", b = dir.path + "/b.fifo";
  REQUIRE(::mkfifo(a.c_str(), 0600) == 0);
  REQUIRE(::mkfifo(b.c_str(), 0600) == 0);
  // The writer opens each FIFO once, as a shell's `cmd > fifo` does, and then is gone.
  std::thread writer([&] {
    for (const auto& [path, text] : {std::pair{a, deadlock_1}, std::pair{b, deadlock_2}}) {
      const int fd = ::open(path.c_str(), O_WRONLY);
      if (fd < 0) return;
      (void)!::write(fd, text.data(), text.size());
      ::close(fd);
    }
  });
  const std::string report =
      format_sync_text(check_nc_files({{"one.nc", {}, a}, {"two.nc", {}, b}}, fanuc2()));
  writer.join();
  CHECK(report == deadlock_report);
}

TEST_CASE("regular files are read from their path, pipes once into a private copy", "[check]") {
  temp_dir dir;
  const std::string file = dir.path + "/a.nc";
  REQUIRE(test::write_file(file, "M100\n"));
  filled_pipe pipe("M100\n");
  const std::vector<nc_source> r = rereadable(
      {{"a.nc", {}, file}, {"p.nc", {}, pipe.path()}, {"p2.nc", {}, pipe.path()}, {"t.nc", "M100\n"}});
  REQUIRE(r.size() == 4);
  CHECK(r[0].copy == nullptr);
  CHECK(r[0].path == file);
  CHECK(r[1].copy != nullptr);
  CHECK(r[2].copy == r[1].copy);  // the same pipe named twice is read once
  CHECK(r[3].copy == nullptr);
  CHECK(r[3].text == "M100\n");
}

TEST_CASE("inputs that cannot be read are named", "[check]") {
  temp_dir dir;
  CHECK(error_of({{"d", {}, dir.path}}) == "cannot read '" + dir.path + "': it is a directory");
  CHECK(error_of({{"x", {}, dir.path + "/none.nc"}}) ==
        "cannot read '" + dir.path + "/none.nc': No such file or directory");
}

TEST_CASE("an endless input without line ends is copied only up to the reader's limit", "[check]") {
  // /dev/zero is a device: copied once, and only until its first line passes 1 MiB, where
  // the reader stops too. Without that the copy would fill the disk.
  CHECK(format_sync_text(check_nc_files({{"zero", {}, "/dev/zero"}, {"b.nc", "M100\n"}}, fanuc2())) ==
        "zero:1:1048577: error: line 1 is longer than 1048576 bytes: no NC block is that long; "
        "the rest of the file is not read\n"
        "zero: error: no NC block in this file: channel 1 has no program\n"
        "b.nc:1:1: error: wait M100 of channel 2 is never met: channel 1 has no program\n"
        "M100\n^\n"
        "check: 2 channels, 0 waits paired, 3 errors\n");
}
