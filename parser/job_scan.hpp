#pragma once
// A quick pass over a CL file before it is posted, for the two facts that the streaming
// post needs up front: does the job carry sync records (the auto policy), and which heads
// and channels does it use (a sync record that names no channels means all of those).
// It looks only at the first word of each line; the real reading is the parser's.
//
// The caller may need less than the whole answer: whether the job has any sync record, and
// whether it uses every channel of the machine, are settled at the first line that shows it.
// `enough` lets the scan stop there: a two-turret job that syncs and uses both heads in its
// first operations is not read twice (docs/benchmark.md, "Issue 23, eighth pass").
#include <functional>
#include <string>
#include <vector>

namespace twinpost {

struct job_scan {
  bool explicit_sync = false;           ///< a SYNC/, SYNCTR/ record or a MANUSpost sync UDE
  std::vector<int> heads;               ///< HEAD/n numbers, and 1 and 2 for HEAD/BOTH
  std::vector<std::string> head_words;  ///< HEAD/MAIN, HEAD/SIDE (upper case)
  std::vector<int> channels;            ///< CHANNEL,n / CHANNL/n
};

/// Scans `path`; a file that cannot be read gives an empty scan (the post reports it).
/// `enough`, when given, is asked as the scan goes, with what it has found so far (which only
/// ever grows): after each part it reads of a regular file's first half (the whole file below
/// 4 MB), 256 KB at first, then larger parts; a pipe is read to its end. Once it says true the
/// scan stops and returns that, the findings of the file up to there. The same file gives the
/// same result every time.
job_scan scan_job(const std::string& path, const std::function<bool(const job_scan&)>& enough = {});

}  // namespace twinpost
