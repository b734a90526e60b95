#include "formats/program_layout.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <memory>

#include "machines/name_template.hpp"
#include "support/errors.hpp"
#include "support/file_reader.hpp"

namespace twinpost {

namespace {

file_ptr open_or_throw(const std::string& path, const char* mode) {
  file_ptr f = open_file_ptr(path.c_str(), mode);
  if (!f) throw config_error(fmt::format("cannot open '{}': {}", path, std::strerror(errno)));
  return f;
}

void add_line(std::string& out, std::string_view s) {
  out.append(s);
  out += '\n';
}

// A header or footer block, numbered in the section's count; a comment line is not a block.
void add_block(std::string& out, const program_format& p, sequence_numbers& seq, std::string_view s) {
  if (s.empty() || s.front() != p.comment_open) out += seq.next();
  add_line(out, s);
}

// A header or footer block as the section's edit makes it (frame_request::edit_block).
void add_edited(std::string& out, const frame_request& r, const channel_def& ch, sequence_numbers& seq,
                const std::string& b, bool header, std::size_t index) {
  const program_format& p = r.machine_def->program;
  if (!r.edit_block || b.empty() || b.front() == p.comment_open) return add_block(out, p, seq, b);
  for (const std::string& e : r.edit_block(ch, b, header, index)) add_block(out, p, seq, e);
}

void put(std::FILE* f, std::string_view s) { std::fwrite(s.data(), 1, s.size(), f); }

[[noreturn]] void write_failed(const frame_request& r, const std::string& name, int err) {
  throw config_error(fmt::format("cannot write '{}': {}", (std::filesystem::path(r.out_dir) / name).string(),
                                 std::strerror(err)));
}

// Copies `from` (from byte `skip` on) into the program `name` in large pieces: it may be far
// bigger than memory should hold.
void copy_file(const frame_request& r, const std::string& name, std::FILE* to, const std::string& from_path,
               long skip = 0) {
  file_ptr from = open_or_throw(from_path, "rb");
  if (skip > 0 && std::fseek(from.get(), skip, SEEK_SET) != 0)
    throw config_error(fmt::format("cannot read '{}'", from_path));
  chunk_reader reader(from.get());
  for (std::string_view chunk; !(chunk = reader.next()).empty();)
    if (std::fwrite(chunk.data(), 1, chunk.size(), to) != chunk.size()) write_failed(r, name, errno);
  if (reader.failed())  // a short program must not pass for the whole one
    throw config_error(fmt::format("cannot read '{}': {}", from_path, std::strerror(errno)));
}

void close_or_throw(const frame_request& r, const std::string& name, file_ptr& f) {
  std::FILE* raw = f.release();
  const bool failed = std::ferror(raw) != 0;
  const int err = errno;
  if (std::fclose(raw) != 0) write_failed(r, name, errno);
  if (failed) write_failed(r, name, err);
}

int program_number(const machine& m, const std::string& name) {
  return m.program_number_of(name).value_or(m.program.program_number);
}

// The values of template_uses::file (no channel: the file is the channels' together) or,
// with a channel, template_uses::section. Nothing else: the loader refuses a template that
// names more, so no default can reach the output.
template_args args_for(const frame_request& r, const channel_def* ch) {
  template_args a;
  a.name = r.name;
  a.program = program_number(*r.machine_def, r.name);
  if (ch) a.channel = ch->number;
  return a;
}

bool merged(const frame_request& r) { return r.layout != layout_kind::split; }

// The first channel opens a merged program; the others are appended after it.
bool opens_file(const frame_request& r, const channel_def& ch) {
  return !merged(r) || &ch == &r.machine_def->channels.front();
}

// A channel's section: marker (merged layouts) and header lines.
std::string section_head(const frame_request& r, const channel_def& ch, sequence_numbers& seq) {
  const machine& m = *r.machine_def;
  const template_args a = args_for(r, &ch);
  std::string s;
  // Appended programs follow the machine's own marker (Mazak G109 L1); sections are `$n`.
  if (merged(r))
    add_line(s, format_template(
                    r.layout == layout_kind::merged_sections ? "${channel}" : m.program.section_marker, a));
  for (std::size_t i = 0; i < m.program.header.size(); ++i)
    add_edited(s, r, ch, seq, format_template(m.program.header[i], a), true, i);
  return s;
}

std::string section_tail(const frame_request& r, const channel_def& ch, sequence_numbers& seq,
                         std::vector<std::string> in_force) {
  const machine& m = *r.machine_def;
  const template_args a = args_for(r, &ch);
  std::string s;
  // The footer's home is the channel's: where the footer lists the machine's home blocks
  // (codes.home) in their order and the channel has its own (channel.home: the Integrex's upper
  // head homes Y with X, `G0 G90 G53 X0. Y0.`; the 31i's path 3 `G28 U0. V0.`), the channel's are
  // written there, so that every axis is home at the end code (review 61 A4: the upper head
  // ended at Y25, its turret without Y could not take the word).
  const std::vector<std::string>& machine_home = m.codes.home;
  const std::vector<std::string>& own_home = m.home(ch.number);
  const std::vector<std::string>& footer = m.program.footer;
  std::size_t home_at = footer.size();
  if (!machine_home.empty() && own_home != machine_home)
    home_at = static_cast<std::size_t>(
        std::search(footer.begin(), footer.end(), machine_home.begin(), machine_home.end()) - footer.begin());
  // (text, footer index) of each block: the footer's, the channel's home in place of codes.home.
  std::vector<std::pair<std::string, std::size_t>> blocks;
  for (std::size_t i = 0; i < footer.size(); ++i) {
    if (i == home_at) {
      // Each its own index (edit_block's answers are kept by it): past the footer's for the
      // blocks a longer home has more (attack 67 H3: two shared one, and Z was never homed).
      for (std::size_t k = 0; k < own_home.size(); ++k)
        blocks.emplace_back(own_home[k],
                            k < machine_home.size() ? i + k : footer.size() + (k - machine_home.size()));
      i += machine_home.size() - 1;
      continue;
    }
    blocks.emplace_back(format_template(footer[i], a), i);
  }
  for (const auto& [b, i] : blocks) {
    // The channel's own last M9 or M5, still in force, or a home block the tool already went
    // out by: the same block again would only say twice that the coolant is off.
    if (auto done = std::find(in_force.begin(), in_force.end(), b); done != in_force.end()) {
      in_force.erase(done);
      continue;
    }
    add_edited(s, r, ch, seq, b, false, i);
  }
  add_block(s, m.program, seq, m.program.end_code);
  return s;
}

std::string file_opening(const frame_request& r) {
  const machine& m = *r.machine_def;
  std::string s;
  if (m.program.percent_lines) add_line(s, "%");
  add_line(s, format_template(m.program.program_line, args_for(r, nullptr)));
  return s;
}

std::string file_closing(const frame_request& r) { return r.machine_def->program.percent_lines ? "%\n" : ""; }

// The head a channel's writer begins with: its header blocks are the first of its count, so
// the same head comes out again under a new name.
std::string first_head(const frame_request& r, const channel_def& ch) {
  sequence_numbers seq(r.machine_def->program, r.machine_def->formats['N']);
  return frame_head(r, ch, seq);
}

}  // namespace

channel_target frame_target(const frame_request& r, const channel_def& ch) {
  if (!merged(r)) return {fmt::format("{}/framed{}", r.tmp_dir, ch.number)};
  if (opens_file(r, ch)) return {fmt::format("{}/framed", r.tmp_dir)};
  return {fmt::format("{}/body{}", r.tmp_dir, ch.number)};
}

std::string frame_file_name(const frame_request& r, const channel_def& ch) {
  const machine& m = *r.machine_def;
  const std::string stem = format_template(m.program.file_name, args_for(r, nullptr));
  return merged(r) ? stem + m.program.extension : stem + ch.file_suffix + m.program.extension;
}

std::string frame_head(const frame_request& r, const channel_def& ch, sequence_numbers& seq) {
  if (!opens_file(r, ch)) return section_head(r, ch, seq);
  return file_opening(r) + section_head(r, ch, seq);
}

std::string frame_tail(const frame_request& r, const channel_def& ch, sequence_numbers& seq,
                       const std::vector<std::string>& in_force) {
  std::string s = section_tail(r, ch, seq, in_force);
  if (!merged(r)) s += file_closing(r);  // a merged program closes after its last channel
  return s;
}

std::vector<framed_file> finish_frames(const frame_request& r, const std::vector<std::string>& heads) {
  const machine& m = *r.machine_def;
  std::vector<framed_file> out;
  for (const channel_def& ch : m.channels) {
    if (!opens_file(r, ch)) continue;
    const std::string path = frame_target(r, ch).path;
    const std::string& written = heads[static_cast<std::size_t>(ch.number - 1)];
    const std::string head = first_head(r, ch);
    const std::string name = frame_file_name(r, ch);
    if (written != head) {
      // Begun under another name: the same blocks under the right head, in a new file.
      const std::string renamed = path + ".head";
      file_ptr f = open_or_throw(renamed, "wb");
      put(f.get(), head);
      copy_file(r, name, f.get(), path, static_cast<long>(written.size()));
      close_or_throw(r, name, f);
      if (std::rename(renamed.c_str(), path.c_str()) != 0) write_failed(r, name, errno);
    }
    out.push_back({name, path, ch.number, written != head});
  }
  if (!merged(r)) return out;
  out.front().rewritten = true;
  // Merged: the other channels' sections (each written whole, marker to end code, into its
  // body file) after the first one's, under the right head, then the closing '%'.
  file_ptr f = open_or_throw(out.front().tmp_path, "ab");
  for (const channel_def& ch : m.channels) {
    if (opens_file(r, ch)) continue;
    const std::string& written = heads[static_cast<std::size_t>(ch.number - 1)];
    const std::string head = first_head(r, ch);
    put(f.get(), head);
    copy_file(r, out.front().name, f.get(), frame_target(r, ch).path, static_cast<long>(written.size()));
  }
  put(f.get(), file_closing(r));
  close_or_throw(r, out.front().name, f);
  return out;
}

}  // namespace twinpost
