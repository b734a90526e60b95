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

}  // namespace twinpost
