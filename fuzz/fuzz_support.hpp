#pragma once
// What the fuzz targets share: the libFuzzer entry point they define, a private scratch
// folder per process, and `require`, which aborts (a finding) with a message when a
// property of twinpost does not hold.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "machines/machine.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace twinpost::fuzz {

/// A folder of this process's own under $TMPDIR (made once, removed at exit).
const std::string& scratch_dir();

/// Every built-in machine, loaded once, in name order.
const std::vector<machine>& builtin_machine_defs();

/// Aborts with "fuzz property failed: what" on stderr when `ok` is false.
void require(bool ok, std::string_view what);

/// The whole content of a file ("" if it cannot be read).
std::string read_all(const std::string& path);

/// What one post gave: ok (exit 0) or a config_error (exit 2), the files it wrote and their
/// bytes.
struct post_outcome {
  bool ok = false;
  bool config = false;
  std::vector<std::string> files;
  std::vector<std::string> contents;
};

/// Posts the CL file `job` into the folder `out` for `m` and holds the properties of every post
/// (a finding aborts): post_job returns or throws config_error; every error has a file and a
/// line; a failed post leaves no file; a post that succeeds wrote exactly the files it names,
/// each to its own path, `check` finds them sound, and (unless `has_insert`: INSERT text goes
/// out verbatim) no number outside comments is unreadable (inf, nan, more than ten digits).
post_outcome post_checked(const std::string& job, const std::string& out, const machine& m,
                          layout_kind layout, bool has_insert);

/// Writes `text` to `path` (aborts on failure: the scratch folder must work).
void write_all(const std::string& path, std::string_view text);

}  // namespace twinpost::fuzz
