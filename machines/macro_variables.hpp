#pragma once
// Macro variables in blocks (Fanuc/Mazak custom macro B: `#501=#501+1`, `G0 G53 W#501`) and the
// ones a machine file reserves for its setup.
//
// A machine's [transfer] blocks read setup values (#500, the sub spindle's grip position): a
// program that writes one moves the next transfer. program.reserved_variables names more. The
// control emulator (analysis/control_emulator) refuses a block that writes a reserved variable,
// whoever wrote the block: the post, an [events] template, a script, or another CAM's post.
#include <string>
#include <string_view>
#include <vector>

#include "machines/machine.hpp"

namespace twinpost {

/// One use of a numbered variable in a block.
struct macro_use {
  int number = 0;      ///< #501 -> 501; -1 for #[...], whose number is known at run time only
  int column = 0;      ///< 1-based column of the '#'
  bool write = false;  ///< the variable is assigned (`#501=`), not read
};

/// The numbered variables a block uses, in order, read as a control that skips blanks reads them
/// (`#5 00` is #500); comments in `(...)` are skipped; an indirect `#[...]` is number -1 (its
/// number is known only at run time). `==` is no assignment.
std::vector<macro_use> macro_uses(std::string_view block);

/// A variable the machine file reserves, and why (for messages).
struct reserved_variable {
  int number = 0;
  std::string why;  ///< "program.reserved_variables", "read by transfer.grip"
};

/// The variables `m` reserves: program.reserved_variables, then every variable its [transfer]
/// blocks read but do not write (#0, the vacant value, excepted). Ascending, each once.
std::vector<reserved_variable> reserved_variables(const machine& m);

}  // namespace twinpost
