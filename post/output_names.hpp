#pragma once
// The names a post gives its files, checked once they are formatted: a machine file's
// template (`file_name`, `file_suffix`, `extension`, with fmt fills) must give a plain file
// name inside the output folder, and no two files of one post may share a name.
#include <string>
#include <vector>

#include "formats/program_layout.hpp"
#include "support/errors.hpp"

namespace twinpost {

/// Why `name` is not a plain file name in a folder ("" when it is): empty, `.` or `..`,
/// a '/' or NUL in it, longer than 255 bytes, or a name the post keeps for itself
/// (`.twinpost-…`).
std::string file_name_problem(const std::string& name);

/// Throws config_error naming the machine file and its template when a file of `files`
/// (as framed for `r`) has no plain name, or when two channels' files share a name.
void check_output_names(const frame_request& r, const std::vector<framed_file>& files);

}  // namespace twinpost
