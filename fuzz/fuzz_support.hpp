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

/// Writes `text` to `path` (aborts on failure: the scratch folder must work).
void write_all(const std::string& path, std::string_view text);

}  // namespace twinpost::fuzz
