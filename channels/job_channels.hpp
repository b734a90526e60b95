#pragma once
// Which channels of the machine a job uses, from the job scan: a sync record that names no
// channels means these (so an idle third path is not made to wait at every mark).
#include <vector>

#include "machines/machine.hpp"
#include "parser/job_scan.hpp"

namespace twinpost {

/// The machine channels the job uses, ascending: head 1's channel (work before any HEAD
/// goes there) and those of every head and channel the scan found.
std::vector<int> used_channels(const job_scan& scan, const machine& m);

/// True when what a job scan has found so far settles both things the post takes from it, so
/// that the scan may stop (parser/job_scan's `enough`): the sync policy (`policy_given` with
/// --sync, or a sync record found) and the channels (every channel of the machine in use: a
/// sync record that names none can mean no more). Under the `auto` policy a job without sync
/// records is never settled (one at its last line would change the policy), nor is one that
/// leaves a channel idle.
bool scan_settled(const job_scan& scan, const machine& m, bool policy_given);

}  // namespace twinpost
