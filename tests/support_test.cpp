// The support layer's small pieces: ASCII classes and case, JSON string literals, the two
// kinds of config_error, severity names.
#include <catch2/catch.hpp>

#include <string>

#include "support/ascii.hpp"
#include "support/diagnostics.hpp"
#include "support/errors.hpp"
#include "support/json.hpp"

using namespace twinpost;

TEST_CASE("ascii classes: ASCII only, whatever the locale", "[support]") {
  CHECK(ascii::is_letter('a'));
  CHECK(ascii::is_letter('Z'));
  CHECK_FALSE(ascii::is_letter('@'));     // one before 'A'
  CHECK_FALSE(ascii::is_letter('['));     // one after 'Z'
  CHECK_FALSE(ascii::is_letter('`'));     // one before 'a'
  CHECK_FALSE(ascii::is_letter('{'));     // one after 'z'
  CHECK_FALSE(ascii::is_letter('\xE9'));  // e-acute in ISO-8859-1: never a letter
  CHECK_FALSE(ascii::is_letter('\xC9'));
  CHECK(ascii::is_digit('0'));
  CHECK(ascii::is_digit('9'));
  CHECK_FALSE(ascii::is_digit('/'));
  CHECK_FALSE(ascii::is_digit(':'));
  CHECK_FALSE(ascii::is_digit('\xB2'));  // superscript two
  CHECK(ascii::is_alnum('q'));
  CHECK(ascii::is_alnum('7'));
  CHECK_FALSE(ascii::is_alnum('_'));
  CHECK(ascii::is_upper('G'));
  CHECK_FALSE(ascii::is_upper('g'));
  CHECK(ascii::is_lower('g'));
  CHECK_FALSE(ascii::is_lower('G'));
}

TEST_CASE("ascii case: letters only", "[support]") {
  CHECK(ascii::upper('a') == 'A');
  CHECK(ascii::upper('z') == 'Z');
  CHECK(ascii::upper('A') == 'A');
  CHECK(ascii::upper('{') == '{');
  CHECK(ascii::upper('\xE9') == '\xE9');  // not 0xC9
  CHECK(ascii::upper_copy("goto/1.5,x_y,\xE9t\xE9") == "GOTO/1.5,X_Y,\xE9T\xE9");
  std::string s = "Head/Both";
  ascii::upper_in_place(s);
  CHECK(s == "HEAD/BOTH");
  CHECK(ascii::iequals("Main", "MAIN"));
  CHECK(ascii::iequals("", ""));
  CHECK_FALSE(ascii::iequals("MAIN", "MAINS"));
  CHECK_FALSE(ascii::iequals("\xE9", "\xC9"));
  CHECK_FALSE(ascii::iequals("[", "{"));              // 0x5B and 0x7B differ by the case bit, not letters
  static_assert(ascii::iequals("partno", "PARTNO"));  // usable in constant expressions
  CHECK(ascii::equals_keyword("goto", "GOTO"));
  CHECK(ascii::equals_keyword("GoTo", "GOTO"));
  CHECK_FALSE(ascii::equals_keyword("GOTO", "goto"));  // the keyword side is taken as written
  CHECK_FALSE(ascii::equals_keyword("GOT", "GOTO"));
  CHECK(ascii::starts_with_keyword("partno/x", "PARTNO"));
  CHECK_FALSE(ascii::starts_with_keyword("part", "PARTNO"));
}

TEST_CASE("json_quote: short escapes, controls, ASCII kept", "[support][json]") {
  CHECK(json_quote("") == "\"\"");
  CHECK(json_quote("GOTO/1,2,3") == "\"GOTO/1,2,3\"");
  CHECK(json_quote("a\\b\"c\n\r\t\b\f") == "\"a\\\\b\\\"c\\n\\r\\t\\b\\f\"");
  CHECK(json_quote(std::string("\x01\x1f\x7f\0", 4)) == "\"\\u0001\\u001f\\u007f\\u0000\"");
}

