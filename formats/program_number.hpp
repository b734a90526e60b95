#pragma once
// The program number (O-number) a job gets: PARTNO when it is a number the control's O
// format holds, else the machine's program_number, with a warning that says so.
#include <string>

#include "machines/machine.hpp"
#include "parser/events.hpp"
#include "support/diagnostics.hpp"

namespace twinpost {

/// Warns when PARTNO `name` (the safe file stem) is all digits but not a program number the
/// O format holds (PARTNO 99999999 on a four-digit control, PARTNO 0): the program takes
/// the machine's program_number instead.
void warn_program_number(const machine& m, diagnostic_sink& diags, const std::string& file,
                         const event& partno, const std::string& name);

}  // namespace twinpost
