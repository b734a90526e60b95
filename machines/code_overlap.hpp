#pragma once
// Two rules. No code a program may carry for another purpose is a wait code of the machine.
// A control takes every word of its waiting range for a wait (Fanuc parameters 8110/8111),
// so a spindle, coolant, stop or end code inside the range would stop the path until its
// partner reaches the same code, and the checker could not tell it from a wait either.
// The loader holds every code a machine file names to it (docs/machines.md, "Codes that
// cannot collide"); the post holds AUXFUN/PREFUN codes to it at their record. And no code
// holds what would make the control read something else than the code (code_text_fault).
#include <string>
#include <string_view>

#include "machines/machine.hpp"

namespace twinpost {

/// True when the word `address``code` is a wait code of `w` (wait_rules::is_any_wait: the
/// range and the fixed waits, on the wait address only).
bool is_wait_word(const wait_rules& w, char address, long long code);

/// "M200-M299", "M200-M298 step 2", "M200-M998, M82, M83": the wait codes as messages name them.
std::string wait_range_text(const wait_rules& w);

/// `text` with the blanks outside comments and `{placeholders}` dropped: its words as a control
/// reads them (a Fanuc reads `G 43` as G43).
std::string squeeze_blanks(std::string_view text, char open, char close);

/// Whether `block` (a code of the machine file) cancels a tool length offset: a G49, or a D or H
/// word of offset 0 (Fanuc's `H0`, Sinumerik's `D0`), comments and placeholders skipped.
bool cancels_length_offset(std::string_view block, char open, char close);

/// How a code is written: `part` of a block, the post's own words after it (a cycle, a spindle
/// or coolant code); a `line` of its own (the program line, the header); or at the `end`
/// (the footer, the end code), where M2/M30/M99 belong.
enum class code_use : unsigned char { part, line, end };

/// What in `text` (a code or template of the machine file) would make the control read
/// something else than the code: a comment that the post's words after it would fall into
/// (`open` with no `close` after it, or in a `part` any comment to the end of the line, `close`
/// = '\n'), or a program end (M2, M30, M99) before the `end`. Empty when nothing. (Line breaks,
/// '%' and bytes outside ASCII are the template reader's: table_reader::check_template.)
std::string code_text_fault(std::string_view text, char open, char close, code_use use);

/// The first word of `block` that is a wait code of `w`, or -1. `block` is a fixed block or
/// a template: text in comments (between `open` and `close`) and placeholders (`{...}`)
/// are skipped, and so is a word whose number has a decimal point (M98.1 is not M98).
long long first_wait_word(std::string_view block, const wait_rules& w, char open, char close);

}  // namespace twinpost
