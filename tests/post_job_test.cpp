// post/post_job and parser/job_scan: file names from PARTNO, and the quick scan.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <thread>

#include <sys/stat.h>

#include <fmt/format.h>

#include "channels/job_channels.hpp"
#include "file_test_support.hpp"
#include "machines/machine_loader.hpp"
#include "parser/job_scan.hpp"
#include "post/post_job.hpp"
#include "post_test_jobs.hpp"

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
// In a folder of this process's own: a fixed name would be shared by tests run side by side.
std::string write_temp(const std::string& text) {
  static const std::string dir = test::fresh_temp_dir("scan");
  static const test::removed_at_end cleanup{dir};  // at the test program's exit
  static int written = 0;
  const std::string path = dir + "/job" + std::to_string(++written) + ".cls";
  REQUIRE(test::write_file(path, text));
  return path;
}
}  // namespace

TEST_CASE("the job scan finds sync records and the heads in use", "[post]") {
  job_scan s =
      scan_job(write_temp("HEAD / 2\n$$ SYNC/1,1,2 in a comment does not count\n"
                          "  head/both\nCHANNEL,3\ngoto/1,2,3"));
  CHECK_FALSE(s.explicit_sync);
  CHECK(s.heads == std::vector<int>{2, 1, 2});
  CHECK(s.channels == std::vector<int>{3});
  CHECK(scan_job(write_temp("HEAD/SIDE\r\n  synctr/next\r\n")).explicit_sync);
  job_scan words = scan_job(write_temp("HEAD/SIDE\n"));
  CHECK(words.head_words == std::vector<std::string>{"SIDE"});
  CHECK(scan_job(write_temp("$$UDE: MANUSPOST - SYNCHRONIZATION/SYNCHRONIZATION NUMBER=1")).explicit_sync);
  // A part transfer is a barrier under every policy, not a sync record: `auto` places the rest.
  CHECK_FALSE(scan_job(write_temp("TRANSFER/GRIP\nTRANSFER/RELEASE")).explicit_sync);
}

TEST_CASE("the job scan reads a head or a sync wherever its line falls in the file", "[post]") {
  // The scan tests sixteen bytes at a time: a record at every place against those blocks,
  // behind motion lines of every length, in a file read in place (a regular file) and through
  // a pipe (read in chunks).
  for (int pad = 0; pad < 40; ++pad) {
    INFO("pad " << pad);
    const std::string moves = "GOTO/" + std::string(static_cast<std::size_t>(pad), '1') + ",0,5\n";
    const std::string text = moves + std::string(static_cast<std::size_t>(pad % 7), ' ') + "HEAD/" +
                             std::to_string(pad + 1) + "\n" + moves + "SYNCTR/1\n" + moves + "CHANNL/2";
    const job_scan s = scan_job(write_temp(text));
    CHECK(s.heads == std::vector<int>{pad + 1});
    CHECK(s.explicit_sync);
    CHECK(s.channels == std::vector<int>{2});
    const job_scan none = scan_job(write_temp(moves + moves + "$$ a comment\n" + moves));
    CHECK_FALSE(none.explicit_sync);
    CHECK(none.heads.empty());
  }
  // The scan reads a file in windows, the first of 256 KB and each next twice the last, up to
  // 8 MB; a window ends at the line end after its nominal end. A record that begins 3 bytes
  // before `at`, after motion lines:
  auto place = [](std::string& text, std::size_t at, const std::string& record) {
    while (text.size() + 11 < at - 3) text += "GOTO/1,2,3\n";
    text += std::string(at - 3 - text.size() - 1, ' ') + "\n" + record + "\n";
  };
  // A job of 8 MB (two halves, below): records across the first window's nominal end and across
  // the second's (the first one ends just after HEAD/6), and one after 8 MB.
  std::string big;
  place(big, std::size_t{256} << 10, "HEAD/6");
  place(big, big.size() + (std::size_t{512} << 10), "HEAD/8");
  place(big, std::size_t{8} << 20, "HEAD/7");
  for (int i = 0; i < 1000; ++i) big += "GOTO/1,2,3\n";
  big += "SYNC/1,1,2\n";
  const job_scan across = scan_job(write_temp(big));
  CHECK(across.heads == std::vector<int>{6, 8, 7});
  CHECK(across.explicit_sync);
  // A job of 20 MB is scanned in two halves at once: a record across the middle, across the
  // first window's end in each half, and records before and after, found in the file's order.
  constexpr std::size_t size = std::size_t{20} << 20, first_window = std::size_t{256} << 10;
  std::string halves = "HEAD/1\n";
  place(halves, first_window, "HEAD/2");
  place(halves, size / 2, "CHANNL/4");
  const std::size_t second = halves.size();  // where the second half starts
  place(halves, size / 2 + 200, "HEAD/MAIN");
  place(halves, second + first_window, "HEAD/3");
  place(halves, size - 100, "SYNC/1,1,2");
  halves += std::string(size - halves.size() - 1, ' ') + "\n";
  REQUIRE(halves.size() == size);
  const job_scan two = scan_job(write_temp(halves));
  CHECK(two.heads == std::vector<int>{1, 2, 3});
  CHECK(two.head_words == std::vector<std::string>{"MAIN"});
  CHECK(two.channels == std::vector<int>{4});
  CHECK(two.explicit_sync);
  const test::removed_at_end fifo_dir{test::fresh_temp_dir("scan-fifo")};
  const std::string fifo = fifo_dir.dir + "/job.cls";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  std::thread feed([&] { test::write_file(fifo, "GOTO/1,2,3\nHEAD/2\nSYNC/1,1,2\n"); });
  const job_scan piped = scan_job(fifo);
  feed.join();
  CHECK(piped.heads == std::vector<int>{2});
  CHECK(piped.explicit_sync);
}

