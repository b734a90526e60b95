#include "formats/program_number.hpp"

#include <fmt/format.h>

namespace twinpost {

void warn_program_number(const machine& m, diagnostic_sink& diags, const std::string& file,
                         const event& partno, const std::string& name) {
  if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) return;
  if (m.program_number_of(name)) return;
  const word_format& o = m.formats['O'];
  diagnostic d;
  d.level = severity::warning;
  d.file = file;
  d.line = partno.line;
  d.column = partno.column;
  d.message = fmt::format(
      "PARTNO {} is not a program number of this control (format.O {}: 1 to {}); the "
      "program takes the machine's program_number {}",
      name, o.text(), o.max_text(), m.program.program_number);
  diags.report(std::move(d));
}

}  // namespace twinpost
