#pragma once
// The real CL files of ../shared/cl-samples are not part of the project. A test that needs
// them and finds no folder must not pass: it says why and ends its process with 77, which
// ctest reports as "Skipped" (SKIP_RETURN_CODE, CMakeLists.txt). Catch2 v2 has no skip.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace twinpost::test {

/// Ends the test process as skipped (exit code 77), printing `reason`. Run outside ctest,
/// the whole test binary ends here: leave the test out with its tag (`~[samples]`).
[[noreturn]] inline void skip_test(const std::string& reason) {
  std::printf("SKIPPED: %s\n", reason.c_str());
  std::fflush(stdout);
  std::_Exit(77);
}

/// The shared CL samples: $TWINPOST_SHARED_DIR/cl-samples when the variable is set, else
/// those of the folder the build was configured with (the cache variable of the same name).
inline std::filesystem::path shared_samples_dir() {
  const char* env = std::getenv("TWINPOST_SHARED_DIR");
  return std::filesystem::path(env && *env ? env : TWINPOST_SHARED_DIR) / "cl-samples";
}

/// The shared CL samples, or a skipped test when there is no such folder.
inline std::filesystem::path require_shared_samples() {
  std::filesystem::path dir = shared_samples_dir();
  if (!std::filesystem::is_directory(dir))
    skip_test("no CL samples at " + dir.string() + " (TWINPOST_SHARED_DIR)");
  return dir;
}

}  // namespace twinpost::test
