// libFuzzer target: mutated CL through the whole post — reader, router, wait allocation,
// channel writers, framing, the self-check and the commit of the output set — in a scratch
// folder, on every built-in machine and layout (the first byte picks them). Properties:
// - post_job returns or throws config_error (exit 0, 1 or 2 in the tool), nothing else;
// - a failed post leaves the output folder as it was (here: absent or empty);
// - every error has a file, and a line unless it is about the whole job;
// - a post that succeeds wrote the files it names, and `check` finds them sound;
// - no word of a posted program is unreadable: no inf or nan, no number of more than ten
//   digits outside comments (the machine's word formats are tighter still); a job with an
//   INSERT record (raw NC text, written verbatim) is not held to this one;
// - the same input posted again gives the same bytes.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "check/sync_check.hpp"
#include "fuzz/fuzz_support.hpp"
#include "machines/layout_rules.hpp"
#include "post/post_job.hpp"
#include "support/ascii.hpp"
#include "support/errors.hpp"

namespace fs = std::filesystem;
using namespace twinpost;

namespace {

struct outcome {
  bool ok = false;
  bool config = false;
  std::vector<std::string> files;
  std::vector<std::string> contents;
};

// True when the job holds the word INSERT in any case (a record of raw NC text).
bool contains_insert(std::string_view cl) {
  for (std::size_t i = 0; i < cl.size(); ++i)
    if (ascii::starts_with_keyword(cl.substr(i), "INSERT")) return true;
  return false;
}

// True when every number outside comments has at most ten digits and nothing reads "inf"/"nan".
bool words_readable(const std::string& text) {
  int digits = 0;
  bool comment = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '(') comment = true;
    if (c == ')' || c == '\n') comment = false;
    if (comment) continue;
    digits = ascii::is_digit(c) ? digits + 1 : (c == '.' ? digits : 0);
    if (digits > 10) return false;
    if ((c == 'i' || c == 'I') && (text.compare(i, 3, "inf") == 0 || text.compare(i, 3, "INF") == 0))
      return false;
    if ((c == 'n' || c == 'N') && (text.compare(i, 3, "nan") == 0 || text.compare(i, 3, "NAN") == 0))
      return false;
  }
  return true;
}

outcome post_once(const std::string& job, const std::string& out, const machine& m, layout_kind layout,
                  bool has_insert) {
  std::error_code ec;
  fs::remove_all(out, ec);
  post_options o;
  o.cl_path = job;
  o.out_dir = out;
  o.layout = layout;
  diagnostic_list diags;
  outcome r;
  try {
    post_summary s = post_job(o, m, diags);
    r.ok = s.ok;
    r.files = s.files;
  } catch (const config_error&) {
    r.config = true;  // the tool's exit 2
  }
  for (const diagnostic& d : diags.all())
    // An error about the job as a whole (no records at all) names the file alone; any other
    // has its line (and, with a line, its source line's column).
    if (d.level == severity::error)
      fuzz::require(!d.file.empty() && (d.line > 0 || (d.column == 0 && d.source_line.empty())),
                    "an error without a position: " + d.message);
  if (!r.ok) {
    fuzz::require(!fs::exists(out, ec) || fs::is_empty(out, ec), "a failed post left files behind");
    return r;
  }
  fuzz::require(!r.files.empty(), "a post that succeeded wrote no file");
  std::vector<std::string> sorted = r.files;
  std::sort(sorted.begin(), sorted.end());
  fuzz::require(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end(),
                "two programs written to one path");
  std::size_t entries = 0;
  for (auto it = fs::directory_iterator(out, ec); !ec && it != fs::directory_iterator(); ++it) ++entries;
  fuzz::require(entries == r.files.size(), "the output folder holds other files than the ones reported");
  std::vector<nc_source> sources;
  for (const std::string& f : r.files) {
    fuzz::require(fs::is_regular_file(f, ec), "a reported file is missing");
    r.contents.push_back(fuzz::read_all(f));
    // INSERT text goes out verbatim (it is NC the CAM user wrote): a job with one is not
    // held to the rule for the words twinpost formats itself.
    fuzz::require(has_insert || words_readable(r.contents.back()), "an unreadable number in " + f);
    sources.push_back({f, {}, f});
  }
  const sync_result check = check_nc_files(sources, m);
  fuzz::require(check.ok, "a posted program set fails `check`");
  return r;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::vector<machine>& all = fuzz::builtin_machine_defs();
  const machine& m = all[data[0] % all.size()];
  static constexpr layout_kind layouts[] = {layout_kind::split, layout_kind::merged_appended,
                                            layout_kind::merged_sections};
  layout_kind layout = layouts[(data[0] / all.size()) % 3];
  // A layout the machine cannot take is refused before posting (machines/layout_rules).
  if (!layout_problem(m, layout).empty()) layout = layout_kind::merged_sections;
  const std::string dir = fuzz::scratch_dir();
  const std::string job = dir + "/job.cls";
  fuzz::write_all(job, std::string_view(reinterpret_cast<const char*>(data) + 1, size - 1));
  const std::string_view cl(reinterpret_cast<const char*>(data) + 1, size - 1);
  const bool has_insert = contains_insert(cl);
  const outcome first = post_once(job, dir + "/out", m, layout, has_insert);
  if (!first.ok) return 0;
  const outcome second = post_once(job, dir + "/again", m, layout, has_insert);
  fuzz::require(second.ok && second.contents == first.contents,
                "the same job posted twice gave different bytes");
  return 0;
}
