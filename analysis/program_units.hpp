#pragma once
// The unit a channel's program is written in, and the G codes that change it, as the control
// reads them: G20 inch and G21 millimetres, or G70 and G71 in Fanuc lathe G-code system C
// (whose G20 and G21 are the OD and threading cycles). One reading for every analysis that
// holds program positions to millimetres (the comparison with the CL, the interference rule).
#include <optional>

#include "machines/machine.hpp"

namespace twinpost {

struct program_units {
  bool system_c = false;  ///< the header gives G70 or G71 and neither G20 nor G21
  bool inch = false;      ///< the program starts in inches (program.output_units)

  /// The unit G`number` selects (true: inch), or none when it is no unit code here.
  std::optional<bool> selected_by(double number) const;
};

program_units units_of(const machine& m);

}  // namespace twinpost