TEST_CASE("json_quote: any bytes give ASCII JSON, and UTF-8 as its characters", "[support][json]") {
  CHECK(json_quote("\xC3\xA9t\xC3\xA9") == "\"\\u00e9t\\u00e9\"");  // UTF-8 e-acute
  CHECK(json_quote("\xE2\x82\xAC") == "\"\\u20ac\"");               // euro sign, 3 bytes
  CHECK(json_quote("\xF0\x9F\x98\x80") == "\"\\ud83d\\ude00\"");    // past U+FFFF: a pair
  CHECK(json_quote("\xEF\xBF\xBF") == "\"\\uffff\"");
}

TEST_CASE("json_quote: bytes that are not UTF-8 are ISO-8859-1", "[support][json]") {
  // CL files are often ISO-8859-1: each byte is its own character, none is lost.
  CHECK(json_quote("G\xE9n\xE9r\xE9") == "\"G\\u00e9n\\u00e9r\\u00e9\"");
  CHECK(json_quote("\xE9t\xC3") == "\"\\u00e9t\\u00c3\"");                      // a cut sequence at the end
  CHECK(json_quote("\xC3(") == "\"\\u00c3(\"");                                 // lead byte, no continuation
  CHECK(json_quote("\x80\xBF") == "\"\\u0080\\u00bf\"");                        // stray continuation bytes
  CHECK(json_quote("\xC0\xAF") == "\"\\u00c0\\u00af\"");                        // overlong '/'
  CHECK(json_quote("\xED\xA0\x80") == "\"\\u00ed\\u00a0\\u0080\"");             // a surrogate, U+D800
  CHECK(json_quote("\xF4\x90\x80\x80") == "\"\\u00f4\\u0090\\u0080\\u0080\"");  // past U+10FFFF
  CHECK(json_quote("\xFF") == "\"\\u00ff\"");
}

TEST_CASE("append_json_string appends", "[support][json]") {
  std::string out = "{\"text\":";
  append_json_string(out, "a\"b");
  CHECK(out == "{\"text\":\"a\\\"b\"");
}

TEST_CASE("config_error: with a place or without", "[support]") {
  const config_error plain("cannot read 'a.cls': No such file or directory");
  CHECK(std::string(plain.what()) == "cannot read 'a.cls': No such file or directory");
  CHECK_FALSE(plain.located());
  const config_error placed = config_error::at("m.toml", 12, 3, "waits.first must be <= waits.last");
  CHECK(std::string(placed.what()) == "m.toml:12:3: error: waits.first must be <= waits.last");
  CHECK(placed.located());
  try {
    throw placed;
  } catch (const config_error& e) {
    CHECK(e.located());  // survives a copy
  }
}

TEST_CASE("severity names and a diagnostic without a place", "[support]") {
  CHECK(std::string(severity_name(severity::note)) == "note");
  CHECK(std::string(severity_name(severity::warning)) == "warning");
  CHECK(std::string(severity_name(severity::error)) == "error");
  CHECK(format_diagnostic({severity::error, "", 0, 0, "no NC files given", {}}) ==
        "error: no NC files given\n");
  CHECK(format_diagnostic({severity::warning, "a.nc", 0, 0, "empty", {}}) == "a.nc: warning: empty\n");
}

TEST_CASE("diagnostic_counts counts errors and warnings, not notes", "[support]") {
  diagnostic_counts n;
  n.add({severity::error, "a", 1, 1, "e", {}});
  n.add({severity::warning, "a", 2, 1, "w", {}});
  n.add({severity::note, "a", 3, 1, "n", {}});
  n.add({severity::error, "a", 4, 1, "e", {}});
  CHECK(n.errors == 2);
  CHECK(n.warnings == 1);
  diagnostic_list list;
  list.report({severity::warning, "a", 2, 1, "w", {}});
  list.report({severity::note, "a", 3, 1, "n", {}});
  CHECK(list.errors() == 0);
  CHECK(list.warnings() == 1);
  CHECK(list.all().size() == 2);
}
