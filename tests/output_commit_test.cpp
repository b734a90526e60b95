// post/output_commit: a post's files are committed as a set (all new or all old), under
// a lock shared by concurrent posts; failed and interrupted posts leave nothing behind.
#include <catch2/catch.hpp>

#include <csignal>
#include <functional>
#include <string>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#include "cli/interrupt.hpp"
#include "machines/machine_loader.hpp"
#include "post/output_commit.hpp"
#include "post_test_jobs.hpp"
#include "support/errors.hpp"

using namespace twinpost;
namespace fs = std::filesystem;

namespace {

// 'A' or 'B' when both programs of the RACE job in `out` are of that version, else what is there.
std::string version_in(const std::string& out) {
  const std::string one = test::read_file(out + "/RACE_1.nc");
  const std::string two = test::read_file(out + "/RACE_2.nc");
  for (char v : {'A', 'B'}) {
    const std::string mark = std::string("VERSION ") + v;
    if (one.find(mark) != std::string::npos && two.find(mark) != std::string::npos) return std::string(1, v);
  }
  return "mixed: " + one + " / " + two;
}

std::string config_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const config_error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("a folder in the way of the second file: the old set stays, untouched", "[post][commit]") {
  const std::string dir = test::fresh_temp_dir("commit-blocked");
  const machine m = load_machine("fanuc-0itd-twin");
  diagnostic_list d;
  REQUIRE(test::post_text(dir, "a.cls", test::race_job('A'), m, dir + "/out", d).ok);
  const std::string old_one = test::read_file(dir + "/out/RACE_1.nc");
  fs::remove(dir + "/out/RACE_2.nc");
  fs::create_directories(dir + "/out/RACE_2.nc/inside");
  CHECK(config_error_of([&] { test::post_text(dir, "b.cls", test::race_job('B'), m, dir + "/out", d); }) ==
        "cannot replace '" + dir + "/out/RACE_2.nc': it is a folder");
  CHECK(test::list_dir(dir + "/out") == "RACE_1.nc RACE_2.nc");
  CHECK(test::read_file(dir + "/out/RACE_1.nc") == old_one);
  CHECK(test::list_dir(dir + "/out/RACE_2.nc") == "inside");
  fs::remove_all(dir);
}

TEST_CASE("the job is never replaced by an output of its own name in its own folder", "[post][commit]") {
  const std::string dir = test::fresh_temp_dir("commit-job");
  const machine m = load_machine("fanuc-0itd-twin");
  diagnostic_list d;
  // -o the job's folder, and a program named as the job; then the page named as it.
  const std::string job = test::race_job('A');
  CHECK(config_error_of([&] { test::post_text(dir, "RACE_2.nc", job, m, dir, d); }) ==
        "cannot replace '" + dir + "/RACE_2.nc': it is the job being posted (give another output folder)");
  CHECK(test::list_dir(dir) == "RACE_2.nc");
  CHECK(test::read_file(dir + "/RACE_2.nc") == job);
  CHECK(config_error_of([&] {
          test::post_text(dir, "a.cls", job, m, dir, d, {},
                          [](post_options& o) { o.timeline_file = "a.cls"; });
        }) == "cannot replace '" + dir + "/a.cls': it is the job being posted (give another output folder)");
  CHECK(test::read_file(dir + "/a.cls") == job);
  fs::remove_all(dir);
}

TEST_CASE("a rename that fails half-way puts every old file back", "[post][commit]") {
  // The renames alone, past the checks that would have refused: the second target is a folder.
  const std::string dir = test::fresh_temp_dir("commit-rollback");
  fs::create_directories(dir + "/stage");
  fs::create_directories(dir + "/out/b.nc/inside");
  REQUIRE(test::write_file(dir + "/out/a.nc", "old a\n"));
  REQUIRE(test::write_file(dir + "/stage/a", "new a\n"));
  REQUIRE(test::write_file(dir + "/stage/b", "new b\n"));
  REQUIRE(test::write_file(dir + "/stage/c", "new c\n"));
  const std::vector<staged_file> files{
      {dir + "/stage/a", "a.nc"}, {dir + "/stage/c", "c.nc"}, {dir + "/stage/b", "b.nc"}};
  CHECK(config_error_of([&] { detail::replace_all(dir + "/out", dir + "/stage", files); }) ==
        "cannot replace '" + dir + "/out/b.nc': Is a directory");
  CHECK(test::list_dir(dir + "/out") == "a.nc b.nc");
  CHECK(test::read_file(dir + "/out/a.nc") == "old a\n");
  fs::remove_all(dir);
}

TEST_CASE("concurrent posts of two versions into one folder leave one complete set", "[post][commit]") {
  const std::string dir = test::fresh_temp_dir("commit-race");
  const machine m = load_machine("fanuc-0itd-twin");
  REQUIRE(test::write_file(dir + "/a.cls", test::race_job('A')));
  REQUIRE(test::write_file(dir + "/b.cls", test::race_job('B')));
  for (int round = 0; round < 40; ++round) {
    const std::string out = dir + "/out" + std::to_string(round % 4) + "/x";  // made by the racers too
    bool ok[2] = {false, false};
    auto post = [&](int i) {
      post_options o;
      o.cl_path = dir + (i == 0 ? "/a.cls" : "/b.cls");
      o.out_dir = out;
      diagnostic_list d;
      ok[i] = post_job(o, m, d).ok;
    };
    std::thread a(post, 0), b(post, 1);
    a.join();
    b.join();
    INFO("round " << round);
    CHECK(ok[0]);
    CHECK(ok[1]);
    CHECK(test::list_dir(out) == "RACE_1.nc RACE_2.nc");
    const std::string v = version_in(out);
    CHECK((v == "A" || v == "B"));
  }
  fs::remove_all(dir);
}

TEST_CASE("racing processes: one complete set, and a failing post keeps the folder another fills",
          "[post][commit]") {
  // Each round: three processes post into a folder that does not exist yet: versions A and
  // B of the part, and a job that fails (it made the folder perhaps, and must not remove it
  // from under the others). Exit code 0 means the post reported success.
  const std::string dir = test::fresh_temp_dir("commit-race-processes");
  const machine m = load_machine("fanuc-0itd-twin");
  std::string bad = test::race_job('C');
  bad.replace(bad.find("HEAD/2"), 6, "HEAD/7");
  REQUIRE(test::write_file(dir + "/a.cls", test::race_job('A')));
  REQUIRE(test::write_file(dir + "/b.cls", test::race_job('B')));
  REQUIRE(test::write_file(dir + "/c.cls", bad));
  for (int round = 0; round < 20; ++round) {
    const std::string out = dir + "/round" + std::to_string(round) + "/out";
    pid_t kids[3];
    for (int i = 0; i < 3; ++i) {
      kids[i] = ::fork();
      REQUIRE(kids[i] >= 0);
      if (kids[i] == 0) {
        post_options o;
        o.cl_path = dir + "/" + static_cast<char>('a' + i) + ".cls";
        o.out_dir = out;
        diagnostic_list d;
        bool ok = false;
        try {
          ok = post_job(o, m, d).ok;
        } catch (...) {
        }
        ::_exit(ok ? 0 : 1);
      }
    }
    int status[3];
    for (int i = 0; i < 3; ++i) REQUIRE(::waitpid(kids[i], &status[i], 0) == kids[i]);
    INFO("round " << round);
    CHECK((WIFEXITED(status[0]) && WEXITSTATUS(status[0]) == 0));
    CHECK((WIFEXITED(status[1]) && WEXITSTATUS(status[1]) == 0));
    CHECK((WIFEXITED(status[2]) && WEXITSTATUS(status[2]) == 1));
    CHECK(test::list_dir(out) == "RACE_1.nc RACE_2.nc");
    const std::string v = version_in(out);
    CHECK((v == "A" || v == "B"));
  }
  fs::remove_all(dir);
}

TEST_CASE("a failed post leaves no folder it made, and no stage", "[post][commit]") {
  const std::string dir = test::fresh_temp_dir("commit-failed");
  const machine m = load_machine("fanuc-0itd-twin");
  diagnostic_list d;
  std::string bad = test::race_job('A');
  bad.replace(bad.find("HEAD/2"), 6, "HEAD/7");
  CHECK_FALSE(test::post_text(dir, "bad.cls", bad, m, dir + "/new/a/b/c", d).ok);
  CHECK(test::list_dir(dir) == "bad.cls");
  // A folder that cannot be made (its name is too long) after two that were: both go again.
  const std::string long_name = dir + "/new/a/" + std::string(300, 'x');
  CHECK(config_error_of([&] { test::post_text(dir, "bad.cls", bad, m, long_name, d); }) ==
        "cannot create '" + long_name + "': File name too long");
  CHECK(test::list_dir(dir) == "bad.cls");
  fs::create_directories(dir + "/kept");
  REQUIRE(test::write_file(dir + "/kept/other.nc", "x\n"));
  CHECK_FALSE(test::post_text(dir, "bad.cls", bad, m, dir + "/kept", d).ok);
  CHECK(test::list_dir(dir + "/kept") == "other.nc");
  fs::remove_all(dir);
}

TEST_CASE("stages of dead runs are removed by the next post, those of live runs kept", "[post][commit]") {
  const std::string dir = test::fresh_temp_dir("commit-stale");
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  REQUIRE(dead > 0);
  REQUIRE(::waitpid(dead, nullptr, 0) == dead);
  const std::string out = dir + "/out";
  for (const std::string& stage :
       {".twinpost-" + std::to_string(dead), ".twinpost-" + std::to_string(dead) + "-3",
        std::string(".twinpost-1-0")}) {
    fs::create_directories(out + "/" + stage);
    REQUIRE(test::write_file(out + "/" + stage + "/framed1", "partial\n"));
  }
  diagnostic_list d;
  REQUIRE(test::post_text(dir, "a.cls", test::race_job('A'), load_machine("fanuc-0itd-twin"), out, d).ok);
  CHECK(test::list_dir(out) == ".twinpost-1-0 RACE_1.nc RACE_2.nc");  // pid 1 lives
  fs::remove_all(dir);
}

TEST_CASE(
    "a post interrupted by SIGTERM, SIGINT or SIGHUP leaves the folder as it was and dies of the signal",
    "[post][commit]") {
  const std::string dir = test::fresh_temp_dir("commit-sigterm");
  const machine m = load_machine("fanuc-0itd-twin");
  REQUIRE(test::write_file(dir + "/big.cls", test::race_job('B', 70000)));
  diagnostic_list d;
  REQUIRE(test::post_text(dir, "a.cls", test::race_job('A'), m, dir + "/out", d).ok);
  const std::string old_one = test::read_file(dir + "/out/RACE_1.nc");
  const std::pair<std::string, int> runs[] = {{dir + "/out", SIGTERM},
                                              {dir + "/new/a/b", SIGTERM},
                                              {dir + "/out", SIGINT},
                                              {dir + "/new/a/b", SIGHUP}};
  for (const auto& [out, sig] : runs) {
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
      // The command-line tool's handler; the progress call (after 65,536 events) is the signal.
      // The handler leaves alone a signal ignored at the start, and a run of these tests under
      // nohup passes its ignored SIGHUP on: the child starts from the defaults.
      for (int s : {SIGINT, SIGTERM, SIGHUP}) ::signal(s, SIG_DFL);
      cli::install_interrupt_cleanup();
      post_options o;
      o.cl_path = dir + "/big.cls";
      o.out_dir = out;
      o.progress = [sig = sig](std::size_t) { ::raise(sig); };
      diagnostic_list own;
      try {
        post_job(o, m, own);
      } catch (...) {
      }
      ::_exit(0);
    }
    int status = 0;
    REQUIRE(::waitpid(child, &status, 0) == child);
    INFO("signal " << sig << " into " << out);
    CHECK(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == sig);
  }
  CHECK(test::list_dir(dir + "/out") == "RACE_1.nc RACE_2.nc");
  CHECK(test::read_file(dir + "/out/RACE_1.nc") == old_one);
  CHECK(test::list_dir(dir) == "a.cls big.cls out");
  fs::remove_all(dir);
}

