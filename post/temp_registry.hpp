#pragma once
// What a post in progress has put on disk that an interrupted run must take away again:
// its staging folder (flat: files only) and the output folders it made (removed deepest
// first, each only if empty). The library never installs signal handlers; the command-line
// tool's handler for SIGINT, SIGTERM and SIGHUP calls remove_registered_temp_dirs() and
// then dies of the signal. Everything the handler touches is fixed-size static memory.
#include <string>
#include <vector>

namespace twinpost {

/// Registers a staging folder and the folders made for it (outermost first); returns a
/// slot for unregister_temp_dirs, or -1 when every slot is taken or the paths are too long
/// (the run then goes on unprotected: an interruption may leave the folder behind).
int register_temp_dirs(const std::string& stage, const std::vector<std::string>& made_dirs);

/// Forgets a slot (the run committed or cleaned up itself).
void unregister_temp_dirs(int slot);

/// Async-signal-safe: removes every registered staging folder with its files, then the
/// registered made folders that are empty, deepest first. Safe to call from a signal handler.
void remove_registered_temp_dirs() noexcept;

}  // namespace twinpost
