// libFuzzer target: mutated NC programs through the checker (`twinpost check`) on every
// built-in machine, as split files, one merged program, or `$n` sections (the first byte
// picks machine and form; split inputs are cut into one file per channel at form feeds,
// '\f'). Properties:
// - check_nc_files returns (no exception, no crash, no sanitizer report);
// - every error names one of the input files, and a line unless it is about the whole file;
// - the program read from disk piece by piece and from memory give the same report;
// - a report that says "sound" has no errors, and one with errors is not sound.
#include <string>
#include <vector>

#include "check/sync_check.hpp"
#include "check/sync_report.hpp"
#include "fuzz/fuzz_support.hpp"

using namespace twinpost;

namespace {

// The input cut at form feeds into at most `n` texts (the last takes the rest).
std::vector<std::string> cut(std::string_view text, std::size_t n) {
  std::vector<std::string> parts;
  while (parts.size() + 1 < n) {
    const std::size_t ff = text.find('\f');
    if (ff == std::string_view::npos) break;
    parts.emplace_back(text.substr(0, ff));
    text.remove_prefix(ff + 1);
  }
  parts.emplace_back(text);
  return parts;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::vector<machine>& all = fuzz::builtin_machine_defs();
  machine m = all[data[0] % all.size()];
  const int form = (data[0] / static_cast<int>(all.size())) % 3;  // 0 split, 1 merged, 2 sections
  if (form == 2) m.program.section_marker = "${channel}";
  const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  const std::vector<std::string> texts =
      form == 0 ? cut(text, m.channels.size()) : std::vector<std::string>{std::string(text)};
  const std::string dir = fuzz::scratch_dir();
  std::vector<nc_source> in_memory, on_disk;
  for (std::size_t i = 0; i < texts.size(); ++i) {
    const std::string name = dir + "/P_" + std::to_string(i + 1) + ".nc";
    fuzz::write_all(name, texts[i]);
    in_memory.push_back({name, texts[i]});
    on_disk.push_back({name, {}, name});
  }
  const sync_result a = check_nc_files(in_memory, m);
  const sync_result b = check_nc_files(on_disk, m);
  fuzz::require(format_sync_text(a) == format_sync_text(b), "streamed and in-memory reading disagree");
  fuzz::require(a.ok == (a.errors == 0), "`sound` and the error count disagree");
  for (const diagnostic& d : a.diagnostics) {
    if (d.level != severity::error) continue;
    bool known = false;
    for (const nc_source& s : in_memory) known = known || d.file == s.name;
    fuzz::require(known, "an error names no input file: " + d.message);
    // A finding about a whole file (no block in it, no section markers) names the file
    // alone; any other has its line (docs/checker.md).
    fuzz::require(d.line > 0 || (d.column == 0 && d.source_line.empty()),
                  "an error without a line: " + d.message);
  }
  return 0;
}