TEST_CASE("a signal ignored when the tool starts stays ignored (nohup)", "[post][commit]") {
  // In a child: what the handler's installation leaves of SIGHUP, ignored or not before it.
  auto after_install = [](bool ignored) {
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
      ::signal(SIGHUP, ignored ? SIG_IGN : SIG_DFL);
      cli::install_interrupt_cleanup();
      struct sigaction now {};
      ::sigaction(SIGHUP, nullptr, &now);
      ::_exit(now.sa_handler == SIG_IGN ? 1 : now.sa_handler == &cli::on_interrupt ? 2 : 3);
    }
    int status = 0;
    REQUIRE(::waitpid(child, &status, 0) == child);
    REQUIRE(WIFEXITED(status));
    return WEXITSTATUS(status);
  };
  CHECK(after_install(true) == 1);   // still ignored: nohup's promise kept
  CHECK(after_install(false) == 2);  // the cleanup handler
}

TEST_CASE("the job must be a regular file with records", "[post]") {
  const std::string dir = test::fresh_temp_dir("post-job-file");
  const machine m = load_machine("fanuc-0itd-twin");
  REQUIRE(::mkfifo((dir + "/fifo.cls").c_str(), 0600) == 0);
  fs::create_directories(dir + "/folder.cls");
  for (const std::string& job : {std::string("/dev/null"), dir + "/fifo.cls", dir + "/folder.cls"}) {
    post_options o;
    o.cl_path = job;
    o.out_dir = dir + "/out";
    diagnostic_list d;
    CHECK(config_error_of([&] { post_job(o, m, d); }) ==
          "'" + job +
              "' is not a regular file (a pipe, FIFO, folder or device): post reads the job twice, give it a "
              "file");
  }
  CHECK(config_error_of([&] {
          post_options o;
          o.cl_path = dir + "/missing.cls";
          o.out_dir = dir + "/out";
          diagnostic_list d;
          post_job(o, m, d);
        }) == "cannot read '" + dir + "/missing.cls': No such file or directory");
  for (const std::string& text : {std::string(""), std::string("$$ only a comment\n")}) {
    diagnostic_list d;
    CHECK_FALSE(test::post_text(dir, "empty.cls", text, m, dir + "/out", d).ok);
    REQUIRE_FALSE(d.all().empty());
    CHECK(d.all().back().message == "the job has no CL records (only comments or nothing)");
    CHECK(d.all().back().level == severity::error);
  }
  CHECK(test::list_dir(dir) == "empty.cls fifo.cls folder.cls");  // out/ was made and removed again
  fs::remove_all(dir);
}

TEST_CASE("a write that fails names the program, not the stage, and the reason", "[post][commit]") {
  // A full disk, as a file size limit in a child process: writes past it fail (EFBIG).
  const std::string dir = test::fresh_temp_dir("commit-full");
  const machine m = load_machine("fanuc-0itd-twin");
  REQUIRE(test::write_file(dir + "/big.cls", test::race_job('B', 70000)));
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    ::signal(SIGXFSZ, SIG_IGN);
    struct rlimit limit {};
    limit.rlim_cur = limit.rlim_max = 100000;
    ::setrlimit(RLIMIT_FSIZE, &limit);
    post_options o;
    o.cl_path = dir + "/big.cls";
    o.out_dir = dir + "/out";
    diagnostic_list d;
    std::string message = "(no error)";
    try {
      post_job(o, m, d);
    } catch (const config_error& e) {
      message = e.what();
    }
    test::write_file(dir + "/message.txt", message);
    ::_exit(0);
  }
  REQUIRE(::waitpid(child, nullptr, 0) == child);
  CHECK(test::read_file(dir + "/message.txt") == "cannot write '" + dir + "/out/RACE_1.nc': File too large");
  CHECK(test::list_dir(dir) == "big.cls message.txt");
  fs::remove_all(dir);
}
