#include "post/sync_at_cl.hpp"

#include <cstdio>
#include <fmt/format.h>
#include <map>
#include <memory>
#include <set>

#include "support/ascii.hpp"
#include "support/file_reader.hpp"

namespace twinpost {

namespace {

std::string place(const std::string& file, int line) { return fmt::format("{}:{}", file, line); }

// The CL lines in `wanted` (line number -> text without its line ending), read in one pass.
void read_lines(const std::string& path, std::map<int, std::string>& wanted) {
  if (wanted.empty()) return;
  const file_ptr f = open_file_ptr(path.c_str(), "rb");
  if (!f) return;
  const int last = wanted.rbegin()->first;
  std::string text;
  int line = 1;
  chunk_reader reader(f.get());
  for (std::string_view chunk; line <= last && !(chunk = reader.next()).empty();) {
    for (std::size_t i = 0; i < chunk.size() && line <= last; ++i) {
      if (chunk[i] != '\n') {
        if (text.size() < 4096) text += chunk[i];  // a caret line, not a copy of a huge record
        continue;
      }
      if (!text.empty() && text.back() == '\r') text.pop_back();
      if (auto it = wanted.find(line); it != wanted.end()) it->second = text;
      text.clear();
      ++line;
    }
  }
  if (auto it = wanted.find(line); it != wanted.end() && !text.empty())
    it->second = text;  // no final newline
}

// `message` with every "file:line" of a known wait (not followed by another digit) replaced.
std::string rewrite(const std::string& message, const std::map<std::string, std::string>& places) {
  std::string out = message;
  for (const auto& [nc, cl] : places) {
    for (std::size_t at = out.find(nc); at != std::string::npos; at = out.find(nc, at)) {
      const std::size_t end = at + nc.size();
      if (end < out.size() && ascii::is_digit(out[end])) {
        at = end;
        continue;
      }
      out.replace(at, nc.size(), cl);
      at += cl.size();
    }
  }
  return out;
}

}  // namespace

namespace {

// A block's text as the control reads it, for matching a written block with a read one:
// without an N number, blanks around and a line end.
std::string_view plain_text(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  if (!s.empty() && (s.front() == 'N' || s.front() == 'n')) {
    std::size_t i = 1;
    while (i < s.size() && ascii::is_digit(s[i])) ++i;
    if (i > 1) s.remove_prefix(i);
  }
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\r' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// NC "file:line" of each block in `wanted` -> the CL line of the written block it is: the
// k-th block of that text after the same number of waits, in the channel's program order.
std::map<std::string, int> block_cl_lines(const std::vector<nc_source>& files, const machine& m,
                                          const std::set<std::string>& wanted,
                                          const std::vector<std::vector<cl_block>>& blocks,
                                          const std::vector<cl_block_index>& block_lines) {
  std::map<std::string, int> out;
  if (wanted.empty() || blocks.empty()) return out;
  using key = std::pair<int, std::string>;  // segment, text
  std::vector<std::map<key, std::vector<int>>> written(blocks.size());
  for (std::size_t c = 0; c < blocks.size(); ++c)
    for (const cl_block& b : blocks[c])
      written[c][{b.segment, std::string(plain_text(b.text))}].push_back(b.cl_line);
  std::vector<int> segment(blocks.size(), 0);
  std::vector<std::map<key, std::size_t>> seen(blocks.size());
  // For block_lines: each channel's blocks counted as read, its waits' counts, and the wanted
  // blocks not among `blocks` with their count and segment.
  struct found_at {
    std::size_t channel, ordinal;
    int segment;
  };
  std::vector<std::size_t> ordinal(blocks.size(), 0);
  std::vector<std::vector<std::size_t>> wait_ordinals(blocks.size());
  std::map<std::string, found_at> by_count;
  nc_read_options o;
  o.on_wait = [&](const nc_wait& w) {
    if (w.channel >= 1 && static_cast<std::size_t>(w.channel) <= segment.size()) {
      const auto c = static_cast<std::size_t>(w.channel - 1);
      ++segment[c];
      wait_ordinals[c].push_back(ordinal[c] - 1);  // its block came just before
    }
  };
  o.on_block = [&](const nc_block& b) {
    const int channel = b.channel;
    const std::string& file = b.file;
    const int line = b.line;
    const std::string_view text = b.text;
    if (channel < 1 || static_cast<std::size_t>(channel) > blocks.size()) return;
    const auto c = static_cast<std::size_t>(channel - 1);
    const std::size_t n = ordinal[c]++;
    const key k{segment[c], std::string(plain_text(text))};
    const auto it = written[c].find(k);
    if (it == written[c].end()) {
      if (c < block_lines.size() && block_lines[c].count > 0 && wanted.count(place(file, line)))
        by_count[place(file, line)] = {c, n, segment[c]};
      return;
    }
    const std::size_t nth = seen[c][k]++;
    const std::string at = place(file, line);
    if (nth < it->second.size() && it->second[nth] > 0 && wanted.count(at)) out[at] = it->second[nth];
  };
  diagnostic_list ignored;
  read_nc_programs(files, m, ignored, o);
  for (const auto& [at, f] : by_count) {
    const cl_block_index& w = block_lines[f.channel];
    const std::vector<std::size_t>& read_waits = wait_ordinals[f.channel];
    // Anchored at the wait before it, or (before any wait) at the first wait.
    const auto anchor = static_cast<std::size_t>(f.segment > 0 ? f.segment - 1 : 0);
    if (anchor >= read_waits.size() || anchor >= w.waits.size()) continue;
    const long index = static_cast<long>(w.waits[anchor]) + static_cast<long>(f.ordinal) -
                       static_cast<long>(read_waits[anchor]);
    if (index < 0 || static_cast<std::size_t>(index) >= w.count) continue;
    if (const int cl = w.cl_line(static_cast<std::size_t>(index)); cl > 0) out[at] = cl;
  }
  return out;
}

}  // namespace

void fill_cl_lines(std::vector<diagnostic>& found, const std::string& cl_path) {
  std::map<int, std::string> lines;
  for (const diagnostic& d : found)
    if (d.file == cl_path && d.line > 0 && d.source_line.empty()) lines[d.line];
  read_lines(cl_path, lines);
  for (diagnostic& d : found)
    if (d.file == cl_path && d.line > 0 && d.source_line.empty()) d.source_line = lines[d.line];
}

std::vector<diagnostic> sync_diagnostics_at_cl(
    const std::vector<diagnostic>& found, const std::vector<nc_source>& files, const machine& m,
    const std::string& cl_path, const std::vector<std::vector<int>>& wait_cl_lines, int cl_last_line,
    const std::vector<std::vector<cl_block>>& blocks, const std::vector<cl_block_index>& block_lines) {
  // The programs are read again only here, when something was found.
  diagnostic_list ignored;
  const nc_programs programs = read_nc_programs(files, m, ignored);
  std::map<std::string, int> cl_line_of;  // NC "file:line" -> CL line
  for (const nc_channel_program& p : programs.channels) {
    const auto c = static_cast<std::size_t>(p.channel - 1);
    if (c >= wait_cl_lines.size()) continue;
    for (std::size_t k = 0; k < p.waits.size() && k < wait_cl_lines[c].size(); ++k)
      if (wait_cl_lines[c][k] > 0)
        cl_line_of[place(p.waits[k].where.file, p.waits[k].where.line)] = wait_cl_lines[c][k];
  }
  // Findings at other blocks (the shared-resource rules): their blocks' CL records.
  std::set<std::string> wanted;
  for (const diagnostic& d : found)
    if (d.line > 0 && !cl_line_of.count(place(d.file, d.line))) wanted.insert(place(d.file, d.line));
  std::set<std::string> at_blocks;
  for (const auto& [nc, line] : block_cl_lines(files, m, wanted, blocks, block_lines)) {
    cl_line_of[nc] = line;
    at_blocks.insert(nc);
  }
  std::map<std::string, std::string> places;
  std::map<int, std::string> sources;
  for (const auto& [nc, line] : cl_line_of) {
    places[nc] = place(cl_path, line);
    sources[line];
  }
  // "channel 2 ends at ..." names the end of a program: the end of the job.
  if (cl_last_line > 0)
    for (const nc_channel_program& p : programs.channels)
      if (p.end.line > 0) places.emplace(place(p.end.file, p.end.line), place(cl_path, cl_last_line));
  read_lines(cl_path, sources);
  std::vector<diagnostic> out;
  for (const diagnostic& d : found) {
    const auto it = cl_line_of.find(place(d.file, d.line));
    diagnostic moved = d;
    moved.message = rewrite(d.message, places);
    if (it == cl_line_of.end()) {
      out.push_back(std::move(moved));
      continue;
    }
    moved.file = cl_path;
    moved.line = it->second;
    moved.source_line = sources[it->second];
    const std::size_t first = moved.source_line.find_first_not_of(" \t");
    moved.column = first == std::string::npos ? 1 : static_cast<int>(first) + 1;
    out.push_back(std::move(moved));
    diagnostic note = d;
    note.level = severity::note;
    // An error (and its notes) stops the post: the program is never written. A warning's is.
    const bool block = at_blocks.count(place(d.file, d.line)) > 0;
    note.message = d.level == severity::warning
                       ? (block ? "the block in the program" : "the wait in the program")
                   : block ? "the block in the program as it would have been written (no file is written)"
                           : "the wait in the program as it would have been written (no file is written)";
    out.push_back(std::move(note));
  }
  return out;
}

}  // namespace twinpost
