#pragma once
// A quick pass over a CL file before it is posted, for the two facts that the streaming
// post needs up front: does the job carry sync records (the auto policy), and which heads
// and channels does it use (a sync record that names no channels means all of those).
// It looks only at the first word of each line; the real reading is the parser's.
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
job_scan scan_job(const std::string& path);

}  // namespace twinpost