TEST_CASE("the job scan stops once the caller has enough", "[post]") {
  // `enough` is asked after each window of the first half (256 KB, then 512 KB, 1 MB ...):
  // the result is what the file holds up to the window where it said so.
  auto has_head = [](int h) {
    return [h](const job_scan& s) { return std::find(s.heads.begin(), s.heads.end(), h) != s.heads.end(); };
  };
  auto job = [](const std::vector<std::pair<std::size_t, std::string>>& records, std::size_t size) {
    std::string text;
    for (const auto& [at, record] : records) {
      while (text.size() + 11 < at) text += "GOTO/1,2,3\n";
      text += record + "\n";
    }
    while (text.size() + 11 < size) text += "GOTO/1,2,3\n";
    return write_temp(text);
  };
  constexpr std::size_t kb = 1024, mb = kb * kb;
  // A short job: one window, asked once at its end.
  const std::string small =
      job({{0, "HEAD/1"}, {100, "SYNC/1,1,2"}, {200, "HEAD/2"}, {90 * kb, "HEAD/3"}}, 100 * kb);
  CHECK(scan_job(small, has_head(2)).heads == std::vector<int>{1, 2, 3});
  // Past the first window: what follows it is not read.
  const std::string one =
      job({{0, "HEAD/1"}, {100, "SYNC/1,1,2"}, {200, "HEAD/2"}, {300 * kb, "HEAD/3"}}, mb);
  const job_scan early = scan_job(one, has_head(2));
  CHECK(early.heads == std::vector<int>{1, 2});
  CHECK(early.explicit_sync);
  CHECK(scan_job(one).heads == std::vector<int>{1, 2, 3});
  CHECK(scan_job(one, has_head(3)).heads == std::vector<int>{1, 2, 3});  // found in the second window
  CHECK(scan_job(one, has_head(9)).heads == std::vector<int>{1, 2, 3});  // never enough: all of it
  // A job of two halves (8 MB): enough in the third window of the first half (it ends past
  // 1.75 MB). The second half's thread, begun after the first window, reads at least its own
  // first window (HEAD/5, just past the middle) before it sees the stop: what it found is
  // dropped, every time.
  const std::string two = job(
      {{0, "HEAD/1"}, {mb, "HEAD/2"}, {3 * mb, "HEAD/3"}, {4 * mb + 100 * kb, "HEAD/5"}, {6 * mb, "HEAD/4"}},
      8 * mb);
  for (int run = 0; run < 3; ++run) CHECK(scan_job(two, has_head(2)).heads == std::vector<int>{1, 2});
  CHECK(scan_job(two, has_head(3)).heads == std::vector<int>{1, 2, 3});
  CHECK(scan_job(two, has_head(4)).heads == std::vector<int>{1, 2, 3, 5, 4});  // in the second half: all
}

