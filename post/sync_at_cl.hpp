#pragma once
// The post checks its own programs before it writes them; what the checker finds is at
// lines of programs that are then never written. This moves each finding at a wait block
// to the CL record that made the wait (the SYNC record, or the HEAD record of a sequential
// job): file:line:col of the CL with its source line, and the places of waits in the
// message become CL places. A note keeps the wait's line in the program as it would have
// been written.
#include <functional>
#include <string>
#include <vector>

#include "check/nc_program.hpp"
#include "machines/machine.hpp"
#include "support/diagnostics.hpp"

namespace twinpost {

/// Every block a channel wrote after its head, by CL line, and the indices of its waits.
/// `cl_line(i)` is asked only for the blocks of findings: the lines stay where the writer
/// keeps them (a temporary file), so memory does not grow with the programs.
struct cl_block_index {
  std::size_t count = 0;                    ///< blocks written after the head
  std::function<int(std::size_t)> cl_line;  ///< the CL line of block i < count
  std::vector<std::size_t> waits;
};

/// A block a channel wrote that may carry a finding of the shared-resource rules
/// (analysis/shared_resources): the waits written before it, its text, its CL record (0: none,
/// a line of the program's head).

struct cl_block {
  int segment = 0;
  std::string text;
  int cl_line = 0;
};

/// The source lines of `found`'s diagnostics at lines of the CL file `cl_path` that have none
/// yet, read from the file in one pass.
void fill_cl_lines(std::vector<diagnostic>& found, const std::string& cl_path);

/// `found` (the checker's diagnostics on `files`) moved to the CL file `cl_path`.
/// `wait_cl_lines[c]`: the CL line of each wait block channel c+1 wrote, in order;
/// `cl_last_line`: the job's last record, where every channel's program ends.
/// `blocks[c]`: channel c+1's blocks that may carry a finding of the shared-resource rules,
/// in order; a finding at one (the k-th block of its text after the same number of waits) is
/// moved to its CL record, with a note at the block as it would have been written.
/// `block_lines[c]`: the CL line of every block channel c+1 wrote after its head, and which of
/// them are its waits (channel_writer::block_cl_lines, wait_block_indices), for findings at any
/// block (the interference rule): a block is found by how many blocks it lies after the wait
/// before it (before the first wait: before that wait). Empty: only `blocks` are matched.
std::vector<diagnostic> sync_diagnostics_at_cl(const std::vector<diagnostic>& found,
                                               const std::vector<nc_source>& files, const machine& m,
                                               const std::string& cl_path,
                                               const std::vector<std::vector<int>>& wait_cl_lines,
                                               int cl_last_line,
                                               const std::vector<std::vector<cl_block>>& blocks = {},
                                               const std::vector<cl_block_index>& block_lines = {});

}  // namespace twinpost
