#include "machines/layout_rules.hpp"

#include <fmt/format.h>

#include "machines/layout_names.hpp"

namespace twinpost {

std::string layout_problem(const machine& m, layout_kind layout) {
  // formats/program_layout writes this marker before every channel's section; without it the
  // channels would run together and the control could not tell them apart.
  if (layout == layout_kind::merged_appended && m.program.section_marker.empty())
    return fmt::format(
        "layout {} needs program.section_marker (the block that opens each "
        "channel's section, such as \"G109 L{{channel}}\")",
        layout_file_name(layout));
  return {};
}

}  // namespace twinpost
