#pragma once
// Committing a post's files as a set: all new or all old (docs/output-commit.md).
//
// A run stages its files in a folder of its own inside the output folder
// (`.twinpost-<pid>-<n>`), so that the final renames stay on one file system. The commit
// holds an exclusive flock on the output folder itself, so that concurrent posts into one
// folder commit one after the other; it checks that every target can be replaced, then
// links each old file into the stage as a backup and renames the new file over it; on any
// failure it puts every old file back and removes the new ones. SIGINT, SIGTERM and SIGHUP
// are held back while the folder changes. A run that fails removes its stage and, under the
// lock, the folders it made (deepest first, each only if empty); stages of dead runs are
// removed by the next run that stages in the folder.
#include <string>
#include <vector>

#include "support/errors.hpp"

namespace twinpost {

struct staged_file {
  std::string tmp_path;  ///< the finished file in the stage
  std::string name;      ///< its name in the output folder (a plain file name)
};

/// One run's stage in an output folder. Throws config_error when the folder cannot be made.
class output_stage {
 public:
  /// Makes `out_dir` and any missing parents (remembering which it made), removes stages
  /// of dead runs, and makes this run's stage, registered for the signal handler.
  explicit output_stage(std::string out_dir);
  /// Unless committed: removes the stage and the folders this run made that are empty.
  ~output_stage();
  output_stage(const output_stage&) = delete;
  output_stage& operator=(const output_stage&) = delete;

  /// The stage folder: the run writes its files here.
  const std::string& dir() const { return stage_; }

  /// Moves `files` into the output folder as a set, under the folder's lock: either every
  /// one is in place, or (config_error) the folder holds exactly what it held before.
  /// Returns the written paths (output folder / name), in order.
  /// `keep`: a file no output may replace (the job being posted: `-o` its own folder and a
  /// program or the page named as it is), refused like a folder in the way.
  std::vector<std::string> commit(const std::vector<staged_file>& files, const std::string& keep = {});

 private:
  /// The constructor's work: the folders, the stage, its registration.
  void make_stage();

  std::string out_;
  std::string stage_;
  std::vector<std::string> made_;  ///< folders this run made, outermost first
  int slot_ = -1;                  ///< in the temp registry
  bool committed_ = false;
};

namespace detail {
/// The renames of a commit without its checks and lock: each old file is kept in
/// `stage_dir` (a hard link, or moved there where linking fails) before the new one takes
/// its name; on a failure every step is undone in reverse. Throws config_error.
void replace_all(const std::string& out_dir, const std::string& stage_dir,
                 const std::vector<staged_file>& files);
}  // namespace detail

}  // namespace twinpost
