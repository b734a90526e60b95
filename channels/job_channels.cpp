#include "channels/job_channels.hpp"

#include <algorithm>
#include <string>
#include <string_view>

namespace twinpost {

std::vector<int> used_channels(const job_scan& scan, const machine& m) {
  std::vector<int> used;
  auto add = [&](const channel_def* c) {
    if (c) used.push_back(c->number);
  };
  add(m.channel_for_head(1));
  for (int h : scan.heads) add(m.channel_for_head(h));
  for (const std::string& w : scan.head_words) add(m.channel_for_head(std::string_view(w)));
  for (int c : scan.channels)
    if (c >= 1 && c <= static_cast<int>(m.channels.size())) used.push_back(c);
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  return used;
}

bool scan_settled(const job_scan& scan, const machine& m, bool policy_given) {
  return (policy_given || scan.explicit_sync) && used_channels(scan, m).size() == m.channels.size();
}

}  // namespace twinpost
