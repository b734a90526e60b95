#include "machines/machine_search.hpp"

#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <iterator>

#include "machines/builtin_machines.hpp"
#include "machines/machine_loader.hpp"
#include "support/errors.hpp"

namespace twinpost {

namespace {

bool is_path(std::string_view s) { return s.find('/') != std::string_view::npos || s.ends_with(".toml"); }

// The text of a regular file, or nothing (a directory opens as a stream on Linux and reads
// as empty: it is no machine file).
std::optional<std::string> read_regular_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (!in.good() && !in.eof()) return std::nullopt;
  return text;
}

located_machine from_file(const std::string& path, std::string text) {
  machine m = parse_machine(text, path);
  return {std::move(m), path, std::move(text)};
}

}  // namespace

std::optional<std::string_view> builtin_machine_text(std::string_view name) {
  for (const builtin_machine_file& f : builtin_machine_files())
    if (f.name == name) return f.toml;
  return std::nullopt;
}

located_machine find_machine(std::string_view name_or_path, const std::vector<std::string>& dirs) {
  const std::string arg(name_or_path);
  if (is_path(arg)) {
    std::optional<std::string> text = read_regular_file(arg);
    if (!text) throw config_error(fmt::format("cannot read machine file '{}'", arg));
    return from_file(arg, std::move(*text));
  }
  std::string looked;
  for (const std::string& dir : dirs) {
    if (dir.empty()) continue;
    const std::string path = (std::filesystem::path(dir) / (arg + ".toml")).string();
    if (std::optional<std::string> text = read_regular_file(path)) return from_file(path, std::move(*text));
    looked += looked.empty() ? path : ", " + path;
  }
  if (std::optional<std::string_view> text = builtin_machine_text(arg)) {
    machine m = parse_machine(*text, fmt::format("machines/builtin/{}.toml", arg));
    return {std::move(m), "built-in", std::string(*text)};
  }
  if (std::optional<std::string> text = read_regular_file(arg)) return from_file(arg, std::move(*text));
  throw config_error(fmt::format("unknown machine '{}': {}no built-in machine and no file of that name", arg,
                                 looked.empty() ? "" : fmt::format("not in {}; ", looked)));
}

}  // namespace twinpost
