#pragma once
// The release version and the commit the binary was built from (generated at build time
// by cli/version.cmake; "unknown" outside a git checkout).

namespace twinpost::cli {

const char* version();  ///< "0.3.0"
const char* commit();   ///< "e9f2573c1d2a" or "e9f2573c1d2a-dirty"

}  // namespace twinpost::cli
