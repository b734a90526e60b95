// The support layer's small pieces: JSON string literals, severity names.
#include <catch2/catch.hpp>

#include <string>

#include "support/diagnostics.hpp"
#include "support/json.hpp"

using namespace twinpost;

TEST_CASE("json_quote: short escapes, controls, ASCII kept", "[support][json]") {
  CHECK(json_quote("") == "\"\"");
  CHECK(json_quote("GOTO/1,2,3") == "\"GOTO/1,2,3\"");
  CHECK(json_quote("a\\b\"c\n\r\t\b\f") == "\"a\\\\b\\\"c\\n\\r\\t\\b\\f\"");
  CHECK(json_quote(std::string("\x01\x1f\x7f\0", 4)) == "\"\\u0001\\u001f\\u007f\\u0000\"");
}

TEST_CASE("json_quote: any bytes give ASCII JSON; UTF-8 as its characters", "[support][json]") {
  CHECK(json_quote("\xC3\xA9t\xC3\xA9") == "\"\\u00e9t\\u00e9\"");  // UTF-8 e-acute
  CHECK(json_quote("\xE2\x82\xAC") == "\"\\u20ac\"");               // euro sign, 3 bytes
  CHECK(json_quote("\xF0\x9F\x98\x80") == "\"\\ud83d\\ude00\"");    // past U+FFFF: a pair
  CHECK(json_quote("\xEF\xBF\xBF") == "\"\\uffff\"");
}

TEST_CASE("json_quote: bytes that are not UTF-8 are ISO-8859-1", "[support][json]") {
  // CL files are often ISO-8859-1: each byte is its own character, none is lost.
  CHECK(json_quote("G\xE9n\xE9r\xE9") == "\"G\\u00e9n\\u00e9r\\u00e9\"");
  CHECK(json_quote("\xE9t\xC3") == "\"\\u00e9t\\u00c3\"");          // a cut sequence at the end
  CHECK(json_quote("\xC3(") == "\"\\u00c3(\"");                      // lead byte, no continuation
  CHECK(json_quote("\x80\xBF") == "\"\\u0080\\u00bf\"");             // stray continuation bytes
  CHECK(json_quote("\xC0\xAF") == "\"\\u00c0\\u00af\"");             // overlong '/'
  CHECK(json_quote("\xED\xA0\x80") == "\"\\u00ed\\u00a0\\u0080\"");  // a surrogate, U+D800
  CHECK(json_quote("\xF4\x90\x80\x80") == "\"\\u00f4\\u0090\\u0080\\u0080\"");  // past U+10FFFF
  CHECK(json_quote("\xFF") == "\"\\u00ff\"");
}

TEST_CASE("append_json_string appends", "[support][json]") {
  std::string out = "{\"text\":";
  append_json_string(out, "a\"b");
  CHECK(out == "{\"text\":\"a\\\"b\"");
}

TEST_CASE("severity names and a diagnostic without a place", "[support]") {
  CHECK(std::string(severity_name(severity::note)) == "note");
  CHECK(std::string(severity_name(severity::warning)) == "warning");
  CHECK(std::string(severity_name(severity::error)) == "error");
  CHECK(format_diagnostic({severity::error, "", 0, 0, "no NC files given", {}}) ==
        "error: no NC files given\n");
  CHECK(format_diagnostic({severity::warning, "a.nc", 0, 0, "empty", {}}) == "a.nc: warning: empty\n");
}
