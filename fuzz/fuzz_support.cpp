#include "fuzz/fuzz_support.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <unistd.h>

#include "check/sync_check.hpp"
#include "machines/builtin_machines.hpp"
#include "machines/machine_loader.hpp"
#include "post/post_job.hpp"
#include "support/ascii.hpp"
#include "support/errors.hpp"

namespace fs = std::filesystem;

namespace twinpost::fuzz {

namespace {

struct scratch {
  std::string path;
  scratch() {
    const char* base = std::getenv("TMPDIR");
    std::string tpl = std::string(base && *base ? base : "/tmp") + "/twinpost-fuzz-XXXXXX";
    if (!::mkdtemp(tpl.data())) {
      std::perror("mkdtemp");
      std::abort();
    }
    path = tpl;
  }
  ~scratch() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

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

}  // namespace

const std::string& scratch_dir() {
  static scratch s;
  return s.path;
}

const std::vector<machine>& builtin_machine_defs() {
  static const std::vector<machine> all = [] {
    std::vector<machine> v;
    for (const builtin_machine_file& f : builtin_machine_files()) v.push_back(load_machine(f.name));
    return v;
  }();
  return all;
}

void require(bool ok, std::string_view what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz property failed: %.*s\n", static_cast<int>(what.size()), what.data());
  std::abort();
}

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_all(const std::string& path, std::string_view text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  require(static_cast<bool>(out), "writing a scratch file");
}

post_outcome post_checked(const std::string& job, const std::string& out, const machine& m,
                          layout_kind layout, bool has_insert) {
  std::error_code ec;
  fs::remove_all(out, ec);
  post_options o;
  o.cl_path = job;
  o.out_dir = out;
  o.layout = layout;
  diagnostic_list diags;
  post_outcome r;
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
      require(!d.file.empty() && (d.line > 0 || (d.column == 0 && d.source_line.empty())),
              "an error without a position: " + d.message);
  if (!r.ok) {
    require(!fs::exists(out, ec) || fs::is_empty(out, ec), "a failed post left files behind");
    return r;
  }
  require(!r.files.empty(), "a post that succeeded wrote no file");
  std::vector<std::string> sorted = r.files;
  std::sort(sorted.begin(), sorted.end());
  require(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end(),
          "two programs written to one path");
  std::size_t entries = 0;
  for (auto it = fs::directory_iterator(out, ec); !ec && it != fs::directory_iterator(); ++it) ++entries;
  require(entries == r.files.size(), "the output folder holds other files than the ones reported");
  std::vector<nc_source> sources;
  for (const std::string& f : r.files) {
    require(fs::is_regular_file(f, ec), "a reported file is missing");
    r.contents.push_back(read_all(f));
    // INSERT text goes out verbatim (it is NC the CAM user wrote): a job with one is not
    // held to the rule for the words twinpost formats itself.
    require(has_insert || words_readable(r.contents.back()), "an unreadable number in " + f);
    sources.push_back({f, {}, f});
  }
  const sync_result check = check_nc_files(sources, m);
  require(check.ok, "a posted program set fails `check`");
  return r;
}

}  // namespace twinpost::fuzz
