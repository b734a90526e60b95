#pragma once
// Posting a CL job end to end: parser -> channels -> formats -> files. Every channel
// writes to its own temporary file on disk while posting: its program file where its blocks
// open one, a body file otherwise (the auxiliary streams of a merged layout, appended when
// all is read); the programs are checked by the same synchronisation checker as
// `twinpost check`, and only then committed into the output folder as a set
// (post/output_commit.hpp). A failed run leaves no file behind.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "analysis/cycle_time.hpp"
#include "channels/router.hpp"
#include "channels/wait_plan.hpp"
#include "machines/machine.hpp"
#include "parser/dialect.hpp"
#include "support/diagnostics.hpp"
#include "support/errors.hpp"

namespace twinpost {

struct post_options {
  std::string cl_path;
  std::string out_dir;
  std::optional<layout_kind> layout;  ///< the machine's layout unless given
  sync_policy policy = sync_policy::automatic;
  std::optional<dialect> forced_dialect;
  /// post --cl-frame: the frame NX MSYS points are written in, instead of the machine's
  /// [program] cl_frame.
  std::optional<cl_frame> frame;
  /// An unknown major word is a warning, not an error (a refused known word stays an error).
  bool permissive = false;
  /// When set, the timeline page of the posted programs (analysis/timeline_report.hpp) is
  /// written into the output folder under this plain file name, as one of the set.
  std::string timeline_file;
  /// post --compare-optimum: the job is also posted under the optimise policy with its own sync
  /// records set aside, nothing of it written, and the summary gives that cycle
  /// (post_summary::optimum_cycle).
  bool compare_optimum = false;
  /// post --tool [C:]N: tool N is in the spindle of channel C (1 unless given) when the job
  /// moves before any tool call (machining/channel_start_tool.cpp); one per channel.
  std::vector<std::pair<int, int>> start_tools;
  /// post --tool-kind: "turn", "mill" or "drill" for every tool whose kind neither the CL
  /// (TLDATA) nor the machine's [[tool]] table gives; empty: none.
  std::string tool_kind;
  /// Threads the post may use: 1 checks the programs after they are written; 2 or more (the
  /// default, 0, where the machine has two cores) checks them on a second thread while they
  /// are written (post/concurrent_check.hpp), and a machine of one channel with a kinematic
  /// chain works its moves out ahead on a third (machining/kin_lookahead.hpp). The output is
  /// the same byte for byte.
  int threads = 0;
  /// Called now and then (every 64k records) with the CL bytes read so far; may be empty.
  std::function<void(std::size_t bytes)> progress;
};

struct post_summary {
  bool ok = false;
  std::vector<std::string> files;  ///< written, in channel order
  int channels = 0;
  long blocks = 0;
  int waits = 0;                                 ///< rendezvous placed
  sync_policy policy = sync_policy::sequential;  ///< the policy actually used
  long records = 0;
  /// The cycle time of the written programs (per operation and wait, no block kept); empty
  /// when the machine file has no [timing].
  std::optional<timeline> timing;
  /// --sync optimise: the cycle of the same job posted sequentially, and the posts it took
  /// (the sequential one first; post/sync_optimise.hpp).
  std::optional<double> sequential_cycle;
  int passes = 1;
  /// --sync optimise: each pair of operations the self-check made keep the CL's order, with
  /// the finding that did ("channel 1 (job.cls:12-20) before channel 2 (job.cls:21-30): ...").
  std::vector<std::string> kept_apart;
  /// --sync optimise: the schedule the written programs follow (each section's operations of
  /// the two channels with their times, and where the channels meet), for `post --json`.
  std::optional<job_operations> schedule;
  /// --compare-optimum: the cycle the optimise policy gives the job with its sync records set
  /// aside (nothing of it written), and its posts; or why it could not be worked out.
  std::optional<double> optimum_cycle;
  int optimum_passes = 0;
  std::vector<std::string> optimum_kept_apart;     ///< its pairs kept in the CL's order, as kept_apart
  std::optional<job_operations> optimum_schedule;  ///< its schedule: where its waits would go
  std::string optimum_unknown;
};

/// The threads a post runs besides its own, with post_options::threads of two or more (with
/// one: none). docs/design.md, "Two cores".
struct post_threads {
  bool reader = false;      ///< the CL reader's (post/reader_thread.hpp)
  bool look_ahead = false;  ///< the 5-axis moves worked out ahead (machining/kin_lookahead.hpp)
  bool check = false;       ///< the check of the programs while they are written (post/concurrent_check.hpp)
};
post_threads plan_threads(const post_options& o, const machine& m);

/// Posts `o.cl_path` (a regular file: it is read twice) for machine `m`. Problems go to
/// `diags`; the summary says whether files were written. Throws config_error for I/O
/// failures, a job that is not a regular file, and file names a machine file makes unsafe
/// or shared (nothing is left behind).
post_summary post_job(const post_options& o, const machine& m, diagnostic_sink& diags);

/// A PARTNO made safe as a file name: letters, digits, '_' and '-' only, at most 32
/// characters, never empty, never a path.
std::string safe_file_stem(std::string_view partno);

}  // namespace twinpost
