#pragma once
// Rendering a sync_result (check/sync_check.hpp) as text or JSON. Pure functions: the
// caller decides where the text goes.
#include <string>
#include <string_view>

#include "check/sync_check.hpp"

namespace twinpost {

/// The one summary line, e.g. "check: 2 channels, 14 waits paired, 1 error" (no newline).
std::string format_sync_summary(const sync_result& r);

/// Every problem as format_diagnostic renders it, then the summary line and a newline.
std::string format_sync_text(const sync_result& r);

/// One JSON object: ok, channels [{channel, file, waits, paired}], paired, errors,
/// warnings, problems [{file, line, column, severity, message}]; ends with a newline.
std::string format_sync_json(const sync_result& r);

}  // namespace twinpost
