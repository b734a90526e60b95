#pragma once
// The machine definitions compiled into the binary (machines/builtin/*.toml).
#include <span>
#include <string_view>

namespace twinpost {

/// One built-in machine file: its name (the file name without .toml) and its TOML text.
struct builtin_machine_file {
  std::string_view name;
  std::string_view toml;
};

/// All built-in machine files, sorted by name.
std::span<const builtin_machine_file> builtin_machine_files();

}  // namespace twinpost
