#include "post/output_names.hpp"
#include "support/errors.hpp"

#include <fmt/format.h>

namespace twinpost {

namespace {
constexpr std::size_t name_max = 255;  // NAME_MAX on Linux file systems
}

std::string file_name_problem(const std::string& name) {
  if (name.empty()) return "it is empty";
  if (name == "." || name == "..") return "it names a folder";
  if (name.find('/') != std::string::npos) return "it has a '/'";
  if (name.find('\0') != std::string::npos) return "it has a NUL byte";
  if (name.size() > name_max) return fmt::format("it is longer than {} bytes", name_max);
  if (name.starts_with(".twinpost-")) return "names beginning '.twinpost-' are the post's own";
  return "";
}

void check_output_names(const frame_request& r, const std::vector<framed_file>& files) {
  const machine& m = *r.machine_def;
  for (const framed_file& f : files) {
    const std::string why = file_name_problem(f.name);
    if (why.empty()) continue;
    const channel_def& ch = m.channels.at(static_cast<std::size_t>(f.channel - 1));
    const std::string suffix = r.layout == layout_kind::split ? ch.file_suffix : "";
    throw config_error(fmt::format(
        "machine file '{}': file_name \"{}\"{} and extension \"{}\" give the file name '{}' "
        "for channel {}: not a plain file name in the output folder ({})",
        m.source, m.program.file_name, suffix.empty() ? "" : fmt::format(", file_suffix \"{}\"", suffix),
        m.program.extension, f.name, f.channel, why));
  }
  for (std::size_t i = 0; i < files.size(); ++i)
    for (std::size_t j = i + 1; j < files.size(); ++j)
      if (files[i].name == files[j].name)
        throw config_error(
            fmt::format("machine file '{}': channels {} and {} would both be written to '{}' "
                        "(file_name \"{}\", split layout): give the channels distinct file_suffix values",
                        m.source, files[i].channel, files[j].channel, files[i].name, m.program.file_name));
}

}  // namespace twinpost
