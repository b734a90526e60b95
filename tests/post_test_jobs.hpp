#pragma once
// Small CL jobs and a post runner for the tests of the post's output handling.
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>

#include "file_test_support.hpp"
#include "post/post_job.hpp"
#include "support/diagnostics.hpp"

namespace twinpost::test {

/// A two-head job named RACE whose every channel carries `PPRINT VERSION <v>`, with
/// `extra_moves` more moves on head 1 (65,536 events give one progress call).
inline std::string race_job(char v, int extra_moves = 0) {
  std::string s = "PARTNO RACE\nHEAD/1\nPPRINT VERSION ";
  s += v;
  // MAIN: the Integrex head also has a milling spindle, and a speed in rpm for a tool of
  // unknown kind names no spindle there.
  s += "\nTURRET/1,1\nSPINDL/RPM,1000,CLW,MAIN\nFEDRAT/0.2,MMPR\nGOTO/20,0,5\nGOTO/20,0,-10\n";
  for (int i = 0; i < extra_moves; ++i) s += i % 2 ? "GOTO/20,0,-10\n" : "GOTO/21,0,-10\n";
  s += "HEAD/2\nPPRINT VERSION ";
  s += v;
  s += "\nTURRET/4,4\nSPINDL/RPM,1000,CLW\nFEDRAT/0.1,MMPR\nGOTO/-10,0,5\nGOTO/-10,0,-3\nFINI\n";
  return s;
}

/// Posts `job_text` (written to `dir`/`job_name`) for `m` into `out`.
inline post_summary post_text(const std::string& dir, const std::string& job_name,
                              const std::string& job_text, const machine& m, const std::string& out,
                              diagnostic_sink& diags, std::optional<layout_kind> layout = {},
                              const std::function<void(post_options&)>& adjust = {}) {
  const std::string job = dir + "/" + job_name;
  if (!write_file(job, job_text)) throw std::runtime_error("cannot write " + job);
  post_options o;
  o.cl_path = job;
  o.out_dir = out;
  o.layout = layout;
  if (adjust) adjust(o);
  return post_job(o, m, diags);
}

/// What a post left behind (post_in_fresh_dir).
struct posted {
  bool ok = false;
  diagnostic_list diags;                     ///< every diagnostic, as reported
  std::string diagnostics;                   ///< those kept, formatted, the job's path written "job.cls"
  std::map<std::string, std::string> files;  ///< the output folder: name -> contents
};

/// Posts `cl` (as job.cls) for `m` in a fresh folder named for `tag`, removed afterwards.
/// `keep` chooses the diagnostics that go into `diagnostics` (all when empty); `adjust` may
/// change the options (--permissive, --dialect).
inline posted post_in_fresh_dir(const std::string& cl, const machine& m, const std::string& tag,
                                const std::function<bool(const diagnostic&)>& keep = {},
                                std::optional<layout_kind> layout = {},
                                const std::function<void(post_options&)>& adjust = {}) {
  const std::string dir = fresh_temp_dir(tag);
  const std::string job = dir + "/job.cls";
  posted p;
  p.ok = post_text(dir, "job.cls", cl, m, dir + "/out", p.diags, layout, adjust).ok;
  for (const diagnostic& d : p.diags.all()) {
    if (keep && !keep(d)) continue;
    std::string text = format_diagnostic(d);
    for (std::size_t at; (at = text.find(job)) != std::string::npos;) text.replace(at, job.size(), "job.cls");
    p.diagnostics += text;
  }
  p.files = read_dir_files(dir + "/out");
  std::filesystem::remove_all(dir);
  return p;
}

}  // namespace twinpost::test