TEST_CASE("the job scan is settled once the policy and every channel are known", "[post]") {
  const machine twin = load_machine("fanuc-0itd-twin");  // channels 1 and 2, heads 1 and 2
  job_scan s;
  s.heads = {1};
  CHECK_FALSE(scan_settled(s, twin, false));
  CHECK_FALSE(scan_settled(s, twin, true));  // channel 2 may still come
  s.explicit_sync = true;
  CHECK_FALSE(scan_settled(s, twin, false));
  s.heads = {1, 2};
  CHECK(scan_settled(s, twin, false));
  s.explicit_sync = false;
  CHECK_FALSE(scan_settled(s, twin, false));  // auto: a sync record may still come
  CHECK(scan_settled(s, twin, true));         // --sync given: the channels are all it needs
  const machine three = load_machine("fanuc-31i-3path");
  s.explicit_sync = true;
  CHECK_FALSE(scan_settled(s, three, false));  // a third path may still be used
  s.channels = {3};
  CHECK(scan_settled(s, three, false));
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

namespace {
// The files a post writes: name -> contents ("(failed)" when the post failed).
std::map<std::string, std::string> post_files(const std::string& cl, const machine& m, const std::string& tag,
                                              diagnostic_list* diags = nullptr,
                                              std::optional<layout_kind> layout = {}) {
  test::posted p = test::post_in_fresh_dir(cl, m, "post-files-" + tag, {}, layout);
  if (diags) *diags = p.diags;
  if (!p.ok) p.files["(failed)"] = "";
  return p.files;
}
}  // namespace

TEST_CASE("a PARTNO after the first blocks still names the program and its head", "[post]") {
  // Channels write straight into their program files, head first; a name that comes late
  // gives the file a new head. Either way the files are those of the PARTNO-first job.
  const std::string body =
      "HEAD/1\nTURRET/1,1\nSPINDL/RPM,1000,CLW,MAIN\nFEDRAT/0.2,MMPR\nGOTO/20,0,5\nGOTO/20,0,-10\n"
      "HEAD/2\nTURRET/4,4\nSPINDL/RPM,1000,CLW\nFEDRAT/0.1,MMPR\nGOTO/-10,0,5\nGOTO/-10,0,-3\n";
  const std::string early = "PARTNO/LATE NAME 7\n" + body + "FINI\n";
  const std::string late = body + "PARTNO/LATE NAME 7\nFINI\n";
  struct run {
    const char* machine;
    std::optional<layout_kind> layout;
    const char* file;
  };
  for (const run& r :
       {run{"fanuc-0itd-twin", {}, "LATE_NAME_7_1.nc"}, run{"integrex-i200st", {}, "LATE_NAME_7.EIA"},
        run{"fanuc-31i-3path", layout_kind::merged_sections, "LATE_NAME_7.nc"}}) {
    INFO(r.machine);
    const auto a = post_files(early, load_machine(r.machine), "early", nullptr, r.layout);
    const auto b = post_files(late, load_machine(r.machine), "late", nullptr, r.layout);
    REQUIRE(a.count(r.file) == 1);
    CHECK(a.at(r.file).find("(LATE_NAME_7)") != std::string::npos);
    CHECK(a == b);
  }
}

TEST_CASE("a layout the machine cannot take fails the post before anything is written", "[post]") {
  // The same rule as the loader's and --layout's (machines/layout_rules): the Fanuc twin
  // has no section marker, so its channels cannot be appended into one program.
  const machine m = load_machine("fanuc-0itd-twin");
  diagnostic_list d;
  const auto files =
      post_files("PARTNO/X\nHEAD/1\nGOTO/1,0,1\nFINI\n", m, "no-marker", &d, layout_kind::merged_appended);
  CHECK(files == std::map<std::string, std::string>{{"(failed)", ""}});
  REQUIRE(d.all().size() == 1);
  CHECK(format_diagnostic(d.all()[0]) ==
        m.source +
            ": error: layout merged_appended needs program.section_marker (the block "
            "that opens each channel's section, such as \"G109 L{channel}\")\n");
  // merged_sections writes `$n` and needs no marker.
  diagnostic_list ok;
  CHECK(post_files("PARTNO/X\nHEAD/1\nTURRET/1,1\nRAPID\nGOTO/1,0,1\nFINI\n", m, "sections", &ok,
                   layout_kind::merged_sections)
            .count("X.nc") == 1);
}

TEST_CASE("the job scan looks only at first words, across read chunks", "[post]") {
  // Letters it looks for inside a line do not count; the reader takes a megabyte at a
  // time, so a HEAD record may straddle two reads, and the last line needs no newline.
  std::string text = "PARTNO SHAFT\nGOTO/1,2,3 $$ HEAD/7\nINSERT SYNC/1,1,2\n  \tCHANNL/2\n";
  while (text.size() < (1u << 20) - 3) text += "GOTO/10.0000,0.0000,-5.0000\n";
  text.resize((1u << 20) - 3);  // the cut falls inside "HEAD/3"
  text += "\nHEAD/3\n";
  for (int i = 0; i < 1000; ++i) text += "goto/1,2,3\n";
  text += "\thead / 4";
  job_scan s = scan_job(write_temp(text));
  CHECK_FALSE(s.explicit_sync);
  CHECK(s.heads == std::vector<int>{3, 4});
  CHECK(s.channels == std::vector<int>{2});
}

TEST_CASE("a post's threads: the reader's own only where the check while writing is light", "[post]") {
  post_options o;
  o.threads = 2;
  auto plan = [&o](const machine& m) {
    const post_threads p = plan_threads(o, m);
    return std::string(p.reader ? "reader " : "") + (p.look_ahead ? "look-ahead " : "") +
           (p.check ? "check" : "");
  };
  const machine twin = load_machine("fanuc-0itd-twin");  // [timing] and [interference]
  CHECK(plan(twin) == "check");
  machine untimed = twin;
  for (channel_def& c : untimed.channels) c.timing = {};
  CHECK(plan(untimed) == "check");  // the interference check alone
  machine light = untimed;
  light.interference = {};
  CHECK(plan(light) == "reader check");
  machine unchecked = twin;
  unchecked.interference = {};
  CHECK(plan(unchecked) == "check");        // the timer alone
  o.layout = layout_kind::merged_sections;  // checked after it is written: the reader's thread
  CHECK(plan(twin) == "reader ");
  o.layout.reset();
  CHECK(plan(load_machine("head-head-5axis")) == "reader look-ahead check");
  o.threads = 1;
  CHECK(plan(twin).empty());
  CHECK(plan(load_machine("head-head-5axis")).empty());
}

TEST_CASE("a one-channel machine: no pre-pass, and a sync record is an error", "[post]") {
  // Nothing to wait for on one channel: the job is read once, and a SYNC in it (a job made
  // for a twin-turret machine) fails the post with the reason instead of being ignored.
  const machine m = load_machine(std::string(TWINPOST_SOURCE_DIR) + "/bench/bench-mill.toml");
  const std::string job =
      "PARTNO ONE\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,500\n"
      "GOTO/0,0,5\nGOTO/10,0,0\n";
  const auto ok = post_files(job + "FINI\n", m, "one-ok");
  REQUIRE(ok.count("ONE.nc") == 1);
  CHECK(ok.at("ONE.nc") ==
        "%\nO1000 (ONE)\nG21\nG90 G17 G40 G49 G80\nG91 G28 Z0\nG90\nT01 M6\nS1000 M3\nG94\n"
        "G1 G43 H01 X0. Y0. Z5. F500.\nX10. Z0.\nG91 G28 Z0\nG90\nM9\nM5\nM30\n%\n");
  diagnostic_list d;
  const auto bad = post_files(job + "SYNC/1,1,2\nFINI\n", m, "one-sync", &d);
  CHECK(bad.count("(failed)") == 1);
  CHECK(bad.size() == 1);  // nothing written
  REQUIRE(d.all().size() == 1);
  CHECK(d.all()[0].message == "sync 1 names channel 2, machine 'bench-mill' has 1 channels");
  CHECK(d.all()[0].line == 7);
}

TEST_CASE("on three threads the post gives what it gives on one, across many batches of events", "[post]") {
  // The reader runs ahead in batches of 4096 events and the check reads the programs while
  // they are written (post/reader_thread, post/concurrent_check): the reader's errors, the
  // writer's errors with their records' source lines (one continued over two lines), and a
  // sound post, all as on one thread.
  std::string cl = "PARTNO/THREADS\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,1000,CLW,MAIN\nFEDRAT/0.2,MMPR\n";
  std::string sound = cl;
  for (int i = 0; i < 9000; ++i) {
    const std::string z = fmt::format("{:.3f}", 5 - (i % 50) * 0.1);
    const std::string move = "GOTO/20,0," + z + "\n";
    sound += move;
    if (i == 4095)
      cl += "GOTO/5000,0,$\n  " + z + "\n";  // the writer's error on a record of two lines
    else if (i % 3001 == 11)
      cl += "GOTO/20,,0,5,\n";  // the reader's
    else if (i % 2999 == 5)
      cl += "GOTO/5000,0,5\n";  // the writer's
    else
      cl += move;
  }
  const std::string tail = "HEAD/2\nTURRET/4,4\nSPINDL/RPM,1000,CLW\nFEDRAT/0.1,MMPR\nGOTO/-10,0,5\nFINI\n";
  // The twin lathe times its programs and checks its turrets, and reads on the post's thread
  // (post_job.cpp, reader_gets_thread); without [timing] and [interference] the reader has a
  // thread of its own.
  const machine twin = load_machine("fanuc-0itd-twin");
  machine light = twin;
  for (channel_def& c : light.channels) c.timing = {};
  light.interference = {};
  for (const machine* mp : {&twin, static_cast<const machine*>(&light)})
    for (const std::string& job : {cl + tail, sound + tail}) {
      const machine& m = *mp;
      const bool fails = job.size() != (sound + tail).size();
      INFO((fails ? "with errors" : "sound") << (mp == &twin ? "" : ", no timing"));
      auto with = [](int n) { return [n](post_options& o) { o.threads = n; }; };
      const test::posted one = test::post_in_fresh_dir(job, m, "threads-1", {}, {}, with(1));
      const test::posted three = test::post_in_fresh_dir(job, m, "threads-2", {}, {}, with(2));
      CHECK(one.ok == !fails);
      CHECK(three.diagnostics == one.diagnostics);
      CHECK(three.files == one.files);
      CHECK(one.files.size() == (fails ? 0u : 2u));
      if (fails) {
        CHECK(
            one.diagnostics.find("job.cls:4101:1: error: channel 1: X10000. is outside channel 1's X travel "
                                 "-10..460 (channel.axis min/max)\nGOTO/5000,0,$\n^\n") != std::string::npos);
        CHECK(
            one.diagnostics.find("job.cls:3018:6: error: GOTO takes 3 or 6 numbers (x,y,z[,i,j,k]), found 4 "
                                 "arguments\nGOTO/20,,0,5,\n     ^\n") != std::string::npos);
      }
    }
}

TEST_CASE("the comparison with the CL finds on the self-check's thread what it finds on the post's",
          "[post][cl_compare]") {
  // On two threads each channel's program is compared with its CL from the self-check's reading
  // (post/concurrent_check): the records go there with the lines written before each, in pieces
  // of 64 KB, or of concurrent_check::records_per_piece records. Both channels' findings, past
  // several pieces, as on one thread; a sound job as on one thread.
  auto job = [](bool bad) {
    std::string cl =
        "PARTNO/T36\nUNITS/MM\nHEAD/1\nTURRET/1,1\nSPINDL/RPM,1000,CLW\nFEDRAT/0.2,MMPR\nGOTO/80,0,2\n";
    for (int i = 0; i < 20000; ++i) {
      if (bad && i == 12500) cl += "INSERT/M5\n";
      cl += fmt::format("GOTO/{},0,{}\n", 40 + i % 7, -(i % 50) * 0.5);
    }
    cl += "GOTO/80,0,2\nHEAD/2\nTURRET/4,4\nSPINDL/RPM,1000,CLW\nFEDRAT/0.1,MMPR\nGOTO/-30,0,5\n";
    for (int i = 0; i < 3000; ++i) {
      if (bad && i == 2000) cl += "INSERT/T0505\n";
      cl += fmt::format("GOTO/{},0,{}\n", -30 - i % 5, -(i % 40) * 0.5);
    }
    return cl + "GOTO/-30,0,5\nFINI\n";
  };
  const machine m = load_machine("fanuc-0itd-twin");
  auto with = [](int n) { return [n](post_options& o) { o.threads = n; }; };
  const test::posted bad1 = test::post_in_fresh_dir(job(true), m, "compare-1", {}, {}, with(1));
  const test::posted bad2 = test::post_in_fresh_dir(job(true), m, "compare-2", {}, {}, with(2));
  CHECK(bad2.diagnostics ==
        "job.cls:12509:1: error: channel 1: the CL cuts with the spindle turning clockwise at 1000 rpm here "
        "(SPINDL at line 5), but the program's main spindle is stopped\nGOTO/45,0,0\n^\n"
        "job.cls:22016:1: error: channel 2: the CL cuts with tool 4 here (the tool call at line 20011), the "
        "program with tool 5 (T0505, read by the tool call T{tool:02}{offset:02})\nGOTO/-30,0,0\n^\n");
  CHECK(bad1.diagnostics == bad2.diagnostics);
  CHECK(bad2.files.empty());
  const test::posted sound1 = test::post_in_fresh_dir(job(false), m, "compare-sound-1", {}, {}, with(1));
  const test::posted sound2 = test::post_in_fresh_dir(job(false), m, "compare-sound-2", {}, {}, with(2));
  CHECK(sound2.ok);
  CHECK(sound2.diagnostics == sound1.diagnostics);
  CHECK(sound2.files == sound1.files);
  REQUIRE(sound2.files.count("T36_1.nc") == 1);
  CHECK(sound2.files.at("T36_1.nc").size() > 3 * 65536);  // several pieces
}
