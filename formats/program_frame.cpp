#include "formats/program_frame.hpp"

#include <cstdio>
#include <fmt/format.h>
#include <memory>

#include "machines/machine_loader.hpp"

namespace twinpost {

namespace {

using file_ptr = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

file_ptr open_or_throw(const std::string& path, const char* mode) {
  std::FILE* f = std::fopen(path.c_str(), mode);
  if (!f) throw config_error(fmt::format("twinpost: error: cannot open '{}'", path));
  return {f, &std::fclose};
}

void put_line(std::FILE* f, std::string_view s) {
  std::fwrite(s.data(), 1, s.size(), f);
  std::fputc('\n', f);
}

// Copies a channel body in large pieces: it may be far bigger than memory should hold.
void copy_body(std::FILE* to, const std::string& body_path) {
  file_ptr from = open_or_throw(body_path, "rb");
  constexpr std::size_t chunk_bytes = 1 << 20;
  auto buf = std::make_unique_for_overwrite<char[]>(chunk_bytes);  // no zeroing: it is overwritten
  std::size_t n;
  while ((n = std::fread(buf.get(), 1, chunk_bytes, from.get())) > 0)
    if (std::fwrite(buf.get(), 1, n, to) != n) throw config_error("twinpost: error: cannot write the program");
}

int program_number(const machine& m, const std::string& name) {
  if (!name.empty() && name.size() <= 8 && name.find_first_not_of("0123456789") == std::string::npos)
    return std::stoi(name);
  return m.program.program_number;
}

void write_channel(std::FILE* f, const machine& m, const channel_def& ch, const frame_request& r,
                   const template_args& a) {
  for (const std::string& h : m.program.header) put_line(f, format_template(h, a));
  copy_body(f, fmt::format("{}/body{}", r.tmp_dir, ch.number));
  for (const std::string& h : m.program.footer) put_line(f, format_template(h, a));
  put_line(f, m.program.end_code);
}

void close_or_throw(file_ptr& f, const std::string& path) {
  std::FILE* raw = f.release();
  if (std::ferror(raw) || std::fclose(raw) != 0) throw config_error(fmt::format("twinpost: error: cannot write '{}'", path));
}

// One program file: '%', the program line, the channels (each after its section marker
// in a merged layout), '%'.
framed_file write_program(const frame_request& r, template_args a, framed_file ff,
                          const std::vector<const channel_def*>& channels, bool markers) {
  const machine& m = *r.machine_def;
  // Appended programs follow the machine's own marker (Mazak G109 L1); sections are `$n`.
  const std::string marker = r.layout == layout_kind::merged_sections ? "${channel}" : m.program.section_marker;
  file_ptr f = open_or_throw(ff.tmp_path, "wb");
  if (m.program.percent_lines) put_line(f.get(), "%");
  put_line(f.get(), format_template(m.program.program_line, a));
  for (const channel_def* ch : channels) {
    a.channel = ch->number;
    if (markers) put_line(f.get(), format_template(marker, a));
    write_channel(f.get(), m, *ch, r, a);
  }
  if (m.program.percent_lines) put_line(f.get(), "%");
  close_or_throw(f, ff.tmp_path);
  return ff;
}

}  // namespace

std::vector<framed_file> frame_programs(const frame_request& r) {
  const machine& m = *r.machine_def;
  template_args a = sample_template_args();
  a.name = r.name;
  a.program = program_number(m, r.name);
  std::string stem = format_template(m.program.file_name, a);
  std::vector<framed_file> out;
  if (r.layout == layout_kind::split) {
    for (const channel_def& ch : m.channels)
      out.push_back(write_program(r, a,
                                  {stem + ch.file_suffix + m.program.extension,
                                   fmt::format("{}/framed{}", r.tmp_dir, ch.number)},
                                  {&ch}, false));
    return out;
  }
  // Merged: one program; each channel follows its section marker (G109 L1 / $1).
  std::vector<const channel_def*> all;
  for (const channel_def& ch : m.channels) all.push_back(&ch);
  out.push_back(write_program(r, a, {stem + m.program.extension, fmt::format("{}/framed", r.tmp_dir)}, all, true));
  return out;
}

}  // namespace twinpost
