#pragma once
// JSON string literals for the tool's machine-readable output (`twinpost parse --json`,
// `twinpost check --json`). Inputs are bytes, not text: CL and NC files are often
// ISO-8859-1, sometimes UTF-8, now and then binary.
#include <string>
#include <string_view>

namespace twinpost {

/// Appends `s` as a JSON string literal, quotes included. The literal is plain ASCII, so it
/// is valid JSON and valid UTF-8 whatever the bytes:
/// - `"` `\` and the controls \n \r \t \b \f as their short escapes; other controls and DEL
///   as \u00XX;
/// - a valid UTF-8 sequence as its character (\uXXXX, a surrogate pair past U+FFFF): a UTF-8
///   file reads as written;
/// - every other byte >= 0x80 as the ISO-8859-1 character of that value (0xE9 -> \u00e9):
///   the usual encoding of CL files, and no byte is lost or merged into U+FFFD.
void append_json_string(std::string& out, std::string_view s);

/// `s` as a JSON string literal (append_json_string).
std::string json_quote(std::string_view s);

}  // namespace twinpost
