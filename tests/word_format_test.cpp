// machines/word_format: the control's digits per address, its defaults, and the [format]
// table of a machine file.
#include <catch2/catch.hpp>

#include <string>

#include "machine_test_support.hpp"
#include "machines/machine.hpp"
#include "machines/machine_loader.hpp"
#include "machines/word_format.hpp"

using namespace twinpost;

namespace {

std::string error_of(const std::string& text) { return test::machine_error_of(text); }

const std::string machine_head = "[machine]\nname = \"m\"\n[waits]\nfirst = 100\nlast = 103\n";
const std::string channels =
    "[[channel]]\nnumber = 1\naxis = [{address = \"X\"}, {address = \"Z\"}]\n"
    "[[channel]]\nnumber = 2\naxis = [{address = \"X\"}, {address = \"Z\"}]\n";

}  // namespace

TEST_CASE("word formats: reading, limits and texts", "[machines][format]") {
  word_format f;
  std::string why;
  REQUIRE(parse_word_format("5.3", f, why));
  CHECK(f.whole == 5);
  CHECK(f.decimals == 3);
  CHECK(f.text() == "5.3");
  CHECK(f.max_text() == "99999.999");
  CHECK(f.max_count(3) == 99999999);
  CHECK(f.max_count(1) == 999999);     // F per minute, one decimal written
  CHECK(f.max_count(4) == 999999990);  // more decimals written than the control reads
  REQUIRE(parse_word_format("4", f, why));
  CHECK(f.text() == "4");
  CHECK(f.max_count(0) == 9999);
  CHECK_FALSE(parse_word_format("5.", f, why));
  CHECK(why == "must be digits before and after the point, such as \"5.3\" or \"4\"");
  CHECK_FALSE(parse_word_format("-5.3", f, why));
  CHECK_FALSE(parse_word_format("10.3", f, why));
  CHECK(why == "has 10 digits before the point; 1..9 are allowed");
  CHECK_FALSE(parse_word_format("5.7", f, why));
  CHECK(why == "has 7 decimals; 0..6 are allowed");
}

TEST_CASE("word formats: the words of a formatted block", "[machines][format]") {
  const word_formats f = default_word_formats("fanuc-0i-td");
  CHECK(check_block_words("T0101", f, '(', ')') == "");
  CHECK(check_block_words("T21474836472147483647", f, '(', ')') ==
        "T word 21474836472147483647 does not fit the control's format (4: at most 9999)");
  CHECK(check_block_words("O1000 (PART 123456789)", f, '(', ')') == "");
  CHECK(check_block_words("O12345 (P)", f, '(', ')') ==
        "O word 12345 does not fit the control's format (4: at most 9999)");
  CHECK(check_block_words("G4 U1.5", f, '(', ')') == "");
  CHECK(check_block_words("G4 U1e+308", f, '(', ')') ==
        "U word 1e+308 does not fit the control's format (5.3: at most 99999.999)");
  CHECK(check_block_words("G50 S4000", f, '(', ')') == "");
  CHECK(check_block_words("T01 M6", f, '(', ')') == "");
  CHECK(check_block_words("G4 P=#1500", f, '(', ')') == "");  // no word: P is not followed by a number
  CHECK(check_block_words("G4 Uinf", f, '(', ')') ==
        "U word inf does not fit the control's format (5.3: at most 99999.999)");
}

TEST_CASE("word formats: defaults per control, and the [format] table", "[machines][format]") {
  const machine fanuc = load_machine("fanuc-0itd-twin");
  CHECK(fanuc.formats['X'].text() == "5.3");
  CHECK(fanuc.formats['O'].text() == "4");
  CHECK(load_machine("fanuc-31i-3path").formats['O'].text() == "4");
  CHECK(load_machine("integrex-i200st").formats['O'].text() == "8");
  const machine m = parse_machine(machine_head + "[format]\nX = \"6.3\"\nT = 6\n" + channels, "m.toml");
  CHECK(m.formats['X'].text() == "6.3");
  CHECK(m.formats['T'].text() == "6");
  CHECK(m.formats['Z'].text() == "5.3");  // the default where none is given
  CHECK(error_of(machine_head + "[format]\nX = \"5.x\"\n" + channels) ==
        "m.toml:7:5: error: format.X \"5.x\" must be digits before and after the point, such as \"5.3\" or "
        "\"4\"");
  CHECK(error_of(machine_head + "[format]\nX = 5.3\n" + channels) ==
        "m.toml:7:5: error: format.X must be a string such as \"5.3\" or an integer, not a floating-point "
        "number");
  CHECK(error_of(machine_head + "[format]\nXX = \"5.3\"\n" + channels)
            .starts_with("m.toml:7:1: error: unknown key"));
  CHECK(error_of(machine_head + "[format]\nZ = \"5.2\"\n" + channels) ==
        "m.toml:7:5: error: format.Z (5.2) has fewer decimals than program.decimals_metric (3)");
  CHECK(error_of(machine_head + "[program]\nprogram_number = 12345\n" + channels) ==
        "m.toml:7:18: error: program.program_number must be in 1..9999 (format.O 4), not 12345");
  CHECK(error_of(machine_head + "[program]\nprogram_number = 0\n" + channels) ==
        "m.toml:7:18: error: program.program_number must be in 1..9999 (format.O 4), not 0");
}
