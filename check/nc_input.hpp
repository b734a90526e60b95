#pragma once
// NC inputs that the checker may read more than once.
//
// check_nc_files reads compactly first and reads again, in full, when it has something to
// say (check/sync_check.hpp). A regular file is simply opened again: memory stays flat
// however long it is. A pipe, a FIFO, /dev/stdin or a terminal can be read only once: a
// second reading would find nothing (or wait for ever on a FIFO), and a deadlock would pass
// for sound. Such an input is read here exactly once, into an anonymous temporary file
// (std::tmpfile: it has no name in any folder, and goes when it is closed or the process
// ends, however it ends), which the reader then reads as often as it needs.
#include <vector>

#include "check/nc_program.hpp"
#include "support/errors.hpp"

namespace twinpost {

/// `files` with every source whose path is not a regular file copied once into a private
/// temporary file (nc_source::copy); the same pipe named twice is copied once. Throws
/// config_error "cannot read 'F'..." for a path that does not exist, is a
/// directory, cannot be opened or read, or cannot be copied (a full disk).
std::vector<nc_source> rereadable(const std::vector<nc_source>& files);

}  // namespace twinpost
