#pragma once
// The names of the output layouts, in one table: the machine file spells them with '_'
// (`layout = "merged_appended"`), the command line with '-' (`--layout merged-appended`).
// The loader, the CLI and their messages all read them from here, in this order.
#include <array>
#include <optional>
#include <string_view>
#include <utility>

#include "machines/machine.hpp"

namespace twinpost {

struct layout_name {
  layout_kind kind;
  std::string_view file;    ///< in a machine file: "merged_appended"
  std::string_view option;  ///< on the command line: "merged-appended"
};

inline constexpr std::array<layout_name, 3> layout_names{{
    {layout_kind::split, "split", "split"},
    {layout_kind::merged_appended, "merged_appended", "merged-appended"},
    {layout_kind::merged_sections, "merged_sections", "merged-sections"},
}};

/// The layout's name in a machine file.
constexpr std::string_view layout_file_name(layout_kind k) {
  for (const layout_name& n : layout_names)
    if (n.kind == k) return n.file;
  return {};
}

/// The layout's name on the command line.
constexpr std::string_view layout_option_name(layout_kind k) {
  for (const layout_name& n : layout_names)
    if (n.kind == k) return n.option;
  return {};
}

/// The layout a command-line option names, if any.
constexpr std::optional<layout_kind> layout_from_option(std::string_view name) {
  for (const layout_name& n : layout_names)
    if (n.option == name) return n.kind;
  return std::nullopt;
}

/// (machine-file name, layout) pairs, for the loader's reader of named values.
constexpr std::array<std::pair<std::string_view, layout_kind>, 3> layout_file_names() {
  std::array<std::pair<std::string_view, layout_kind>, 3> out{};
  for (std::size_t i = 0; i < layout_names.size(); ++i) out[i] = {layout_names[i].file, layout_names[i].kind};
  return out;
}

}  // namespace twinpost
